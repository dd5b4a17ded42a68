"""Determinism: the same seed gives the same trajectory in another
process, and the same seed and scripted policy give the same episodes as
`env-server rollout`."""

from __future__ import annotations

import hashlib
import json
import subprocess
import sys
from collections import Counter

import numpy as np
from conftest import env_server_binary, play_random

import halffield

#: A program printing the digest of a seeded run.
DIGEST = """
import sys
sys.path.insert(0, {tests!r})
from test_determinism import digest
print(digest({seed}, {episodes}))
"""


def digest(seed: int, episodes: int) -> str:
    """SHA-256 of every observation, reward, flag and info of a seeded run
    (observations in the HFO set, actions drawn from the masks)."""
    h = hashlib.sha256()
    for step in play_random(halffield.parallel_env(), seed, episodes):
        h.update(repr(_plain(step)).encode())
    return h.hexdigest()


def _plain(value: object) -> object:
    if isinstance(value, np.ndarray):
        return value.tobytes().hex()
    if isinstance(value, dict):
        return sorted((k, _plain(v)) for k, v in value.items())
    if isinstance(value, tuple):
        return tuple(_plain(v) for v in value)
    return value


def test_same_seed_same_trajectory_in_two_processes() -> None:
    from pathlib import Path

    tests = str(Path(__file__).parent)
    program = DIGEST.format(tests=tests, seed=17, episodes=15)
    runs = [
        subprocess.run(
            [sys.executable, "-c", program], check=True, capture_output=True, text=True
        ).stdout.strip()
        for _ in range(2)
    ]
    assert runs[0] == runs[1] == digest(17, 15)
    assert digest(18, 15) != runs[0]


def _python_rollout(policy: str, seed: int, episodes: int) -> tuple[Counter, int]:
    env = halffield.parallel_env()
    scripted = halffield.ScriptedPolicy(policy, seed)
    outcomes: Counter = Counter()
    frames = 0
    env.reset(seed=seed)
    for episode in range(episodes):
        if episode:
            env.reset()
        while env.agents:
            _, _, _, _, infos = env.step(scripted(env))
        outcomes[infos["offense_0"]["status"]] += 1
        frames += infos["offense_0"]["frame"]
    return outcomes, frames


def test_scripted_episodes_match_env_server_rollout() -> None:
    binary = env_server_binary()
    names = {
        "goal": "GOAL",
        "captured": "CAPTURED_BY_DEFENSE",
        "out_of_bounds": "OUT_OF_BOUNDS",
        "out_of_time": "OUT_OF_TIME",
    }
    for policy, seed, episodes in [("random", 11, 300), ("uniform", 3, 100), ("pass", 5, 50)]:
        command = [
            str(binary),
            "rollout",
            "--policy",
            policy,
            "--episodes",
            str(episodes),
            "--seed",
            str(seed),
            "--json",
        ]
        rollout = json.loads(
            subprocess.run(command, check=True, capture_output=True, text=True).stdout
        )
        expected = Counter({names[k]: v for k, v in rollout["outcomes"].items() if v})
        outcomes, frames = _python_rollout(policy, seed, episodes)
        assert outcomes == expected, policy
        assert frames == rollout["frames"], policy
