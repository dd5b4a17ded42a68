"""The batch: shapes, same-step autoreset, and the same episodes as the
single environment."""

from __future__ import annotations

import threading
import time

import numpy as np

import halffield


def test_shapes_and_dtypes() -> None:
    batch = halffield.BatchEnv(5, offense=2, observation="authors")
    observations, infos = batch.reset(seed=1)
    assert observations.shape == (5, 2, 10 + 6 + 3) and observations.dtype == np.float32
    assert infos["action_mask"].shape == (5, 2, 4) and infos["action_mask"].dtype == np.int8
    assert observations in batch.observation_space
    result = batch.step(np.zeros((5, 2), dtype=np.int64))
    observations, rewards, terminations, truncations, infos = result
    assert rewards.shape == (5,) and rewards.dtype == np.float64
    assert terminations.dtype == truncations.dtype == np.bool_
    assert infos["status"].dtype == np.int8 and infos["frame"].shape == (5,)
    assert infos["final_obs"].shape == observations.shape
    assert batch.action_space.shape == (5, 2)


def test_environment_i_plays_as_a_single_environment_seeded_seed_plus_i() -> None:
    n, seed, steps = 4, 20, 600
    batch = halffield.BatchEnv(n)
    singles = [halffield.parallel_env() for _ in range(n)]
    observations, infos = batch.reset(seed=seed)
    single_views = [env.reset(seed=seed + i) for i, env in enumerate(singles)]
    rng = np.random.default_rng(0)
    ended = 0
    for _ in range(steps):
        for i, (obs, inf) in enumerate(single_views):
            for j, agent in enumerate(singles[i].possible_agents):
                np.testing.assert_array_equal(observations[i, j], obs[agent])
                np.testing.assert_array_equal(infos["action_mask"][i, j], inf[agent]["action_mask"])
        actions = np.array(
            [
                [int(rng.choice(np.flatnonzero(m))) for m in env_masks]
                for env_masks in infos["action_mask"]
            ]
        )
        observations, rewards, terminations, truncations, infos = batch.step(actions)
        for i, env in enumerate(singles):
            obs, rew, term, trunc, inf = env.step(
                dict(zip(env.possible_agents, actions[i].tolist()))
            )
            status = inf["offense_0"]["status"]
            assert halffield.STATUS_NAMES[infos["status"][i]] == status
            assert infos["frame"][i] == inf["offense_0"]["frame"]
            assert rewards[i] == rew["offense_0"]
            assert (terminations[i], truncations[i]) == (term["offense_0"], trunc["offense_0"])
            if status == "IN_GAME":
                assert not infos["final_obs"][i].any()
                single_views[i] = (obs, inf)
            else:
                ended += 1
                for j, agent in enumerate(env.possible_agents):
                    np.testing.assert_array_equal(infos["final_obs"][i, j], obs[agent])
                single_views[i] = env.reset()
    assert ended >= n


def test_a_batch_on_its_own_threads_plays_the_same_episodes() -> None:
    results = []
    for threads in (None, 1, 3):
        batch = halffield.BatchEnv(6, threads=threads)
        observations, _ = batch.reset(seed=4)
        steps = [observations]
        for t in range(150):
            actions = np.full((6, 3), t % 5, dtype=np.int64)
            observations, rewards, _, _, infos = batch.step(actions)
            steps += [observations, rewards, infos["status"], infos["final_obs"]]
        results.append(steps)
    for other in results[1:]:
        for a, b in zip(results[0], other):
            np.testing.assert_array_equal(a, b)


def test_the_batch_releases_the_gil() -> None:
    """Another Python thread keeps running while one step of a large batch
    is in Rust: had the step held the GIL, the thread would stop for the
    whole call (the longest gap between its ticks would be the call)."""
    batch = halffield.BatchEnv(4096)
    batch.reset(seed=1)
    actions = np.zeros((4096, 3), dtype=np.int64)
    ticks: list[float] = []
    stop = threading.Event()

    def count() -> None:
        while not stop.is_set():
            ticks.append(time.perf_counter())

    thread = threading.Thread(target=count)
    thread.start()
    try:
        time.sleep(0.01)
        start = time.perf_counter()
        batch.step(actions)
        end = time.perf_counter()
    finally:
        stop.set()
        thread.join()
    inside = [start] + [t for t in ticks if start < t < end] + [end]
    longest_gap = max(b - a for a, b in zip(inside, inside[1:]))
    assert longest_gap < 0.5 * (end - start), (longest_gap, end - start)
