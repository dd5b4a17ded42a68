"""The scripts beside the package on small statistics files: compare.py
and learned.py print their tables with hfo_oracle.stats."""

import json

import compare
import learned


def stats_file(tmp_path, name, simulator, policy, goals, episodes, **extra):
    d = {
        "simulator": simulator,
        "policy": policy,
        "episodes": episodes,
        "seed": 1,
        "goal_pct": 100 * goals / episodes,
        "mean_frames": 60.0,
        "mean_frames_to_goal": 40.0,
        "outcomes": {
            "goal": goals,
            "captured": episodes - goals,
            "out_of_bounds": 0,
            "out_of_time": 0,
        },
        "decisions": {
            "shots": [{"from_m": 0, "to_m": 10, "released": 10, "goals": 5}],
            "after_pass": {"teammate": 3, "same": 1},
            "after_dribble": {"same": 4},
            "possessions_per_episode": 2.0,
        },
        "sd": {"frames": 10.0, "frames_to_goal": 5.0, "possessions_per_episode": 1.0},
    }
    d.update(extra)
    path = tmp_path / name
    path.write_text(json.dumps(d))
    return str(path)


def test_compare_sets_two_simulators_side_by_side(tmp_path, capsys):
    files = [
        stats_file(tmp_path, "hfo.json", "hfo", "shoot", 45, 100),
        stats_file(tmp_path, "ours.json", "ours", "shoot", 60, 100),
    ]
    assert compare.main(files) == 0
    out = capsys.readouterr().out
    assert out.startswith("### policy `shoot`")
    lines = out.splitlines()
    assert lines[2].startswith("| statistic | ours (100 episodes, seed 1) | hfo (100")
    goal = next(line for line in lines if line.startswith("| goal % |"))
    # 60/100 against 45/100: Wilson intervals, pooled z 2.12 (significant).
    assert goal == ("| goal % | 60.0 [50.2, 69.1] (60/100) | 45.0 [35.6, 54.8] (45/100) | 2.12 * |")
    frames = next(line for line in lines if line.startswith("| frames per episode |"))
    assert frames == (
        "| frames per episode | 60.00 [58.04, 61.96] (n=100) "
        "| 60.00 [58.04, 61.96] (n=100) | 0.00 |"
    )


def test_learned_pools_the_runs_of_each_team(tmp_path, capsys):
    actions = {"move": 0, "shoot": 10, "dribble": 20, "pass_near": 5, "pass_far": 5}
    files = []
    for sim, goals in (("ours", 30), ("hfo", 20)):
        for run in range(2):
            files.append(
                stats_file(
                    tmp_path,
                    "%s-%d.json" % (sim, run),
                    sim,
                    "team",
                    goals + 10 * run,
                    100,
                    actions=actions,
                    team=["/x/adhoc-td-1000/run-%d-agent-0.snapshot" % run],
                )
            )
    assert learned.main(files) == 0
    row = capsys.readouterr().out.splitlines()[2]
    # 70/200 against 50/200; frames pooled from two equal runs: sd 10.
    assert row.startswith("| adhoc-td-1000 (2) | 35.0 [28.7, 41.8] | 25.0 [19.5, 31.4] | 2.18 * |")
    assert "| 60.0 ± 1.4 | 60.0 ± 1.4 | 0 / 25 / 50 / 12 / 12 | 0 / 25 / 50 / 12 / 12 |" in row
