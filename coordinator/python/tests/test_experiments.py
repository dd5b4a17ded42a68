"""run() and study() in this process: the same files as the command line,
a Python learner joining AdHocTD teammates as an object, its exception
raised with its traceback, its snapshots saved and loaded, Ctrl-C stopping
cleanly and resuming."""

from __future__ import annotations

import json
import re
import signal
import subprocess
import sys
import time
import traceback
from pathlib import Path

import pytest
from conftest import ROOT, workspace_binary

import adhoc_advising
from adhoc_advising.learner import Start, Transition

sys.path.insert(0, str(ROOT / "coordinator" / "python" / "examples"))
from nearest_teammate import NearestTeammate  # noqa: E402
from numpy_learner import LinearSarsa  # noqa: E402

#: Keys of measured times, which differ from one invocation to the next.
MEASURED = {"training_s", "evaluation_s", "wall_s", "frames_per_sec"}


def without_times(value: object) -> object:
    """A JSON value without its measured times."""
    if isinstance(value, dict):
        return {k: without_times(v) for k, v in value.items() if k not in MEASURED}
    if isinstance(value, list):
        return [without_times(v) for v in value]
    return value


def assert_same_results(a: Path, b: Path) -> None:
    """The same files, the CSVs byte for byte, the JSONs but for times."""
    names = sorted(p.name for p in a.iterdir())
    assert names == sorted(p.name for p in b.iterdir())
    for name in names:
        if name.endswith(".json"):
            left = without_times(json.loads((a / name).read_text()))
            assert left == without_times(json.loads((b / name).read_text())), name
        else:
            assert (a / name).read_bytes() == (b / name).read_bytes(), name


def mixed_team(learner: object) -> list[dict]:
    """Two Rust AdHocTD agents and one AdHocTD agent learning with `learner`."""
    return [
        {"algorithm": "adhoc-td"},
        {"algorithm": "adhoc-td"},
        {"algorithm": "adhoc-td", "learner": learner},
    ]


SMALL = {"runs": 2, "episodes": 100, "eval_every": 50, "eval_episodes": 10, "threads": 2}
TINY = {"runs": 1, "episodes": 2, "eval_every": 2, "eval_episodes": 1}


def run_command_line(out: Path, *args: str, **options: object) -> None:
    """`coordinator run ARGS --<option>=<value>... --transport in-process`
    into `out`, the options named as `run()` names them."""
    flags = [f"--{key.replace('_', '-')}={value}" for key, value in options.items()]
    subprocess.run(
        [str(workspace_binary("coordinator")), "run", *args, *flags]
        + ["--transport", "in-process", "--quiet", "--out", str(out)],
        check=True,
        capture_output=True,
        timeout=300,
    )


def test_run_writes_what_the_command_line_writes(tmp_path: Path) -> None:
    options = {"runs": 2, "episodes": 150, "eval_every": 50, "eval_episodes": 10, "seed": 7}
    adhoc_advising.run(
        out=tmp_path / "py",
        algorithm="adhoc-visit",
        mistake_correcting=True,
        advice_loss=0.1,
        **options,
    )
    run_command_line(
        tmp_path / "cli",
        "--algorithm=adhoc-visit",
        "--mistake-correcting",
        "--advice-loss=0.1",
        **options,
    )
    assert_same_results(tmp_path / "py", tmp_path / "cli")


def test_a_rust_learner_by_name_is_the_command_lines(tmp_path: Path) -> None:
    """``learner="dqn"`` is ``--learner dqn``; an unknown name a ValueError."""
    options = {"runs": 1, "episodes": 60, "eval_every": 30, "eval_episodes": 5, "seed": 3}
    adhoc_advising.run(out=tmp_path / "py", algorithm="adhoc-td", learner="dqn", **options)
    run_command_line(tmp_path / "cli", "--algorithm=adhoc-td", "--learner=dqn", **options)
    assert_same_results(tmp_path / "py", tmp_path / "cli")
    config = json.loads((tmp_path / "py" / "config.json").read_text())
    assert all(agent["learner"] == "dqn" for agent in config["config"]["team"])
    with pytest.raises(ValueError, match="learner"):
        adhoc_advising.run(out=tmp_path / "bad", algorithm="adhoc-td", learner="lstm", **options)


