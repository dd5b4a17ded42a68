"""The command line: ``hfo_oracle.py [options]`` plays the episodes and
writes the statistics; ``hfo_oracle.py agent [options]`` is one agent
process (started by the harness, not by hand).

Per batch of episodes the harness starts HFO with rcssserver's logs in a
temporary directory and the three agents (:mod:`hfo_oracle.launch`); once
the batch is over it joins the logs with the agents' choices
(:mod:`hfo_oracle.tally`) and deletes them. Batches are pipelined: batch k
is parsed while batch k+1 plays.
"""

from __future__ import annotations

import argparse
import os
import shutil
import signal
import sys
import tempfile
import time
from collections.abc import Sequence
from typing import Any

from hfo_oracle import launch
from hfo_oracle.agent import split_factory
from hfo_oracle.schema import POLICIES, write_json
from hfo_oracle.tally import Tally

MAX_ATTEMPTS = 4  # plays of one batch before giving up on a run that hangs

# The factory of our own agents, for the help and the errors: the Python
# package of our agents, which --python must have.
OUR_AGENTS = "adhoc_advising:GreedyAgent"


def parse_args(argv: Sequence[str]) -> argparse.Namespace:
    """The harness's options, checked; ``policy`` is ``team`` with
    ``--team``, whose files are made absolute and which needs
    ``--team-factory``."""
    p = argparse.ArgumentParser(
        prog="hfo_oracle.py",
        description="Play N episodes of a fixed policy on the real HFO (3 offense agents vs "
        "agent2d's goalie) and write per-decision statistics as JSON.",
    )
    p.add_argument(
        "--hfo-dir",
        default=os.environ.get("HFO_DIR"),
        help="built HFO tree (bin/HFO, bin/rcssserver, hfo/libhfo_c.so); default $HFO_DIR",
    )
    p.add_argument(
        "--python",
        default=sys.executable,
        help="Python interpreter with numpy, for HFO's launcher and the agents",
    )
    who = p.add_mutually_exclusive_group(required=True)
    who.add_argument("--policy", choices=POLICIES)
    who.add_argument(
        "--team",
        nargs=launch.OFFENSE_AGENTS,
        metavar="SNAPSHOT",
        help="a learned team: its agents' snapshot files, each made an agent by --team-factory",
    )
    p.add_argument(
        "--team-factory",
        metavar="MODULE:CALLABLE",
        help="with --team: the callable that makes an agent of a snapshot file, "
        "imported by --python in each agent process; the agent's act(state, "
        "can_kick) returns its action's index in the paper's 6-feature state. "
        "For our agents (coordinator run --save-agents), played greedily as our "
        "evaluations play: %s" % OUR_AGENTS,
    )
    p.add_argument("--episodes", type=int, required=True)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--out", required=True, help="output JSON file")
    p.add_argument(
        "--batch",
        type=int,
        default=500,
        help="episodes per HFO run (the logs of one run are parsed and deleted "
        "while the next one plays); default 500",
    )
    p.add_argument(
        "--net",
        choices=("auto", "isolated", "host"),
        default="auto",
        help="auto: run in a loopback-only network namespace when possible",
    )
    p.add_argument("--tmp", default=None, help="parent directory for the temporary logs")
    p.add_argument("--keep-logs", action="store_true", help="do not delete the logs (debugging)")
    args = p.parse_args(argv)
    check_team_factory(p, args)
    if not args.hfo_dir or not os.path.exists(os.path.join(args.hfo_dir, "bin", "HFO")):
        p.error("--hfo-dir (or $HFO_DIR) must point at a built HFO tree containing bin/HFO")
    args.hfo_dir = os.path.abspath(args.hfo_dir)
    if args.team:
        args.team = [os.path.abspath(f) for f in args.team]
        missing = [f for f in args.team if not os.path.isfile(f)]
        if missing:
            p.error("--team: no such file: %s" % ", ".join(missing))
        args.policy = "team"
    if args.episodes <= 0:
        p.error("--episodes must be positive")
    if args.batch <= 0:
        p.error("--batch must be positive")
    return args


