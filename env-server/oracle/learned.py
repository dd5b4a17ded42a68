#!/usr/bin/env python3
"""Learned teams on both simulators, side by side: reads the statistics of
`team_ours.py` (ours) and `hfo_oracle.py --team` (the real HFO), pairs them
by team, pools the runs of each algorithm and training length, and prints a
Markdown table with 95 % intervals (Wilson for percentages, normal for
means) and the z statistic of the goal difference.

    python3 learned.py results/ours-*.json results/hfo-*.json

A team's name is its snapshot directory (e.g. `adhoc-td-1000`: the agents
of an AdHocTD run after 1000 training episodes). Standard library only.
"""

import argparse
import json
import math
import os
import sys
from collections import defaultdict

from compare import Z, wilson

ACTIONS = ("move", "shoot", "dribble", "pass_near", "pass_far")
OUTCOMES = ("goal", "captured", "out_of_bounds", "out_of_time")


def team_name(d):
    """The directory of the team's snapshot files."""
    return os.path.basename(os.path.dirname(d["team"][0]))


def pool(stats):
    """One statistics object of several runs of a team: counts added, frame
    means weighted by episodes, their standard deviations combined."""
    n = sum(d["episodes"] for d in stats)
    out = {k: sum(d["outcomes"][k] for d in stats) for k in OUTCOMES}
    actions = {k: sum(d["actions"][k] for d in stats) for k in ACTIONS}
    mean = sum(d["mean_frames"] * d["episodes"] for d in stats) / n
    # Pooled variance: within-run plus between-run spread.
    ss = sum((d["episodes"] - 1) * d["sd"]["frames"] ** 2
             + d["episodes"] * (d["mean_frames"] - mean) ** 2 for d in stats)
    return {"episodes": n, "outcomes": out, "actions": actions, "mean_frames": mean,
            "sd_frames": math.sqrt(ss / (n - 1)), "runs": len(stats)}


def pct(k, n):
    w = wilson(k, n)
    return "%.1f [%.1f, %.1f]" % w if w else "–"


def z_prop(k1, n1, k2, n2):
    p = (k1 + k2) / (n1 + n2)
    se = math.sqrt(p * (1 - p) * (1 / n1 + 1 / n2))
    return (k1 / n1 - k2 / n2) / se if se else 0.0


def mix(d):
    tot = sum(d["actions"].values()) or 1
    return " / ".join("%.0f" % (100 * d["actions"][a] / tot) for a in ACTIONS)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("files", nargs="+")
    args = p.parse_args(argv)
    runs = defaultdict(lambda: defaultdict(list))
    for f in args.files:
        with open(f) as fh:
            d = json.load(fh)
        runs[team_name(d)][d["simulator"]].append(d)
    print("| team (runs) | goal %: ours | real HFO | z | captured / out / time-out %: ours "
          "| real HFO | frames: ours | real HFO | kickers' choices % (move / shoot / dribble "
          "/ pass near / far): ours | real HFO |")
    print("|" + "---|" * 11)
    for name in sorted(runs, key=lambda t: (t.rsplit("-", 1)[0], int(t.rsplit("-", 1)[1]))):
        sims = runs[name]
        if set(sims) != {"ours", "hfo"}:
            continue
        a, b = pool(sims["ours"]), pool(sims["hfo"])
        z = z_prop(a["outcomes"]["goal"], a["episodes"], b["outcomes"]["goal"], b["episodes"])
        rest = lambda d: " / ".join("%.1f" % (100 * d["outcomes"][k] / d["episodes"])
                                    for k in OUTCOMES[1:])
        frames = lambda d: "%.1f ± %.1f" % (d["mean_frames"],
                                             Z * d["sd_frames"] / math.sqrt(d["episodes"]))
        print("| %s (%d) | %s | %s | %.2f%s | %s | %s | %s | %s | %s | %s |" % (
            name, a["runs"], pct(a["outcomes"]["goal"], a["episodes"]),
            pct(b["outcomes"]["goal"], b["episodes"]), z, " *" if abs(z) > Z else "",
            rest(a), rest(b), frames(a), frames(b), mix(a), mix(b)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
