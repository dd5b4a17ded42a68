"""The Gymnasium environment: one learning attacker among teammates that
follow a scripted policy or a Python function."""

from __future__ import annotations

from typing import Any, Callable

import gymnasium
import numpy as np
from gymnasium import spaces

from halffield import _core, _halffield

#: A teammate's policy: its observation and action mask to its action.
TeammatePolicy = Callable[[np.ndarray, np.ndarray], int]


class HalfFieldOffenseEnv(gymnasium.Env):
    """HFO's task for one learner, ``offense_0``, whose ``offense - 1``
    teammates follow ``teammates``: a scripted policy's name (``"random"``,
    the paper's random agent; ``"shoot"``, ``"dribble"``, ``"pass"``,
    ``"uniform"``), drawing from the reset's seed, or a function of a
    teammate's observation and action mask returning its action.

    Observations, actions, action masks (``info["action_mask"]``), rewards,
    terminations, truncations and ``info`` are those of
    :class:`halffield.HalfFieldOffenseParallelEnv` for ``offense_0``.
    """

    metadata = {"render_modes": list(_core.RENDER_MODES), "render_fps": _core.RENDER_FPS}

    def __init__(
        self,
        teammates: str | TeammatePolicy = "random",
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
        if isinstance(teammates, str):
            _halffield.ScriptedPolicy(teammates, 0)  # checks the name now
        elif not callable(teammates):
            raise TypeError(
                f"teammates must be a scripted policy's name or a function, got {teammates!r}"
            )
        self.teammates = teammates
        self.simulator = _halffield.Env(self.settings)
        self.observation_space = _core.observation_box(self.settings)
        self.action_space = spaces.Discrete(self.settings.action_count)
        self._agents: list[str] = list(self.settings.agents)
        self._policy: _halffield.ScriptedPolicy | None = None
        self._last: tuple[np.ndarray, np.ndarray] | None = None
        self._ended: str | None = None

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        """Starts an episode: with ``seed``, of a new simulator and teammate
        policy drawing from it; without, the next episode of the same random
        streams. ``options`` is not used."""
        super().reset(seed=seed)
        sim_seed = _core.first_seed(seed, self._last is not None)
        observations, masks = self.simulator.reset(sim_seed)
        if sim_seed is not None and isinstance(self.teammates, str):
            self._policy = _halffield.ScriptedPolicy(self.teammates, sim_seed)
        self._last, self._ended = (observations, masks), None
        return observations[0], {"status": "IN_GAME", "frame": 0, "action_mask": masks[0]}

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        """Plays one frame: the learner's ``action`` and its teammates'."""
        if self._last is None:
            raise RuntimeError("no episode has started: call reset() first")
        if self._ended is not None:
            raise RuntimeError(f"the episode has ended ({self._ended}): call reset() before step()")
        actions = self._teammate_actions()
        actions[0] = _core.action_index(self._agents[0], action)
        observations, masks, reward, status, frame = self.simulator.step(actions)
        self._last = (observations, masks)
        if status != "IN_GAME":
            self._ended = f"{status} at frame {frame}"
        truncated = status == "OUT_OF_TIME"
        terminated = status != "IN_GAME" and not truncated
        info = {"status": status, "frame": frame, "action_mask": masks[0]}
        return observations[0], reward, terminated, truncated, info

    def render(self) -> np.ndarray | str | None:
        """The field as it stands: an RGB array (``render_mode="rgb_array"``)
        or an SVG document (``"svg"``)."""
        return _core.render(self.simulator, self.render_mode)

    def _teammate_actions(self) -> list[int]:
        """Every agent's action under ``teammates`` (the learner's is replaced)."""
        if self._policy is not None:
            return list(self.simulator.scripted_actions(self._policy))
        observations, masks = self._last
        actions = [_core.MOVE]
        for agent, obs, mask in zip(self._agents[1:], observations[1:], masks[1:]):
            actions.append(_core.action_index(agent, self.teammates(obs, mask)))
        return actions
