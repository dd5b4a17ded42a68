"""A strategy written in Python: the channel on its own (each decision's
request and answer), then the example (examples/nearest_teammate.py) as one
agent of a team over zenoh beside two Rust AdHocTD agents, and a strategy
that raises mid-run."""

from __future__ import annotations

import io
import json
import re
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import pytest
from batch_strategies import Student, Teacher
from conftest import ROOT, assert_ended_cleanly, workspace_binary

import adhoc_advising
from adhoc_advising.learner import Transition
from adhoc_advising.strategy import (
    AdvisingStrategy,
    AskContext,
    Batch,
    EndContext,
    GiveContext,
    Outcome,
    Standing,
    Start,
    TransitionNote,
    serve,
)

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
    # Nothing new overridden: no new message is sent or asked.
    new = (
        "asks_by_values",
        "records_transitions",
        "ends_episodes",
        "ends_evaluations",
        "receives_batches",
        "reports_advice_outcomes",
        "hears_advice_outcomes",
    )
    assert not any(traits[key] for key in new)
    assert asks == {"decision": False} and gives == {"decision": False}
    # Greedy, ties in the framework's order: DRIBBLE before PASS_NEAR.
    assert advice == {"action": 2}
    # The majority, credited to the first advisor who gave it.
    assert follow == {"advice": {"advisor": 1, "action": 2}}
    assert spent == {"spent": 3}


TRANSITION = {
    "state": [0.5, -0.5, 0.0, 0.25, 0.125, 1.0],
    "action": 1,
    "reward": 1.0,
    "next_state": None,
    "next_action": None,
}


def test_the_new_hooks_see_the_observation_the_end_and_what_arrives() -> None:
    seen: list[object] = []

    class Teacher(AdvisingStrategy):
        asks_by_values = True
        reports_advice_outcomes = True

        def __init__(self, start: Start) -> None:
            pass

        def asks(self, at: AskContext) -> bool:
            seen.append(at)
            return False

        def gives(self, at: GiveContext) -> bool:
            seen.append(at)
            return False

        def learned(self, transition: Transition) -> None:
            seen.append(transition)

        def end_episode(self, end: EndContext) -> list[Batch]:
            seen.append(end)
            return [Batch(to=0, transitions=(seen[2],))]

        def end_evaluation(self, end: EndContext) -> None:
            seen.append(end)

        def received(self, from_: int, batch: Batch) -> list[int]:
            seen.append((from_, batch))
            return [0]

        def advice_outcome(self, asker: int, followed: bool, advantage: float) -> None:
            seen.append((asker, followed, advantage))

    state = TRANSITION["state"]
    values = [None, 0.5, 0.25, None, None]
    end = {
        "final_reward": 1.0,
        "outcome": "goal",
        "episode_return": 1.5,
        "me": 2,
        "team_size": 3,
        "counters": COUNTERS,
    }
    status, answers = talk(
        Teacher,
        START,
        {
            "op": "asks",
            "fresh": True,
            "visits": 0,
            "training_episodes": 3,
            "counters": COUNTERS,
            "uncertainty": None,
            "state": state,
            "features": [0.5, 0.25],
            "values": values,
        },
        {
            "op": "gives",
            "visits": 9,
            "values": values,
            "counters": COUNTERS,
            "asker": 1,
            "state": state,
            "features": [],
        },
        {"op": "learned", "transition": TRANSITION},
        {"op": "end_episode", **end},
        {"op": "end_evaluation", **end, "outcome": "out_of_time"},
        {
            "op": "received",
            "from": 1,
            "to": 2,
            "transitions": [TRANSITION],
            "notes": [{"frames": 3, "uncertainty": 0.5}],
            "standing": {"episodes": 40, "uncertainty": None, "mean_return": -0.25},
        },
        {"op": "advice_outcome", "asker": 0, "followed": True, "advantage": -0.5},
    )
    assert status == 0
    traits, asks, gives, batches, learns = answers
    assert all(
        traits[key]
        for key in (
            "asks_by_values",
            "records_transitions",
            "ends_episodes",
            "ends_evaluations",
            "receives_batches",
            "reports_advice_outcomes",
            "hears_advice_outcomes",
        )
    )
    assert asks == {"decision": False} and gives == {"decision": False}
    assert batches == {
        "batches": [{"to": 0, "transitions": [TRANSITION], "notes": [], "standing": None}]
    }
    assert learns == {"learn": [0]}
    ask, give, learned, ended, evaluated, received, outcome = seen
    assert (ask.state, ask.features, ask.values) == (tuple(state), (0.5, 0.25), tuple(values))
    assert (give.asker, give.state, give.features) == (1, tuple(state), ())
    assert learned == Transition(tuple(state), 1, 1.0, None, None)
    assert (ended.outcome, ended.episode_return, ended.me) == ("goal", 1.5, 2)
    assert evaluated.outcome == "out_of_time"
    assert received == (
        1,
        Batch(2, (learned,), (TransitionNote(3, 0.5),), Standing(40, None, -0.25)),
    )
    assert outcome == (0, True, -0.5)


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


