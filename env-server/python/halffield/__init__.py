"""RoboCup 2D Half Field Offense, simulated: PettingZoo and Gymnasium
environments of HFO's task, attackers choosing HFO's high-level actions
against HFO's goalkeeper.

- :func:`parallel_env` / :class:`HalfFieldOffenseParallelEnv`: every attacker an agent (PettingZoo).
- ``gymnasium.make("halffield/HalfFieldOffense-v0", teammates=...)`` /
  :class:`HalfFieldOffenseEnv`: one learner among scripted teammates.
- :class:`BatchEnv`: many environments stepped in one call.
- :class:`ScriptedPolicy`: the simulator's scripted policies.
"""

from __future__ import annotations

import gymnasium

from halffield._core import DRIBBLE, MOVE, PASS, SHOOT, STATUS_NAMES
from halffield.batch import BatchEnv
from halffield.gym_env import HalfFieldOffenseEnv
from halffield.parallel import HalfFieldOffenseParallelEnv, parallel_env
from halffield.policy import ScriptedPolicy

__all__ = [
    "DRIBBLE",
    "GYM_ID",
    "MOVE",
    "PASS",
    "SHOOT",
    "STATUS_NAMES",
    "ScriptedPolicy",
    "BatchEnv",
    "HalfFieldOffenseEnv",
    "HalfFieldOffenseParallelEnv",
    "parallel_env",
]

#: The Gymnasium id of :class:`HalfFieldOffenseEnv`.
GYM_ID = "halffield/HalfFieldOffense-v0"

#: The name of :class:`ScriptedPolicy` before 0.3, still importable.
BaselinePolicy = ScriptedPolicy

if GYM_ID not in gymnasium.registry:
    gymnasium.register(id=GYM_ID, entry_point="halffield.gym_env:HalfFieldOffenseEnv")
