"""Experiments and studies in this process: :func:`run` and :func:`study`
take the arguments of ``coordinator run`` and ``coordinator study`` and
write the same files (docs/results.md), which :func:`adhoc_advising.load`
reads back as DataFrames.

The Rust learners are the command line's, bit for bit. A team may also give
an agent a Python learner (``learner=``, an
:class:`adhoc_advising.learner.Learner`) or a Python strategy as its
algorithm (``algorithm=``, an
:class:`adhoc_advising.strategy.AdvisingStrategy`, recorded as algorithm
``external``): as a class, made for every run with its
``Start`` (whose ``seed`` is the agent's), or as an instance, copied for
every run. It is called directly, in this process. Its exceptions end the
run and are raised again as the cause of a ``RuntimeError`` naming the agent
and the call; the runs finished before stay on disk.

The GIL is released while Rust plays; Ctrl-C stops after the episodes in
flight, the files whole, and the same call resumes.
"""

from __future__ import annotations

import json
import math
import os
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Union

from adhoc_advising import _adhoc_advising
from adhoc_advising._objects import Made, made

#: A team: a team file's path, the agents' tables (each as a team file's
#: ``[[agent]]`` table, where ``learner`` may be a Python learner and
#: ``algorithm`` a Python strategy), or both ``{"agent": [...], "event": [...]}``.
TeamSpec = Union[str, "os.PathLike[str]", Sequence[Mapping[str, Any]], Mapping[str, Any]]


def _team_tables(team: Any) -> tuple[str, list[tuple[Made | None, Made | None]]]:
    """The team's tables as JSON and, per agent, its Python learner and
    strategy: ``learner`` given as an object, ``algorithm`` given as a
    strategy (recorded as algorithm ``external``; ``strategy`` with
    ``algorithm = "external"`` is its spelling before 0.3)."""
    tables = {"agent": team} if not isinstance(team, Mapping) else dict(team)
    agents = []
    objects: list[tuple[Made | None, Made | None]] = []
    for i, table in enumerate(tables.get("agent", [])):
        if not isinstance(table, Mapping):
            kind = type(table).__name__
            raise TypeError(f"team[{i}] must be a dict of an agent's keys, got {kind}")
        table = dict(table)
        algorithm = table.get("algorithm")
        if algorithm is not None and not isinstance(algorithm, str):
            table["algorithm"] = "external"
            table["strategy"] = algorithm
        # What a file could say (a learner's name or process, the old
        # spelling of `algorithm`) stays in the table; anything else is an
        # object.
        given = {
            role: table.pop(role)
            for role in ("learner", "strategy")
            if role in table and not isinstance(table[role], (str, Mapping))
        }
        objects.append(
            (made("learner", given.get("learner")), made("strategy", given.get("strategy")))
        )
        agents.append(table)
    tables["agent"] = agents
    return json.dumps(_finite_or_null(tables), allow_nan=False), objects


