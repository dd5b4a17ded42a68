"""The PettingZoo environment: every attacker an agent, all stepped together."""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium import spaces
from pettingzoo import ParallelEnv

from halffield import _core, _halffield


class HalfFieldOffenseParallelEnv(ParallelEnv):
    """HFO's task: ``offense`` attackers (agents ``offense_0``, ...) against
    HFO's goalkeeper.

    Observations are float32 vectors of the chosen set (``"hfo"``: today's
    HFO high-level features; ``"authors"``: the 2016 set of the paper's
    code; ``"paper"``: the paper's 6 features). Actions are integers: MOVE
    (0), SHOOT (1), DRIBBLE (2), PASS to teammate ``j`` (3 + j, teammates
    in the observation's order). ``infos[agent]["action_mask"]`` (int8,
    1 = allowed) allows only MOVE to an agent that cannot kick; what a kick
    action of such an agent does is ``masked_action``: ``"hfo"`` (as in
    HFO: the action runs and issues no body command), ``"move"`` (it MOVEs
    instead) or ``"raise"`` (``ValueError``).

    Every agent gets the team's reward: +1 for a goal, -1 when the keeper
    captures the ball or it goes out of bounds, 0 otherwise. A goal, a
    capture and out of bounds terminate the episode; running out of time
    truncates it. ``infos[agent]`` also holds HFO's ``"status"`` name and
    the ``"frame"`` (agent decisions so far in the episode).
    """

    metadata = {
        "name": "halffield_v0",
        "render_modes": list(_core.RENDER_MODES),
        "render_fps": _core.RENDER_FPS,
        "is_parallelizable": True,
    }

    def __init__(
        self,
        offense: int = 3,
        observation: str = "hfo",
        masked_action: str = "hfo",
        render_mode: str | None = None,
        frames_per_trial: int = 200,
        untouched_time: int = 100,
        pass_to_named_receiver: bool = False,
    ) -> None:
        self.render_mode = _core.check_render_mode(render_mode)
        self.settings = _core.make_settings(
            offense,
            observation,
            masked_action,
            frames_per_trial,
            untouched_time,
            pass_to_named_receiver,
        )
        self.simulator = _halffield.Env(self.settings)
        self.possible_agents: list[str] = list(self.settings.agents)
        self.agents: list[str] = []
        self.observation_spaces = {
            a: _core.observation_box(self.settings) for a in self.possible_agents
        }
        self.action_spaces = {
            a: spaces.Discrete(self.settings.action_count) for a in self.possible_agents
        }
        self.state_space = _core.state_box(self.settings)
        self._started = False

    def observation_space(self, agent: str) -> spaces.Box:
        """The observation space of ``agent`` (the same object every call)."""
        return self.observation_spaces[self._known(agent)]

    def action_space(self, agent: str) -> spaces.Discrete:
        """The action space of ``agent`` (the same object every call)."""
        return self.action_spaces[self._known(agent)]

    def reset(
        self, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, np.ndarray], dict[str, dict[str, Any]]]:
        """Starts an episode: with ``seed``, of a new simulator drawing from
        it; without, the next episode of the same random stream (the first
        one seeded by the operating system). ``options`` is not used."""
        observations, masks = self.simulator.reset(_core.first_seed(seed, self._started))
        self._started = True
        self.agents = list(self.possible_agents)
        return self._split(observations), self._infos(masks, "IN_GAME", 0)

    def step(
        self, actions: dict[str, Any]
    ) -> tuple[
        dict[str, np.ndarray],
        dict[str, float],
        dict[str, bool],
        dict[str, bool],
        dict[str, dict[str, Any]],
    ]:
        """Plays one frame with one action per agent in :attr:`agents`."""
        ordered = _core.ordered_actions(actions, self.agents, self.possible_agents)
        observations, masks, reward, status, frame = self.simulator.step(ordered)
        truncated = status == "OUT_OF_TIME"
        terminated = status != "IN_GAME" and not truncated
        result = (
            self._split(observations),
            {a: reward for a in self.agents},
            {a: terminated for a in self.agents},
            {a: truncated for a in self.agents},
            self._infos(masks, status, frame),
        )
        if status != "IN_GAME":
            self.agents = []
        return result

    def state(self) -> np.ndarray:
        """The global state: the ball's and every player's position and
        velocity, and the players' body directions, each in [-1, 1]."""
        return self.simulator.state()

    def render(self) -> np.ndarray | str | None:
        """The field as it stands: an RGB array (``render_mode="rgb_array"``)
        or an SVG document (``"svg"``)."""
        return _core.render(self.simulator, self.render_mode)

    def close(self) -> None:
        """Nothing to release: the simulator lives in this process."""

    def _known(self, agent: str) -> str:
        if agent not in self.action_spaces:
            raise ValueError(f"unknown agent {agent!r} (agents: {', '.join(self.possible_agents)})")
        return agent

    def _split(self, observations: np.ndarray) -> dict[str, np.ndarray]:
        return dict(zip(self.possible_agents, observations))

    def _infos(self, masks: np.ndarray, status: str, frame: int) -> dict[str, dict[str, Any]]:
        return {
            a: {"status": status, "frame": frame, "action_mask": mask}
            for a, mask in zip(self.possible_agents, masks)
        }


def parallel_env(**kwargs: Any) -> HalfFieldOffenseParallelEnv:
    """A :class:`HalfFieldOffenseParallelEnv` (PettingZoo's constructor convention)."""
    return HalfFieldOffenseParallelEnv(**kwargs)