@pytest.mark.parametrize(
    ("agent", "key"),
    [
        ({"learner": "dqn", "hidden": 0}, "hidden"),
        ({"learner": "dqn", "hidden": [64, 2000]}, "hidden"),
        ({"learner": "dqn", "lr": -1.0}, "lr"),
        ({"learner": "dqn", "lr": float("nan")}, "lr"),
        ({"learner": "dqn", "batch": 100, "replay": 10}, "batch"),
        ({"observation": "hfo"}, "observation"),
        ({"learner": "dqn", "epsilon_end": float("inf")}, "epsilon_end"),
    ],
)
def test_a_bad_learner_setting_is_a_value_error_and_writes_nothing(
    tmp_path: Path, agent: dict, key: str
) -> None:
    """One clear line naming the agent and the key, nothing written."""
    out = tmp_path / "bad"
    with pytest.raises(ValueError, match=rf"team\[0\].*\b{key}\b"):
        adhoc_advising.run(out=out, team=[agent, {}, {}], **TINY)
    assert not out.exists()


def test_a_dqn_reads_hfos_features_where_a_table_says_so(tmp_path: Path) -> None:
    """``observation="hfo"`` in a DQN's table is the team file's; with the
    tabular learner it is a ValueError naming the key, and nothing is
    written."""
    options = {"runs": 1, "episodes": 40, "eval_every": 20, "eval_episodes": 5, "seed": 3}
    dqn = {"algorithm": "adhoc-td", "learner": "dqn", "warmup": 8, "batch": 8}
    hfo = [{**dqn, "observation": "hfo"}] * 3
    adhoc_advising.run(out=tmp_path / "py", team=hfo, **options)
    team = tmp_path / "team.toml"
    agent = '[[agent]]\nalgorithm = "adhoc-td"\nlearner = "dqn"\nwarmup = 8\nbatch = 8\n'
    team.write_text((agent + 'observation = "hfo"\n\n') * 3)
    run_command_line(tmp_path / "cli", f"--team={team}", **options)
    assert_same_results(tmp_path / "py", tmp_path / "cli")
    config = json.loads((tmp_path / "py" / "config.json").read_text())
    assert [a["observation"] for a in config["config"]["team"]] == ["hfo"] * 3
    adhoc_advising.run(out=tmp_path / "paper", team=[dqn] * 3, **options)
    paper = (tmp_path / "paper" / "run-0.csv").read_bytes()
    assert paper != (tmp_path / "py" / "run-0.csv").read_bytes()
    message = "`observation`: does not apply to learner sarsa; it belongs to learner dqn"
    with pytest.raises(ValueError, match=re.escape(message)):
        adhoc_advising.run(out=tmp_path / "bad", team=[{"observation": "hfo"}] * 3, **options)
    assert not (tmp_path / "bad").exists()


def test_a_team_file_and_its_tables_give_the_same_results(tmp_path: Path) -> None:
    team = tmp_path / "team.toml"
    team.write_text(
        '[[agent]]\nalgorithm = "torrey"\n\n[[agent]]\nalgorithm = "adhoc-td"\n\n'
        '[[agent]]\nalgorithm = "no-advice"\n'
    )
    adhoc_advising.run(out=tmp_path / "file", team=team, **SMALL)
    tables = [{"algorithm": a} for a in ("torrey", "adhoc-td", "no-advice")]
    adhoc_advising.run(out=tmp_path / "tables", team=tables, **SMALL)
    assert_same_results(tmp_path / "file", tmp_path / "tables")


def test_a_python_learner_learns_beside_adhoc_td_and_is_deterministic(tmp_path: Path) -> None:
    for out in ("a", "b"):
        adhoc_advising.run(out=tmp_path / out, team=mixed_team(LinearSarsa), seed=3, **SMALL)
    assert_same_results(tmp_path / "a", tmp_path / "b")
    config = json.loads((tmp_path / "a" / "config.json").read_text())
    recorded = config["config"]["team"][2]["plugin"]["learner"]
    assert recorded == "numpy-linear-sarsa 2 (numpy_learner.LinearSarsa)"
    run = json.loads((tmp_path / "a" / "run-0.json").read_text())
    python_agent = run["points"][-1]["agents"][2]
    assert python_agent["advice_requests"] > 0 and python_agent["advice_given"] > 0


