#!/usr/bin/env python3
"""Learned teams on both simulators, side by side: reads the statistics of
`team_ours.py` (ours) and `hfo_oracle.py --team` (the real HFO), pairs them
by team, pools the runs of each algorithm and training length, and prints a
Markdown table with 95 % intervals (Wilson for percentages, normal for
means) and the z statistic of the goal difference (the statistics of
`hfo_oracle/stats.py`).

    python3 learned.py results/ours-*.json results/hfo-*.json

A team's name is its snapshot directory (e.g. `adhoc-td-1000`: the agents
of an AdHocTD run after 1000 training episodes). Standard library only.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections import defaultdict
from collections.abc import Sequence
from typing import Any

from hfo_oracle.schema import ACTIONS, OUTCOMES
from hfo_oracle.stats import Z95, normal_half_width, pooled, wilson, z_proportions


def team_name(d: dict[str, Any]) -> str:
    """The directory of the team's snapshot files."""
    return os.path.basename(os.path.dirname(d["team"][0]))


def pool(stats: list[dict[str, Any]]) -> dict[str, Any]:
    """One statistics object of several runs of a team: counts added, frame
    means weighted by episodes, their standard deviations combined."""
    n, mean, sd = pooled((d["episodes"], d["mean_frames"], d["sd"]["frames"]) for d in stats)
    out = {k: sum(d["outcomes"][k] for d in stats) for k in OUTCOMES}
    actions = {k: sum(d["actions"][k] for d in stats) for k in ACTIONS}
    return {
        "episodes": n,
        "outcomes": out,
        "actions": actions,
        "mean_frames": mean,
        "sd_frames": sd,
        "runs": len(stats),
    }


def pct(k: int, n: int) -> str:
    """A percentage with its Wilson interval."""
    w = wilson(k, n)
    return "%.1f [%.1f, %.1f]" % w if w else "–"


def rest(d: dict[str, Any]) -> str:
    """The captured, out of bounds and time-out percentages."""
    return " / ".join("%.1f" % (100 * d["outcomes"][k] / d["episodes"]) for k in OUTCOMES[1:])


def frames(d: dict[str, Any]) -> str:
    """The mean frames per episode with the half width of its interval."""
    return "%.1f ± %.1f" % (d["mean_frames"], normal_half_width(d["sd_frames"], d["episodes"]))


def mix(d: dict[str, Any]) -> str:
    """The kickers' choices in percent, in the order of ACTIONS."""
    tot = sum(d["actions"].values()) or 1
    return " / ".join("%.0f" % (100 * d["actions"][a] / tot) for a in ACTIONS)


def main(argv: Sequence[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("files", nargs="+")
    args = p.parse_args(argv)
    runs = defaultdict(lambda: defaultdict(list))
    for f in args.files:
        with open(f) as fh:
            d = json.load(fh)
        runs[team_name(d)][d["simulator"]].append(d)
    print(
        "| team (runs) | goal %: ours | real HFO | z | captured / out / time-out %: ours "
        "| real HFO | frames: ours | real HFO | kickers' choices % (move / shoot / dribble "
        "/ pass near / far): ours | real HFO |"
    )
    print("|" + "---|" * 11)
    for name in sorted(runs, key=lambda t: (t.rsplit("-", 1)[0], int(t.rsplit("-", 1)[1]))):
        sims = runs[name]
        if set(sims) != {"ours", "hfo"}:
            continue
        a, b = pool(sims["ours"]), pool(sims["hfo"])
        z = z_proportions(
            a["outcomes"]["goal"], a["episodes"], b["outcomes"]["goal"], b["episodes"]
        )
        print(
            "| %s (%d) | %s | %s | %s | %s | %s | %s | %s | %s | %s |"
            % (
                name,
                a["runs"],
                pct(a["outcomes"]["goal"], a["episodes"]),
                pct(b["outcomes"]["goal"], b["episodes"]),
                "–" if z is None else "%.2f%s" % (z, " *" if abs(z) > Z95 else ""),
                rest(a),
                rest(b),
                frames(a),
                frames(b),
                mix(a),
                mix(b),
            )
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
