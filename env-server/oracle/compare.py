#!/usr/bin/env python3
"""Side-by-side comparison of per-decision statistics files (our simulator's
`env-server rollout --json` and the real-HFO oracle `hfo_oracle.py`, same
schema).  Prints one Markdown table per policy, with 95 % intervals: Wilson
intervals for percentages, normal intervals for means.

    python3 compare.py docs/calibration/ours-*.json docs/calibration/hfo-*.json

Columns are the files of that policy (our simulator first).  With exactly two
columns a last column gives the two-sample z statistic of the difference
(pooled two-proportion test for percentages, Welch for means); |z| > 1.96 is
marked with `*`.  Means need a standard deviation: it is read from the
optional "sd" object ({"frames", "frames_to_goal", "possessions_per_episode"})
that the oracle writes; a file without it gets the mean alone.

Standard library only; the statistics are the package `hfo_oracle`'s
(`hfo_oracle/stats.py`).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Sequence
from typing import Any

from hfo_oracle.schema import NEXT_KEYS, POLICIES
from hfo_oracle.stats import Z95, normal_half_width, wilson, z_means, z_proportions

OUTCOMES = [
    ("goal", "goal %"),
    ("captured", "captured %"),
    ("out_of_bounds", "out of bounds %"),
    ("out_of_time", "time-out %"),
]


class Cell:
    """A value with what is needed for its interval and for a z test."""

    def __init__(self, kind: str, **kw: Any) -> None:
        self.kind = kind  # "prop" (k, n) or "mean" (mean, sd, n)
        self.__dict__.update(kw)

    def text(self) -> str:
        if self.kind == "prop":
            w = wilson(self.k, self.n)
            if w is None:
                return "– (0/0)"
            return "%.1f [%.1f, %.1f] (%d/%d)" % (w[0], w[1], w[2], self.k, self.n)
        if self.mean is None:
            return "–"
        if self.sd is None or not self.n:
            return "%.2f (n=%d, no sd)" % (self.mean, self.n or 0)
        half = normal_half_width(self.sd, self.n)
        return "%.2f [%.2f, %.2f] (n=%d)" % (self.mean, self.mean - half, self.mean + half, self.n)


def z_stat(a: Cell | None, b: Cell | None) -> float | None:
    """The z statistic of the difference of two cells of the same row."""
    if a is None or b is None:
        return None
    if a.kind == "prop":
        return z_proportions(a.k, a.n, b.k, b.n)
    return z_means(a.mean, a.sd, a.n, b.mean, b.sd, b.n)


def sd_of(d: dict[str, Any], key: str) -> float | None:
    sd = d.get("sd") or {}
    v = sd.get(key)
    if v is None:
        v = d.get("sd_" + key)
    return v


def rows_for(d: dict[str, Any]) -> list[tuple[str, Cell]]:
    """[(row label, Cell)] for one statistics object."""
    n = d["episodes"]
    out = d["outcomes"]
    dec = d["decisions"]
    rows = []
    for key, label in OUTCOMES:
        rows.append((label, Cell("prop", k=out.get(key, 0), n=n)))
    rows.append(
        ("frames per episode", Cell("mean", mean=d.get("mean_frames"), sd=sd_of(d, "frames"), n=n))
    )
    rows.append(
        (
            "frames to goal",
            Cell(
                "mean",
                mean=d.get("mean_frames_to_goal"),
                sd=sd_of(d, "frames_to_goal"),
                n=out.get("goal", 0),
            ),
        )
    )
    for b in dec["shots"]:
        hi = "∞" if b["to_m"] is None else "%g" % b["to_m"]
        rows.append(
            (
                "shot success %% [%g, %s) m" % (b["from_m"], hi),
                Cell("prop", k=b["goals"], n=b["released"]),
            )
        )
    shots = sum(b["released"] for b in dec["shots"])
    goals = sum(b["goals"] for b in dec["shots"])
    rows.append(("shot success % (all)", Cell("prop", k=goals, n=shots)))
    for name in ("after_pass", "after_dribble"):
        mix = dec[name]
        tot = sum(mix.get(k, 0) for k in NEXT_KEYS)
        for k in NEXT_KEYS:
            rows.append(("%s: %s %%" % (name, k), Cell("prop", k=mix.get(k, 0), n=tot)))
    rows.append(
        (
            "possessions per episode",
            Cell(
                "mean",
                mean=dec.get("possessions_per_episode"),
                sd=sd_of(d, "possessions_per_episode"),
                n=n,
            ),
        )
    )
    return rows


def main(argv: Sequence[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("files", nargs="+", help="statistics JSON files (ours and hfo)")
    args = p.parse_args(argv)
    by_policy = {}
    for f in args.files:
        with open(f) as fh:
            d = json.load(fh)
        by_policy.setdefault(d["policy"], []).append((f, d))
    for policy in sorted(by_policy, key=lambda x: (POLICIES.index(x) if x in POLICIES else 99, x)):
        cols = sorted(by_policy[policy], key=lambda fd: (fd[1].get("simulator") != "ours", fd[0]))
        labels = []
        for f, d in cols:
            lab = "%s (%s episodes, seed %s)" % (
                d.get("simulator", "?"),
                d["episodes"],
                d.get("seed"),
            )
            if sum(1 for g, e in cols if e.get("simulator") == d.get("simulator")) > 1:
                lab += " " + os.path.basename(f)
            labels.append(lab)
        tables = [rows_for(d) for _, d in cols]
        two = len(cols) == 2
        print("### policy `%s`\n" % policy)
        head = ["statistic"] + labels + (["z (1st − 2nd)"] if two else [])
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
        for i, (label, _) in enumerate(tables[0]):
            cells = [t[i][1] for t in tables]
            line = [label] + [c.text() for c in cells]
            if two:
                z = z_stat(cells[0], cells[1])
                line.append("–" if z is None else ("%.2f%s" % (z, " *" if abs(z) > Z95 else "")))
            print("| " + " | ".join(line) + " |")
        print()
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except BrokenPipeError:  # e.g. piped into head
        sys.exit(0)
