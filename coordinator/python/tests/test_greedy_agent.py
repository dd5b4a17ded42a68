"""GreedyAgent: a learner of ours, trained by the coordinator and saved,
plays in Python as our evaluations play it."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from conftest import workspace_binary

import adhoc_advising
import halffield


def _trained_team(out: Path) -> list[Path]:
    """The three snapshot files of a short NoAdvice run of the coordinator
    built beside env-server."""
    coordinator = workspace_binary("coordinator")
    if not coordinator.is_file():
        pytest.fail(f"{coordinator} is missing: build the workspace first")
    subprocess.run(
        [str(coordinator), "run", "--algorithm", "no-advice", "--runs", "1", "--episodes", "40"]
        + ["--eval-every", "40", "--eval-episodes", "2", "--transport", "in-process", "--quiet"]
        + ["--save-agents", str(out / "agents"), "--out", str(out / "run")],
        check=True,
    )
    return [out / "agents" / f"run-0-agent-{i}.snapshot" for i in range(3)]


def test_a_trained_team_plays_the_papers_actions(tmp_path: Path) -> None:
    team = [adhoc_advising.GreedyAgent(p) for p in _trained_team(tmp_path)]
    assert adhoc_advising.PAPER_ACTIONS == ["move", "shoot", "dribble", "pass-near", "pass-far"]
    assert len({agent.digest for agent in team}) == 3, "three different tables"
    env = halffield.parallel_env(observation="paper")
    observations, infos = env.reset(seed=3)
    kicks = 0
    while env.agents:
        actions = {}
        for i, name in enumerate(env.agents):
            can_kick = bool(infos[name]["action_mask"][halffield.SHOOT])
            choice = team[i].act(observations[name].tolist(), can_kick)
            assert choice == 0 or can_kick, "only a kicker kicks"
            kicks += choice != 0
            # Our simulator's PASS goes where HFO's does whatever the receiver.
            actions[name] = min(choice, halffield.PASS)
        observations, _, _, _, infos = env.step(actions)
    assert kicks > 0
    # A state no run ever saw: the greedy order's first kick, SHOOT.
    assert team[0].act([0.123] * 6, True) == adhoc_advising.PAPER_ACTIONS.index("shoot")


def test_bad_snapshots_and_states_are_refused(tmp_path: Path) -> None:
    with pytest.raises(OSError, match="cannot read"):
        adhoc_advising.GreedyAgent(tmp_path / "missing.snapshot")
    junk = tmp_path / "junk.snapshot"
    junk.write_bytes(b"not a snapshot")
    with pytest.raises(ValueError, match="not a usable snapshot"):
        adhoc_advising.GreedyAgent(junk)
    agent = adhoc_advising.GreedyAgent(_trained_team(tmp_path)[0])
    with pytest.raises(ValueError, match="6 features"):
        agent.act([0.0] * 5, True)
    with pytest.raises(ValueError, match="finite"):
        agent.act([float("nan")] * 6, True)
