"""A short learning run: the example's SARSA team, over the Python API,
scores more often than the paper's random policy within 1,500 episodes."""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))

import sarsa  # noqa: E402


def test_sarsa_beats_the_random_policy() -> None:
    random_rate = sarsa.random_goal_rate(1000, seed=1)
    rates = sarsa.train(1500, seed=1, block=250)
    assert 0.05 < random_rate < 0.2, random_rate
    # Everything is seeded: the curve is the same on every run.
    assert rates[-1] > random_rate + 0.2, (rates, random_rate)
    assert rates[-1] > rates[0], rates
