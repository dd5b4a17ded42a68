"""An advising strategy written in Python: the decisions of one agent of an
advising team (when to ask, whom, when to give, what, and what to do with
what arrives), run by the Rust agent process.

The agent keeps everything the framework owns (its learner, the visit counts
n(s), the counters, the exchange over zenoh, network conditions) and asks
this child process for each decision: a team file's
``algorithm = "external"`` with
``strategy_process = { command = ["python3", "my_strategy.py"] }``, or
``agent --strategy "python3 my_strategy.py" ...``. That child calls
:func:`serve` with a factory of :class:`AdvisingStrategy` objects, one per
run, and answers over its standard input and output, one JSON object per
line (docs/strategies.md). Standard library only.

Actions are indices: 0 MOVE, 1 SHOOT, 2 DRIBBLE, 3 PASS_NEAR, 4 PASS_FAR;
advice is a kick action (1-4). Values are Q(s, a) by action index, ``None``
where the learner has not learned the action. A state is the paper's six
features; transitions are :class:`~adhoc_advising.learner.Transition`.
A decision or hook the class does not override costs no message.
"""

from __future__ import annotations

import sys
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from typing import IO, Callable, Optional

from adhoc_advising._channel import serve_lines
from adhoc_advising.learner import State, Transition

#: Q(s, a) by action index, ``None`` where unlearned.
Values = tuple[Optional[float], ...]

#: Kick actions in the order the framework breaks ties: SHOOT, DRIBBLE,
#: PASS_FAR, PASS_NEAR.
KICK_TIE_ORDER = (1, 2, 4, 3)


@dataclass(frozen=True)
class Start:
    """What a strategy is told when its run starts."""

    agent: int
    team_size: int
    run: int
    #: Seed for the strategy's own random choices.
    seed: int
    actions: tuple[str, ...]


@dataclass(frozen=True)
class AdviceCounters:
    """The agent's communication and budget counters (docs/results.md)."""

    advice_requests: int
    advice_replies_received: int
    #: Steps acted on advice: the ask budget spent.
    ask_spent: int
    #: Answers given: the give budget spent.
    advice_given: int
    shared_sent: int
    shared_received: int


#: The name of :class:`AdviceCounters` before 0.3, still importable.
Counters = AdviceCounters


@dataclass(frozen=True)
class AskContext:
    """What an advisee knows when it decides whether to ask."""

    #: The state was not advised yet in this episode.
    fresh: bool
    #: Its visits n(s) of the state.
    visits: int
    training_episodes: int
    counters: AdviceCounters
    #: Its learner's uncertainty there, if the strategy asks by it and the
    #: learner can tell.
    uncertainty: float | None
    #: The state: the paper's six features.
    state: State = (0.0,) * 6
    #: HFO's features of it, where its observations carry them (else empty).
    features: tuple[float, ...] = ()
    #: Its learner's values there, if the strategy asks by them
    #: (``asks_by_values``).
    values: Values | None = None


@dataclass(frozen=True)
class GiveContext:
    """What an advisor knows when it decides whether to answer."""

    #: Its visits n(s) of the advisee's state (0: never met).
    visits: int
    #: Its learner's values there.
    values: Values
    counters: AdviceCounters
    #: The asker's id.
    asker: int = 0
    #: The asker's state: the paper's six features.
    state: State = (0.0,) * 6
    #: HFO's features of it, where the request carries them (else empty).
    features: tuple[float, ...] = ()


@dataclass(frozen=True)
class EndContext:
    """What an agent knows when an episode ends."""

    #: The reward of its terminal step: +1 goal, -1 captured or out, 0
    #: out of time.
    final_reward: float
    #: How it ended: ``"goal"``, ``"captured"``, ``"out_of_bounds"`` or
    #: ``"out_of_time"``.
    outcome: str
    #: The sum of its rewards this episode (undiscounted), the final one
    #: included.
    episode_return: float
    me: int
    team_size: int
    counters: AdviceCounters


@dataclass(frozen=True)
class TransitionNote:
    """What a sender notes of one transition of a batch (EF-OnTL's tuple)."""

    #: The frames from its kick to the next decision, at least 1.
    frames: int
    #: The sender's uncertainty of it (finite).
    uncertainty: float


@dataclass(frozen=True)
class Standing:
    """What an agent tells its teammates of itself with a batch."""

    #: Its training episodes so far.
    episodes: int
    #: The mean uncertainty of the experience it keeps, ``None`` while it
    #: keeps none.
    uncertainty: float | None
    #: Its mean episode return over its recent training episodes.
    mean_return: float


