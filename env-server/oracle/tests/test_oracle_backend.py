"""The real HFO as env-server's simulator (hfo_oracle.backend and
hfo_oracle.relay) against the fake HFO tree in fake_hfo/: commands in,
frames out, one line each, as env-server speaks to it."""

import io
import json
import os
import subprocess
import sys
import tempfile

from hfo_oracle import relay

TESTS = os.path.dirname(os.path.abspath(__file__))
ORACLE = os.path.dirname(TESTS)
FAKE_HFO = os.path.join(TESTS, "fake_hfo")


def backend(tmp_path, commands, *extra):
    """The backend's lines answering ``commands`` (then the end of its
    input), and its exit status."""
    rundir = tempfile.mkdtemp(dir=str(tmp_path))
    env = dict(os.environ, FAKE_HFO_RUNDIR=rundir, PYTHONPATH=ORACLE, PYTHONDONTWRITEBYTECODE="1")
    env.pop("HFO_ORACLE_NETNS", None)
    cmd = [
        sys.executable,
        "-m",
        "hfo_oracle",
        "backend",
        "--hfo-dir",
        FAKE_HFO,
        "--python",
        sys.executable,
        "--offense",
        "3",
        "--frames-per-trial",
        "200",
        "--untouched-time",
        "100",
        "--seed",
        "5",
        "--net",
        "host",
        *extra,
    ]
    done = subprocess.run(
        cmd,
        input="".join(c + "\n" for c in commands),
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
    )
    return [json.loads(line) for line in done.stdout.splitlines()], done.returncode


def test_episodes_are_the_trials_after_the_warm_up(tmp_path):
    # fakegame's trials: 8 frames each, agent 7 (HFO's first player) can
    # kick at the third; odd trials are goals, even ones out of bounds.
    steps = ["SSMM"] * 8
    frames, status = backend(tmp_path, ["R"] + steps + ["R"] + steps + ["Q"])
    assert status == 0
    assert len(frames) == 18
    first = frames[0]
    assert (first["frame"], first["outcome"]) == (0, "in-game")
    assert len(first["states"]) == 3 and all(len(s) == 6 for s in first["states"])
    assert len(first["pos"]) == 3
    assert [f["kick"][0] for f in frames[:3]] == [False, False, True]
    assert [f["outcome"] for f in frames[1:9]] == ["in-game"] * 7 + ["goal"]
    assert frames[8]["frame"] == 8
    assert frames[9]["frame"] == 0 and frames[17]["outcome"] == "out-of-bounds"


def test_an_abandoned_trial_is_played_out_before_the_next(tmp_path):
    frames, status = backend(tmp_path, ["R", "SMMM", "R", "SMMM"])
    assert status == 0
    assert [f["frame"] for f in frames] == [0, 1, 0, 1]
    # Trial 1 (a goal) abandoned, the episode is trial 2: out of bounds.
    more, _ = backend(tmp_path, ["R", "SMMM", "R"] + ["SMMM"] * 8)
    assert [f["outcome"] for f in more[-2:]] == ["in-game", "out-of-bounds"]


def test_bad_commands_end_it_with_an_error_line(tmp_path):
    for commands in (["R", "SXMM"], ["R", "SMM"], ["X"]):
        frames, status = backend(tmp_path, commands)
        assert status == 1
        assert "error" in frames[-1], frames


def test_a_missing_hfo_is_named():
    env = dict(os.environ, PYTHONPATH=ORACLE)
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "hfo_oracle",
            "backend",
            "--hfo-dir",
            "/nonexistent",
            "--python",
            sys.executable,
            "--offense",
            "3",
            "--frames-per-trial",
            "200",
            "--untouched-time",
            "100",
            "--seed",
            "1",
        ],
        input="",
        env=env,
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert done.returncode == 1
    error = json.loads(done.stdout)["error"]
    assert "bin/HFO" in error and "build_hfo.sh" in error


def test_a_relay_reports_each_cycle_and_acts_as_told():
    class Env:
        def __init__(self):
            self.acted, self.cycle = [], 0

        def getNumTeammates(self):  # noqa: N802 (HFO's names)
            return 2

        def getState(self):  # noqa: N802 (HFO's names)
            s = [0.0] * 27
            s[5] = 1.0
            s[16:22] = [0.1, 0.0, 8.0, 0.5, 0.0, 11.0]
            return s

        def act(self, *action):
            self.acted.append(action)

        def step(self):
            self.cycle += 1
            return 1 if self.cycle == 3 else 0  # GOAL at the third step

    class Hfo:
        IN_GAME, GOAL, CAPTURED_BY_DEFENSE, OUT_OF_BOUNDS, OUT_OF_TIME, SERVER_DOWN = range(6)
        MOVE, SHOOT, PASS, DRIBBLE = 8, 9, 10, 11

    env, out = Env(), io.StringIO()
    assert relay.play(env, Hfo, io.StringIO("S\nN\nD\nQ\n"), out) == 0
    lines = [json.loads(line) for line in out.getvalue().splitlines()]
    assert [line["status"] for line in lines] == ["in-game", "in-game", "in-game", "goal"]
    assert all(line["kick"] and len(line["state"]) == 6 for line in lines)
    assert env.acted == [(9,), (10, 8.0), (11,)]
