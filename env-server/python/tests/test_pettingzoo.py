"""The PettingZoo environment: PettingZoo's own API and seed tests, and
what the environment promises beyond them."""

from __future__ import annotations

import numpy as np
import pytest
from pettingzoo.test import parallel_api_test, parallel_seed_test

import halffield

OBSERVATIONS = ["hfo", "authors", "paper"]


@pytest.mark.parametrize("offense", [1, 2, 3, 4])
@pytest.mark.parametrize("observation", OBSERVATIONS)
def test_parallel_api(offense: int, observation: str) -> None:
    parallel_api_test(
        halffield.parallel_env(offense=offense, observation=observation), num_cycles=300
    )


@pytest.mark.parametrize("observation", OBSERVATIONS)
def test_parallel_seed(observation: str) -> None:
    parallel_seed_test(lambda: halffield.parallel_env(observation=observation))


def test_agents_spaces_and_sizes() -> None:
    env = halffield.parallel_env()
    assert env.possible_agents == ["offense_0", "offense_1", "offense_2"]
    assert env.agents == []
    for agent in env.possible_agents:
        assert env.observation_space(agent) is env.observation_space(agent)
        assert env.action_space(agent) is env.action_space(agent)
        assert env.action_space(agent).n == 5
        assert env.observation_space(agent).shape == (10 + 6 * 2 + 3 + 2,)
    assert env.observation_space("offense_0") is not env.observation_space("offense_1")
    assert halffield.parallel_env(observation="authors").observation_space("offense_0").shape == (
        25,
    )
    assert halffield.parallel_env(observation="paper").observation_space("offense_0").shape == (6,)
    assert halffield.parallel_env(offense=1).action_space("offense_0").n == 3


@pytest.mark.parametrize("observation", OBSERVATIONS)
def test_observations_are_float32_in_their_space(observation: str) -> None:
    env = halffield.parallel_env(observation=observation)
    observations, infos = env.reset(seed=3)
    for _ in range(100):
        for agent, obs in observations.items():
            assert obs.dtype == np.float32
            assert obs in env.observation_space(agent)
            assert infos[agent]["action_mask"].dtype == np.int8
        if not env.agents:
            observations, infos = env.reset()
        observations, _, _, _, infos = env.step({a: halffield.MOVE for a in env.agents})


def test_the_kick_flag_agrees_with_the_mask_in_every_set() -> None:
    envs = {name: halffield.parallel_env(observation=name) for name in OBSERVATIONS}
    kick_index = {"hfo": 5, "authors": 5, "paper": 0}
    firsts = {name: env.reset(seed=8) for name, env in envs.items()}
    seen_kick = False
    for step in range(2000):
        flags = []
        for name, env in envs.items():
            observations, infos = firsts[name]
            for agent in env.possible_agents:
                can_kick = bool(infos[agent]["action_mask"][halffield.SHOOT])
                assert (observations[agent][kick_index[name]] == 1.0) == can_kick
                flags.append(can_kick)
                seen_kick |= can_kick
        rng = np.random.default_rng(step)
        actions = {a: int(rng.integers(5)) for a in envs["hfo"].possible_agents}
        for name, env in envs.items():
            if not env.agents:
                firsts[name] = env.reset()
            else:
                result = env.step(actions)
                firsts[name] = (result[0], result[4])
    assert seen_kick


def test_hfo_observation_layout() -> None:
    env = halffield.parallel_env()
    observations, _ = env.reset(seed=5)
    state = env.state()
    for i, agent in enumerate(env.possible_agents):
        obs = observations[agent]
        # Own position (HFO's normalisation) as in the global state.
        assert obs[0] == pytest.approx(state[4 + 5 * i], abs=1e-6)
        assert obs[1] == pytest.approx(state[5 + 5 * i], abs=1e-6)
        # The ball's position, the keeper's block, its unum 1.
        assert obs[3] == pytest.approx(state[0], abs=1e-6)
        assert obs[4] == pytest.approx(state[1], abs=1e-6)
        assert obs[22] == pytest.approx(state[4 + 5 * 3], abs=1e-6)
        assert obs[24] == 1.0
        # Teammates nearest first, by their unums 7, 8, 11 and positions.
        unums = {7: 0, 8: 1, 11: 2}
        mates = [unums[int(obs[18])], unums[int(obs[21])]]
        assert sorted(mates + [i]) == [0, 1, 2]
        me = np.array([state[4 + 5 * i], state[5 + 5 * i]])
        dists = [
            np.linalg.norm((np.array([state[4 + 5 * j], state[5 + 5 * j]]) - me) * [63.0, 74.8])
            for j in mates
        ]
        assert dists[0] <= dists[1]
        # After a reset the last action failed (HFO's NOOPs); stamina is full.
        assert (obs[25], obs[26]) == (-1.0, 1.0)


def test_terminal_step_statuses_rewards_and_agents() -> None:
    env = halffield.parallel_env()
    seen = set()
    _, infos = env.reset(seed=2)
    rng = np.random.default_rng(2)
    for _ in range(300):
        frame = 0
        while env.agents:
            agents = list(env.agents)
            actions = {a: int(rng.choice(np.flatnonzero(infos[a]["action_mask"]))) for a in agents}
            _, rewards, terminations, truncations, infos = env.step(actions)
            frame += 1
            status = infos["offense_0"]["status"]
            assert (
                set(rewards) == set(terminations) == set(truncations) == set(infos) == set(agents)
            )
            assert all(
                info["status"] == status and info["frame"] == frame for info in infos.values()
            )
            expected = {"GOAL": 1.0, "CAPTURED_BY_DEFENSE": -1.0, "OUT_OF_BOUNDS": -1.0}.get(
                status, 0.0
            )
            assert set(rewards.values()) == {expected}
            terminal = status in ("GOAL", "CAPTURED_BY_DEFENSE", "OUT_OF_BOUNDS")
            assert set(terminations.values()) == {terminal}
            assert set(truncations.values()) == {status == "OUT_OF_TIME"}
            assert (status == "IN_GAME") == bool(env.agents)
            seen.add(status)
        _, infos = env.reset()
    assert {"GOAL", "CAPTURED_BY_DEFENSE", "OUT_OF_BOUNDS", "IN_GAME"} <= seen


def test_state_space_and_render() -> None:
    env = halffield.parallel_env(render_mode="rgb_array")
    env.reset(seed=1)
    state = env.state()
    assert state.dtype == np.float32 and state in env.state_space
    image = env.render()
    assert image.dtype == np.uint8 and image.ndim == 3 and image.shape[2] == 3
    assert image.shape[0] > 500 and image.shape[1] > 500
    svg = halffield.parallel_env(render_mode="svg")
    svg.reset(seed=1)
    text = svg.render()
    assert text.startswith("<svg") and "in play at frame 0" in text.lower()
    with pytest.warns(UserWarning, match="render_mode"):
        assert halffield.parallel_env().render() is None