@dataclass(frozen=True)
class Batch:
    """Experience sent to teammate ``to`` at an episode's end, which its
    learner learns as one batch (at most 4096 transitions; notes spanning
    at most 262,144 frames in all)."""

    to: int
    transitions: tuple[Transition, ...]
    #: One note per transition, or none.
    notes: tuple[TransitionNote, ...] = ()
    standing: Standing | None = None


@dataclass(frozen=True)
class Advice:
    """One piece of advice and who gave it."""

    advisor: int
    action: int


@dataclass(frozen=True)
class SharedValues:
    """One sharer's values of the state and its visits of it."""

    advisor: int
    values: Values
    visits: int


@dataclass(frozen=True)
class Replies:
    """What arrived for one request, in the order the advisors were asked."""

    #: The framework's key of the tile-coded state asked about.
    key: int
    advice: tuple[Advice, ...]
    values: tuple[SharedValues, ...]


@dataclass(frozen=True)
class Outcome:
    """How a training decision with the ball turned out."""

    #: The advisor whose advice was played, ``None`` for its own choice.
    advisor: int | None
    #: r + gamma V(s') - V(s) under the values just learned, V a state's
    #: best learned kick action's value (docs/algorithms.md, peer learning).
    advantage: float


def greedy(values: Values) -> int:
    """The greedy kick action, ties to the first in :data:`KICK_TIE_ORDER`
    (an unlearned value counts as 0)."""
    return max(KICK_TIE_ORDER, key=lambda a: values[a] or 0.0)


class AdvisingStrategy:
    """Base class of a strategy. Every decision has the default of the Rust
    seam (``agent::AdvisingStrategy``): never ask, ask nobody, never give,
    advise the greedy action, follow the majority. Override what your
    method decides; the class attributes say which modes it runs in."""

    #: Reported to the framework and logged, so results stay attributable.
    name: str = "python-strategy"
    version: str = "0"
    #: Whether the agent learns (False: a fixed policy).
    learns: bool = True
    #: Whether :meth:`asks` is told the learner's uncertainty.
    asks_by_uncertainty: bool = False
    #: Mistake Correcting: the intended action travels with the request and
    #: advisors that agree stay silent.
    mistake_correcting: bool = False
    #: Whether that intended action is the learner's greedy one (else its
    #: own, exploring, choice).
    intends_greedy: bool = False
    #: Whether its answers are its values (:meth:`adopt` takes them) instead
    #: of an action.
    shares_values: bool = False
    #: Whether :meth:`asks` is told its learner's values
    #: (``AskContext.values``).
    asks_by_values: bool = False
    #: Whether it tells each advisor whose advice arrived how the decision
    #: turned out (that advisor's :meth:`advice_outcome` hears it).
    reports_advice_outcomes: bool = False

    def reuse(self, key: int, values: Values) -> int | None:
        """Advisee, first at a training step with the ball: an action to play
        without asking (advice it stored), or ``None``. Only asked if
        overridden."""
        return None

    def asks(self, at: AskContext) -> bool:
        """Advisee: whether this training step with the ball asks."""
        return False

    def advisors(
        self, me: int, team_size: int, positions: Sequence[tuple[float, float]]
    ) -> Sequence[int]:
        """Advisee: whom to ask (the framework leaves out who is not
        reachable now). ``positions``: every agent's (x, y) on the field."""
        return ()

    def gives(self, at: GiveContext) -> bool:
        """Advisor: whether to answer a request about a state."""
        return False

    def advice(self, values: Values) -> int:
        """Advisor: the action advised where its learner holds ``values``."""
        return greedy(values)

    def follow(self, replies: Replies) -> Advice | None:
        """Advisee: the advice to play (one of ``replies.advice``), or
        ``None`` for its own choice. Default: the majority, ties to the
        action advised first."""
        votes = Counter(a.action for a in replies.advice)
        if not votes:
            return None
        most = max(votes.values())
        return next(a for a in replies.advice if votes[a.action] == most)

    def adopt(self, replies: Replies, visits: int) -> Values | None:
        """Advisee of a value-sharing strategy: the values its learner takes
        as its own for the state (it visited it ``visits`` times), or
        ``None``. Asked only when values arrived."""
        return None

    def learn_outcome(self, outcome: Outcome) -> None:
        """What it learns about its advisors from a decision's outcome. Only
        sent if overridden."""

    def advice_outcome(self, asker: int, followed: bool, advantage: float) -> None:
        """Advisor: ``asker`` (whose strategy reports advice outcomes) tells
        how a decision on which its advice arrived turned out: whether it
        played the action advised, and the decision's advantage. Only sent if
        overridden."""

    def learned(self, transition: Transition) -> None:
        """A training transition its agent just learned. Only sent if
        overridden."""

    def end_episode(self, end: EndContext) -> Sequence[Batch]:
        """A training episode ended: the batches of experience it sends its
        teammates (at most one per teammate), each transition one unit of
        ``shared_sent``. Only asked if overridden."""
        return ()

    def end_evaluation(self, end: EndContext) -> None:
        """An evaluation episode ended. Only sent if overridden."""

    def received(self, from_: int, batch: Batch) -> Sequence[int] | None:
        """A batch of experience arrived from agent ``from_`` (``batch.to``
        is this agent): the indices of the transitions its learner learns as
        one batch, in that order, or ``None`` for all of them as they came
        (an empty list: none). Only asked if overridden."""
        return None

    def spent_budget(self, counters: AdviceCounters) -> int:
        """The budget the results plot: by default the answers given."""
        return counters.advice_given


