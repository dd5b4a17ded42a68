#!/usr/bin/env python3
"""A learned team on our simulator: plays N episodes of three of our agents'
snapshot files (`coordinator run --save-agents`), greedily as our
evaluations play, on one long-lived simulator, and writes the statistics
`hfo_oracle.py --team A B C --team-factory adhoc_advising:GreedyAgent`
writes for the real HFO (outcomes, frames, the kickers' choices), for
`learned.py` (env-server/oracle) to set side by side.

Needs the `halffield` package (env-server/python) and our agents' package
`adhoc_advising` (coordinator/python), whose `GreedyAgent` plays each
agent; the statistics' vocabulary is the harness's (`hfo_oracle` in
env-server/oracle, found from this file's place in the tree):

    python3 coordinator/oracle/team_ours.py --team A B C --episodes 4000 --seed 1 --out ours.json
"""

from __future__ import annotations

import argparse
import os
import sys
from typing import Any

# The harness's package, a layer below in env-server/oracle.
sys.path.insert(
    0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "env-server", "oracle")
)

import halffield
from adhoc_advising import GreedyAgent
from hfo_oracle.schema import ACTIONS, STATUS_OUTCOMES, write_json
from hfo_oracle.stats import mean, sample_sd


def play(team: list[str], episodes: int, seed: int) -> dict[str, Any]:
    """Statistics of ``episodes`` episodes of ``team`` from ``seed``."""
    agents = [GreedyAgent(path) for path in team]
    env = halffield.parallel_env(observation="paper")
    outcomes = dict.fromkeys(STATUS_OUTCOMES.values(), 0)
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
        outcome = STATUS_OUTCOMES[info["status"]]
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
        "mean_frames": mean(frames),
        "mean_frames_to_goal": mean(frames_goal),
        "outcomes": outcomes,
        "actions": actions,
        "sd": {"frames": sample_sd(frames), "frames_to_goal": sample_sd(frames_goal)},
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
    write_json(a.out, play(a.team, a.episodes, a.seed))
    return 0


if __name__ == "__main__":
    sys.exit(main())
