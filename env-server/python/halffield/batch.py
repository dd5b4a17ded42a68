"""Many environments stepped in one call, for throughput."""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium import spaces

from halffield import _core, _halffield


class BatchEnv:
    """``num_envs`` environments of the same settings, stepped together in
    one call that releases the GIL and spreads them over ``threads``
    threads of their own, or by default over rayon's global pool (one
    thread per core; ``RAYON_NUM_THREADS`` sets how many).

    It follows Gymnasium's vector conventions for a team: numpy arrays in
    and out, with an agents axis after the environments axis, and
    same-step autoreset (as HFO itself does): when an environment's episode
    ends, the observation returned is the first of its next episode, and
    ``infos["final_obs"]`` holds the episode's last one. Environment ``i``
    of ``reset(seed)`` plays exactly as a
    :class:`halffield.HalfFieldOffenseParallelEnv` reset with ``seed + i``.

    ``step`` returns observations (envs x agents x features, float32),
    the team's rewards (envs, float64), terminations and truncations
    (envs, bool) and ``infos``: ``"status"`` (HFO's status numbers, int8,
    names in :data:`halffield.STATUS_NAMES`), ``"frame"`` (frames of the
    step's episode), ``"action_mask"`` (envs x agents x actions, int8) and
    ``"final_obs"`` (zeros where no episode ended).
    """

    metadata = {"autoreset_mode": "SameStep"}

    def __init__(
        self,
        num_envs: int,
        offense: int = 3,
        observation: str = "hfo",
        masked_action: str = "hfo",
        frames_per_trial: int = 200,
        untouched_time: int = 100,
        pass_to_named_receiver: bool = False,
        threads: int | None = None,
    ) -> None:
        self.settings = _core.make_settings(
            offense,
            observation,
            masked_action,
            frames_per_trial,
            untouched_time,
            pass_to_named_receiver,
        )
        if (
            isinstance(num_envs, bool)
            or not isinstance(num_envs, (int, np.integer))
            or not 1 <= num_envs <= _halffield.MAX_BATCH_ENVS
        ):
            raise ValueError(
                f"num_envs must be an integer from 1 to {_halffield.MAX_BATCH_ENVS}, "
                f"got {num_envs!r}"
            )
        self.num_envs = int(num_envs)
        if threads is not None and (
            isinstance(threads, bool) or not isinstance(threads, (int, np.integer)) or threads < 1
        ):
            raise ValueError(f"threads must be a positive integer or None, got {threads!r}")
        self.simulator = _halffield.BatchEnv(
            self.settings, self.num_envs, None if threads is None else int(threads)
        )
        self.agents: list[str] = list(self.settings.agents)
        self.single_observation_space = _core.observation_box(self.settings)
        self.single_action_space = spaces.Discrete(self.settings.action_count)
        shape = (self.num_envs, self.settings.offense)
        box = self.single_observation_space
        self.observation_space = spaces.Box(
            low=np.broadcast_to(box.low, shape + box.shape),
            high=np.broadcast_to(box.high, shape + box.shape),
            dtype=np.float32,
        )
        self.action_space = spaces.MultiDiscrete(np.full(shape, self.settings.action_count))

    def reset(
        self, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """New simulators, environment ``i`` drawing from ``seed + i``
        (``seed`` from the operating system when ``None``). ``options`` is
        not used."""
        observations, masks = self.simulator.reset(_core.first_seed(seed, False))
        return observations, {"action_mask": masks}

    def step(
        self, actions: Any
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict[str, np.ndarray]]:
        """Plays one frame of every environment; ``actions`` holds integer
        action indices of shape (envs, agents). Every action is checked
        before any environment steps."""
        actions = np.asarray(actions)
        if actions.dtype.kind not in "iu":
            raise TypeError(f"actions must be integers, got an array of dtype {actions.dtype}")
        observations, masks, rewards, status, frames, final = self.simulator.step(
            actions.astype(np.int64, copy=False)
        )
        truncations = status == _core.STATUS_NAMES.index("OUT_OF_TIME")
        terminations = (status != 0) & ~truncations
        infos = {"status": status, "frame": frames, "action_mask": masks, "final_obs": final}
        return observations, rewards, terminations, truncations, infos

    def close(self) -> None:
        """Nothing to release: the simulators live in this process."""
