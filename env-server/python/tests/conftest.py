"""Shared helpers of the tests: the env-server binary and episode loops."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest

import halffield

#: The repository's root.
ROOT = Path(__file__).resolve().parents[3]


def env_server_binary() -> Path:
    """The `env-server` binary to compare with: ``$HALFFIELD_ENV_SERVER``,
    else the newest of the target directory's release and debug builds.
    Missing, the test is skipped on a developer's machine and fails in CI
    (``CI`` set), where .ci/run has built it."""
    explicit = os.environ.get("HALFFIELD_ENV_SERVER")
    if explicit:
        path = Path(explicit)
        if not path.is_file():
            pytest.fail(f"HALFFIELD_ENV_SERVER={explicit} is not a file")
        return path
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    built = [
        p
        for p in (target / "release" / "env-server", target / "debug" / "env-server")
        if p.is_file()
    ]
    if built:
        return max(built, key=lambda p: p.stat().st_mtime)
    message = (
        f"no env-server binary under {target}: build it with `cargo build -p env-server-process` "
        "or set HALFFIELD_ENV_SERVER"
    )
    if os.environ.get("CI"):
        pytest.fail(message + " (CI must run this comparison)")
    pytest.skip(message)


def play_random(env: halffield.HalfFieldOffenseParallelEnv, seed: int, episodes: int) -> list[Any]:
    """Every step's results of ``episodes`` episodes of ``env`` from
    ``reset(seed=seed)``, with actions drawn from the masks by a generator
    seeded alike."""
    import numpy as np

    rng = np.random.default_rng(seed)
    history: list[Any] = []
    observations, infos = env.reset(seed=seed)
    for episode in range(episodes):
        if episode:
            observations, infos = env.reset()
        history.append(observations)
        while env.agents:
            actions = {}
            for agent in env.agents:
                allowed = np.flatnonzero(infos[agent]["action_mask"])
                actions[agent] = int(rng.choice(allowed))
            step = env.step(actions)
            observations, infos = step[0], step[4]
            history.append(step)
    return history
