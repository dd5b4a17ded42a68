"""The real HFO as env-server's simulator (``env-server serve --real-hfo``):
``python -m hfo_oracle backend ...``, started by env-server, starts HFO's
launcher (rcssserver, the trainer, agent2d's goalkeeper) and one relay per
offense player (:mod:`hfo_oracle.relay`), then steps the game as
env-server's commands say, one line each way per command
(docs/protocol.md, "The real HFO").

Commands, on the standard input: ``R`` (begin an episode: the trial in
progress, if any, is played out with MOVE first), ``S`` followed by one
action code per player (step: ``SMSM``), ``Q`` (quit; so does the end of
the input). Each is answered on the standard output with one JSON line,
the frame: ``{"frame": k, "outcome": "in-game" | "goal" | "captured" |
"out-of-bounds" | "out-of-time", "kick": [...], "states": [...], "pos":
[...]}``, or ``{"error": "..."}`` before the backend exits. Diagnostics go
to the standard error.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
from collections.abc import Sequence
from typing import IO, Any

from hfo_oracle import launch

# How long HFO may take to ask for each player (s).
CONNECT_WAIT = 60.0
TERMINAL = ("goal", "captured", "out-of-bounds", "out-of-time")


class BackendError(RuntimeError):
    """Why the backend cannot go on: sent to env-server as its last line."""


def parse_args(argv: Sequence[str]) -> argparse.Namespace:
    """The backend's command line (given by env-server)."""
    p = argparse.ArgumentParser(prog="hfo_oracle.py backend")
    p.add_argument("--hfo-dir", required=True)
    p.add_argument(
        "--python", required=True, help="interpreter with HFO's Python interface's needs (numpy)"
    )
    p.add_argument("--offense", type=int, required=True)
    p.add_argument("--frames-per-trial", type=int, required=True)
    p.add_argument("--untouched-time", type=int, required=True)
    p.add_argument("--seed", type=int, required=True)
    p.add_argument("--net", choices=("auto", "isolated", "host"), default="auto")
    return p.parse_args(argv)


class Players:
    """The relays, one per offense player, in HFO's connection order, and
    the files of what each printed (HFO's library is talkative)."""

    def __init__(self, procs: list[subprocess.Popen], logs: list[str]) -> None:
        self.procs = procs
        self.logs = logs

    def ended(self, i: int) -> BackendError:
        """Why player ``i`` stopped answering: its exit and last words."""
        try:
            with open(self.logs[i], errors="replace") as f:
                tail = " | ".join(line.strip() for line in f.readlines()[-3:])
        except OSError:
            tail = ""
        return BackendError(
            "player %d of the real HFO ended (exit status %s)%s"
            % (i, self.procs[i].poll(), ": " + tail if tail else "")
        )

    def read(self) -> list[dict[str, Any]]:
        """Each relay's line of the current cycle."""
        lines = []
        for i, p in enumerate(self.procs):
            assert p.stdout is not None
            text = p.stdout.readline()
            if not text:
                try:
                    p.wait(timeout=5)
                except subprocess.TimeoutExpired:
                    pass
                raise self.ended(i)
            try:
                lines.append(json.loads(text))
            except ValueError:
                raise BackendError(
                    "player %d of the real HFO wrote %r, not a cycle's line" % (i, text[:80])
                ) from None
        return lines

    def send(self, codes: str) -> None:
        """One action code to each relay."""
        for p, code in zip(self.procs, codes):
            assert p.stdin is not None
            p.stdin.write(code + "\n")
            p.stdin.flush()


class Game:
    """The game as env-server sees it: the current cycle of every player,
    whether it is the first of a trial (no step taken in it yet), and the
    episode env-server began, if one is in progress, with its frame."""

    def __init__(self, players: Players) -> None:
        self.players = players
        self.lines = players.read()
        self.fresh = False  # the warm-up trial, begun before the players joined
        self.begun = False
        self.frame = 0

    def status(self) -> str:
        """The status of the step that led to the current cycle; players
        that disagree or a server that went down are errors."""
        statuses = {line["status"] for line in self.lines}
        if "server-down" in statuses:
            raise BackendError("its server went down")
        if len(statuses) != 1:
            raise BackendError("the players disagree on the game's status: %s" % sorted(statuses))
        return statuses.pop()

    def cycle(self, codes: str) -> str:
        """Every player acts as ``codes`` says; the new status."""
        self.players.send(codes)
        self.lines = self.players.read()
        status = self.status()
        self.fresh = status in TERMINAL
        return status

    def begin(self) -> None:
        """Plays out the trial in progress with MOVE, if a step was taken
        in it; the current cycle is then the first of the episode."""
        moves = "M" * len(self.players.procs)
        while not self.fresh:
            self.cycle(moves)
        self.begun, self.frame = True, 0

    def step(self, codes: str) -> str:
        """Steps the episode begun; its new status."""
        if not self.begun:
            raise BackendError("a step outside an episode: begin one with R")
        status = self.cycle(codes)
        self.frame += 1
        self.begun = status not in TERMINAL
        return status

    def frame_line(self, outcome: str) -> str:
        """The answer to a command: the current frame."""
        return (
            json.dumps(
                {
                    "frame": self.frame,
                    "outcome": outcome,
                    "kick": [line["kick"] for line in self.lines],
                    "states": [line["state"] for line in self.lines],
                    "pos": [line["pos"] for line in self.lines],
                },
                separators=(",", ":"),
            )
            + "\n"
        )


