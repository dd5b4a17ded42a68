"""RoboCup 2D Half Field Offense, simulated: PettingZoo and Gymnasium
environments of HFO's task, attackers choosing HFO's high-level actions
against HFO's goalkeeper.

- :func:`parallel_env` / :class:`HalfFieldOffenseParallelEnv`: every attacker an agent (PettingZoo).
- ``gymnasium.make("halffield/HalfFieldOffense-v0", teammates=...)`` /
  :class:`HalfFieldOffenseEnv`: one learner among baseline or scripted teammates.
- :class:`BatchEnv`: many environments stepped in one call.
- :class:`BaselinePolicy`: the simulator's baseline policies.
"""

from __future__ import annotations

import gymnasium

from halffield._core import DRIBBLE, MOVE, PASS, SHOOT, STATUS_NAMES
from halffield.batch import BatchEnv
from halffield.gym_env import HalfFieldOffenseEnv
from halffield.parallel import HalfFieldOffenseParallelEnv, parallel_env
from halffield.policy import BaselinePolicy

__all__ = [
    "DRIBBLE",
    "GYM_ID",
    "MOVE",
    "PASS",
    "SHOOT",
    "STATUS_NAMES",
    "BaselinePolicy",
    "BatchEnv",
    "HalfFieldOffenseEnv",
    "HalfFieldOffenseParallelEnv",
    "parallel_env",
]

#: The Gymnasium id of :class:`HalfFieldOffenseEnv`.
GYM_ID = "halffield/HalfFieldOffense-v0"

if GYM_ID not in gymnasium.registry:
    gymnasium.register(id=GYM_ID, entry_point="halffield.gym_env:HalfFieldOffenseEnv")
