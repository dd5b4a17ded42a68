"""Starting and stopping the processes of one HFO run: HFO's launcher
(``bin/HFO``, which starts rcssserver, the trainer and the goalkeeper) and
our three offense agents (:mod:`hfo_oracle.agent`), each the leader of its
own process group, all on loopback; and the loopback-only network namespace
the harness runs in where it can.
"""

from __future__ import annotations

import os
import random
import shutil
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import IO, Any

# The paper's setup: 3 offense agents against agent2d's goalkeeper.
OFFENSE_AGENTS = 3

# The directory holding this package: on the agents' PYTHONPATH so that
# `python -m hfo_oracle` finds it under any interpreter.
PACKAGE_PARENT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class StuckBatchError(RuntimeError):
    """An HFO run that hangs: it is discarded and replayed."""


class Procs:
    """Processes started by the harness, each the leader of its own process
    group (so that rcssserver and the NPCs started by HFO's launcher go with
    it). :meth:`kill_all` ends exactly these groups."""

    def __init__(self) -> None:
        self.items: list[subprocess.Popen] = []

    def start(self, cmd: Sequence[str], **kw: Any) -> subprocess.Popen:
        """Starts ``cmd`` (``subprocess.Popen``'s keywords) in a new session."""
        p = subprocess.Popen(cmd, start_new_session=True, **kw)
        self.items.append(p)
        return p

    def kill_all(self, grace: float = 1.0) -> None:
        """SIGTERM to every group, SIGKILL to what is left after ``grace``
        seconds."""
        for p in self.items:
            self._signal(p, signal.SIGTERM)
        deadline = time.time() + grace
        for p in self.items:
            try:
                p.wait(timeout=max(0.0, deadline - time.time()))
            except subprocess.TimeoutExpired:
                pass
        for p in self.items:
            self._signal(p, signal.SIGKILL)
            try:
                p.wait(timeout=5)
            except subprocess.TimeoutExpired:
                pass
        self.items = []

    @staticmethod
    def _signal(p: subprocess.Popen, sig: int) -> None:
        # The group outlives its leader when children remain, so signal the
        # group even if the leader has exited; a group id cannot be reused
        # while any member is alive.
        try:
            os.killpg(p.pid, sig)
        except (ProcessLookupError, PermissionError):
            pass


def free_port() -> int:
    """A base port P with P, P+1, P+2 free on UDP loopback (rcssserver's
    player, coach and online-coach ports)."""
    for _ in range(200):
        base = random.SystemRandom().randrange(20000, 60000)
        socks = []
        try:
            for off in range(3):
                s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
                socks.append(s)
                s.bind(("127.0.0.1", base + off))
            return base
        except OSError:
            continue
        finally:
            for s in socks:
                s.close()
    raise RuntimeError("no free UDP port triple found")


def wait_for_line(path: str, needle: str, proc: subprocess.Popen, timeout: float) -> bool:
    """Whether ``needle`` appears in the file ``path`` within ``timeout``
    seconds while ``proc`` runs."""
    deadline = time.time() + timeout
    while time.time() < deadline:
        try:
            with open(path, errors="replace") as f:
                if needle in f.read():
                    return True
        except FileNotFoundError:
            pass
        if proc.poll() is not None:
            return False
        time.sleep(0.05)
    return False


@dataclass
class Setup:
    """What every run plays: the built HFO tree, the interpreter of its
    launcher and of the agents, the policy (``team`` for a learned team)
    and, for a team, the agents' snapshot files and the factory
    (``MODULE:CALLABLE``) that makes each an agent."""

    hfo_dir: str
    python: str
    policy: str
    team: Sequence[str] | None = None
    team_factory: str | None = None


class Batch:
    """One HFO run of ``episodes`` counted episodes (plus the warm-up trial)
    and its files in ``workdir``."""

    def __init__(
        self, index: int, episodes: int, seed: int, workdir: str, attempt: int = 0
    ) -> None:
        self.index = index
        self.episodes = episodes
        self.seed = seed
        self.dir = os.path.join(workdir, "batch%04d-%d" % (index, attempt))
        self.logdir = os.path.join(self.dir, "log")
        os.makedirs(self.logdir)
        self.hfo_out = os.path.join(self.dir, "hfo.out")
        self.agent_files = [
            os.path.join(self.dir, "agent%d.txt" % i) for i in range(OFFENSE_AGENTS)
        ]
        self.launcher: subprocess.Popen | None = None
        self.agents: list[subprocess.Popen] = []

    @property
    def trials(self) -> int:
        """The trials HFO plays: the warm-up and the counted episodes."""
        return self.episodes + 1


def with_package_path(env: dict[str, str], *first: str) -> dict[str, str]:
    """``env`` with ``first`` and this package's directory put in front of
    its PYTHONPATH."""
    paths = list(first) + [PACKAGE_PARENT]
    if env.get("PYTHONPATH"):
        paths.append(env["PYTHONPATH"])
    return dict(env, PYTHONPATH=os.pathsep.join(paths))