def test_an_instance_is_copied_for_every_run(tmp_path: Path) -> None:
    template = LinearSarsa(Start(0, 3, 0, 11, 6, tuple(adhoc_advising.PAPER_ACTIONS)))
    adhoc_advising.run(out=tmp_path / "out", team=mixed_team(template), **SMALL)
    assert not template.weights.any(), "the given instance itself learned"


class Failing(LinearSarsa):
    """Raises in its 30th `learn`."""

    name = "failing"

    def __init__(self, start: Start) -> None:
        super().__init__(start)
        self.calls = 0

    def learn(self, t: Transition) -> None:
        self.calls += 1
        if self.calls == 30:
            raise ValueError("a broken update")
        super().learn(t)


def test_a_learner_raising_ends_the_run_with_its_traceback(tmp_path: Path) -> None:
    out = tmp_path / "out"
    with pytest.raises(RuntimeError) as raised:
        adhoc_advising.run(out=out, team=mixed_team(Failing), **SMALL)
    message = str(raised.value)
    assert "agent 2's learner `failing" in message and "raised in `learn`" in message, message
    cause = raised.value.__cause__
    assert isinstance(cause, ValueError) and str(cause) == "a broken update"
    frames = [f.name for f in traceback.extract_tb(cause.__traceback__)]
    assert "learn" in frames, frames
    for written in out.glob("*.json"):
        json.loads(written.read_text())
    assert not [p for p in out.iterdir() if p.name.startswith(".")], list(out.iterdir())


def test_a_python_learner_is_saved_and_loaded(tmp_path: Path) -> None:
    saved = tmp_path / "saved"
    adhoc_advising.run(
        out=tmp_path / "train",
        team=mixed_team(LinearSarsa),
        save_agents=saved,
        **{**SMALL, "runs": 1},
    )
    snapshot = saved / "run-0-agent-2.snapshot"
    assert snapshot.stat().st_size > 0

    restored: list[bytes] = []

    class Recording(LinearSarsa):
        def restore(self, state: bytes) -> None:
            restored.append(state)
            super().restore(state)

    team = mixed_team(Recording)
    team[2]["load"] = str(snapshot)
    adhoc_advising.run(out=tmp_path / "again", team=team, **{**SMALL, "runs": 1})
    assert restored and restored[0].startswith(b"\x93NUMPY"), restored[:1]


def test_a_python_strategy_decides_in_process(tmp_path: Path) -> None:
    team = [
        {"algorithm": "adhoc-td"},
        {"algorithm": "adhoc-td"},
        {"algorithm": NearestTeammate},
    ]
    for out in ("a", "b"):
        adhoc_advising.run(out=tmp_path / out, team=team, seed=5, **SMALL)
    assert_same_results(tmp_path / "a", tmp_path / "b")
    # The spelling before 0.3 plays the same.
    old = [*team[:2], {"algorithm": "external", "strategy": NearestTeammate}]
    adhoc_advising.run(out=tmp_path / "old", team=old, seed=5, **SMALL)
    assert_same_results(tmp_path / "a", tmp_path / "old")
    config = json.loads((tmp_path / "a" / "config.json").read_text())
    recorded = config["config"]["team"][2]["plugin"]["strategy"]
    assert recorded == "nearest-teammate 1 (nearest_teammate.NearestTeammate)"
    agents = json.loads((tmp_path / "a" / "run-0.json").read_text())["points"][-1]["agents"]
    # It asks one teammate a time: about one reply per request.
    assert 0 < agents[2]["advice_replies_received"] <= agents[2]["advice_requests"]
    assert agents[2]["advice_given"] > 0


class Unreachable(NearestTeammate):
    """Names itself as an advisor."""

    def advisors(self, me: int, team_size: int, positions: object) -> list[int]:
        return [me]


def test_a_strategy_answering_wrongly_is_named(tmp_path: Path) -> None:
    team = [
        {"algorithm": "adhoc-td"},
        {"algorithm": "adhoc-td"},
        {"algorithm": Unreachable},
    ]
    with pytest.raises(RuntimeError, match=r"agent 2's strategy `nearest-teammate.*`advisors`"):
        adhoc_advising.run(out=tmp_path / "out", team=team, **SMALL)


