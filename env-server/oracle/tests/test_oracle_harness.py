"""The whole harness, `hfo_oracle.py` as the docs run it, against the fake HFO
tree in fake_hfo/ (a launcher that writes rcssserver's logs of a scripted
game and an `hfo` module that plays it): processes started and ended,
batches pipelined, the agents' choices joined, the statistics written; a
learned team made by the stand-in factory in fake_team/."""

import json
import os
import shutil
import subprocess
import sys

import pytest

TESTS = os.path.dirname(os.path.abspath(__file__))
ORACLE = os.path.dirname(TESTS)
FAKE_HFO = os.path.join(TESTS, "fake_hfo")
# The stand-in team factory's directory, on the harness's PYTHONPATH as a
# user's factory would be.
FAKE_TEAM = os.path.join(TESTS, "fake_team")
FACTORY = "fixed_agent:FixedAgent"


def namespaces_work():
    """Whether the harness can make a loopback-only network namespace."""
    unshare, ip = shutil.which("unshare"), shutil.which("ip")
    return (
        bool(unshare and ip)
        and subprocess.run(
            [unshare, "-rn", ip, "link", "set", "lo", "up"], capture_output=True
        ).returncode
        == 0
    )


def run_harness(tmp_path, *args, net="host"):
    rundir = tmp_path / "run"
    rundir.mkdir()
    work = tmp_path / "tmp"
    work.mkdir()
    env = dict(
        os.environ,
        FAKE_HFO_RUNDIR=str(rundir),
        PYTHONDONTWRITEBYTECODE="1",
        PYTHONPATH=os.pathsep.join(filter(None, [FAKE_TEAM, os.environ.get("PYTHONPATH")])),
    )
    env.pop("HFO_ORACLE_NETNS", None)
    cmd = [
        sys.executable,
        os.path.join(ORACLE, "hfo_oracle.py"),
        "--hfo-dir",
        FAKE_HFO,
        "--python",
        sys.executable,
        "--net",
        net,
        "--tmp",
        str(work),
        *args,
    ]
    done = subprocess.run(
        cmd, env=env, cwd=str(tmp_path), capture_output=True, text=True, timeout=120
    )
    # Nothing is left in the temporary directory.
    assert os.listdir(str(work)) == [], done.stderr
    return done


def test_a_policy_is_played_in_pipelined_batches(tmp_path):
    out = tmp_path / "hfo-shoot.json"
    done = run_harness(
        tmp_path,
        "--policy",
        "shoot",
        "--episodes",
        "5",
        "--batch",
        "2",
        "--seed",
        "3",
        "--out",
        str(out),
        net="auto",
    )
    assert done.returncode == 0, done.stderr
    assert "5/5 episodes played" in done.stderr
    r = json.loads(out.read_text())
    assert (r["simulator"], r["policy"], r["seed"], r["episodes"]) == ("hfo", "shoot", 3, 5)
    # Runs of 2, 2 and 1 episodes after a warm-up trial each: fakegame's odd
    # trials are goals, its even ones out of bounds.
    assert r["outcomes"] == {"goal": 3, "captured": 0, "out_of_bounds": 2, "out_of_time": 0}
    assert r["mean_frames"] == 8.0
    assert r["decisions"]["shots"][1] == {"from_m": 10, "to_m": 15, "released": 5, "goals": 3}
    assert r["actions"] == {"move": 0, "shoot": 5, "dribble": 0, "pass_near": 0, "pass_far": 0}
    assert r["checks"]["kicks"] == 5
    assert all(v == 0 for k, v in r["checks"].items() if k != "kicks"), r["checks"]
    assert "team" not in r and r["wall_seconds"] >= 0
    assert not (tmp_path / "hfo-shoot.json.tmp").exists()
    # --net auto: in a network namespace of its own where one can be made.
    if namespaces_work():
        assert (tmp_path / "run" / "netns").read_text() != os.readlink("/proc/self/ns/net")