def start_batch(batch: Batch, setup: Setup, procs: Procs) -> None:
    """Starts HFO's launcher for ``batch``, then each agent once HFO asks
    for it."""
    port = free_port()
    env = with_package_path(dict(os.environ), setup.hfo_dir)
    cmd = [
        setup.python,
        "-u",
        os.path.join(setup.hfo_dir, "bin", "HFO"),
        "--offense-agents=%d" % OFFENSE_AGENTS,
        "--defense-npcs=1",
        "--fullstate",
        "--headless",
        "--frames-per-trial=200",
        "--trials=%d" % batch.trials,
        "--port=%d" % port,
        "--log-dir=%s" % batch.logdir,
        "--seed=%d" % (batch.seed % 2147483647),
    ]
    with open(batch.hfo_out, "w") as out:
        batch.launcher = procs.start(
            cmd,
            cwd=setup.hfo_dir,
            env=env,
            stdout=out,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
        )
    config_dir = os.path.join(setup.hfo_dir, "bin", "teams", "base", "config", "formations-dt")
    for i in range(OFFENSE_AGENTS):
        if not wait_for_line(
            batch.hfo_out,
            "Waiting for player-controlled agent base_left-%d" % i,
            batch.launcher,
            60,
        ):
            raise StuckBatchError("batch %d: HFO did not ask for agent %d" % (batch.index, i))
        acmd = [
            setup.python,
            "-m",
            "hfo_oracle",
            "agent",
            "--port=%d" % port,
            "--policy=%s" % setup.policy,
            "--seed=%d" % (batch.seed * 7 + 1000 * i + 1),
            "--config-dir=%s" % config_dir,
            "--out=%s" % batch.agent_files[i],
        ]
        if setup.team:
            acmd.append("--snapshot=%s" % setup.team[i])
            acmd.append("--team-factory=%s" % setup.team_factory)
        with open(os.path.join(batch.dir, "agent%d.err" % i), "w") as err:
            batch.agents.append(
                procs.start(
                    acmd,
                    cwd=setup.hfo_dir,
                    env=env,
                    stdout=subprocess.DEVNULL,
                    stderr=err,
                    stdin=subprocess.DEVNULL,
                )
            )


def finish_batch(batch: Batch, stall: float = 30.0) -> None:
    """Waits for the batch to end.

    rcssserver quits by itself after the last trial and then renames its
    logs from incomplete.rcg/.rcl to their final names. HFO's trainer
    (bin/Trainer.py) can miss that: right after the last trial it asks the
    server for the connected players and, the server being gone, retries for
    ever. So the batch is over when every trial has been reported and the
    logs are closed, whether or not the launcher has exited (kill_all ends
    it). A trial lasts at most ~200 cycles, well under a second of wall
    time: if HFO reports nothing new for ``stall`` seconds the batch is
    stuck (:class:`StuckBatchError`).
    """
    assert batch.launcher is not None, "finish_batch before start_batch"
    ended = 0
    last_size, last_change = -1, time.time()
    while batch.launcher.poll() is None:
        try:
            size = os.path.getsize(batch.hfo_out)
        except OSError:
            size = 0
        now = time.time()
        if size != last_size:
            last_size, last_change = size, now
            with open(batch.hfo_out, errors="replace") as f:
                ended = sum(1 for line in f if line.startswith("EndOfTrial:"))
        if ended >= batch.trials and logs_closed(batch.logdir):
            break
        if now - last_change > stall:
            raise StuckBatchError("batch %d: no progress for %.0f s" % (batch.index, stall))
        time.sleep(0.2)
    if not logs_closed(batch.logdir):
        raise StuckBatchError("batch %d: HFO ended before rcssserver closed its logs" % batch.index)
    for p in batch.agents:
        try:
            p.wait(timeout=stall)
        except subprocess.TimeoutExpired:
            raise StuckBatchError(
                "batch %d: an agent did not exit after the server quit" % batch.index
            ) from None


def logs_closed(logdir: str) -> bool:
    """Whether rcssserver has closed (renamed) its game and action logs."""
    names = os.listdir(logdir)
    return (
        not any(n.startswith("incomplete.rc") for n in names)
        and any(n.endswith(".rcg") for n in names)
        and any(n.endswith(".rcl") for n in names)
    )


def report_stuck(batch: Batch, err: BaseException, stream: IO[str] = sys.stderr) -> None:
    """Prints why ``batch`` is replayed, with the last lines of the
    launcher's and the agents' output."""
    print("[hfo_oracle] %s; replaying it. Last lines of its output:" % err, file=stream)
    paths = [batch.hfo_out] + [
        os.path.join(batch.dir, "agent%d.err" % i) for i in range(OFFENSE_AGENTS)
    ]
    for path in paths:
        try:
            with open(path, errors="replace") as f:
                tail = f.readlines()[-8:]
        except OSError:
            continue
        print("  --- %s" % os.path.basename(path), file=stream)
        for line in tail:
            print("  " + line.rstrip()[:200], file=stream)
    stream.flush()


def enter_network_namespace(net: str, argv: Sequence[str]) -> None:
    """Re-executes the harness (``python -m hfo_oracle ARGV``) inside a new
    user and network namespace whose only interface is loopback, so that
    nothing rcssserver binds is reachable from outside. Returns normally
    when ``net`` is ``host``, when already inside, or, for ``auto``, when
    no namespace can be made; exits when ``isolated`` cannot be had."""
    if net == "host" or os.environ.get("HFO_ORACLE_NETNS") == "1":
        return
    unshare, ip = shutil.which("unshare"), shutil.which("ip")
    ok = False
    if unshare and ip:
        ok = (
            subprocess.run(
                [unshare, "-rn", ip, "link", "set", "lo", "up"],
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            ).returncode
            == 0
        )
    if not ok:
        if net == "isolated":
            sys.exit("--net isolated: cannot create a network namespace (unshare -rn)")
        print(
            "note: no network namespace available; processes use 127.0.0.1 only, "
            "but rcssserver binds its ports on all interfaces",
            file=sys.stderr,
        )
        return
    os.environ.update(with_package_path(dict(os.environ)), HFO_ORACLE_NETNS="1")
    sys.stdout.flush()
    sys.stderr.flush()
    os.execvp(
        unshare,
        [
            unshare,
            "-rn",
            "sh",
            "-c",
            ip + ' link set lo up && exec "$@"',
            "sh",
            sys.executable,
            "-m",
            "hfo_oracle",
        ]
        + list(argv),
    )
