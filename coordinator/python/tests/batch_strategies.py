"""Strategies of the tests that send and receive batches of experience: a
teacher that sends agent 0 the transitions it learned in each training
episode, noted and with its standing, and a student that checks what
arrived and names what its learner learns of it. Each plots what it sent or
received as its budget. As a strategy process: ``python3
batch_strategies.py teacher`` (or ``student-all``, ``student-even``,
``student-none``)."""

from __future__ import annotations

import sys
from collections.abc import Sequence

from adhoc_advising.learner import Transition
from adhoc_advising.strategy import (
    AdviceCounters,
    AdvisingStrategy,
    Batch,
    EndContext,
    Standing,
    Start,
    TransitionNote,
    serve,
)


class Teacher(AdvisingStrategy):
    """Sends agent 0 each training episode's transitions as one batch, the
    i-th noted as one frame of uncertainty i, with its episodes so far as
    its standing; ``silent`` sends nothing."""

    name = "teacher"

    def __init__(self, start: Start, silent: bool = False) -> None:
        self.silent = silent
        self.episode: list[Transition] = []
        self.episodes = 0

    def learned(self, transition: Transition) -> None:
        self.episode.append(transition)

    def end_episode(self, end: EndContext) -> list[Batch]:
        self.episodes += 1
        batch, self.episode = tuple(self.episode), []
        if self.silent or not batch:
            return []
        notes = tuple(TransitionNote(frames=1, uncertainty=float(i)) for i in range(len(batch)))
        standing = Standing(self.episodes, None, end.episode_return)
        return [Batch(to=0, transitions=batch, notes=notes, standing=standing)]

    def spent_budget(self, counters: AdviceCounters) -> int:
        return counters.shared_sent


class Student(AdvisingStrategy):
    """Checks that each batch arrived as the teacher sent it and counts it;
    its learner learns ``all`` of it, its ``even`` transitions or ``none``."""

    name = "student"

    def __init__(self, start: Start, learns: str = "all") -> None:
        self.learns = learns
        self.arrived = 0

    def received(self, from_: int, batch: Batch) -> Sequence[int] | None:
        n = len(batch.transitions)
        assert (from_, batch.to) == (1, 0)
        assert [note.uncertainty for note in batch.notes] == list(range(n))
        assert batch.standing is not None and batch.standing.episodes >= 1
        self.arrived += n
        return {"all": None, "even": range(0, n, 2), "none": []}[self.learns]

    def spent_budget(self, counters: AdviceCounters) -> int:
        assert self.arrived == counters.shared_received
        return self.arrived


if __name__ == "__main__":
    role = sys.argv[1]
    if role == "teacher":
        raise SystemExit(serve(Teacher))
    learns = role.removeprefix("student-")
    raise SystemExit(serve(lambda start: Student(start, learns)))
