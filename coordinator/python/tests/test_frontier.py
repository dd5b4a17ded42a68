"""The communication frontier from Python: a tiny study that sweeps a
method's budgets, played in process, read by load() (Study.frontier) and
drawn by plots.frontier, held against the runs' own counters."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

pandas = pytest.importorskip("pandas")
pytest.importorskip("matplotlib")

import matplotlib  # noqa: E402

matplotlib.use("Agg")

from matplotlib.collections import PathCollection  # noqa: E402

import adhoc_advising as aa  # noqa: E402
from adhoc_advising import plots  # noqa: E402

STUDY = """
name = "tiny-frontier"
description = "a swept method, a control that sends nothing"
runs = 2
episodes = 40
eval_every = 20
eval_episodes = 5
seed = 3
transport = "in-process"
baseline = "no-advice"

[[entry]]
name = "no-advice"
algorithm = "no-advice"

[[entry]]
name = "control"
algorithm = "no-advice"

[[entry]]
algorithm = "early-advising"
sweep = { ask_budget = [2, 200], give_budget = [2, 200] }
"""


@pytest.fixture(scope="module")
def study_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    directory = tmp_path_factory.mktemp("frontier")
    config = directory / "tiny-frontier.toml"
    config.write_text(STUDY)
    return aa.study(config=config, out=directory / "out", progress=False)


def test_the_frontier_loads_with_the_costs_the_runs_counted(study_dir: Path) -> None:
    study = aa.load(study_dir)
    f = study.frontier.set_index("entry")
    swept = [e for e in study.entries if e.startswith("early-advising-")]
    assert list(f.index) == ["control", *swept] and len(swept) == 2
    assert set(f.loc[swept, "group"]) == {"early-advising"}
    assert f.loc["control", "group"] == "control" and f.loc["control", "messages"] == 0
    # Each cost: per run, the team's advising messages at the last
    # evaluation over its agents and the training episodes; mean over runs.
    last = study.agents[study.agents.episode == 40]
    per_run = last.groupby(["entry", "run"]).advising_messages.sum() / (3 * 40)
    for entry in swept:
        assert f.loc[entry, "messages"] == pytest.approx(per_run[entry].mean())
    # The gains are the report's.
    gains = study.gains.set_index("entry").last_ten_gain
    assert f.last_ten_gain.to_dict() == pytest.approx(gains.to_dict())


def test_the_figure_draws_each_group_in_cost_order_with_its_front_ringed(
    study_dir: Path,
) -> None:
    study = aa.load(study_dir)
    for cost in ("messages", "bytes"):
        ax = plots.frontier(study, cost=cost)
        assert ax.get_xscale() == "log"
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert labels == ["control (sent none)", "early-advising"]
        swept = study.frontier[study.frontier.group == "early-advising"]
        curve = next(c for c in ax.containers if c.get_label() == "early-advising")
        assert list(curve.lines[0].get_xdata()) == sorted(swept[cost])
        # Every entry on the front that a log axis can place is ringed.
        rings = sum(len(c.get_offsets()) for c in ax.collections if isinstance(c, PathCollection))
        assert rings == int(swept[f"front_{cost}"].sum())
    with pytest.raises(ValueError, match="messages"):
        plots.frontier(study, cost="frames")


def test_a_study_without_a_frontier_says_so(study_dir: Path, tmp_path: Path) -> None:
    copy = tmp_path / "copy"
    shutil.copytree(study_dir, copy)
    significance = json.loads((copy / "significance.json").read_text())
    del significance["frontier"]
    (copy / "significance.json").write_text(json.dumps(significance))
    study = aa.load(copy)
    assert study.frontier.empty
    with pytest.raises(ValueError, match="no frontier"):
        plots.frontier(study)
