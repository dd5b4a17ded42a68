"""Shared helpers of the tests: the workspace's binaries."""

from __future__ import annotations

import json
import os
import subprocess
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


def assert_ended_cleanly(
    result: subprocess.CompletedProcess[str], out: Path, script: Path, *words: str
) -> None:
    """A run whose child `script` failed: it ended with one error line holding
    every one of `words`, left no process of `script` behind, and wrote only
    whole files (no `run-0.json` for the broken run)."""
    assert result.returncode != 0
    line = next(x for x in result.stderr.splitlines() if words[0] in x)
    assert all(w in line for w in words), result.stderr
    for cmdline in Path("/proc").glob("[0-9]*/cmdline"):
        try:
            assert str(script) not in cmdline.read_text(), f"{cmdline.parent} outlived the run"
        except OSError:
            pass
    for written in out.glob("*.json"):
        json.loads(written.read_text())
    assert not (out / "run-0.json").exists()