def check_team_factory(p: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """Exits with status 2 and one line when ``--team`` has no well-formed
    ``--team-factory``, or a policy has one."""
    error = None
    if args.team and args.team_factory is None:
        error = "--team needs --team-factory MODULE:CALLABLE (our agents: %s)" % OUR_AGENTS
    elif args.team:
        try:
            split_factory(args.team_factory)
        except ValueError as e:
            error = "%s (our agents: %s)" % (e, OUR_AGENTS)
    elif args.team_factory is not None:
        error = "--team-factory goes with --team"
    if error:
        p.exit(2, "%s: error: %s\n" % (p.prog, error))


def batch_sizes(episodes: int, batch: int) -> list[int]:
    """``episodes`` split into runs of at most ``batch``."""
    sizes = []
    left = episodes
    while left > 0:
        sizes.append(min(batch, left))
        left -= sizes[-1]
    return sizes


def harness_main(argv: Sequence[str]) -> int:
    """Plays the episodes batch by batch and writes the statistics file."""
    args = parse_args(argv)
    launch.enter_network_namespace(args.net, argv)

    def on_term(signum: int, _frame: Any) -> None:
        raise KeyboardInterrupt("signal %d" % signum)

    signal.signal(signal.SIGTERM, on_term)
    signal.signal(signal.SIGHUP, on_term)

    setup = launch.Setup(args.hfo_dir, args.python, args.policy, args.team, args.team_factory)
    procs = launch.Procs()
    workdir = tempfile.mkdtemp(prefix="hfo-oracle-", dir=args.tmp)
    tally = Tally()
    t0 = time.time()
    sizes = batch_sizes(args.episodes, args.batch)
    try:
        prev = None
        for i, n in enumerate(sizes):
            attempt = 0
            while True:
                b = launch.Batch(i, n, args.seed * 1000 + i + 100000 * attempt, workdir, attempt)
                try:
                    launch.start_batch(b, setup, procs)
                    if prev is not None:
                        _parse_and_drop(prev, tally, args.keep_logs)
                        prev = None
                    launch.finish_batch(b)
                    procs.kill_all(grace=0.2)  # nothing should be left; make sure
                    break
                except launch.StuckBatchError as e:
                    # A run that hangs (seen rarely: a client never joins or
                    # the game stops advancing) is discarded as a whole and
                    # replayed with another port and seed.
                    procs.kill_all()
                    launch.report_stuck(b, e)
                    if not args.keep_logs:
                        shutil.rmtree(b.dir, ignore_errors=True)
                    tally.checks["batches_replayed"] += 1
                    attempt += 1
                    if attempt >= MAX_ATTEMPTS:
                        raise
            prev = b
            print(
                "[hfo_oracle] %s: %d/%d episodes played, %.0f s"
                % (args.policy, sum(sizes[: i + 1]), args.episodes, time.time() - t0),
                file=sys.stderr,
                flush=True,
            )
        _parse_and_drop(prev, tally, args.keep_logs)
        res = tally.result(args.policy, args.seed)
        if args.team:
            res["team"] = args.team
            res["team_factory"] = args.team_factory
        res["wall_seconds"] = round(time.time() - t0, 1)
        write_json(args.out, res)
        print(
            "[hfo_oracle] %s: goal %.2f%%, mean frames %.1f, wrote %s (%.0f s)"
            % (args.policy, res["goal_pct"], res["mean_frames"], args.out, time.time() - t0),
            file=sys.stderr,
            flush=True,
        )
        return 0
    finally:
        procs.kill_all()
        if not args.keep_logs:
            shutil.rmtree(workdir, ignore_errors=True)


def _parse_and_drop(batch: launch.Batch, tally: Tally, keep_logs: bool) -> None:
    tally.add_batch(batch.logdir, batch.hfo_out, batch.agent_files, batch.trials)
    if not keep_logs:
        shutil.rmtree(batch.dir, ignore_errors=True)


def main(argv: Sequence[str]) -> int:
    """``agent ...`` runs one agent process, ``relay ...`` one player of
    the backend, ``backend ...`` the real HFO as env-server's simulator,
    anything else the harness."""
    if argv and argv[0] == "agent":
        from hfo_oracle import agent

        return agent.main(argv[1:])
    if argv and argv[0] == "relay":
        from hfo_oracle import relay

        return relay.main(argv[1:])
    if argv and argv[0] == "backend":
        from hfo_oracle import backend

        return backend.main(argv[1:])
    return harness_main(argv)


def entry() -> None:
    """The scripts' entry point: runs :func:`main` on ``sys.argv`` and exits
    with its status (130 when interrupted)."""
    try:
        sys.exit(main(sys.argv[1:]))
    except KeyboardInterrupt:
        print("[hfo_oracle] interrupted; all started processes were stopped", file=sys.stderr)
        sys.exit(130)
