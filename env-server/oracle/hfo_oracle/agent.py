"""The HFO agent process: one offense player connected to rcssserver through
HFO's Python interface (``hfo``, found through ``PYTHONPATH=<hfo-dir>``),
playing a fixed high-level policy or a learned agent, and writing its choice
file (:mod:`hfo_oracle.logs`).

It runs under ``--python`` (HFO's interpreter), started by the launcher as
``python -m hfo_oracle agent ...``. An agent that cannot kick always MOVEs;
with the ball it chooses as its policy says.
"""

from __future__ import annotations

import argparse
import importlib
import math
import random
from collections.abc import Callable, Sequence
from typing import Any

from hfo_oracle import logs
from hfo_oracle.schema import ACTION_CODES, POLICIES

# The codes a fixed policy draws from, uniformly, with the ball
# (:data:`hfo_oracle.schema.ACTION_CODES`): the paper's random agent draws
# DRIBBLE, SHOOT and the two PASSes with weights 2, 2, 1, 1.
POLICY_CODES = {"random": "DDSSFN", "shoot": "S", "dribble": "D", "pass": "N", "uniform": "SDNF"}

HALF_LENGTH, HALF_WIDTH = 52.5, 34.0
# HFO normalises positions over the HFO area plus 10 % on each side.
X_RANGE = (-0.1 * HALF_LENGTH, HALF_LENGTH + 0.1 * HALF_LENGTH)
Y_RANGE = (-HALF_WIDTH - 0.1 * HALF_WIDTH, HALF_WIDTH + 0.1 * HALF_WIDTH)

# Indices in HFO's high-level feature set (src/highlevel_feature_extractor.cpp)
# with T teammates: 0 x, 1 y, 5 able to kick (+1/-1), 6 distance to the goal
# centre, 7 angle to it, 8 goal opening, 10 .. 10+T-1 each teammate's goal
# opening, then from 10 + 3T the teammates' x, y and uniform number.
ABLE_KICK = 5


def unnormalise(value: float, lo: float, hi: float) -> float:
    """Undoes HFO's ``norm``: a feature in [-1, 1] back to [lo, hi]."""
    return lo + (value + 1.0) * 0.5 * (hi - lo)


def teammates(state: Sequence[float], num_teammates: int) -> list[tuple[float, int]]:
    """``(distance in m, uniform number)`` of every teammate the state
    shows, nearest first (a teammate HFO marks invalid, -2, is left out)."""
    me_x = unnormalise(state[0], *X_RANGE)
    me_y = unnormalise(state[1], *Y_RANGE)
    base = 10 + 3 * num_teammates
    out = []
    for i in range(num_teammates):
        x, y, unum = state[base + 3 * i : base + 3 * i + 3]
        if unum <= 0 or x < -1.5 or y < -1.5:
            continue
        tx, ty = unnormalise(x, *X_RANGE), unnormalise(y, *Y_RANGE)
        out.append((math.hypot(tx - me_x, ty - me_y), int(round(unum))))
    out.sort()
    return out


def pass_target(state: Sequence[float], num_teammates: int, code: str) -> int:
    """The uniform number a PASS of ``code`` names: the nearest teammate for
    ``N``, the farthest for ``F``; 0 when no teammate is shown."""
    near_first = teammates(state, num_teammates)
    if not near_first:
        return 0
    return near_first[0][1] if code == "N" else near_first[-1][1]


def paper_state(state: Sequence[float]) -> list[float]:
    """The paper's 6 features as our simulator computes them (its
    ``features::paper_state``), from today's HFO high-level set: able to
    kick (5); the distance to the goal centre (6: norm(r, 0, maxR) with
    maxR = |(52.5, 68)|), renormalised as the authors' set does (0 to
    62.548, clamped); the angle to it (7) and the goal opening (8), as they
    are; the nearest then the farthest teammate's goal opening (10, 11: HFO
    lists teammates nearest first)."""
    max_r = math.hypot(HALF_LENGTH, 2 * HALF_WIDTH)
    distance = (state[6] + 1.0) * 0.5 * max_r
    authors_max = math.hypot(HALF_LENGTH, HALF_WIDTH)
    return [
        state[ABLE_KICK],
        2.0 * min(distance, authors_max) / authors_max - 1.0,
        state[7],
        state[8],
        state[10],
        state[11],
    ]


