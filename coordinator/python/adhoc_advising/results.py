"""The results of `coordinator run` and `coordinator study` as tidy pandas
DataFrames, columns named as docs/results.md names them.

    >>> from adhoc_advising.results import load
    >>> study = load("out/advising-methods")        # a study directory
    >>> study.curves.groupby(["entry", "episode"]).goal_pct.mean()
    >>> study.gains                                  # one row per entry

:func:`load` takes a study directory (``study.json``), an experiment
directory (``config.json``) or one run's ``run-<k>.json``, and reads only
what those files hold: nothing is recomputed. A published study
(``analyse DIR --publish DEST``) holds its runs gzipped, ``run-<k>.json.gz``
and ``run-<k>.csv.gz``: they are read where the plain files are absent.
pandas is needed (``pip install pandas``); nothing else.
"""

from __future__ import annotations

import gzip
import json
import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import pandas as pd

#: The estimates of a `summary.json` evaluation point, each with its mean and
#: interval (columns `<metric>`, `<metric>_ci_low`, `<metric>_ci_high`, `<metric>_n`).
SUMMARY_METRICS = (
    "goal_pct",
    "time_to_goal",
    "spent_budget",
    "advising_messages",
    "advising_bytes",
)

#: The estimates of a `significance.json` frontier point.
FRONTIER_ESTIMATES = ("messages", "bytes", "last_ten_gain", "area_gain")
#: The estimates of a gain; `first` and `first_gain` (the jumpstart) are
#: absent from significance.json files written before them.
GAIN_ESTIMATES = ("last_ten", "last_ten_gain", "area", "area_gain", "first", "first_gain")


def _pandas() -> Any:
    try:
        import pandas
    except ImportError as error:  # pragma: no cover - depends on the environment
        raise ImportError("adhoc_advising.results needs pandas: pip install pandas") from error
    return pandas


@dataclass(frozen=True)
class Experiment:
    """One experiment directory (`coordinator run --out DIR`, or a study's
    entry)."""

    path: Path
    #: `config.json`: the format version, the configuration, snapshot digests.
    config: dict
    #: Every run's evaluation points: `run`, then the columns of `run-<k>.csv`
    #: (`episode`, `goal_pct`, `time_to_goal`, ..., `advising_bytes`).
    curves: pd.DataFrame
    #: Every agent's counters at every point: `run`, `episode`, `agent`, and
    #: `run-<k>.json`'s `points[].agents[]` keys (`give_spent`, `ask_spent`, ...).
    agents: pd.DataFrame
    #: `summary.json`'s points: `episode`, and per metric its mean, interval
    #: and sample size; empty before the experiment finished.
    summary: pd.DataFrame
    #: Who advised whom: `run`, `advisee`, `advisor`, `decisions` (absent
    #: runs acted on no advice).
    advice: pd.DataFrame


@dataclass(frozen=True)
class Study:
    """One study directory (`coordinator study --out DIR`)."""

    path: Path
    #: `study.json`.
    config: dict
    #: Each entry's experiment, by name, in the study's order.
    entries: dict[str, Experiment] = field(repr=False)
    #: Every entry's curves, with an `entry` column first.
    curves: pd.DataFrame = field(repr=False)
    #: Every entry's agents' counters, with an `entry` column first.
    agents: pd.DataFrame = field(repr=False)
    #: Every entry's summary points, with an `entry` column first.
    summary: pd.DataFrame = field(repr=False)
    #: Every entry's who advised whom, with an `entry` column first.
    advice: pd.DataFrame = field(repr=False)
    #: `significance.json`'s `gains`: one row per entry compared with a
    #: baseline, with its `baseline`, each estimate as `<name>`,
    #: `<name>_ci_low`, `<name>_ci_high`, `<name>_n`.
    gains: pd.DataFrame = field(repr=False)
    #: `significance.json`'s `aggregate`: one row per entry and window
    #: (`last_ten`, `area`): its `baseline` (None for a baseline), `mean`,
    #: `mean_ci_low`, ..., `p_improvement`.
    aggregate: pd.DataFrame = field(repr=False)
    #: `significance.json`'s `holm`: one row per entry.
    holm: pd.DataFrame = field(repr=False)
    #: `significance.json`'s `comparisons`: one row per pair.
    comparisons: pd.DataFrame = field(repr=False)
    #: `significance.json`'s `frontier.points`: one row per entry compared
    #: with a baseline, with its `group`, its `baseline`, its costs `messages` and `bytes` and its
    #: `last_ten_gain` and `area_gain` (each as in :attr:`gains`),
    #: `front_messages`, `front_bytes` and `messages_per_point`; empty
    #: without a frontier.
    frontier: pd.DataFrame = field(repr=False)


