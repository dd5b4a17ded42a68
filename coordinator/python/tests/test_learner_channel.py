"""adhoc_advising.learner.serve on its own: the channel's requests and answers,
and a learner's failure reported as the agent expects it."""

from __future__ import annotations

import io
import json

from adhoc_advising.learner import Learner, Start, Transition, serve

START = {
    "op": "start",
    "agent": 2,
    "team_size": 3,
    "run": 0,
    "seed": 7,
    "features": 6,
    "actions": ["MOVE", "SHOOT", "DRIBBLE", "PASS_NEAR", "PASS_FAR"],
}
STATE = [0.1, -0.2, 0.3, 0.0, 0.5, -1.0]


class Counting(Learner):
    """Values that count the transitions learned; raises on a zero reward."""

    name, version = "counting", "3"

    def __init__(self, start: Start) -> None:
        assert start.actions[1] == "SHOOT" and start.seed == 7
        self.learned: list[Transition] = []

    def values(self, state, index):
        return [None, float(len(self.learned)), 0.0, 0.0, 0.0]

    def choose(self, state, index) -> int:
        return 2

    def learn(self, transition: Transition) -> None:
        if transition.reward == 0.0:
            raise ZeroDivisionError("a zero reward")
        self.learned.append(transition)


def talk(*requests: dict) -> tuple[int, list[dict]]:
    answers = io.StringIO()
    lines = io.StringIO("".join(json.dumps(r) + "\n" for r in requests))
    status = serve(Counting, lines, answers)
    return status, [json.loads(line) for line in answers.getvalue().splitlines()]


def test_queries_are_answered_and_the_rest_is_not() -> None:
    learn = {
        "op": "learn",
        "state": STATE,
        "action": 1,
        "reward": 1.0,
        "next_state": None,
        "next_action": None,
    }
    query = {"op": "values", "state": STATE, "index": 4}
    status, answers = talk(
        START, query, learn, {"op": "end_episode"}, query, {**query, "op": "choose"}
    )
    assert status == 0
    assert answers == [
        {"name": "counting", "version": "3"},
        {"q": [None, 0.0, 0.0, 0.0, 0.0]},
        {"q": [None, 1.0, 0.0, 0.0, 0.0]},
        {"action": 2},
    ]
    # A shared episode is learned as the learner's own steps by default.
    status, answers = talk(START, {"op": "replay", "episode": [learn, learn]}, query)
    assert answers[-1] == {"q": [None, 2.0, 0.0, 0.0, 0.0]}


def test_a_failure_is_one_error_answer_and_ends_the_loop() -> None:
    bad_learn = {
        "op": "learn",
        "state": STATE,
        "action": 1,
        "reward": 0.0,
        "next_state": STATE,
        "next_action": 2,
    }
    query = {"op": "values", "state": STATE, "index": None}
    status, answers = talk(START, bad_learn, query)
    assert status == 1
    assert answers[-1] == {"error": "ZeroDivisionError: a zero reward"}
    status, answers = talk(query)
    assert (status, answers) == (1, [{"error": "RuntimeError: `values` before `start`"}])
    status, answers = talk(START, {"op": "dance"})
    assert answers[-1] == {"error": "ValueError: unknown request `dance`"}


def test_print_in_a_learner_goes_to_the_log_not_the_channel(capsys) -> None:
    class Chatty(Counting):
        def choose(self, state, index) -> int:
            print("debug: choosing")
            return super().choose(state, index)

    answers = io.StringIO()
    query = {"op": "choose", "state": STATE, "index": 1}
    lines = io.StringIO("".join(json.dumps(r) + "\n" for r in (START, query)))
    assert serve(Chatty, lines, answers) == 0
    assert [json.loads(line) for line in answers.getvalue().splitlines()][1] == {"action": 2}
    assert "debug: choosing" in capsys.readouterr().err