def split_factory(spec: str) -> tuple[str, str]:
    """``MODULE:CALLABLE`` as its module and its callable's (dotted) name;
    :class:`ValueError` when ``spec`` is not that."""
    module, colon, name = spec.partition(":")
    names = module.split(".") + name.split(".")
    if not colon or not all(n.isidentifier() for n in names):
        raise ValueError("--team-factory %r is not MODULE:CALLABLE" % spec)
    return module, name


def load_factory(spec: str) -> Callable[[str], Any]:
    """The callable ``spec`` (``MODULE:CALLABLE``) names, imported in this
    interpreter: called with a snapshot file, it returns an agent whose
    ``act(state, can_kick)`` is the index of its action
    (:data:`hfo_oracle.schema.ACTIONS`) in the paper's 6-feature state."""
    module, name = split_factory(spec)
    found: Any = importlib.import_module(module)
    for attribute in name.split("."):
        found = getattr(found, attribute)
    return found


def parse_args(argv: Sequence[str]) -> argparse.Namespace:
    """The agent's command line (given by the launcher)."""
    p = argparse.ArgumentParser(prog="hfo_oracle.py agent")
    p.add_argument("--port", type=int, required=True)
    p.add_argument("--policy", choices=POLICIES + ("team",), required=True)
    p.add_argument("--snapshot", help="with --policy team: this agent's snapshot file")
    p.add_argument(
        "--team-factory",
        metavar="MODULE:CALLABLE",
        help="with --policy team: what makes the agent of its snapshot file",
    )
    p.add_argument("--seed", type=int, required=True)
    p.add_argument("--config-dir", required=True)
    p.add_argument("--out", required=True)
    a = p.parse_args(argv)
    if a.policy == "team" and (a.snapshot is None or a.team_factory is None):
        p.error("--policy team needs --snapshot and --team-factory")
    return a


def main(argv: Sequence[str]) -> int:
    """Plays until the server goes down, writing the choice file."""
    a = parse_args(argv)
    import hfo  # HFO's own interface, from PYTHONPATH=<hfo-dir>

    learner = None
    if a.policy == "team":
        learner = load_factory(a.team_factory)(a.snapshot)
    codes = POLICY_CODES.get(a.policy, "")
    rng = random.Random(a.seed)
    env = hfo.HFOEnvironment()
    env.connectToServer(
        hfo.HIGH_LEVEL_FEATURE_SET, a.config_dir, a.port, "localhost", "base_left", False
    )
    num_teammates = env.getNumTeammates()
    kick_actions = {"M": hfo.MOVE, "S": hfo.SHOOT, "D": hfo.DRIBBLE}
    with open(a.out, "w", buffering=1 << 16) as out:
        out.write(logs.unum_line(env.getUnum()))
        episode = 0
        status = hfo.IN_GAME
        while status != hfo.SERVER_DOWN:
            step = 0
            status = hfo.IN_GAME
            while status == hfo.IN_GAME:
                s = env.getState()
                if s[ABLE_KICK] > 0.5:
                    if learner is not None:
                        code = ACTION_CODES[learner.act(paper_state(s), True)]
                    else:
                        code = codes[rng.randrange(len(codes))]
                    target = 0
                    if code in kick_actions:
                        env.act(kick_actions[code])
                    else:
                        target = pass_target(s, num_teammates, code)
                        env.act(hfo.PASS, float(target))
                    out.write(logs.decision_line(episode, step, code, target))
                else:
                    env.act(hfo.MOVE)
                status = env.step()
                step += 1
            out.write(logs.episode_line(episode, step, env.statusToString(status)))
            episode += 1
    try:
        env.act(hfo.QUIT)
    except Exception:
        pass
    return 0
