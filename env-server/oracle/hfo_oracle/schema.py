"""The vocabulary of the per-decision statistics files (the schema shared
with ``env-server rollout --json``) and their atomic write."""

from __future__ import annotations

import json
import os
from typing import Any

# The fixed policies of ``--policy`` (README.md, "What it measures").
POLICIES = ("random", "shoot", "dribble", "pass", "uniform")

# How an episode ends, as the statistics name it.
OUTCOMES = ("goal", "captured", "out_of_bounds", "out_of_time")

# HFO's status names (``hfo.py``, the .hfo log, the trainer, the referee)
# to the outcomes above.
STATUS_OUTCOMES = {
    "GOAL": "goal",
    "CAPTURED_BY_DEFENSE": "captured",
    "OUT_OF_BOUNDS": "out_of_bounds",
    "OUT_OF_TIME": "out_of_time",
}

# What follows a PASS or a DRIBBLE kick: the next kick by a teammate or by
# the same player, or the episode's end.
NEXT_KEYS = ("teammate", "same", "captured", "out_of_bounds", "goal", "out_of_time")

# Shot release distance bins in metres, [from, to); None is open-ended.
SHOT_BINS: tuple[tuple[float, float | None], ...] = (
    (0, 10),
    (10, 15),
    (15, 20),
    (20, 25),
    (25, 30),
    (30, None),
)

# The paper's actions by their index in our simulator
# (``halffield.PAPER_ACTIONS``), as the statistics name them, and the
# one-letter code of each in the agents' choice files.
ACTIONS = ("move", "shoot", "dribble", "pass_near", "pass_far")
ACTION_CODES = "MSDNF"
ACTION_NAMES = dict(zip(ACTION_CODES, ACTIONS))

# The centre of the goal the offense attacks (m).
GOAL_X, GOAL_Y = 52.5, 0.0


def shot_bin(distance: float) -> int:
    """The index in :data:`SHOT_BINS` of a shot released ``distance`` m from
    the goal centre."""
    for i, (lo, hi) in enumerate(SHOT_BINS):
        if distance >= lo and (hi is None or distance < hi):
            return i
    return len(SHOT_BINS) - 1


def write_json(path: str, obj: Any) -> None:
    """Writes ``obj`` as indented JSON to ``path`` through a temporary file
    beside it, so that ``path`` is either absent, old or complete."""
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(obj, f, indent=2)
        f.write("\n")
    os.replace(tmp, path)
