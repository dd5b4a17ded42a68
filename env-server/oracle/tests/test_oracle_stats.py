"""hfo_oracle.stats against values worked out by hand or by definition."""

import math
import random

import pytest

from hfo_oracle import stats


def test_mean_and_sample_sd():
    assert stats.mean([]) is None
    assert stats.mean([1, 2, 6]) == 3
    assert stats.sample_sd([4]) is None
    assert stats.sample_sd([2, 4, 4, 4, 5, 5, 7, 9]) == pytest.approx(math.sqrt(32 / 7))


def test_wilson_interval():
    assert stats.wilson(0, 0) is None
    # 5 of 10: 50 % [23.66, 76.34].
    p, lo, hi = stats.wilson(5, 10)
    assert p == 50.0
    assert lo == pytest.approx(23.6593, abs=1e-4)
    assert hi == pytest.approx(76.3407, abs=1e-4)
    # 0 of 20: the interval starts at 0 and is not degenerate.
    p, lo, hi = stats.wilson(0, 20)
    assert (p, lo) == (0.0, 0.0)
    assert hi == pytest.approx(16.1125, abs=1e-4)
    p, lo, hi = stats.wilson(20, 20)
    assert (p, hi) == (100.0, 100.0)
    assert lo == pytest.approx(100 - 16.1125, abs=1e-4)


def test_normal_half_width():
    assert stats.normal_half_width(2.0, 16) == pytest.approx(stats.Z95 * 0.5)
    assert stats.Z95 == pytest.approx(1.959964, abs=1e-6)


def test_z_of_two_proportions():
    # 60/100 against 45/100: pooled p 0.525.
    se = math.sqrt(0.525 * 0.475 * (2 / 100))
    assert stats.z_proportions(60, 100, 45, 100) == pytest.approx(0.15 / se)
    assert stats.z_proportions(45, 100, 60, 100) == pytest.approx(-0.15 / se)
    assert stats.z_proportions(1, 0, 1, 10) is None
    assert stats.z_proportions(0, 10, 0, 10) is None  # no variance


def test_welch_z_of_two_means():
    z = stats.z_means(10.0, 3.0, 100, 9.0, 4.0, 50)
    assert z == pytest.approx(1.0 / math.sqrt(9 / 100 + 16 / 50))
    assert stats.z_means(10.0, None, 100, 9.0, 4.0, 50) is None
    assert stats.z_means(None, 3.0, 100, 9.0, 4.0, 50) is None
    assert stats.z_means(10.0, 3.0, 0, 9.0, 4.0, 50) is None
    assert stats.z_means(1.0, 0.0, 5, 1.0, 0.0, 5) is None


def test_pooled_samples_are_their_union():
    rng = random.Random(7)
    samples = [[rng.gauss(m, 3) for _ in range(n)] for m, n in ((60, 40), (70, 25), (55, 3))]
    n, m, sd = stats.pooled((len(s), stats.mean(s), stats.sample_sd(s)) for s in samples)
    union = [x for s in samples for x in s]
    assert n == len(union)
    assert m == pytest.approx(stats.mean(union))
    assert sd == pytest.approx(stats.sample_sd(union))