def _counters(raw: dict) -> Counters:
    return AdviceCounters(**{name: int(raw[name]) for name in AdviceCounters.__dataclass_fields__})


def _values(raw: Sequence[float | None]) -> Values:
    return tuple(None if v is None else float(v) for v in raw)


def _state(raw: Sequence[float] | None) -> State | None:
    return None if raw is None else tuple(float(x) for x in raw)


def _transition(raw: dict) -> Transition:
    return Transition(
        state=tuple(float(x) for x in raw["state"]),
        action=int(raw["action"]),
        reward=float(raw["reward"]),
        next_state=_state(raw["next_state"]),
        next_action=_action(raw["next_action"]),
    )


def _standing(raw: dict | None) -> Standing | None:
    if raw is None:
        return None
    u = None if raw["uncertainty"] is None else float(raw["uncertainty"])
    return Standing(int(raw["episodes"]), u, float(raw["mean_return"]))


def _wire_standing(s: Standing | None) -> dict | None:
    if s is None:
        return None
    u = None if s.uncertainty is None else float(s.uncertainty)
    return {"episodes": int(s.episodes), "uncertainty": u, "mean_return": float(s.mean_return)}


def _batch(message: dict) -> Batch:
    """A batch as it arrived."""
    notes = (TransitionNote(int(n["frames"]), float(n["uncertainty"])) for n in message["notes"])
    return Batch(
        to=int(message["to"]),
        transitions=tuple(_transition(t) for t in message["transitions"]),
        notes=tuple(notes),
        standing=_standing(message["standing"]),
    )


def _wire_batch(b: Batch) -> dict:
    """A batch as the agent reads it."""
    return {
        "to": int(b.to),
        "transitions": [_wire(t) for t in b.transitions],
        "notes": [{"frames": int(n.frames), "uncertainty": float(n.uncertainty)} for n in b.notes],
        "standing": _wire_standing(b.standing),
    }


def _indices(chosen: Sequence[int] | None) -> list[int] | None:
    return None if chosen is None else [int(i) for i in chosen]


def _wire(t: Transition) -> dict:
    """A transition as the agent reads it."""
    return {
        "state": [float(x) for x in t.state],
        "action": int(t.action),
        "reward": float(t.reward),
        "next_state": None if t.next_state is None else [float(x) for x in t.next_state],
        "next_action": _action(t.next_action),
    }


def _end(message: dict) -> EndContext:
    return EndContext(
        final_reward=float(message["final_reward"]),
        outcome=str(message["outcome"]),
        episode_return=float(message["episode_return"]),
        me=int(message["me"]),
        team_size=int(message["team_size"]),
        counters=_counters(message["counters"]),
    )


def _replies(message: dict) -> Replies:
    return Replies(
        key=int(message["key"]),
        advice=tuple(Advice(int(a["advisor"]), int(a["action"])) for a in message["advice"]),
        values=tuple(
            SharedValues(int(v["advisor"]), _values(v["values"]), int(v["visits"]))
            for v in message["values"]
        ),
    )


def _overrides(strategy: AdvisingStrategy, method: str) -> bool:
    return getattr(type(strategy), method) is not getattr(AdvisingStrategy, method)


