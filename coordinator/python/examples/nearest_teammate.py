"""Ask the nearest teammate you still trust: an advising strategy in Python.

An agent that meets a state it has visited fewer than ``ASK_BELOW`` times
asks one teammate, the nearest on the field among those whose advice has not
turned out worse than its own choices, and plays the advice. It answers a
request when it has visited the state at least ``GIVE_FROM`` times. Each side
spends at most ``BUDGET`` (the paper's budgets). A teammate stays trusted
for its first ``TRIAL`` pieces of advice played, then while the summed
advantage of the decisions made on its advice is not negative. The advantage
is the framework's (``Outcome.advantage``): r + gamma V(s') - V(s) under the
values just learned, V a state's best learned kick action's value where the
agent chose (its action's where it could only move), V(s') 0 at the
episode's end.

The agent process runs it as the decisions of algorithm ``external``
(docs/strategies.md), in a team file::

    [[agent]]
    algorithm = "external"
    strategy_process = { command = ["python3", "examples/nearest_teammate.py"] }

Its learner stays the framework's SARSA(lambda) (or a learner process).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from adhoc_advising.strategy import (
    Advice,
    AdvisingStrategy,
    AskContext,
    GiveContext,
    Outcome,
    Replies,
    Start,
    serve,
)

ASK_BELOW, GIVE_FROM, BUDGET = 5, 20, 1000
#: Decisions on an advisor's advice before its trust is judged.
TRIAL = 20


class NearestTeammate(AdvisingStrategy):
    """Ask the nearest trusted teammate; answer where experienced."""

    name = "nearest-teammate"
    version = "1"

    def __init__(self, start: Start) -> None:
        self.me = start.agent
        #: Per teammate: decisions on its advice and their summed advantage.
        self.followed = [0] * start.team_size
        self.advantage = [0.0] * start.team_size

    def trusted(self, j: int) -> bool:
        return self.followed[j] < TRIAL or self.advantage[j] >= 0.0

    def asks(self, at: AskContext) -> bool:
        return at.fresh and at.visits < ASK_BELOW and at.counters.ask_spent < BUDGET

    def advisors(
        self, me: int, team_size: int, positions: Sequence[tuple[float, float]]
    ) -> Sequence[int]:
        others = [j for j in range(team_size) if j != me and self.trusted(j)]
        if not others:
            return ()
        return (min(others, key=lambda j: math.dist(positions[j], positions[me])),)

    def gives(self, at: GiveContext) -> bool:
        return at.visits >= GIVE_FROM and at.counters.advice_given < BUDGET

    def follow(self, replies: Replies) -> Advice | None:
        return replies.advice[0] if replies.advice else None

    def learn_outcome(self, outcome: Outcome) -> None:
        if outcome.advisor is not None:
            self.followed[outcome.advisor] += 1
            self.advantage[outcome.advisor] += outcome.advantage


if __name__ == "__main__":
    raise SystemExit(serve(NearestTeammate))
