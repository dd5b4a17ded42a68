#!/usr/bin/env python3
"""A learned team on our simulator: plays N episodes of three of our agents'
snapshot files (`coordinator run --save-agents`), greedily as our
evaluations play, on one long-lived simulator, and writes the statistics
`hfo_oracle.py --team` writes for the real HFO (outcomes, frames, the
kickers' choices), for `learned.py` to set side by side.

Needs the `halffield` package (env-server/python):

    python3 team_ours.py --team A B C --episodes 4000 --seed 1 --out ours.json
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys

import halffield

ACTIONS = ("move", "shoot", "dribble", "pass_near", "pass_far")
OUTCOMES = {"GOAL": "goal", "CAPTURED_BY_DEFENSE": "captured",
            "OUT_OF_BOUNDS": "out_of_bounds", "OUT_OF_TIME": "out_of_time"}


def sd(xs: list[float]) -> float | None:
    """The sample standard deviation, or None below two samples."""
    if len(xs) < 2:
        return None
    m = sum(xs) / len(xs)
    return math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1))


def play(team: list[str], episodes: int, seed: int) -> dict:
    """Statistics of ``episodes`` episodes of ``team`` from ``seed``."""
    agents = [halffield.GreedyAgent(path) for path in team]
    env = halffield.parallel_env(observation="paper")
    outcomes = dict.fromkeys(OUTCOMES.values(), 0)
    actions = dict.fromkeys(ACTIONS, 0)
    frames: list[float] = []
    frames_goal: list[float] = []
    for episode in range(episodes):
        observations, infos = env.reset(seed=seed) if episode == 0 else env.reset()
        while env.agents:
            chosen = {}
            for agent, name in zip(agents, env.agents):
                can_kick = bool(infos[name]["action_mask"][halffield.SHOOT])
                choice = agent.act(observations[name].tolist(), can_kick)
                if can_kick:
                    actions[ACTIONS[choice]] += 1
                # Pass near and far are one PASS here, as in HFO, whose
                # PASS ignores the receiver it names (docs/hfo-sim-spec.md 6.4).
                chosen[name] = min(choice, halffield.PASS)
            observations, _, _, _, infos = env.step(chosen)
        info = next(iter(infos.values()))
        outcome = OUTCOMES[info["status"]]
        outcomes[outcome] += 1
        frames.append(info["frame"])
        if outcome == "goal":
            frames_goal.append(info["frame"])
    return {
        "simulator": "ours",
        "policy": "team",
        "team": [os.path.abspath(p) for p in team],
        "episodes": episodes,
        "seed": seed,
        "goal_pct": 100.0 * outcomes["goal"] / episodes,
        "mean_frames": sum(frames) / episodes,
        "mean_frames_to_goal": sum(frames_goal) / len(frames_goal) if frames_goal else None,
        "outcomes": outcomes,
        "actions": actions,
        "sd": {"frames": sd(frames), "frames_to_goal": sd(frames_goal)},
    }


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--team", nargs=3, required=True, metavar="SNAPSHOT")
    p.add_argument("--episodes", type=int, required=True)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--out", required=True, help="output JSON file")
    a = p.parse_args(argv)
    if a.episodes <= 0:
        p.error("--episodes must be positive")
    result = play(a.team, a.episodes, a.seed)
    tmp = a.out + ".tmp"
    with open(tmp, "w") as f:
        json.dump(result, f, indent=2)
        f.write("\n")
    os.replace(tmp, a.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