def _traits(strategy: AdvisingStrategy) -> dict:
    """The ``start`` answer: who it is and which decisions it makes."""
    return {
        "name": strategy.name,
        "version": strategy.version,
        "learns": bool(strategy.learns),
        "reuses": _overrides(strategy, "reuse"),
        "asks_by_uncertainty": bool(strategy.asks_by_uncertainty),
        "mistake_correcting": bool(strategy.mistake_correcting),
        "intends_greedy": bool(strategy.intends_greedy),
        "shares_values": bool(strategy.shares_values),
        "learns_from_outcomes": _overrides(strategy, "learn_outcome"),
        "asks_by_values": bool(strategy.asks_by_values),
        "records_transitions": _overrides(strategy, "learned"),
        "ends_episodes": _overrides(strategy, "end_episode"),
        "ends_evaluations": _overrides(strategy, "end_evaluation"),
        "receives_batches": _overrides(strategy, "received"),
        "reports_advice_outcomes": bool(strategy.reports_advice_outcomes),
        "hears_advice_outcomes": _overrides(strategy, "advice_outcome"),
    }


def _action(value: int | None) -> int | None:
    return None if value is None else int(value)


def _answer(strategy: AdvisingStrategy, message: dict) -> dict | None:
    """The answer to one request of a started strategy (``None``: none)."""
    op = message["op"]
    if op == "reuse":
        return {"action": _action(strategy.reuse(message["key"], _values(message["values"])))}
    if op == "asks":
        at = AskContext(
            fresh=bool(message["fresh"]),
            visits=int(message["visits"]),
            training_episodes=int(message["training_episodes"]),
            counters=_counters(message["counters"]),
            uncertainty=message["uncertainty"],
            state=tuple(float(x) for x in message.get("state", (0.0,) * 6)),
            features=tuple(float(x) for x in message.get("features", ())),
            values=None if message.get("values") is None else _values(message["values"]),
        )
        return {"decision": bool(strategy.asks(at))}
    if op == "advisors":
        positions = [tuple(p) for p in message["positions"]]
        chosen = strategy.advisors(message["me"], message["team_size"], positions)
        return {"advisors": [int(j) for j in chosen]}
    if op == "gives":
        at = GiveContext(
            visits=int(message["visits"]),
            values=_values(message["values"]),
            counters=_counters(message["counters"]),
            asker=int(message.get("asker", 0)),
            state=tuple(float(x) for x in message.get("state", (0.0,) * 6)),
            features=tuple(float(x) for x in message.get("features", ())),
        )
        return {"decision": bool(strategy.gives(at))}
    if op == "advice":
        return {"action": int(strategy.advice(_values(message["values"])))}
    if op == "follow":
        followed = strategy.follow(_replies(message))
        if followed is None:
            return {"advice": None}
        return {"advice": {"advisor": int(followed.advisor), "action": int(followed.action)}}
    if op == "adopt":
        taken = strategy.adopt(_replies(message), int(message["visits"]))
        return {"values": None if taken is None else list(_values(taken))}
    if op == "learn_outcome":
        strategy.learn_outcome(Outcome(message["advisor"], float(message["advantage"])))
        return None
    if op == "advice_outcome":
        strategy.advice_outcome(
            int(message["asker"]), bool(message["followed"]), float(message["advantage"])
        )
        return None
    if op == "learned":
        strategy.learned(_transition(message["transition"]))
        return None
    if op == "end_episode":
        return {"batches": [_wire_batch(b) for b in strategy.end_episode(_end(message))]}
    if op == "end_evaluation":
        strategy.end_evaluation(_end(message))
        return None
    if op == "received":
        return {"learn": _indices(strategy.received(int(message["from"]), _batch(message)))}
    if op == "spent_budget":
        return {"spent": int(strategy.spent_budget(_counters(message["counters"])))}
    raise ValueError(f"unknown request `{op}`")


def serve(
    make: Callable[[Start], AdvisingStrategy],
    requests: IO[str] = sys.stdin,
    answers: IO[str] = sys.stdout,
) -> int:
    """Answers the agent process until it closes ``requests``; returns the
    exit status. A strategy that raises is reported to the agent (which ends
    with a line naming it and the exception) and ends the loop with 1.
    ``print()`` in the class goes to standard error (the agent's log), not
    to the channel."""
    strategy: AdvisingStrategy | None = None

    def answer(message: dict) -> dict | None:
        nonlocal strategy
        if message["op"] == "start":
            fields = {k: v for k, v in message.items() if k != "op"}
            fields["actions"] = tuple(fields["actions"])
            strategy = make(Start(**fields))
            return _traits(strategy)
        if strategy is None:
            raise RuntimeError(f"`{message['op']}` before `start`")
        return _answer(strategy, message)

    return serve_lines(answer, requests, answers)