def test_a_team_of_snapshots_replays_as_an_animation_and_a_game_log(tmp_path: Path) -> None:
    saved = tmp_path / "saved"
    adhoc_advising.run(
        out=tmp_path / "train", algorithm="adhoc-td", save_agents=saved, **{**SMALL, "runs": 1}
    )
    team = [
        {"algorithm": "adhoc-td", "load": str(saved / f"run-0-agent-{i}.snapshot")}
        for i in range(3)
    ]
    replay = adhoc_advising.replay(team=team, seed=4)
    assert replay == adhoc_advising.replay(team=team, seed=4)
    frames = int(re.search(r"after (\d+) frames?", replay.summary).group(1))
    shows = [line for line in replay.rcg.splitlines() if line.startswith("(show ")]
    assert len(shows) == frames + 1 and replay.rcg.startswith("ULG5")
    # The three attackers, the keeper and the ball move.
    assert replay.svg.count("<animateTransform") == 5
    assert replay._repr_svg_() == replay.svg
    assert replay.save(tmp_path / "episode.rcg").read_text() == replay.rcg
    assert replay.svg in replay.save(tmp_path / "episode.html").read_text()
    with pytest.raises(ValueError, match=".svg, .html or .rcg"):
        replay.save(tmp_path / "episode.png")


def test_bad_arguments_are_named(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="algorithm"):
        adhoc_advising.run(out=tmp_path / "a", algorithm="no-such-method")
    with pytest.raises(ValueError, match="runs"):
        adhoc_advising.run(out=tmp_path / "b", algorithm="adhoc-td", runs=0)
    with pytest.raises(TypeError, match="learner"):
        adhoc_advising.run(out=tmp_path / "c", team=mixed_team(42))
    with pytest.raises(ValueError, match="zenoh"):
        adhoc_advising.study(out=tmp_path / "d", config=study_file(tmp_path, "zenoh"))


def study_file(directory: Path, transport: str = "in-process") -> Path:
    """A small study of two entries."""
    path = directory / f"{transport}.toml"
    path.write_text(
        f'name = "small"\nruns = 2\nepisodes = 100\neval_every = 50\neval_episodes = 10\n'
        f'transport = "{transport}"\nbaseline = "no-advice"\n\n'
        '[[entry]]\nname = "no-advice"\nalgorithm = "no-advice"\n\n'
        '[[entry]]\nname = "adhoc-td"\nalgorithm = "adhoc-td"\n'
    )
    return path


def test_a_study_in_process_reads_back_as_dataframes(tmp_path: Path) -> None:
    pytest.importorskip("pandas")
    out = adhoc_advising.study(out=tmp_path / "small", config=study_file(tmp_path))
    assert (out / "REPORT.md").is_file()
    study = adhoc_advising.load(out)
    assert set(study.curves["entry"]) == {"no-advice", "adhoc-td"}
    assert list(study.gains["entry"]) == ["adhoc-td"]


CTRL_C = """
import adhoc_advising, signal, sys
# As in a terminal, whatever the shell that started the tests ignores.
signal.signal(signal.SIGINT, signal.default_int_handler)
adhoc_advising.run(out=sys.argv[1], algorithm="adhoc-td", runs=2, episodes=20000,
                   eval_every=500, eval_episodes=20, threads=2)
print("finished")
"""


def test_ctrl_c_stops_cleanly_and_the_same_call_resumes(tmp_path: Path) -> None:
    out = tmp_path / "out"
    child = subprocess.Popen(
        [sys.executable, "-c", CTRL_C, str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    deadline = time.monotonic() + 120
    # Interrupted once its runs are under way (their first evaluation
    # written), seconds before they could end.
    while not (out / "run-0.csv").exists() and time.monotonic() < deadline:
        time.sleep(0.1)
    time.sleep(0.5)
    child.send_signal(signal.SIGINT)
    _, stderr = child.communicate(timeout=120)
    assert child.returncode != 0 and "KeyboardInterrupt" in stderr, stderr
    for written in out.glob("*.json"):
        json.loads(written.read_text())
    assert not [p for p in out.iterdir() if p.name.startswith(".")], list(out.iterdir())
    again = subprocess.run(
        [sys.executable, "-c", CTRL_C, str(out)], capture_output=True, text=True, timeout=600
    )
    assert again.returncode == 0 and "finished" in again.stdout, again.stderr
    assert (out / "summary.json").is_file()