def test_a_learned_team_is_played_through_its_snapshots(tmp_path):
    team = []
    for i in range(3):
        path = tmp_path / ("agent-%d.snapshot" % i)
        path.write_text("1")  # the stand-in agent's action: SHOOT
        team.append(str(path))
    out = tmp_path / "hfo-team.json"
    done = run_harness(
        tmp_path, "--team", *team, "--team-factory", FACTORY, "--episodes", "2", "--out", str(out)
    )
    assert done.returncode == 0, done.stderr
    r = json.loads(out.read_text())
    assert r["policy"] == "team" and r["team"] == team and r["team_factory"] == FACTORY
    # --net host: in this network.
    assert (tmp_path / "run" / "netns").read_text() == os.readlink("/proc/self/ns/net")
    assert r["actions"]["shoot"] == 2 and r["outcomes"]["goal"] == 1


def test_bad_command_lines_are_refused(tmp_path):
    out = str(tmp_path / "x.json")
    done = run_harness(tmp_path, "--policy", "shoot", "--episodes", "0", "--out", out)
    assert done.returncode == 2 and "--episodes must be positive" in done.stderr
    missing = str(tmp_path / "missing.snapshot")
    second = tmp_path / "second"
    second.mkdir()
    team = ["--team", missing, missing, missing, "--team-factory", FACTORY]
    done = run_harness(second, *team, "--episodes", "1", "--out", out)
    assert done.returncode == 2 and "--team: no such file" in done.stderr
    third = tmp_path / "third"
    third.mkdir()
    policy = ["--policy", "shoot", "--team-factory", FACTORY]
    done = run_harness(third, *policy, "--episodes", "1", "--out", out)
    assert done.returncode == 2 and done.stderr == (
        "hfo_oracle.py: error: --team-factory goes with --team\n"
    )
    done = subprocess.run(
        [
            sys.executable,
            os.path.join(ORACLE, "hfo_oracle.py"),
            "--hfo-dir",
            str(tmp_path),
            "--policy",
            "shoot",
            "--episodes",
            "1",
            "--out",
            out,
        ],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 2 and "must point at a built HFO tree" in done.stderr
    assert not os.path.exists(out)


@pytest.mark.parametrize(
    "factory, error",
    [
        ([], "--team needs --team-factory MODULE:CALLABLE"),
        (["--team-factory", "fixed_agent"], "--team-factory 'fixed_agent' is not MODULE:CALLABLE"),
        (["--team-factory", "fixed agent:FixedAgent"], "--team-factory 'fixed agent:"),
        (["--team-factory", "fixed_agent:"], "--team-factory 'fixed_agent:' is not"),
    ],
)
def test_a_team_without_a_well_formed_factory_is_refused(tmp_path, factory, error):
    path = tmp_path / "agent.snapshot"
    path.write_text("1")
    out = tmp_path / "x.json"
    team = ["--team", str(path), str(path), str(path)]
    done = run_harness(tmp_path, *team, *factory, "--episodes", "1", "--out", str(out))
    # One line, without the usage.
    assert done.returncode == 2 and len(done.stderr.splitlines()) == 1, done.stderr
    assert done.stderr.startswith("hfo_oracle.py: error: " + error), done.stderr
    assert not out.exists()


@pytest.mark.parametrize("entry", [["hfo_oracle.py"], ["-m", "hfo_oracle"]])
def test_the_script_and_the_package_are_the_same_command(entry):
    args = [os.path.join(ORACLE, entry[0])] if entry[0].endswith(".py") else entry
    done = subprocess.run(
        [sys.executable, *args, "--help"], cwd=ORACLE, capture_output=True, text=True, timeout=60
    )
    assert done.returncode == 0 and "--hfo-dir" in done.stdout
    done = subprocess.run(
        [sys.executable, *args, "agent", "--help"],
        cwd=ORACLE,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 0 and "--config-dir" in done.stdout