def _finite_or_null(value: Any) -> Any:
    """``value`` with NaN and infinities as ``None`` (JSON's null), which
    the native side refuses naming the key, as it does a file's NaN."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, Mapping):
        return {key: _finite_or_null(v) for key, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite_or_null(v) for v in value]
    return value


def _team(team: TeamSpec | None) -> tuple[str | None, str | None, list]:
    """A team as the native side takes it: a file, or tables and objects."""
    if isinstance(team, (str, os.PathLike)):
        return os.fspath(team), None, []
    if team is None:
        return None, None, []
    tables, objects = _team_tables(team)
    return None, tables, objects


def run(
    *,
    out: str | os.PathLike[str],
    algorithm: str | None = None,
    team: TeamSpec | None = None,
    mistake_correcting: bool = False,
    learner: str | None = None,
    runs: int = 50,
    episodes: int = 5000,
    eval_every: int = 20,
    eval_episodes: int = 100,
    seed: int = 1,
    profile: str = "paper",
    ci_level: float | None = None,
    offense: int | None = None,
    evaluation_memory: str = "carried",
    advice_latency: str | None = None,
    advice_loss: float | None = None,
    advice_timeout_ms: int | None = None,
    threads: int | None = None,
    save_agents: str | os.PathLike[str] | None = None,
    progress: bool | None = None,
) -> Path:
    """Plays an experiment into ``out`` as ``coordinator run --transport
    in-process`` does with the same options (docs/settings.md), and returns
    ``out``. ``algorithm`` (every agent) or ``team``: a team file's path, or
    its agents' tables as dicts, where ``learner`` and ``strategy`` may be
    Python objects. ``learner``: with ``algorithm``, every agent's Rust
    learner by name (``"sarsa"``, ``"ensemble"``, ``"dqn"``; default: the
    one the algorithm needs), as ``--learner``.
    ``progress``: a bar on stderr (default: when stderr is a terminal).
    An existing ``out`` of the same experiment is resumed."""
    team_file, team_tables, objects = _team(team)
    if progress is None:
        progress = sys.stderr.isatty()
    _adhoc_advising.run(
        out=os.fspath(out),
        objects=objects,
        algorithm=algorithm,
        team_file=team_file,
        team_tables=team_tables,
        mistake_correcting=mistake_correcting,
        learner=learner,
        runs=runs,
        episodes=episodes,
        eval_every=eval_every,
        eval_episodes=eval_episodes,
        seed=seed,
        profile=profile,
        ci_level=ci_level,
        offense=offense,
        evaluation_memory=evaluation_memory,
        advice_latency=advice_latency,
        advice_loss=advice_loss,
        advice_timeout_ms=advice_timeout_ms,
        threads=threads,
        save_agents=None if save_agents is None else os.fspath(save_agents),
        progress=progress,
    )
    return Path(out)


def study(
    *,
    out: str | os.PathLike[str],
    preset: str | None = None,
    config: str | os.PathLike[str] | None = None,
    runs: int | None = None,
    episodes: int | None = None,
    threads: int | None = None,
    progress: bool | None = None,
) -> Path:
    """Plays a study into ``out`` as ``coordinator study`` does: ``preset``
    (e.g. ``"quick"``, ``"paper-scratch"``) or a study file ``config``,
    with ``runs`` and ``episodes`` overriding every experiment's; statistics,
    figures and ``REPORT.md``. Returns ``out``; an existing ``out`` of the
    same study is resumed."""
    if progress is None:
        progress = sys.stderr.isatty()
    _adhoc_advising.study(
        out=os.fspath(out),
        preset=preset,
        config=None if config is None else os.fspath(config),
        runs=runs,
        episodes=episodes,
        threads=threads,
        progress=progress,
    )
    return Path(out)


@dataclass(frozen=True)
class Replay:
    """One recorded evaluation episode of a team. In a notebook it shows
    as its animation."""

    #: How it ended, e.g. ``"goal after 87 frames"``.
    summary: str
    #: The animation: players and ball moving, 10 frames a second (SVG).
    svg: str
    #: Every path of the episode in one still picture (SVG).
    paths_svg: str
    #: The episode as an rcssserver game log (version 5), for rcssmonitor
    #: or soccerwindow2.
    rcg: str

    def _repr_svg_(self) -> str:
        return self.svg

    def save(self, path: str | os.PathLike[str]) -> Path:
        """Writes it by the name's suffix: ``.svg`` (the animation),
        ``.html`` (the animation in a page) or ``.rcg`` (the game log)."""
        path = Path(path)
        contents = {
            ".svg": self.svg,
            ".html": f"<!doctype html><title>{self.summary}</title>\n{self.svg}\n",
            ".rcg": self.rcg,
        }.get(path.suffix)
        if contents is None:
            raise ValueError(f"{path}: the name must end in .svg, .html or .rcg")
        path.write_text(contents)
        return path


def replay(
    *,
    algorithm: str | None = None,
    team: TeamSpec | None = None,
    seed: int = 1,
    episode: int = 1,
    profile: str = "paper",
) -> Replay:
    """Plays evaluation episode ``episode`` (1-based) of a team on a
    simulator seeded ``seed`` and records it: its agents as a run starts
    them (a team's ``load`` snapshots, e.g. ``run(save_agents=...)``'s),
    greedy, learning nothing."""
    team_file, team_tables, objects = _team(team)
    summary, svg, paths_svg, rcg = _adhoc_advising.replay(
        objects=objects,
        algorithm=algorithm,
        team_file=team_file,
        team_tables=team_tables,
        seed=seed,
        episode=episode,
        profile=profile,
    )
    return Replay(summary, svg, paths_svg, rcg)
