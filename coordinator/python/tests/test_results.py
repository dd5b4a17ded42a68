"""adhoc_advising.results.load on the files a real study writes: a small
study played by the coordinator binary, read back as DataFrames whose
numbers agree with one another and with the files."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from conftest import workspace_binary

pandas = pytest.importorskip("pandas")

from adhoc_advising.results import Experiment, Study, load  # noqa: E402

STUDY = """
name = "tiny"
description = "two entries, two runs"
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
name = "adhoc-td"
algorithm = "adhoc-td"
"""


@pytest.fixture(scope="module")
def study_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    directory = tmp_path_factory.mktemp("study")
    config = directory / "tiny.toml"
    config.write_text(STUDY)
    out = directory / "out"
    subprocess.run(
        [
            str(workspace_binary("coordinator")),
            "study",
            "--config",
            str(config),
            "--quiet",
            "--out",
            str(out),
        ],
        check=True,
        capture_output=True,
        timeout=600,
    )
    return out


def test_a_study_loads_as_tidy_frames_that_agree(study_dir: Path) -> None:
    study = load(study_dir)
    assert isinstance(study, Study)
    assert list(study.entries) == ["no-advice", "adhoc-td"]
    # Two entries x two runs x evaluations at 0, 20 and 40.
    assert len(study.curves) == 2 * 2 * 3
    for column in ("entry", "run", "episode", "goal_pct", "give_spent_0", "advising_bytes"):
        assert column in study.curves.columns
    means = study.curves.groupby(["entry", "episode"]).goal_pct.mean()
    for row in study.summary.itertuples():
        assert means[(row.entry, row.episode)] == pytest.approx(row.goal_pct)
    # Every agent's counters at every point, as the runs' JSON hold them.
    assert set(study.agents.agent) == {0, 1, 2}
    assert len(study.agents) == 2 * 2 * 3 * 3
    # Who advised whom, each entry's as its experiment holds it.
    adhoc_td = study.advice[study.advice.entry == "adhoc-td"].drop(columns="entry")
    assert adhoc_td.reset_index(drop=True).equals(study.entries["adhoc-td"].advice)
    assert set(study.advice.columns) == {"entry", "run", "advisee", "advisor", "decisions"}
    # The gains and aggregates name every entry but the baseline's gain.
    assert list(study.gains.entry) == ["adhoc-td"]
    assert {"last_ten_gain", "last_ten_gain_ci_low", "area_gain", "first_gain"} <= set(
        study.gains.columns
    )
    assert list(study.gains.baseline) == ["no-advice"]
    assert set(study.aggregate.window) == {"last_ten", "area"}
    # Each aggregate names its entry's baseline; the baseline's is none.
    baselines = study.aggregate.groupby("entry", sort=False).baseline.first()
    assert baselines.isna()["no-advice"] and baselines["adhoc-td"] == "no-advice"


def test_who_advised_whom_adds_up_to_the_advice_acted_on(study_dir: Path) -> None:
    entry = load(study_dir / "adhoc-td")
    assert isinstance(entry, Experiment)
    assert entry.config["config"]["team"][0]["algorithm"] == "adhoc-td"
    last = entry.agents[entry.agents.episode == 40].set_index(["run", "agent"]).ask_spent
    followed = entry.advice.groupby(["run", "advisee"]).decisions.sum()
    for (run, agent), acted_on in last.items():
        assert followed.get((run, agent), 0) == acted_on


def test_one_run_and_a_wrong_path(study_dir: Path) -> None:
    run = load(study_dir / "adhoc-td" / "run-1.json")
    assert list(run.episode) == [0, 20, 40] and set(run.run) == {1}
    with pytest.raises(FileNotFoundError, match="neither study.json"):
        load(study_dir / "figures")


def test_a_published_study_loads_as_the_study_itself(study_dir: Path, tmp_path: Path) -> None:
    """`analyse DIR --publish DEST` gzips every run (run-<k>.json.gz,
    run-<k>.csv.gz); load() reads them as it reads the plain files."""
    published = tmp_path / "published"
    subprocess.run(
        [str(workspace_binary("analyse")), str(study_dir), "--publish", str(published)],
        check=True,
        capture_output=True,
        timeout=600,
    )
    assert not list(published.glob("*/run-*.json")) and not list(published.glob("*/run-*.csv"))
    assert (published / "adhoc-td" / "run-1.csv.gz").is_file()
    ours, theirs = load(study_dir), load(published)
    assert isinstance(theirs, Study) and len(theirs.curves) == 2 * 2 * 3
    for frame in ("curves", "agents", "summary", "advice", "gains", "aggregate", "comparisons"):
        pandas.testing.assert_frame_equal(getattr(theirs, frame), getattr(ours, frame))
    pandas.testing.assert_frame_equal(
        load(published / "adhoc-td" / "run-1.json.gz"), load(study_dir / "adhoc-td" / "run-1.json")
    )


def test_what_a_reproduction_carries_redraws_its_figures(study_dir: Path, tmp_path: Path) -> None:
    """docs/reproduction/<study>/ keeps study.json, significance.json and each
    entry's config.json and summary.json, not the runs: enough for load()
    and the plots."""
    plots = pytest.importorskip("adhoc_advising.plots")
    pytest.importorskip("matplotlib")
    import shutil

    kept = tmp_path / "kept"
    kept.mkdir()
    for name in ("study.json", "significance.json"):
        shutil.copy(study_dir / name, kept / name)
    for entry in ("no-advice", "adhoc-td"):
        (kept / entry).mkdir()
        for name in ("config.json", "summary.json"):
            shutil.copy(study_dir / entry / name, kept / entry / name)
    study = load(kept)
    assert study.curves.empty and list(study.gains.entry) == ["adhoc-td"]
    assert study.summary.equals(load(study_dir).summary)
    for draw in (plots.curves, plots.gains, plots.gain_vs_messages):
        assert draw(study).has_data()
