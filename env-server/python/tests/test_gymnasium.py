"""The Gymnasium environment: Gymnasium's checker, its registration and
its teammates."""

from __future__ import annotations

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import halffield


@pytest.mark.parametrize("observation", ["hfo", "authors", "paper"])
@pytest.mark.parametrize("render_mode", [None, "rgb_array", "svg"])
def test_check_env(observation: str, render_mode: str) -> None:
    env = gymnasium.make(halffield.GYM_ID, observation=observation, render_mode=render_mode)
    check_env(env.unwrapped, skip_render_check=render_mode is None)


def test_registered_with_gymnasium_make() -> None:
    env = gymnasium.make("halffield/HalfFieldOffense-v0", teammates="dribble", offense=2)
    observation, info = env.reset(seed=1)
    assert observation.shape == (10 + 6 + 3 + 2,)
    assert env.action_space.n == 4
    assert info["status"] == "IN_GAME" and info["frame"] == 0
    check_env(env.unwrapped)


def _episode_outcomes(env: gymnasium.Env, seed: int, episodes: int) -> list[tuple[str, int]]:
    outcomes = []
    _, info = env.reset(seed=seed)
    for episode in range(episodes):
        if episode:
            _, info = env.reset()
        done = False
        while not done:
            action = halffield.SHOOT if info["action_mask"][halffield.SHOOT] else halffield.MOVE
            _, reward, terminated, truncated, info = env.step(action)
            done = terminated or truncated
        outcomes.append((info["status"], info["frame"]))
    return outcomes


def test_named_teammates_are_seeded_by_the_reset() -> None:
    first = _episode_outcomes(halffield.HalfFieldOffenseEnv(teammates="random"), 4, 20)
    again = _episode_outcomes(halffield.HalfFieldOffenseEnv(teammates="random"), 4, 20)
    other = _episode_outcomes(halffield.HalfFieldOffenseEnv(teammates="random"), 5, 20)
    assert first == again
    assert first != other


def test_callable_teammates_see_their_own_observation_and_mask() -> None:
    calls = []

    def teammate(observation: np.ndarray, mask: np.ndarray) -> int:
        calls.append((observation.shape, mask.tolist()))
        return halffield.DRIBBLE if mask[halffield.DRIBBLE] else halffield.MOVE

    env = halffield.HalfFieldOffenseEnv(teammates=teammate, observation="paper")
    outcomes = _episode_outcomes(env, 3, 5)
    assert len(outcomes) == 5
    assert calls and all(shape == (6,) and len(mask) == 5 for shape, mask in calls)
    assert any(mask[halffield.DRIBBLE] for _, mask in calls)


def test_a_teammate_function_returning_a_bad_action_is_named() -> None:
    env = halffield.HalfFieldOffenseEnv(teammates=lambda obs, mask: 9)
    env.reset(seed=1)
    with pytest.raises(ValueError, match=r"action 9 of offense_1 is out of range"):
        env.step(halffield.MOVE)
    bad = halffield.HalfFieldOffenseEnv(teammates=lambda obs, mask: "shoot")
    bad.reset(seed=1)
    with pytest.raises(TypeError, match="the action of offense_1 must be an integer"):
        bad.step(halffield.MOVE)


def test_the_learner_is_offense_0_of_the_parallel_env() -> None:
    """With teammates that always MOVE, the single environment plays as the
    parallel one given the same actions."""
    single = halffield.HalfFieldOffenseEnv(teammates=lambda obs, mask: halffield.MOVE)
    parallel = halffield.parallel_env()
    obs, info = single.reset(seed=9)
    observations, infos = parallel.reset(seed=9)
    rng = np.random.default_rng(9)
    for _ in range(300):
        np.testing.assert_array_equal(obs, observations["offense_0"])
        action = int(rng.choice(np.flatnonzero(info["action_mask"])))
        obs, reward, terminated, truncated, info = single.step(action)
        actions = {a: halffield.MOVE for a in parallel.agents}
        actions["offense_0"] = action
        observations, rewards, terminations, truncations, infos = parallel.step(actions)
        assert (reward, terminated, truncated) == (
            rewards["offense_0"],
            terminations["offense_0"],
            truncations["offense_0"],
        )
        assert info["status"] == infos["offense_0"]["status"]
        if terminated or truncated:
            obs, info = single.reset()
            observations, infos = parallel.reset()