def load(path: str | Path) -> Study | Experiment | pd.DataFrame:
    """A study (a directory with `study.json`), an experiment (a directory
    with `config.json`) or one run (a `run-<k>.json` or `run-<k>.json.gz`
    file: its curve, as :attr:`Experiment.curves` holds it)."""
    path = Path(path)
    if path.is_file():
        return _run_points(path)
    if (path / "study.json").is_file():
        return _study(path)
    if (path / "config.json").is_file():
        return _experiment(path)
    raise FileNotFoundError(
        f"{path} holds neither study.json (a study) nor config.json (an experiment), "
        "and is not a run-<k>.json(.gz) file"
    )


def _read_json(path: Path) -> Any:
    """A JSON file, gunzipped when its name ends in `.gz`."""
    opener = gzip.open if path.suffix == ".gz" else open
    with opener(path, "rt", encoding="utf-8") as f:
        return json.load(f)


def _plain_or_gzipped(path: Path) -> Path:
    """`path`, or its gzipped copy `<path>.gz` (a published study's) when
    only that exists."""
    gzipped = path.with_name(path.name + ".gz")
    return gzipped if not path.is_file() and gzipped.is_file() else path


def _runs(directory: Path) -> list[int]:
    """The finished runs of an experiment directory (`run-<k>.json`, or
    `run-<k>.json.gz` in a published study), in order."""
    found = (re.fullmatch(r"run-(\d+)\.json(\.gz)?", p.name) for p in directory.iterdir())
    return sorted({int(m.group(1)) for m in found if m})


def _run_points(path: Path) -> pd.DataFrame:
    """One run's curve, from its JSON file (as its CSV's columns)."""
    pandas = _pandas()
    run = _read_json(path)
    rows = []
    for point in run["points"]:
        row = {"run": run["run"]}
        row.update({k: v for k, v in point.items() if k != "agents"})
        rows.append(row)
    return pandas.DataFrame(rows)


def _curves(directory: Path, runs: list[int]) -> pd.DataFrame:
    """Every finished run's `run-<k>.csv`, with a `run` column first."""
    pandas = _pandas()
    frames = []
    for k in runs:
        frame = pandas.read_csv(_plain_or_gzipped(directory / f"run-{k}.csv"))
        frame.insert(0, "run", k)
        frames.append(frame)
    return pandas.concat(frames, ignore_index=True) if frames else pandas.DataFrame()


def _experiment(directory: Path) -> Experiment:
    pandas = _pandas()
    runs = _runs(directory)
    agents, advice = [], []
    for k in runs:
        run = _read_json(_plain_or_gzipped(directory / f"run-{k}.json"))
        for point in run["points"]:
            for i, counters in enumerate(point["agents"]):
                agents.append({"run": k, "episode": point["episode"], "agent": i, **counters})
        for i, row in enumerate(run.get("advice_matrix", [])):
            for j, decisions in enumerate(row):
                if i != j:
                    advice.append({"run": k, "advisee": i, "advisor": j, "decisions": decisions})
    summary_path = directory / "summary.json"
    points = _read_json(summary_path)["eval_points"] if summary_path.is_file() else []
    # Unknown estimates (null) as NaN, so every column is numeric.
    summary = pandas.DataFrame(
        [{"episode": p["episode"], **_flatten(p, SUMMARY_METRICS)} for p in points]
    ).apply(pandas.to_numeric)
    return Experiment(
        path=directory,
        config=_read_json(directory / "config.json"),
        curves=_curves(directory, runs),
        agents=pandas.DataFrame(agents),
        summary=summary,
        advice=pandas.DataFrame(advice, columns=["run", "advisee", "advisor", "decisions"]),
    )


