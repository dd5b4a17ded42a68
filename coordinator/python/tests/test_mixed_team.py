"""A Python learner as one agent of an advising team over zenoh: two Rust
AdHocTD agents and the numpy example (examples/numpy_learner.py) learn
together for 300 episodes, real processes over loopback; then the same
learner raising mid-run."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from conftest import ROOT, assert_ended_cleanly, workspace_binary

EXAMPLE = ROOT / "coordinator" / "python" / "examples" / "numpy_learner.py"


def team_file(directory: Path, learner: Path) -> Path:
    """Agents 0 and 1 Rust AdHocTD, agent 2 AdHocTD around `learner`."""
    command = json.dumps([sys.executable, str(learner)])
    path = directory / "team.toml"
    path.write_text(
        '[[agent]]\nalgorithm = "adhoc-td"\n\n[[agent]]\nalgorithm = "adhoc-td"\n\n'
        f'[[agent]]\nalgorithm = "adhoc-td"\n'
        f'learner = {{ command = {command}, source = "{learner}" }}\n'
    )
    return path


def run(team: Path, out: Path, episodes: int) -> subprocess.CompletedProcess[str]:
    """`coordinator run` of one run of `team` over loopback zenoh."""
    bin_dir = workspace_binary("coordinator").parent
    return subprocess.run(
        [
            str(bin_dir / "coordinator"),
            "run",
            "--team",
            str(team),
            "--runs",
            "1",
            "--episodes",
            str(episodes),
            "--eval-every",
            "100",
            "--eval-episodes",
            "20",
            "--transport",
            "zenoh",
            "--quiet",
            "--out",
            str(out),
        ],
        capture_output=True,
        text=True,
        timeout=900,
    )


def test_advice_flows_both_ways_with_a_python_learner(tmp_path: Path) -> None:
    result = run(team_file(tmp_path, EXAMPLE), tmp_path / "out", 300)
    assert result.returncode == 0, result.stderr
    config = json.loads((tmp_path / "out" / "config.json").read_text())
    learner = config["config"]["team"][2]["learner"]
    assert learner["command"][-1] == str(EXAMPLE)
    assert len(learner["source_fnv64"]) == 16
    last = json.loads((tmp_path / "out" / "run-0.json").read_text())["points"][-1]["agents"]
    python, rust = last[2], last[:2]
    # The Python agent asked and was answered; it answered the Rust agents.
    assert python["advice_requests"] > 0 and python["advice_replies_received"] > 0
    assert python["advice_given"] > 0
    assert sum(a["advice_replies_received"] for a in rust) > 0
    assert all(a["messages_dropped"] == 0 for a in last)


FAULTY = """
import sys
sys.path.insert(0, {examples!r})
from numpy_learner import LinearSarsa
from adhoc_advising.learner import serve

class Faulty(LinearSarsa):
    learned = 0

    def learn(self, transition):
        self.learned += 1
        if self.learned == 200:
            raise ZeroDivisionError("a planned fault")
        super().learn(transition)

raise SystemExit(serve(Faulty))
"""


def test_a_learner_that_raises_ends_the_run_with_its_cause(tmp_path: Path) -> None:
    faulty = tmp_path / "faulty_learner.py"
    faulty.write_text(FAULTY.format(examples=str(EXAMPLE.parent)))
    out = tmp_path / "out"
    result = run(team_file(tmp_path, faulty), out, 300)
    assert_ended_cleanly(result, out, faulty, "ZeroDivisionError", "agent 2", "a planned fault")


def test_a_python_learner_is_saved_and_loaded_with_its_own_state(tmp_path: Path) -> None:
    """--save-agents keeps the numpy learner's weights (snapshot version 2);
    a team file's `load` starts it from them."""
    team = team_file(tmp_path, EXAMPLE)
    agents = tmp_path / "agents"
    first = subprocess.run(
        [
            str(workspace_binary("coordinator").parent / "coordinator"),
            "run",
            "--team",
            str(team),
            "--runs",
            "1",
            "--episodes",
            "100",
            "--eval-every",
            "100",
            "--eval-episodes",
            "5",
            "--transport",
            "zenoh",
            "--quiet",
            "--save-agents",
            str(agents),
            "--out",
            str(tmp_path / "first"),
        ],
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert first.returncode == 0, first.stderr
    saved = (agents / "run-0-agent-2.snapshot").read_bytes()
    assert saved[:8] == b"ADVQTAB\0" and int.from_bytes(saved[8:10], "little") == 2
    snapshot = agents / "run-0-agent-2.snapshot"
    team.write_text(team.read_text().replace("learner = ", f'load = "{snapshot}"\nlearner = ', 1))
    second = run(team, tmp_path / "second", 20)
    assert second.returncode == 0, second.stderr
    config = json.loads((tmp_path / "second" / "config.json").read_text())
    assert config["snapshot_digests"][2] is not None
