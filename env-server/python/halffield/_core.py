"""What every environment of the package shares: settings, spaces, seeds,
actions and statuses, and pictures."""

from __future__ import annotations

import operator
import secrets
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from gymnasium import spaces

from halffield import _halffield

#: Index of MOVE in every agent's action space.
MOVE = 0
#: Index of SHOOT.
SHOOT = 1
#: Index of DRIBBLE.
DRIBBLE = 2
#: Index of PASS to the first teammate; PASS to teammate ``j`` is ``PASS + j``.
PASS = 3

#: HFO's statuses by number (``hfo.IN_GAME`` = 0 ... ``hfo.OUT_OF_TIME`` = 4).
STATUS_NAMES: tuple[str, ...] = tuple(_halffield.STATUS_NAMES)

#: Render modes of every environment.
RENDER_MODES = ("rgb_array", "svg")

#: Frames per second of the simulated game (one frame is 100 ms).
RENDER_FPS = 10


def make_settings(
    offense: int,
    observation: str,
    masked_action: str,
    frames_per_trial: int,
    untouched_time: int,
    pass_to_named_receiver: bool,
) -> _halffield.TaskSettings:
    """Checks the settings of an environment (``ValueError`` names the bad one)."""
    for name, value in (
        ("offense", offense),
        ("frames_per_trial", frames_per_trial),
        ("untouched_time", untouched_time),
    ):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
            raise ValueError(f"{name} must be a non-negative integer, got {value!r}")
    return _halffield.TaskSettings(
        offense=int(offense),
        observation=observation,
        masked_action=masked_action,
        frames_per_trial=int(frames_per_trial),
        untouched_time=int(untouched_time),
        pass_to_named_receiver=bool(pass_to_named_receiver),
    )


def check_render_mode(render_mode: str | None) -> str | None:
    """``render_mode`` if it is one of :data:`RENDER_MODES` or ``None``."""
    if render_mode is not None and render_mode not in RENDER_MODES:
        choices = ", ".join(RENDER_MODES)
        raise ValueError(
            f"unknown render_mode {render_mode!r} (expected None or one of: {choices})"
        )
    return render_mode


def observation_box(settings: _halffield.TaskSettings) -> spaces.Box:
    """One agent's observation space: every feature in [-1, 1] but the raw
    uniform numbers, in [1, 11]."""
    low, high = settings.observation_bounds()
    return spaces.Box(low=low, high=high, dtype=np.float32)


def state_box(settings: _halffield.TaskSettings) -> spaces.Box:
    """The global state's space."""
    return spaces.Box(low=-1.0, high=1.0, shape=(settings.state_size,), dtype=np.float32)


def check_seed(seed: Any) -> int:
    """``seed`` as the simulator's seed, an integer in [0, 2**64)."""
    try:
        value = operator.index(seed)
    except TypeError:
        raise TypeError(f"seed must be an integer, got {seed!r}") from None
    if not 0 <= value < 2**64:
        raise ValueError(f"seed must be in [0, 2**64), got {value}")
    return value


def first_seed(seed: int | None, started: bool) -> int | None:
    """The seed a ``reset(seed)`` passes to the simulator: ``seed`` itself;
    without one, a fresh seed from the operating system for the first
    episode and ``None`` (the same random stream) after it."""
    if seed is not None:
        return check_seed(seed)
    return None if started else secrets.randbits(64)


def action_index(agent: str, action: Any) -> int:
    """``action`` of ``agent`` as an integer (range and mask are checked by the simulator)."""
    try:
        return operator.index(action)
    except TypeError:
        raise TypeError(f"the action of {agent} must be an integer, got {action!r}") from None


def ordered_actions(
    actions: Mapping[str, Any], live: Sequence[str], agents: Sequence[str]
) -> list[int]:
    """One action per live agent, in agent order, from ``actions``."""
    if not isinstance(actions, Mapping):
        raise TypeError(
            f"actions must be a dict of agent name to action, got {type(actions).__name__}"
        )
    for name in actions:
        if name not in live:
            if name in agents:
                raise ValueError(f"{name} is not playing: its episode has ended, call reset()")
            raise ValueError(f"unknown agent {name!r} (agents: {', '.join(agents)})")
    missing = [name for name in live if name not in actions]
    if missing:
        raise ValueError(
            f"no action for {', '.join(missing)}: step() needs one action per agent in env.agents"
        )
    return [action_index(name, actions[name]) for name in live]


def render(simulator: Any, render_mode: str | None) -> np.ndarray | str | None:
    """A picture of ``simulator`` in ``render_mode``: an RGB array, SVG text,
    or ``None`` (with a warning) when the environment has no render mode."""
    if render_mode is None:
        from gymnasium import logger

        logger.warn(
            "render() was called without a render_mode: pass render_mode='rgb_array' or 'svg'"
        )
        return None
    if render_mode == "svg":
        return simulator.render_svg()
    return simulator.render_rgb()