def _flatten(record: dict, names: Sequence[str]) -> dict:
    """`{name: {n, mean, ci_low, ci_high}}` as `name`, `name_ci_low`,
    `name_ci_high`, `name_n`."""
    flat = {}
    for name in names:
        estimate = record[name]
        flat[name] = estimate["mean"]
        flat[f"{name}_ci_low"] = estimate["ci_low"]
        flat[f"{name}_ci_high"] = estimate["ci_high"]
        flat[f"{name}_n"] = estimate["n"]
    return flat


def _with_entry(frames: dict[str, pd.DataFrame]) -> pd.DataFrame:
    pandas = _pandas()
    tagged = [f.assign(entry=name) for name, f in frames.items() if not f.empty]
    if not tagged:
        return pandas.DataFrame()
    joined = pandas.concat(tagged, ignore_index=True)
    return joined[["entry", *[c for c in joined.columns if c != "entry"]]]


def _study(directory: Path) -> Study:
    pandas = _pandas()
    config = _read_json(directory / "study.json")
    entries = {
        e["name"]: _experiment(directory / e["name"])
        for e in config["entry"]
        if (directory / e["name"] / "config.json").is_file()
    }
    significance_path = directory / "significance.json"
    significance = _read_json(significance_path) if significance_path.is_file() else {}
    gains = pandas.DataFrame(
        [
            {
                "entry": g["entry"],
                "baseline": g["baseline"],
                **_flatten(g, [name for name in GAIN_ESTIMATES if name in g]),
            }
            for g in significance.get("gains", [])
        ]
    )
    aggregate_rows = []
    for e in (significance.get("aggregate") or {}).get("entries", []):
        for window in ("last_ten", "area"):
            a = e.get(window)
            if not a:
                continue
            improvement = a.get("p_improvement") or {}
            ci = improvement.get("ci") or [None, None]
            aggregate_rows.append(
                {
                    "entry": e["entry"],
                    "baseline": e.get("baseline"),
                    "window": window,
                    "mean": a["mean"],
                    "mean_ci_low": a["mean_ci"][0],
                    "mean_ci_high": a["mean_ci"][1],
                    "iqm": a["iqm"],
                    "iqm_ci_low": a["iqm_ci"][0],
                    "iqm_ci_high": a["iqm_ci"][1],
                    "p_improvement": improvement.get("estimate"),
                    "p_improvement_ci_low": ci[0],
                    "p_improvement_ci_high": ci[1],
                }
            )
    frontier = pandas.DataFrame(
        [
            {
                "entry": p["entry"],
                "group": p["group"],
                "baseline": p.get("baseline"),
                **_flatten(p, FRONTIER_ESTIMATES),
                "front_messages": p["front_messages"],
                "front_bytes": p["front_bytes"],
                "messages_per_point": p["messages_per_point"],
            }
            for p in (significance.get("frontier") or {}).get("points", [])
        ]
    )
    if not frontier.empty:
        numeric = [c for c in frontier.columns if c not in ("entry", "group", "baseline")]
        frontier[numeric] = frontier[numeric].apply(pandas.to_numeric)
    return Study(
        path=directory,
        config=config,
        entries=entries,
        curves=_with_entry({n: e.curves for n, e in entries.items()}),
        agents=_with_entry({n: e.agents for n, e in entries.items()}),
        summary=_with_entry({n: e.summary for n, e in entries.items()}),
        advice=_with_entry({n: e.advice for n, e in entries.items()}),
        gains=gains,
        aggregate=pandas.DataFrame(aggregate_rows),
        holm=pandas.DataFrame(significance.get("holm", [])),
        comparisons=pandas.DataFrame(significance.get("comparisons", [])),
        frontier=frontier,
    )