BATCHES = Path(__file__).parent / "batch_strategies.py"


def last_agents(out: Path) -> list[dict]:
    """Every agent's counters at the last evaluation of run 0 in `out`."""
    return json.loads((out / "run-0.json").read_text())["points"][-1]["agents"]


SCHEDULE = {"runs": 1, "episodes": 40, "eval_every": 20, "eval_episodes": 5}


def test_a_batch_is_sent_at_an_episode_s_end_and_learned_in_process(tmp_path: Path) -> None:
    team = [{"algorithm": Student, "learner": "dqn"}, {"algorithm": Teacher}]
    adhoc_advising.run(out=tmp_path / "out", team=team, **SCHEDULE)
    student, teacher = last_agents(tmp_path / "out")
    # Every transition sent arrived, notes and standing as sent (the
    # student checks them), one message per training episode.
    assert 0 < student["give_spent"] == teacher["give_spent"]
    assert 0 < teacher["advising_messages"] <= 40


def frames(out: Path) -> tuple[int, int]:
    """The training and evaluation frames run 0 in `out` played."""
    timing = json.loads((out / "run-0.json").read_text())["timing"]
    return timing["training_frames"], timing["evaluation_frames"]


def test_a_receiver_s_learner_learns_the_transitions_it_names(tmp_path: Path) -> None:
    def play(name: str, learns: str, silent: bool = False) -> tuple[int, int]:
        team = [
            {"algorithm": lambda start: Student(start, learns), "learner": "dqn"},
            {"algorithm": lambda start: Teacher(start, silent)},
        ]
        adhoc_advising.run(out=tmp_path / name, team=team, **SCHEDULE)
        return frames(tmp_path / name)

    alone = play("alone", "none", silent=True)
    # Naming none of what arrived leaves the student as if nothing had.
    assert play("none", "none") == alone
    assert play("even", "even") != alone
    assert play("all", "all") != alone


def test_a_receiver_naming_a_transition_it_was_not_sent_ends_the_run(tmp_path: Path) -> None:
    class Greedy(Student):
        def received(self, from_: int, batch: Batch) -> list[int]:
            return [len(batch.transitions)]

    team = [{"algorithm": Greedy, "learner": "dqn"}, {"algorithm": Teacher}]
    with pytest.raises(RuntimeError, match="answered `received` with what it cannot") as ended:
        adhoc_advising.run(out=tmp_path / "out", team=team, **SCHEDULE)
    assert re.fullmatch(r"transition (\d+) of a batch of \1", str(ended.value.__cause__))


def test_a_batch_the_wire_cannot_carry_ends_the_run(tmp_path: Path) -> None:
    class Careless(Teacher):
        def end_episode(self, end: EndContext) -> list[Batch]:
            return [replace(b, notes=b.notes[:1]) for b in super().end_episode(end)]

    team = [{"algorithm": Student, "learner": "dqn"}, {"algorithm": Careless}]
    with pytest.raises(RuntimeError, match="answered `end_episode` with what it cannot") as ended:
        adhoc_advising.run(out=tmp_path / "out", team=team, **SCHEDULE)
    cause = r"an experience batch of (\d+) transitions with 1 notes"
    assert re.fullmatch(cause, str(ended.value.__cause__))


def test_a_batch_travels_over_zenoh(tmp_path: Path) -> None:
    def agent(role: str, extra: str = "") -> str:
        command = json.dumps([sys.executable, str(BATCHES), role])
        return (
            f'[[agent]]\nalgorithm = "external"\n{extra}'
            f'strategy_process = {{ command = {command}, source = "{BATCHES}" }}\n\n'
        )

    team = tmp_path / "team.toml"
    team.write_text(agent("student-even", 'learner = "dqn"\n') + agent("teacher"))
    result = run(team, tmp_path / "out", 100)
    assert result.returncode == 0, result.stderr
    student, teacher = last_agents(tmp_path / "out")
    # A batch of the last episode may still wait while the student evaluates.
    assert 0 < student["give_spent"] <= teacher["give_spent"]
    assert 0 < teacher["advising_messages"] <= 100
    assert all(a["messages_dropped"] == 0 for a in (student, teacher))
