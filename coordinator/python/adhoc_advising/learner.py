"""A learner written in Python as one agent of an advising team.

The `agent` process of the Rust implementation keeps everything the advising
framework owns (budgets, the ask and give probabilities, the visit counts
n(s), votes, the protocol over zenoh) and hands the learning to a child
process: ``agent --id 2 --team-size 3 ... -- python3 my_learner.py``, or a
team file's ``learner = ["python3", "my_learner.py"]``. That child calls
:func:`serve` with a factory of :class:`Learner` objects, one per run, and
answers over its standard input and output, one JSON object per line
(docs/learners.md). Standard library only; the learner may use anything.

A state is the paper's six features (a tuple of floats) and ``index``, the
framework's number of its tile-coded state (``None`` for a state training
never met). Actions are indices into ``actions`` of :class:`Start`:
0 MOVE, 1 SHOOT, 2 DRIBBLE, 3 PASS_NEAR, 4 PASS_FAR; a kicker chooses 1-4.
"""

from __future__ import annotations

import base64
import math
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from typing import IO, Callable

from adhoc_advising._channel import serve_lines

State = tuple[float, ...]


@dataclass(frozen=True)
class Start:
    """What a learner is told when its run starts."""

    agent: int
    team_size: int
    run: int
    #: Seed for the learner's own random choices.
    seed: int
    features: int
    actions: tuple[str, ...]


@dataclass(frozen=True)
class Transition:
    """One step of an episode: ``next_state``/``next_action`` are ``None``
    when the episode ended with it."""

    state: State
    action: int
    reward: float
    next_state: State | None
    next_action: int | None


class Learner:
    """Base class of a learner; override :meth:`values`, :meth:`choose`,
    :meth:`learn` and, where it keeps per-episode state, :meth:`end_episode`."""

    #: Reported to the framework and logged, so results stay attributable.
    name: str = "python-learner"
    version: str = "0"

    def values(self, state: State, index: int | None) -> Sequence[float | None]:
        """Q(s, a) for every action (5), ``None`` for an action it has not
        learned. AdHocTD's and Torrey's confidence is the spread of the kick
        actions' values; an advisor's answer is their argmax."""
        raise NotImplementedError

    def choose(self, state: State, index: int | None) -> int:
        """Its own action (1-4) when it can kick and trains, exploring."""
        raise NotImplementedError

    def learn(self, transition: Transition) -> None:
        """Learns one transition of its own (training only)."""
        raise NotImplementedError

    def end_episode(self) -> None:
        """The episode ended (e.g. clear eligibility traces)."""

    def save(self) -> bytes | None:
        """Its learned state as bytes, for a snapshot (``save_agents``,
        ``load``, a restart after a crash); ``None`` (the default): it has no
        snapshot."""
        return None

    def restore(self, state: bytes) -> None:
        """Starts again from bytes :meth:`save` returned."""
        raise NotImplementedError(f"{type(self).__name__} cannot restore a saved state")

    def replay(self, episode: Sequence[Transition]) -> None:
        """Learns a teammate's shared goal episode (EpisodeSharing); by
        default as its own steps, then ends that episode."""
        for transition in episode:
            self.learn(transition)
        self.end_episode()


def _state(value: Sequence[float] | None) -> State | None:
    return None if value is None else tuple(float(x) for x in value)


def _transition(message: dict) -> Transition:
    return Transition(
        state=_state(message["state"]),  # type: ignore[arg-type]
        action=int(message["action"]),
        reward=float(message["reward"]),
        next_state=_state(message["next_state"]),
        next_action=message["next_action"],
    )


def _answer(learner: Learner | None, message: dict, make: Callable[[Start], Learner]):
    """The learner after `message`, and the answer to write (or ``None``)."""
    op = message["op"]
    if op == "start":
        fields = {k: v for k, v in message.items() if k != "op"}
        fields["actions"] = tuple(fields["actions"])
        learner = make(Start(**fields))
        return learner, {"name": learner.name, "version": learner.version}
    if learner is None:
        raise RuntimeError(f"`{op}` before `start`")
    if op == "values":
        values = learner.values(_state(message["state"]), message["index"])
        q = [None if v is None else float(v) for v in values]
        bad = [v for v in q if v is not None and not math.isfinite(v)]
        if bad:
            raise ValueError(f"values() returned {bad[0]}, not a finite number")
        return learner, {"q": q}
    if op == "choose":
        action = learner.choose(_state(message["state"]), message["index"])
        return learner, {"action": int(action)}
    if op == "save":
        state = learner.save()
        return learner, {"state": None if state is None else base64.b64encode(state).decode()}
    if op == "restore":
        learner.restore(base64.b64decode(message["state"]))
        return learner, {}
    if op == "learn":
        learner.learn(_transition(message))
    elif op == "end_episode":
        learner.end_episode()
    elif op == "replay":
        learner.replay([_transition(t) for t in message["episode"]])
    else:
        raise ValueError(f"unknown request `{op}`")
    return learner, None


def serve(
    make: Callable[[Start], Learner],
    requests: IO[str] = sys.stdin,
    answers: IO[str] = sys.stdout,
) -> int:
    """Answers the agent process until it closes ``requests``; returns the
    exit status. A learner that raises is reported to the agent (which ends
    with a line naming it and the exception) and ends the loop with 1.
    ``print()`` in the class goes to standard error (the agent's log), not
    to the channel."""
    learner: Learner | None = None

    def answer(message: dict) -> dict | None:
        nonlocal learner
        learner, reply = _answer(learner, message, make)
        return reply

    return serve_lines(answer, requests, answers)
