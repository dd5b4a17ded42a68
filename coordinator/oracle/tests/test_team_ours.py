"""team_ours.py writes the statistics of a learned team played on our
simulator, as hfo_oracle.py --team writes them for the real HFO (on
stand-ins for halffield and adhoc_advising)."""

import json
import sys
import types

import pytest


class FakeParallelEnv:
    """Two-frame episodes of three agents; the first ends in a goal, the
    others captured."""

    def __init__(self):
        self.episode = -1
        self.agents = []

    def reset(self, seed=None):
        self.episode += 1
        self.frame = 0
        self.agents = ["offense_0", "offense_1", "offense_2"]
        return self._observe("IN_GAME")

    def _observe(self, status):
        mask = [1, 1, 1, 1, 1]
        obs = {a: types.SimpleNamespace(tolist=lambda: [0.0] * 6) for a in self.agents}
        infos = {
            a: {"action_mask": mask, "status": status, "frame": self.frame} for a in self.agents
        }
        return obs, infos

    def step(self, chosen):
        assert all(0 <= c <= 3 for c in chosen.values())
        self.frame += 1
        if self.frame < 2:
            obs, infos = self._observe("IN_GAME")
        else:
            obs, infos = self._observe("GOAL" if self.episode == 0 else "CAPTURED_BY_DEFENSE")
            self.agents = []
        return obs, {}, {}, {}, infos


class FakeGreedyAgent:
    def __init__(self, snapshot):
        self.action = int(open(snapshot).read())

    def act(self, state, can_kick):
        return self.action


def test_team_ours_writes_a_team_s_statistics(tmp_path, monkeypatch):
    monkeypatch.setitem(
        sys.modules,
        "halffield",
        types.SimpleNamespace(parallel_env=lambda observation: FakeParallelEnv(), SHOOT=1, PASS=3),
    )
    monkeypatch.setitem(
        sys.modules, "adhoc_advising", types.SimpleNamespace(GreedyAgent=FakeGreedyAgent)
    )
    team = []
    for i, action in enumerate((1, 2, 4)):  # shoot, dribble, pass far
        path = tmp_path / f"agent-{i}.snapshot"
        path.write_text(str(action))
        team.append(str(path))
    import team_ours

    out = tmp_path / "ours.json"
    assert team_ours.main(["--team", *team, "--episodes", "3", "--out", str(out)]) == 0
    r = json.loads(out.read_text())
    assert r["simulator"] == "ours" and r["policy"] == "team" and r["team"] == team
    assert r["outcomes"] == {"goal": 1, "captured": 2, "out_of_bounds": 0, "out_of_time": 0}
    assert r["goal_pct"] == pytest.approx(100 / 3)
    assert r["mean_frames"] == 2.0 and r["mean_frames_to_goal"] == 2.0
    assert r["actions"] == {"move": 0, "shoot": 6, "dribble": 6, "pass_near": 0, "pass_far": 6}
    assert r["sd"] == {"frames": 0.0, "frames_to_goal": None}
