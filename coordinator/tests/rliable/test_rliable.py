"""The aggregate statistics of a study's report (coordinator/src/bootstrap.rs)
against rliable's (Agarwal et al. 2021) on the same per-run scores
(../fixtures/scores.json), through `coordinator aggregate`.

Point estimates agree to 1e-9. The intervals are bootstrap percentiles, so
they agree up to Monte-Carlo error: ours come from 2000 resamples, rliable's
here from 20000. With the scores' bootstrap standard deviation s (about 2
goal-% points for the mean and IQM here, 0.12 for P(X > Y)), the standard
error of a 2.5 % quantile of B resamples is sqrt(0.025 * 0.975 / B) / phi(1.96), about 0.06 s for
B = 2000: 0.12 to 0.16 points, and 0.007. The tolerances, 1 point and 0.05,
are some 6 of those standard errors, so the test does not fail by chance
(the endpoints measured differ by at most 0.25 points and 0.008)."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

rliable = pytest.importorskip("rliable")
from rliable import library as rly  # noqa: E402
from rliable import metrics  # noqa: E402

ROOT = Path(__file__).resolve().parents[3]
FIXTURE = ROOT / "coordinator" / "tests" / "fixtures" / "scores.json"
BASELINE = "no-advice"
LEVEL = 0.95
REPS = 20000
#: Tolerances of the interval endpoints (see above).
SCORE_TOLERANCE = 1.0
PROBABILITY_TOLERANCE = 0.05


def coordinator_binary() -> Path:
    """`$COORDINATOR`, else the target directory's debug build; missing, the
    test is skipped on a developer's machine and fails in CI."""
    explicit = os.environ.get("COORDINATOR")
    if explicit:
        return Path(explicit)
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    path = target / "debug" / "coordinator"
    if path.is_file():
        return path
    message = f"no coordinator binary at {path}: build it with `cargo build -p coordinator`"
    if os.environ.get("CI"):
        pytest.fail(message)
    pytest.skip(message)


@pytest.fixture(scope="module")
def ours() -> dict:
    out = subprocess.run(
        [
            coordinator_binary(),
            "aggregate",
            "--scores",
            FIXTURE,
            "--baseline",
            BASELINE,
            "--level",
            str(LEVEL),
        ],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    return json.loads(out)


@pytest.fixture(scope="module")
def scores() -> dict[str, np.ndarray]:
    """Every algorithm's scores as rliable takes them: runs x one task."""
    return {k: np.array(v)[:, None] for k, v in json.loads(FIXTURE.read_text()).items()}


def theirs(score_dict, func):
    return rly.get_interval_estimates(
        score_dict,
        func,
        reps=REPS,
        confidence_interval_size=LEVEL,
        random_state=np.random.RandomState(0),
    )


@pytest.mark.parametrize(
    "name,func", [("mean", metrics.aggregate_mean), ("iqm", metrics.aggregate_iqm)]
)
def test_mean_and_iqm(ours, scores, name, func):
    points, intervals = theirs(scores, func)
    for algorithm in scores:
        got = ours["algorithms"][algorithm]
        assert got[name] == pytest.approx(points[algorithm], abs=1e-9), algorithm
        low, high = got[name + "_ci"]
        assert abs(low - intervals[algorithm][0]) < SCORE_TOLERANCE, (
            algorithm,
            low,
            intervals[algorithm],
        )
        assert abs(high - intervals[algorithm][1]) < SCORE_TOLERANCE, (
            algorithm,
            high,
            intervals[algorithm],
        )


def test_probability_of_improvement(ours, scores):
    others = [a for a in scores if a != BASELINE]
    pairs = {a: [scores[a], scores[BASELINE]] for a in others}
    points, intervals = theirs(pairs, metrics.probability_of_improvement)
    assert "p_improvement" not in ours["algorithms"][BASELINE]
    for algorithm in others:
        got = ours["algorithms"][algorithm]["p_improvement"]
        assert got["estimate"] == pytest.approx(points[algorithm], abs=1e-9), algorithm
        low, high = got["ci"]
        assert abs(low - intervals[algorithm][0]) < PROBABILITY_TOLERANCE, (
            algorithm,
            low,
            intervals[algorithm],
        )
        assert abs(high - intervals[algorithm][1]) < PROBABILITY_TOLERANCE, (
            algorithm,
            high,
            intervals[algorithm],
        )


def test_the_intervals_are_reproducible(ours):
    again = subprocess.run(
        [
            coordinator_binary(),
            "aggregate",
            "--scores",
            FIXTURE,
            "--baseline",
            BASELINE,
            "--level",
            str(LEVEL),
        ],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    assert json.loads(again) == ours
