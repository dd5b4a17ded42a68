"""Shared helpers of the tests: the workspace's binaries."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

#: The repository's root.
ROOT = Path(__file__).resolve().parents[3]


def workspace_binary(name: str) -> Path:
    """The workspace binary `name` (coordinator, agent, env-server): in
    ``$ADHOC_BIN_DIR``, else the newest of the target directory's release and
    debug builds. Missing, the test is skipped on a developer's machine and
    fails in CI (``CI`` set), where .ci/run has built it."""
    explicit = os.environ.get("ADHOC_BIN_DIR")
    if explicit:
        path = Path(explicit) / name
        if not path.is_file():
            pytest.fail(f"ADHOC_BIN_DIR={explicit} has no {name}")
        return path
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    built = [p for p in (target / "release" / name, target / "debug" / name) if p.is_file()]
    if built:
        return max(built, key=lambda p: p.stat().st_mtime)
    message = f"no {name} binary under {target}: build the workspace or set ADHOC_BIN_DIR"
    if os.environ.get("CI"):
        pytest.fail(message)
    pytest.skip(message)
