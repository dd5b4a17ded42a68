"""A strategy written in Python: the channel on its own (each decision's
request and answer), then the example (examples/nearest_teammate.py) as one
agent of a team over zenoh beside two Rust AdHocTD agents, and a strategy
that raises mid-run."""

from __future__ import annotations

import io
import json
import subprocess
import sys
from pathlib import Path

from conftest import ROOT, assert_ended_cleanly, workspace_binary

from adhoc_advising.strategy import AdvisingStrategy, Outcome, Start, serve

EXAMPLE = ROOT / "coordinator" / "python" / "examples" / "nearest_teammate.py"
sys.path.insert(0, str(EXAMPLE.parent))

from nearest_teammate import NearestTeammate  # noqa: E402

START = {
    "op": "start",
    "agent": 2,
    "team_size": 3,
    "run": 0,
    "seed": 7,
    "actions": ["MOVE", "SHOOT", "DRIBBLE", "PASS_NEAR", "PASS_FAR"],
}
COUNTERS = {
    "advice_requests": 0,
    "advice_replies_received": 0,
    "ask_spent": 0,
    "advice_given": 3,
    "shared_sent": 0,
    "shared_received": 0,
}


def talk(make, *requests: dict) -> tuple[int, list[dict]]:
    answers = io.StringIO()
    lines = io.StringIO("".join(json.dumps(r) + "\n" for r in requests))
    status = serve(make, lines, answers)
    return status, [json.loads(line) for line in answers.getvalue().splitlines()]


def test_the_defaults_are_the_seams() -> None:
    values = [None, 0.5, 2.0, 2.0, None]
    status, answers = talk(
        lambda start: AdvisingStrategy(),
        START,
        {
            "op": "asks",
            "fresh": True,
            "visits": 0,
            "training_episodes": 3,
            "counters": COUNTERS,
            "uncertainty": None,
        },
        {"op": "gives", "visits": 9, "values": values, "counters": COUNTERS},
        {"op": "advice", "values": values},
        {
            "op": "follow",
            "key": 11,
            "values": [],
            "advice": [
                {"advisor": 0, "action": 3},
                {"advisor": 1, "action": 2},
                {"advisor": 2, "action": 2},
            ],
        },
        {"op": "spent_budget", "counters": COUNTERS},
    )
    assert status == 0
    traits, asks, gives, advice, follow, spent = answers
    assert traits["name"] == "python-strategy"
    assert not traits["reuses"] and not traits["learns_from_outcomes"]
    assert asks == {"decision": False} and gives == {"decision": False}
    # Greedy, ties in the framework's order: DRIBBLE before PASS_NEAR.
    assert advice == {"action": 2}
    # The majority, credited to the first advisor who gave it.
    assert follow == {"advice": {"advisor": 1, "action": 2}}
    assert spent == {"spent": 3}


def test_the_example_asks_the_nearest_teammate_it_trusts() -> None:
    positions = [[0.0, 0.0], [30.0, 0.0], [10.0, 0.0]]
    outcomes = [{"op": "learn_outcome", "advisor": 0, "advantage": -1.0}] * 20
    status, answers = talk(
        NearestTeammate,
        START,
        {"op": "advisors", "me": 2, "team_size": 3, "positions": positions},
        *outcomes,
        {"op": "advisors", "me": 2, "team_size": 3, "positions": positions},
    )
    assert status == 0
    traits, nearest, after = answers
    assert traits["name"] == "nearest-teammate" and traits["learns_from_outcomes"]
    assert nearest == {"advisors": [0]}
    # Agent 0's advice turned out worse than the agent's own choices.
    assert after == {"advisors": [1]}


def test_a_strategy_that_raises_is_reported_and_ends_the_loop() -> None:
    class Broken(AdvisingStrategy):
        def __init__(self, start: Start) -> None:
            pass

        def learn_outcome(self, outcome: Outcome) -> None:
            raise KeyError("no such advisor")

    status, answers = talk(
        Broken,
        START,
        {"op": "learn_outcome", "advisor": 5, "advantage": 0.0},
        {"op": "spent_budget", "counters": COUNTERS},
    )
    assert status == 1
    assert answers[-1] == {"error": "KeyError: 'no such advisor'"}


def team_file(directory: Path, strategy: Path) -> Path:
    """Agents 0 and 1 Rust AdHocTD, agent 2 the Python strategy `strategy`."""
    command = json.dumps([sys.executable, str(strategy)])
    path = directory / "team.toml"
    path.write_text(
        '[[agent]]\nalgorithm = "adhoc-td"\n\n[[agent]]\nalgorithm = "adhoc-td"\n\n'
        '[[agent]]\nalgorithm = "external"\n'
        f'strategy_process = {{ command = {command}, source = "{strategy}" }}\n'
    )
    return path


def run(team: Path, out: Path, episodes: int) -> subprocess.CompletedProcess[str]:
    """`coordinator run` of one run of `team` over loopback zenoh."""
    return subprocess.run(
        [
            str(workspace_binary("coordinator")),
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


def test_the_example_advises_and_is_advised_in_a_team_over_zenoh(tmp_path: Path) -> None:
    result = run(team_file(tmp_path, EXAMPLE), tmp_path / "out", 300)
    assert result.returncode == 0, result.stderr
    config = json.loads((tmp_path / "out" / "config.json").read_text())
    agent = config["config"]["team"][2]
    assert agent["algorithm"] == "external"
    assert agent["strategy_process"]["command"][-1] == str(EXAMPLE)
    assert len(agent["strategy_process"]["source_fnv64"]) == 16
    last = json.loads((tmp_path / "out" / "run-0.json").read_text())["points"][-1]["agents"]
    python, rust = last[2], last[:2]
    # It asked one teammate per request and acted on the advice; it answered
    # the Rust agents, who asked it among others.
    assert python["advice_requests"] > 0 and python["ask_spent"] > 0
    assert python["advice_replies_received"] <= python["advice_requests"]
    assert python["advice_given"] > 0
    assert sum(a["advice_replies_received"] for a in rust) > 0
    assert all(a["messages_dropped"] == 0 for a in last)


FAULTY = """
import sys
sys.path.insert(0, {examples!r})
from nearest_teammate import NearestTeammate
from adhoc_advising.strategy import serve

class Faulty(NearestTeammate):
    asked = 0

    def asks(self, at):
        self.asked += 1
        if self.asked == 200:
            raise ZeroDivisionError("a planned fault")
        return super().asks(at)

raise SystemExit(serve(Faulty))
"""


def test_a_strategy_that_raises_ends_the_run_with_its_cause(tmp_path: Path) -> None:
    faulty = tmp_path / "faulty_strategy.py"
    faulty.write_text(FAULTY.format(examples=str(EXAMPLE.parent)))
    out = tmp_path / "out"
    result = run(team_file(tmp_path, faulty), out, 300)
    assert_ended_cleanly(
        result, out, faulty, "ZeroDivisionError", "agent 2: its strategy", "a planned fault"
    )
