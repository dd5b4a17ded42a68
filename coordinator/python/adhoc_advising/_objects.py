"""Python learners and strategies as the native side of :func:`run` calls
them in process: adapters taking and returning plain values (tuples,
numbers), around the user's objects and the package's dataclasses."""

from __future__ import annotations

import copy
from collections.abc import Sequence
from typing import Any, Callable, Optional

from adhoc_advising import _adhoc_advising
from adhoc_advising import learner as learners
from adhoc_advising import strategy as strategies

#: What the native side gets of one object: ``make(agent, team_size, run,
#: seed)`` of its adapter, and what the results record of it.
Made = tuple[Callable[[int, int, int, int], Any], str]

#: Q(s, a) by action index as the native side passes them.
RawValues = Sequence[Optional[float]]


class LearnerAdapter:
    """A :class:`~adhoc_advising.learner.Learner` as the native side calls it."""

    __slots__ = ("learner",)

    def __init__(self, learner: learners.Learner) -> None:
        for method in ("values", "choose", "learn"):
            if not callable(getattr(learner, method, None)):
                raise TypeError(f"{type(learner).__name__} has no method `{method}`")
        self.learner = learner

    def values(self, state: learners.State, index: int | None) -> list[float | None]:
        return [None if v is None else float(v) for v in self.learner.values(state, index)]

    def choose(self, state: learners.State, index: int | None) -> int:
        return int(self.learner.choose(state, index))

    def learn(self, transitions: list[tuple]) -> None:
        """The transitions queued since the last call, in order."""
        learn, make = self.learner.learn, learners.Transition
        for t in transitions:
            learn(make(*t))

    def end_episode(self) -> None:
        self.learner.end_episode()

    def replay(self, episode: list[tuple]) -> None:
        self.learner.replay([learners.Transition(*t) for t in episode])

    def save(self) -> bytes | None:
        state = self.learner.save()
        return None if state is None else bytes(state)

    def restore(self, state: bytes) -> None:
        self.learner.restore(state)


def _counters(raw: Sequence[int]) -> strategies.AdviceCounters:
    return strategies.AdviceCounters(*raw)


def _replies(key: int, advice: Sequence[tuple], shared: Sequence[tuple]) -> strategies.Replies:
    return strategies.Replies(
        key=key,
        advice=tuple(strategies.Advice(a, x) for a, x in advice),
        values=tuple(strategies.SharedValues(a, strategies._values(v), n) for a, v, n in shared),
    )


def _end(
    final_reward: float,
    outcome: str,
    episode_return: float,
    me: int,
    team_size: int,
    counters: Sequence[int],
) -> strategies.EndContext:
    return strategies.EndContext(
        final_reward, outcome, episode_return, me, team_size, _counters(counters)
    )


def _batch_tuple(b: strategies.Batch) -> tuple:
    """A batch as the native side takes it."""
    s = strategies._wire_standing(b.standing)
    standing = None if s is None else (s["episodes"], s["uncertainty"], s["mean_return"])
    notes = [(int(n.frames), float(n.uncertainty)) for n in b.notes]
    return (int(b.to), [_tuple(t) for t in b.transitions], notes, standing)


def _tuple(t: learners.Transition) -> tuple:
    """A transition as the native side takes it."""
    state = tuple(float(x) for x in t.state)
    following = None if t.next_state is None else tuple(float(x) for x in t.next_state)
    action = None if t.next_action is None else int(t.next_action)
    return (state, int(t.action), float(t.reward), following, action)