def start(a: argparse.Namespace, procs: launch.Procs, workdir: str) -> Players:
    """Starts HFO's launcher, then each relay once HFO asks for it."""
    port = launch.free_port()
    env = launch.with_package_path(dict(os.environ), a.hfo_dir)
    hfo_out = os.path.join(workdir, "hfo.out")
    cmd = [
        a.python,
        "-u",
        os.path.join(a.hfo_dir, "bin", "HFO"),
        "--offense-agents=%d" % a.offense,
        "--defense-npcs=1",
        "--fullstate",
        "--headless",
        "--frames-per-trial=%d" % a.frames_per_trial,
        "--untouched-time=%d" % a.untouched_time,
        "--no-logging",
        "--port=%d" % port,
        "--seed=%d" % (a.seed % 2147483647),
    ]
    with open(hfo_out, "w") as out:
        launcher = procs.start(
            cmd,
            cwd=a.hfo_dir,
            env=env,
            stdout=out,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
        )
    config_dir = os.path.join(a.hfo_dir, "bin", "teams", "base", "config", "formations-dt")
    relays, logs = [], []
    for i in range(a.offense):
        needle = "Waiting for player-controlled agent base_left-%d" % i
        if not launch.wait_for_line(hfo_out, needle, launcher, CONNECT_WAIT):
            with open(hfo_out, errors="replace") as f:
                tail = " | ".join(line.strip() for line in f.readlines()[-5:])
            raise BackendError(
                "HFO did not ask for player %d within %.0f s; its last lines: %s"
                % (i, CONNECT_WAIT, tail or "(none)")
            )
        cmd = [
            a.python,
            "-m",
            "hfo_oracle",
            "relay",
            "--port=%d" % port,
            "--config-dir=%s" % config_dir,
        ]
        logs.append(os.path.join(workdir, "player%d.err" % i))
        with open(logs[-1], "w") as err:
            relays.append(
                procs.start(
                    cmd,
                    cwd=a.hfo_dir,
                    env=env,
                    stdin=subprocess.PIPE,
                    stdout=subprocess.PIPE,
                    stderr=err,
                    text=True,
                )
            )
    return Players(relays, logs)


def serve(game: Game, inp: IO[str], out: IO[str]) -> None:
    """Answers env-server's commands until ``Q`` or the end of the input."""
    for text in inp:
        command = text.strip()
        if command == "Q":
            return
        if command == "R":
            game.begin()
            outcome = "in-game"
        elif (
            command.startswith("S")
            and len(command) == 1 + len(game.players.procs)
            and all(c in "MSDNF" for c in command[1:])
        ):
            outcome = game.step(command[1:])
        else:
            raise BackendError(
                "unknown command %r: expected R, S and one of MSDNF per player, or Q" % command[:40]
            )
        out.write(game.frame_line(outcome))
        out.flush()


def main(argv: Sequence[str]) -> int:
    """Starts the real HFO and serves (the first ``R`` plays out the
    warm-up trial)."""
    a = parse_args(argv)
    if not os.path.isfile(os.path.join(a.hfo_dir, "bin", "HFO")):
        print(
            json.dumps(
                {
                    "error": "no built HFO at %s (bin/HFO is missing): build it with "
                    "env-server/oracle/build_hfo.sh" % a.hfo_dir
                }
            ),
            flush=True,
        )
        return 1
    launch.enter_network_namespace(a.net, ["backend"] + list(argv))

    def on_term(signum: int, _frame: Any) -> None:
        raise KeyboardInterrupt("signal %d" % signum)

    signal.signal(signal.SIGTERM, on_term)
    procs = launch.Procs()
    workdir = tempfile.mkdtemp(prefix="hfo-backend-")
    try:
        game = Game(start(a, procs, workdir))
        serve(game, sys.stdin, sys.stdout)
        return 0
    except BackendError as e:
        print(json.dumps({"error": str(e)}), flush=True)
        return 1
    finally:
        procs.kill_all(grace=0.5)
        shutil.rmtree(workdir, ignore_errors=True)
