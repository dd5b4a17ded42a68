"""The statistics of the oracle's tables: means and sample standard
deviations, Wilson intervals for percentages, normal intervals for means,
two-sample z statistics, and runs pooled into one sample.

The one copy of these formulas: the harness (:mod:`hfo_oracle.tally`),
``team_ours.py``, ``compare.py`` and ``learned.py`` all use it.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

# The two-sided 95 % quantile of the standard normal distribution.
Z95 = 1.959963984540054


def mean(xs: Sequence[float]) -> float | None:
    """The mean of ``xs``, or None when it is empty."""
    return sum(xs) / len(xs) if xs else None


def sample_sd(xs: Sequence[float]) -> float | None:
    """The sample standard deviation of ``xs`` (n - 1 in the denominator), or
    None below two values."""
    if len(xs) < 2:
        return None
    m = sum(xs) / len(xs)
    return math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1))


def wilson(k: int, n: int, z: float = Z95) -> tuple[float, float, float] | None:
    """``k`` successes out of ``n`` as a percentage with its Wilson score
    interval: ``(percentage, low, high)``, or None when ``n`` is 0."""
    if not n:
        return None
    p = k / n
    den = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / den
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / den
    return 100 * p, 100 * max(0.0, centre - half), 100 * min(1.0, centre + half)


def normal_half_width(sd: float, n: int, z: float = Z95) -> float:
    """The half width of the normal interval of a mean of ``n`` values whose
    standard deviation is ``sd``."""
    return z * sd / math.sqrt(n)


def z_proportions(k1: int, n1: int, k2: int, n2: int) -> float | None:
    """The pooled two-proportion z statistic of ``k1/n1 - k2/n2``, or None
    when a sample is empty or the pooled variance is 0."""
    if not n1 or not n2:
        return None
    p = (k1 + k2) / (n1 + n2)
    se = math.sqrt(p * (1 - p) * (1 / n1 + 1 / n2))
    return None if se == 0 else (k1 / n1 - k2 / n2) / se


def z_means(
    mean1: float | None, sd1: float | None, n1: int, mean2: float | None, sd2: float | None, n2: int
) -> float | None:
    """Welch's z statistic of ``mean1 - mean2``, or None when a mean or a
    standard deviation is missing, a sample is empty or the error is 0."""
    if None in (mean1, sd1, mean2, sd2) or not n1 or not n2:
        return None
    se = math.sqrt(sd1**2 / n1 + sd2**2 / n2)
    return None if se == 0 else (mean1 - mean2) / se


def pooled(groups: Iterable[tuple[int, float, float]]) -> tuple[int, float, float]:
    """Several samples, each given as ``(n, mean, sample sd)``, as one:
    ``(n, mean, sample sd)`` of their union (the within-sample plus the
    between-sample spread). Needs at least two values in all."""
    groups = list(groups)
    n = sum(g[0] for g in groups)
    m = sum(g[0] * g[1] for g in groups) / n
    ss = sum((gn - 1) * gsd**2 + gn * (gm - m) ** 2 for gn, gm, gsd in groups)
    return n, m, math.sqrt(ss / (n - 1))