class StrategyAdapter:
    """An :class:`~adhoc_advising.strategy.AdvisingStrategy` as the native
    side calls it; counters arrive in the order of
    :class:`~adhoc_advising.strategy.Counters`' fields."""

    __slots__ = ("strategy", "agent")

    def __init__(self, strategy: strategies.AdvisingStrategy, agent: int) -> None:
        if not isinstance(strategy, strategies.AdvisingStrategy):
            raise TypeError(f"{type(strategy).__name__} is not an AdvisingStrategy")
        self.strategy = strategy
        self.agent = agent

    def traits(self) -> dict:
        """Who it is and which decisions it makes, as a strategy process
        answers ``start``."""
        return strategies._traits(self.strategy)

    def reuse(self, key: int, values: RawValues) -> int | None:
        return strategies._action(self.strategy.reuse(key, strategies._values(values)))

    def asks(
        self,
        fresh: bool,
        visits: int,
        episodes: int,
        counters: Sequence[int],
        uncertainty: float | None,
        state: learners.State,
        features: Sequence[float],
        values: RawValues | None,
    ) -> bool:
        at = strategies.AskContext(
            fresh,
            visits,
            episodes,
            _counters(counters),
            uncertainty,
            state,
            tuple(features),
            None if values is None else strategies._values(values),
        )
        return bool(self.strategy.asks(at))

    def advisors(self, me: int, team_size: int, positions: list[tuple[float, float]]) -> list[int]:
        return [int(j) for j in self.strategy.advisors(me, team_size, positions)]

    def gives(
        self,
        visits: int,
        values: RawValues,
        counters: Sequence[int],
        asker: int,
        state: learners.State,
        features: Sequence[float],
    ) -> bool:
        at = strategies.GiveContext(
            visits, strategies._values(values), _counters(counters), asker, state, tuple(features)
        )
        return bool(self.strategy.gives(at))

    def advice(self, values: RawValues) -> int:
        return int(self.strategy.advice(strategies._values(values)))

    def follow(
        self, key: int, advice: Sequence[tuple], shared: Sequence[tuple]
    ) -> tuple[int, int] | None:
        followed = self.strategy.follow(_replies(key, advice, shared))
        return None if followed is None else (int(followed.advisor), int(followed.action))

    def adopt(
        self, key: int, advice: Sequence[tuple], shared: Sequence[tuple], visits: int
    ) -> list[float | None] | None:
        taken = self.strategy.adopt(_replies(key, advice, shared), visits)
        return None if taken is None else list(strategies._values(taken))

    def learn_outcome(self, advisor: int | None, advantage: float) -> None:
        self.strategy.learn_outcome(strategies.Outcome(advisor, advantage))

    def advice_outcome(self, asker: int, followed: bool, advantage: float) -> None:
        self.strategy.advice_outcome(asker, followed, advantage)

    def learned(self, transition: tuple) -> None:
        self.strategy.learned(learners.Transition(*transition))

    def end_episode(self, *end: Any) -> list[tuple]:
        """The batches it sends: ``(to, transitions, notes, standing)``,
        each as tuples."""
        return [_batch_tuple(b) for b in self.strategy.end_episode(_end(*end))]

    def end_evaluation(self, *end: Any) -> None:
        self.strategy.end_evaluation(_end(*end))

    def received(
        self,
        from_: int,
        transitions: list[tuple],
        notes: list[tuple[int, float]],
        standing: tuple[int, float | None, float] | None,
    ) -> list[int] | None:
        """The indices of the transitions its learner learns, ``None``: all."""
        batch = strategies.Batch(
            self.agent,
            tuple(learners.Transition(*t) for t in transitions),
            tuple(strategies.TransitionNote(*n) for n in notes),
            None if standing is None else strategies.Standing(*standing),
        )
        return strategies._indices(self.strategy.received(from_, batch))

    def spent_budget(self, counters: Sequence[int]) -> int:
        return int(self.strategy.spent_budget(_counters(counters)))


def _label(thing: Any) -> str:
    """What the results record of an object: its name, version and class."""
    cls = thing if isinstance(thing, type) else type(thing)
    name = getattr(thing, "name", cls.__name__)
    version = getattr(thing, "version", "")
    where = f"{cls.__module__}.{cls.__qualname__}"
    return " ".join(str(x) for x in (name, version, f"({where})") if x != "")


def made(role: str, thing: Any) -> Made | None:
    """The native side's factory of ``thing``, a ``role`` (``learner`` or
    ``strategy``): a class or a factory taking the role's ``Start``, or an
    instance, copied for every run; ``None`` for none."""
    if thing is None:
        return None
    base, adapter = {
        "learner": (learners.Learner, lambda learner, agent: LearnerAdapter(learner)),
        "strategy": (strategies.AdvisingStrategy, StrategyAdapter),
    }[role]
    if isinstance(thing, base):

        def make(agent: int, team_size: int, run: int, seed: int) -> Any:
            return adapter(copy.deepcopy(thing), agent)

    elif callable(thing):
        actions = tuple(_adhoc_advising.PAPER_ACTIONS)
        if role == "learner":
            features = _adhoc_advising.STATE_FEATURES

            def make(agent: int, team_size: int, run: int, seed: int) -> Any:
                start = learners.Start(agent, team_size, run, seed, features, actions)
                return adapter(thing(start), agent)

        else:

            def make(agent: int, team_size: int, run: int, seed: int) -> Any:
                return adapter(thing(strategies.Start(agent, team_size, run, seed, actions)), agent)

    else:
        raise TypeError(
            f"a {role} is a {base.__name__} class, a factory taking a Start, or a "
            f"{base.__name__} instance, not {type(thing).__name__}"
        )
    return make, _label(thing)
