"""Strategies of the tests that send and receive batches of experience: a
teacher that sends agent 0 the transitions it learned in each training
episode, and a student that counts what arrived. Each plots what it sent or
received as its budget. As a strategy process: ``python3
batch_strategies.py teacher`` (or ``student``)."""

from __future__ import annotations

import sys

from adhoc_advising.learner import Transition
from adhoc_advising.strategy import (
    AdviceCounters,
    AdvisingStrategy,
    Batch,
    EndContext,
    Start,
    serve,
)


class Teacher(AdvisingStrategy):
    """Sends agent 0 each training episode's transitions as one batch."""

    name = "teacher"

    def __init__(self, start: Start) -> None:
        self.episode: list[Transition] = []

    def learned(self, transition: Transition) -> None:
        self.episode.append(transition)

    def end_episode(self, end: EndContext) -> list[Batch]:
        batch, self.episode = tuple(self.episode), []
        return [Batch(to=0, transitions=batch)] if batch else []

    def spent_budget(self, counters: AdviceCounters) -> int:
        return counters.shared_sent


class Student(AdvisingStrategy):
    """Counts the transitions that arrived, as its strategy is told them."""

    name = "student"

    def __init__(self, start: Start) -> None:
        self.arrived = 0

    def received(self, from_: int, batch: list[Transition]) -> None:
        assert from_ == 1
        self.arrived += len(batch)

    def spent_budget(self, counters: AdviceCounters) -> int:
        assert self.arrived == counters.shared_received
        return self.arrived


if __name__ == "__main__":
    raise SystemExit(serve({"teacher": Teacher, "student": Student}[sys.argv[1]]))
