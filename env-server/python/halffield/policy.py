"""The simulator's scripted policies, for teams and comparisons."""

from __future__ import annotations

from halffield import _core, _halffield
from halffield.parallel import HalfFieldOffenseParallelEnv


class ScriptedPolicy:
    """A scripted policy with its own random stream: ``"random"`` (the
    paper's random agent), ``"shoot"``, ``"dribble"``, ``"pass"`` or
    ``"uniform"``. An agent that cannot kick MOVEs. Given the same seed, it
    chooses as ``env-server rollout --policy NAME --seed SEED`` does, so a
    :class:`halffield.HalfFieldOffenseParallelEnv` reset with that seed and
    played with it repeats the rollout's episodes."""

    def __init__(self, name: str, seed: int) -> None:
        self._native = _halffield.ScriptedPolicy(name, _core.check_seed(seed))

    @property
    def name(self) -> str:
        """The policy's name."""
        return self._native.name

    def __call__(self, env: HalfFieldOffenseParallelEnv) -> dict[str, int]:
        """Every playing agent's action in ``env`` as it stands."""
        if not env.agents:
            raise RuntimeError("the episode has ended: call env.reset() first")
        actions = env.simulator.scripted_actions(self._native)
        return dict(zip(env.possible_agents, actions))
