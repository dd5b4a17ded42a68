"""The files one HFO run leaves, and their parsers.

rcssserver, started by HFO's launcher with logging on, writes into the run's
log directory:

- the trial log ``*.hfo``: one tab-separated line per trial, ``number,
  start cycle, end cycle, duration, result-unum`` (``#`` starts a comment);
- the action log ``*.rcl``: every command each player sent and every
  referee message, each line starting ``cycle,subcycle<TAB>``;
- the game log ``*.rcg`` (version 5): the server's parameters, the player
  types, then one ``(show ...)`` line per cycle with the ball's and every
  player's position, type and command counters.

HFO's trainer prints ``EndOfTrial: <goals> / <trial> <end cycle>
<STATUS>-<unum>`` on the launcher's output, and each agent process of ours
writes its choice file (:func:`read_agent_file`, written with the
``*_line`` functions below).

The game and action logs of 500 episodes take 0.1-0.3 GB, so they are read
line by line, as bytes, decoding only the lines wanted.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from typing import NamedTuple

# HFO's ``statusToString`` (what an agent sees) to its status names.
AGENT_STATUS = {
    "Goal": "GOAL",
    "CapturedByDefense": "CAPTURED_BY_DEFENSE",
    "OutOfBounds": "OUT_OF_BOUNDS",
    "OutOfTime": "OUT_OF_TIME",
}

_REFEREE_END = re.compile(r"\(referee (GOAL|CAPTURED_BY_DEFENSE|OUT_OF_BOUNDS|OUT_OF_TIME)")
_KICK_LINE = re.compile(r"^(\d+),\d+\tRecv base_left_(\d+): .*?\(kick ")
_TYPE_ID = re.compile(r"\(id (\d+)\)")
_KICKABLE_MARGIN = re.compile(r"\(kickable_margin ([-\d.e+]+)\)")
_PLAYER_SIZE = re.compile(r"\(player_size ([-\d.e+]+)\)")
_BALL_SIZE = re.compile(rb"\(ball_size ([-\d.e+]+)\)")


class Trial(NamedTuple):
    """One trial of the ``.hfo`` log: its first and last cycle and HFO's
    status name of its result (``GOAL``, ...)."""

    start: int
    end: int
    result: str


def find_log(logdir: str, suffix: str) -> str:
    """The path of the one file of ``logdir`` whose name ends with
    ``suffix``; RuntimeError when there is none or more than one."""
    names = [n for n in os.listdir(logdir) if n.endswith(suffix)]
    if len(names) != 1:
        raise RuntimeError("expected one %s log in %s, found %r" % (suffix, logdir, names))
    return os.path.join(logdir, names[0])


def parse_hfo_log(path: str) -> list[Trial]:
    """The trials of rcssserver's ``.hfo`` log, in order."""
    trials = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            _num, start, end, _duration, result = line.split("\t")
            trials.append(Trial(int(start), int(end), result.strip().split("-")[0]))
    return trials


def parse_trainer_output(path: str) -> list[tuple[int, str]]:
    """``(end cycle, status name)`` of every ``EndOfTrial:`` line that HFO's
    trainer printed on the launcher's output."""
    ends = []
    with open(path, errors="replace") as f:
        for line in f:
            if line.startswith("EndOfTrial:"):
                t = line.split()
                ends.append((int(t[4]), t[5].split("-")[0]))
    return ends


def parse_rcl(
    path: str, offense: Iterable[int]
) -> tuple[dict[int, list[int]], list[tuple[int, str]]]:
    """From the ``.rcl`` action log: the uniform numbers of the ``offense``
    players that sent a ``(kick ...)`` command, by cycle, and the referee's
    end-of-trial messages as ``(cycle, status name)``."""
    offense = set(offense)
    kicks: dict[int, list[int]] = {}
    ends = []
    with open(path, "rb") as f:
        for raw in f:
            if b"(kick " in raw:
                m = _KICK_LINE.match(raw.decode("ascii", "replace"))
                if m and int(m.group(2)) in offense:
                    kicks.setdefault(int(m.group(1)), []).append(int(m.group(2)))
            elif b"(referee " in raw:
                line = raw.decode("ascii", "replace")
                m = _REFEREE_END.search(line)
                if m:
                    ends.append((int(line[: line.index(",")]), m.group(1)))
    return kicks, ends


