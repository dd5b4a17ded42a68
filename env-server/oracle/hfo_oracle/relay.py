"""One offense player of the real HFO whose choices come from elsewhere: the
player process of the backend (:mod:`hfo_oracle.backend`), started by it as
``python -m hfo_oracle relay ...`` under HFO's interpreter.

Every cycle it writes one line to its standard output, a JSON object with
the status of the step that led to this cycle (``in-game``, ``goal``,
``captured``, ``out-of-bounds``, ``out-of-time``; ``server-down`` ends
it), whether it can kick, the paper's 6-feature state and its position
(m), and reads one line from its standard input: the one-letter code of
its action (:data:`hfo_oracle.schema.ACTION_CODES`; ``Q`` or the end of
the input ends it).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Sequence
from typing import IO, Any

from hfo_oracle.agent import ABLE_KICK, X_RANGE, Y_RANGE, paper_state, pass_target, unnormalise

# HFO's statuses (hfo.py) by the names the backend's lines use.
STATUS_NAMES = ("in-game", "goal", "captured", "out-of-bounds", "out-of-time", "server-down")


def parse_args(argv: Sequence[str]) -> argparse.Namespace:
    """The relay's command line (given by the backend)."""
    p = argparse.ArgumentParser(prog="hfo_oracle.py relay")
    p.add_argument("--port", type=int, required=True)
    p.add_argument("--config-dir", required=True)
    return p.parse_args(argv)


def frame_line(status: str, state: Sequence[float] | None) -> str:
    """The line of one cycle: ``status`` and, but for ``server-down``, what
    ``state`` (HFO's high-level features) shows."""
    line: dict[str, Any] = {"status": status}
    if state is not None:
        # HFO's features are numpy's float32: plain numbers for JSON.
        line["kick"] = bool(state[ABLE_KICK] > 0.5)
        line["state"] = [float(x) for x in paper_state(state)]
        line["pos"] = [
            float(unnormalise(state[0], *X_RANGE)),
            float(unnormalise(state[1], *Y_RANGE)),
        ]
    return json.dumps(line, separators=(",", ":")) + "\n"


def play(env: Any, hfo: Any, inp: IO[str], out: IO[str]) -> int:
    """Relays ``env``'s cycles to ``out`` and the actions read from ``inp``
    to ``env`` until the server goes down or the input ends."""
    statuses = {
        getattr(hfo, name): text
        for name, text in zip(
            (
                "IN_GAME",
                "GOAL",
                "CAPTURED_BY_DEFENSE",
                "OUT_OF_BOUNDS",
                "OUT_OF_TIME",
                "SERVER_DOWN",
            ),
            STATUS_NAMES,
        )
    }
    kicks = {"M": hfo.MOVE, "S": hfo.SHOOT, "D": hfo.DRIBBLE}
    num_teammates = env.getNumTeammates()
    status = "in-game"
    while True:
        down = status == "server-down"
        state = None if down else env.getState()
        out.write(frame_line(status, state))
        out.flush()
        if down:
            return 0
        code = inp.readline().strip()
        if code in ("", "Q"):
            return 0
        if code in kicks:
            env.act(kicks[code])
        elif code in ("N", "F"):
            env.act(hfo.PASS, float(pass_target(state, num_teammates, code)))
        else:
            raise ValueError("relay: unknown action code %r, expected one of MSDNF or Q" % code)
        status = statuses.get(env.step(), "server-down")


def main(argv: Sequence[str]) -> int:
    """Connects to the server and relays until it goes down."""
    a = parse_args(argv)
    # HFO's library prints to the standard output: the lines go to a copy
    # of it, and what is printed to the standard error.
    lines = os.fdopen(os.dup(1), "w")
    os.dup2(2, 1)
    import hfo  # HFO's own interface, from PYTHONPATH=<hfo-dir>

    env = hfo.HFOEnvironment()
    env.connectToServer(
        hfo.HIGH_LEVEL_FEATURE_SET, a.config_dir, a.port, "localhost", "base_left", False
    )
    try:
        return play(env, hfo, sys.stdin, lines)
    finally:
        try:
            env.act(hfo.QUIT)
        except Exception:
            pass
