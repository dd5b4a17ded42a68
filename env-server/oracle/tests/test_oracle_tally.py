"""The join of one run's logs with the agents' choices (hfo_oracle.tally),
on scripted runs written by fakegame in the logs' formats."""

import json
import os

import fakegame
import pytest

from hfo_oracle.schema import SHOT_BINS
from hfo_oracle.tally import CHECKS, Tally

# A warm-up trial and two counted ones (fakegame.POSITION: 7 at (40, 0), 8
# at (40, -8), 11 at (30, 10); the ball 0.3 m in front of its kicker).
SCHEDULE = [
    {"start": 0, "end": 12, "result": "GOAL", "kicks": [[5, 7, "S", True]]},
    {
        "start": 20,
        "end": 40,
        "result": "GOAL",
        "kicks": [
            [24, 7, "D", False],  # a dribble kick keeping the ball,
            [26, 7, "N", True],  # a pass to 8,
            [29, 8, "S", False],  # a shot's first kick, not released,
            [30, 8, "S", True],
        ],  # its second: the goal, from 14.6 m
        "choices": [[33, 11, "M"], [35, 11, "D"]],
    },  # a DRIBBLE with no kick
    {
        "start": 50,
        "end": 70,
        "result": "CAPTURED_BY_DEFENSE",
        "kicks": [
            [55, 11, None, True],  # a kick without a choice,
            [58, 11, "F", True],
        ],  # a pass the keeper takes
        "commands": [[60, 8]],
    },  # a kick command out of reach
]


def tally_of(tmp_path, schedule, **change):
    logdir, out, agents = fakegame.write_batch(str(tmp_path), schedule)
    for name, text in change.items():
        with open(os.path.join(str(tmp_path), name), "w") as f:
            f.write(text)
    t = Tally()
    t.add_batch(logdir, out, agents, len(schedule))
    return t


def test_a_run_is_joined_into_the_statistics(tmp_path):
    t = tally_of(tmp_path, SCHEDULE)
    r = t.result("uniform", 5)
    assert r["simulator"] == "hfo" and r["policy"] == "uniform" and r["seed"] == 5
    # The warm-up trial is not counted.
    assert r["episodes"] == 2
    assert r["outcomes"] == {"goal": 1, "captured": 1, "out_of_bounds": 0, "out_of_time": 0}
    assert r["goal_pct"] == 50.0
    # Frames: end - start - 2.
    assert r["mean_frames"] == 18.0 and r["mean_frames_to_goal"] == 18.0
    shots = r["decisions"]["shots"]
    assert [(b["from_m"], b["to_m"]) for b in shots] == list(SHOT_BINS)
    assert [(b["released"], b["goals"]) for b in shots] == [
        (0, 0),
        (1, 1),
        (0, 0),
        (0, 0),
        (0, 0),
        (0, 0),
    ]
    assert r["decisions"]["after_pass"] == {
        "teammate": 1,
        "same": 0,
        "captured": 1,
        "out_of_bounds": 0,
        "goal": 0,
        "out_of_time": 0,
    }
    assert r["decisions"]["after_dribble"] == {
        "teammate": 0,
        "same": 1,
        "captured": 0,
        "out_of_bounds": 0,
        "goal": 0,
        "out_of_time": 0,
    }
    # 7 then 8 in the first counted trial, 11 alone in the second.
    assert r["decisions"]["possessions_per_episode"] == 1.5
    assert r["actions"] == {"move": 1, "shoot": 2, "dribble": 2, "pass_near": 1, "pass_far": 1}
    assert r["sd"] == {
        "frames": 0.0,
        "frames_to_goal": None,
        "possessions_per_episode": pytest.approx(0.7071067811865476),
    }
    assert r["checks"] == dict.fromkeys(CHECKS, 0) | {
        "kicks": 6,
        "shots_not_released": 1,
        "kicks_without_choice": 1,
        "choices_without_kick": 1,
        "kick_commands_not_kickable": 1,
    }
    json.dumps(r)  # a JSON object as it stands


def test_runs_add_up(tmp_path):
    t = Tally()
    for i in range(2):
        d = tmp_path / str(i)
        d.mkdir()
        logdir, out, agents = fakegame.write_batch(str(d), fakegame.simple_schedule(4))
        t.add_batch(logdir, out, agents, 4)
    r = t.result("shoot", 1)
    assert r["episodes"] == 6
    assert r["outcomes"]["goal"] == 4 and r["outcomes"]["out_of_bounds"] == 2
    assert r["decisions"]["shots"][1] == {"from_m": 10, "to_m": 15, "released": 6, "goals": 4}
    assert r["actions"]["shoot"] == 6
    assert r["checks"]["kicks"] == 6


def test_disagreeing_sources_are_counted(tmp_path):
    # The trainer reports trial 1 as out of bounds and misses trial 2; agent
    # 8 saw trial 1 one frame longer and as out of time.
    trainer = fakegame.trainer_output(SCHEDULE).splitlines(keepends=True)
    trainer[2] = trainer[2].replace("GOAL-7", "OUT_OF_BOUNDS-7")
    agent8 = fakegame.agent_file(SCHEDULE, 8).replace("E 1 18 Goal", "E 1 19 OutOfTime")
    t = tally_of(tmp_path, SCHEDULE, **{"hfo.out": "".join(trainer[:3]), "agent-8.txt": agent8})
    assert t.checks["trainer_outcome_mismatches"] == 2
    assert t.checks["agent_frames_mismatches"] == 1
    assert t.checks["agent_outcome_mismatches"] == 1
    assert t.checks["referee_outcome_mismatches"] == 0


def test_a_run_with_missing_trials_is_refused(tmp_path):
    logdir, out, agents = fakegame.write_batch(str(tmp_path), SCHEDULE)
    with pytest.raises(RuntimeError, match="3 trials in the .hfo log, expected 4"):
        Tally().add_batch(logdir, out, agents, 4)
    agent = fakegame.agent_file(SCHEDULE[:2], 7)
    with open(agents[0], "w") as f:
        f.write(agent.replace("E 2 1 ServerDown\n", ""))
    with pytest.raises(RuntimeError, match="agent 7 saw 2 episodes, HFO played 3"):
        Tally().add_batch(logdir, out, agents, 3)


def test_a_kick_the_counter_does_not_show_is_counted(tmp_path):
    logdir, out, agents = fakegame.write_batch(str(tmp_path), SCHEDULE)
    rcg = os.path.join(logdir, "20260101-base_left_0.rcg")
    with open(rcg) as f:
        lines = f.readlines()
    # 7 kicked at 5 and 24: its counter shows 2 from cycle 25 on; say 1.
    i = next(i for i, line in enumerate(lines) if line.startswith("(show 25 "))
    assert "(c 2 12" in lines[i]
    lines[i] = lines[i].replace("(c 2 12", "(c 1 12", 1)
    with open(rcg, "w") as f:
        f.writelines(lines)
    t = Tally()
    t.add_batch(logdir, out, agents, len(SCHEDULE))
    assert t.checks["kick_count_mismatches"] == 1
