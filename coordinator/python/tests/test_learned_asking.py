"""The example that learns when to ask (examples/learned_asking.py): its rule
on its own, then as one agent of a team beside two Rust AdHocTD agents, in
this process and over zenoh."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from conftest import ROOT, workspace_binary

import adhoc_advising
from adhoc_advising.strategy import (
    Advice,
    AdviceCounters,
    AskContext,
    Replies,
    Start,
)

EXAMPLE = ROOT / "coordinator" / "python" / "examples" / "learned_asking.py"
sys.path.insert(0, str(EXAMPLE.parent))

from learned_asking import LearnedAsking  # noqa: E402

COUNTERS = AdviceCounters(0, 0, 0, 0, 0, 0)
ACTIONS = ("MOVE", "SHOOT", "DRIBBLE", "PASS_NEAR", "PASS_FAR")


def test_it_stops_asking_where_advice_keeps_agreeing() -> None:
    strategy = LearnedAsking(Start(2, 3, 0, 7, ACTIONS))
    # Its greedy action here is SHOOT, two kick values close.
    at = AskContext(
        fresh=True,
        visits=3,
        training_episodes=1,
        counters=COUNTERS,
        uncertainty=None,
        state=(0.5, -0.5, 0.0, 0.25, 0.125, 1.0),
        values=(None, 0.5, 0.45, None, None),
    )
    agreeing = Replies(key=1, advice=(Advice(0, 1), Advice(1, 1)), values=())
    asked = 0
    while strategy.asks(at):
        asked += 1
        assert strategy.follow(agreeing) == Advice(0, 1)
        assert asked < 100, "it never stopped asking"
    assert asked > 0 and strategy.labels == asked and strategy.differed == 0


def test_it_asks_and_is_advised_in_process(tmp_path: Path) -> None:
    team = [
        {"algorithm": "adhoc-td"},
        {"algorithm": "adhoc-td"},
        {"algorithm": LearnedAsking},
    ]
    schedule = {"runs": 1, "episodes": 100, "eval_every": 50, "eval_episodes": 10}
    adhoc_advising.run(out=tmp_path / "out", team=team, seed=3, **schedule)
    agents = json.loads((tmp_path / "out" / "run-0.json").read_text())["points"][-1]["agents"]
    python = agents[2]
    assert python["advice_requests"] > 0 and python["ask_spent"] > 0
    # Two advisors asked per request.
    assert python["advice_replies_received"] <= 2 * python["advice_requests"]


def test_it_asks_and_is_advised_over_zenoh(tmp_path: Path) -> None:
    command = json.dumps([sys.executable, str(EXAMPLE)])
    team = tmp_path / "team.toml"
    team.write_text(
        '[[agent]]\nalgorithm = "adhoc-td"\n\n[[agent]]\nalgorithm = "adhoc-td"\n\n'
        '[[agent]]\nalgorithm = "external"\n'
        f'strategy_process = {{ command = {command}, source = "{EXAMPLE}" }}\n'
    )
    out = tmp_path / "out"
    schedule = ["--runs", "1", "--episodes", "100", "--eval-every", "50", "--eval-episodes", "10"]
    result = subprocess.run(
        [str(workspace_binary("coordinator")), "run", "--team", str(team), *schedule]
        + ["--transport", "zenoh", "--quiet", "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert result.returncode == 0, result.stderr
    agents = json.loads((out / "run-0.json").read_text())["points"][-1]["agents"]
    python = agents[2]
    assert python["advice_requests"] > 0 and python["ask_spent"] > 0
    assert all(a["messages_dropped"] == 0 for a in agents)