@dataclass
class KickAreas:
    """What decides whether the ball is kickable, as the ``.rcg`` header
    gives it: the ball's size and each player type's kickable margin and
    size."""

    ball_size: float = 0.085
    by_type: dict[int, tuple[float, float]] = field(default_factory=dict)

    def radius(self, player_type: int) -> float:
        """The distance from a player of ``player_type`` within which it can
        kick the ball (rcssserver's defaults for a type not listed)."""
        margin, size = self.by_type.get(player_type, (0.7, 0.3))
        return margin + size + self.ball_size


class PlayerShow(NamedTuple):
    """A player in one ``(show ...)`` line: position (m), player type and
    its kick counter."""

    x: float
    y: float
    player_type: int
    kicks: int


class Show(NamedTuple):
    """One ``(show ...)`` line: the cycle, the ball's position and the
    players asked for, by key (such as ``"l 7"``)."""

    cycle: int
    ball: tuple[float, float]
    players: dict[str, PlayerShow]


def iter_rcg(path: str, wanted: Iterable[str], areas: KickAreas) -> Iterator[Show]:
    """The ``(show ...)`` lines of a version 5 ``.rcg`` game log
    (rcssserver's ``logger.cpp``), keeping the players whose keys are in
    ``wanted`` (``"l 7"``: the left side's number 7). ``areas`` is filled
    from the ``server_param`` and ``player_type`` lines, which precede the
    first show."""
    wanted = set(wanted)
    with open(path, "rb") as f:
        for raw in f:
            if raw.startswith(b"(show "):
                yield _show(raw.decode("ascii", "replace"), wanted)
            elif raw.startswith(b"(player_type "):
                line = raw.decode("ascii", "replace")
                pid = int(_TYPE_ID.search(line).group(1))
                margin = float(_KICKABLE_MARGIN.search(line).group(1))
                size = float(_PLAYER_SIZE.search(line).group(1))
                areas.by_type[pid] = (margin, size)
            elif raw.startswith(b"(server_param "):
                m = _BALL_SIZE.search(raw)
                if m:
                    areas.ball_size = float(m.group(1))


def _show(line: str, wanted: set[str]) -> Show:
    # (show C ((b) x y vx vy) ((l 7) type state x y vx vy body neck ... (c kick dash ...)) ...)
    chunks = line.split("((")
    cycle = int(chunks[0].split()[1])
    b = chunks[1].split()  # "b)", x, y, vx, vy)
    ball = (float(b[1]), float(b[2]))
    players = {}
    for chunk in chunks[2:]:
        key = chunk[: chunk.index(")")]
        if key not in wanted:
            continue
        t = chunk.split()  # side, "unum)", type, state, x, y, ...
        counters = t.index("(c")
        players[key] = PlayerShow(float(t[4]), float(t[5]), int(t[2]), int(t[counters + 1]))
    return Show(cycle, ball, players)


# The agents' choice files: one line per fact, space-separated.


def unum_line(unum: int) -> str:
    """``U <unum>``: the agent's uniform number (the first line)."""
    return "U %d\n" % unum


def decision_line(episode: int, step: int, code: str, target: int) -> str:
    """``D <episode> <step> <code> <target>``: in a decision in which it
    could kick, the agent chose the action of ``code``
    (:data:`hfo_oracle.schema.ACTION_CODES`), passing to uniform number
    ``target`` (0: no pass, or no teammate to pass to)."""
    return "D %d %d %s %d\n" % (episode, step, code, target)


def episode_line(episode: int, steps: int, status: str) -> str:
    """``E <episode> <steps> <status>``: the episode ended after ``steps``
    decisions with HFO's ``statusToString`` ``status``."""
    return "E %d %d %s\n" % (episode, steps, status)


class AgentRecord(NamedTuple):
    """An agent's choice file: its uniform number, its choices by
    ``(episode, step)``, and ``(steps, status)`` of every episode."""

    unum: int | None
    decisions: dict[tuple[int, int], str]
    episodes: list[tuple[int, str]]


def read_agent_file(path: str) -> AgentRecord:
    """Reads a choice file written with the ``*_line`` functions."""
    unum, decisions, episodes = None, {}, []
    with open(path) as f:
        for line in f:
            t = line.split()
            if not t:
                continue
            if t[0] == "D":
                decisions[(int(t[1]), int(t[2]))] = t[3]
            elif t[0] == "E":
                episodes.append((int(t[2]), t[3]))
            elif t[0] == "U":
                unum = int(t[1])
    return AgentRecord(unum, decisions, episodes)
