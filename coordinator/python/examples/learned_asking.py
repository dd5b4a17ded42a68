"""Learn when to ask: an advising strategy in Python that asks where it
expects advice to differ from what it would do itself.

Before each decision with the ball it reads the state (the paper's six
features) and its learner's values there (``asks_by_values``), and predicts
with a small online logistic rule the probability that its teammates'
advice differs from its own greedy action. The rule's inputs are the six
features and the gap between its best and second-best learned kick values
(a small gap: values still close, advice likely to matter). It asks, while
its budget lasts, where that probability is at least ``ASK_FROM``; every
answer that arrives is a label (1: some advice differed from its greedy
action, 0: all agreed), learned by one gradient step. Untrained, it predicts
0.5 and asks; as advice keeps agreeing with it in a region of the field, it
stops asking there.

It asks every teammate and answers a request where it has visited the state
at least ``GIVE_FROM`` times. In a team file::

    [[agent]]
    algorithm = "external"
    strategy_process = { command = ["python3", "examples/learned_asking.py"] }
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from adhoc_advising.strategy import (
    Advice,
    AdvisingStrategy,
    AskContext,
    GiveContext,
    Replies,
    Start,
    Values,
    greedy,
    serve,
)

ASK_FROM, GIVE_FROM, BUDGET = 0.5, 20, 1000
#: The logistic rule's step size.
RATE = 0.1


def kick_gap(values: Values) -> float:
    """The gap between the best and the second-best learned kick values, 1
    (no doubt) with fewer than two learned, at most 1."""
    learned = sorted((v for v in values[1:] if v is not None), reverse=True)
    if len(learned) < 2:
        return 1.0
    return min(learned[0] - learned[1], 1.0)


class LearnedAsking(AdvisingStrategy):
    """Ask where advice is predicted to differ from its own greedy action."""

    name = "learned-asking"
    version = "1"
    asks_by_values = True

    def __init__(self, start: Start) -> None:
        self.me = start.agent
        #: The rule's weights: bias, six features, value gap.
        self.weights = [0.0] * 8
        #: The inputs and greedy action of the decision that asked.
        self.asked: tuple[list[float], int] | None = None
        #: Labels learned, and how many said advice differed.
        self.labels = 0
        self.differed = 0

    def predict(self, x: Sequence[float]) -> float:
        """The probability that advice differs where the inputs are ``x``."""
        z = sum(w * xi for w, xi in zip(self.weights, x))
        return 1.0 / (1.0 + math.exp(-max(min(z, 30.0), -30.0)))

    def asks(self, at: AskContext) -> bool:
        values = at.values or (None,) * 5
        x = [1.0, *at.state, kick_gap(values)]
        ask = at.counters.ask_spent < BUDGET and self.predict(x) >= ASK_FROM
        self.asked = (x, greedy(values)) if ask else None
        return ask

    def advisors(
        self, me: int, team_size: int, positions: Sequence[tuple[float, float]]
    ) -> Sequence[int]:
        return [j for j in range(team_size) if j != me]

    def gives(self, at: GiveContext) -> bool:
        return at.visits >= GIVE_FROM and at.counters.advice_given < BUDGET

    def follow(self, replies: Replies) -> Advice | None:
        if self.asked is not None and replies.advice:
            x, own = self.asked
            label = float(any(a.action != own for a in replies.advice))
            error = label - self.predict(x)
            self.weights = [w + RATE * error * xi for w, xi in zip(self.weights, x)]
            self.labels += 1
            self.differed += int(label)
        self.asked = None
        return super().follow(replies)


if __name__ == "__main__":
    raise SystemExit(serve(LearnedAsking))
