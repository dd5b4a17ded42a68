"""The PyTorch example (examples/torch_dqn.py), a Double DQN: it learns which
kick pays on made-up kicks, one seed giving one network, and keeps what it
learned through save and restore; beside two Rust AdHocTD agents it learns
and advises in process, the same seed giving the same files on one thread
or two and its snapshot loading into a new run, and over zenoh as a
learner process, its snapshot saved. Skipped where torch is not installed
(docs/learners.md says how to install it)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import ROOT, workspace_binary

import adhoc_advising
from adhoc_advising.learner import Start, Transition

pytest.importorskip("torch")

EXAMPLES = ROOT / "coordinator" / "python" / "examples"
EXAMPLE = EXAMPLES / "torch_dqn.py"
sys.path.insert(0, str(EXAMPLES))
from torch_dqn import DoubleDqn  # noqa: E402

START = Start(2, 3, 0, 7, 6, tuple(adhoc_advising.PAPER_ACTIONS))
SMALL = {"runs": 2, "episodes": 150, "eval_every": 50, "eval_episodes": 10, "threads": 2}
#: Keys of measured times, which differ from one invocation to the next.
MEASURED = {"training_s", "evaluation_s", "wall_s", "frames_per_sec"}


def without_times(value: object) -> object:
    """A JSON value without its measured times."""
    if isinstance(value, dict):
        return {k: without_times(v) for k, v in value.items() if k not in MEASURED}
    if isinstance(value, list):
        return [without_times(v) for v in value]
    return value


def assert_same_results(a: Path, b: Path, runs: int) -> None:
    """Every run file of `a` equals `b`'s, but for the times measured."""
    for k in range(runs):
        assert (a / f"run-{k}.csv").read_text() == (b / f"run-{k}.csv").read_text(), k
        left = json.loads((a / f"run-{k}.json").read_text())
        assert without_times(left) == without_times(json.loads((b / f"run-{k}.json").read_text()))


def mixed_team(learner: object) -> list[dict]:
    """Two Rust AdHocTD agents and one AdHocTD agent learning with `learner`."""
    return [
        {"algorithm": "adhoc-td"},
        {"algorithm": "adhoc-td"},
        {"algorithm": "adhoc-td", "learner": learner},
    ]


def learner_bytes(snapshot: bytes) -> bytes:
    """The learner's own bytes in a snapshot of format version 2: the last
    item of its postcard body (a varint length, then the bytes), before the
    body's 8-byte checksum; torch.save's bytes are a zip archive."""
    assert snapshot[:8] == b"ADVQTAB\0" and int.from_bytes(snapshot[8:10], "little") == 2
    end = len(snapshot) - 8
    at = snapshot.find(b"PK\x03\x04")
    while at >= 0:
        length, shift, i = 0, 0, at
        # The varint before `at`, read backwards: its last byte is < 0x80.
        digits = []
        while i > 0 and (not digits or snapshot[i - 1] >= 0x80) and len(digits) < 10:
            i -= 1
            digits.append(snapshot[i])
        for byte in reversed(digits):
            length |= (byte & 0x7F) << shift
            shift += 7
        if length == end - at:
            return snapshot[at:end]
        at = snapshot.find(b"PK\x03\x04", at + 1)
    raise AssertionError("no learner bytes in the snapshot")


def one_kick_episodes(dqn: DoubleDqn, states: list[tuple[float, ...]], kicks: int) -> None:
    """One-kick episodes: SHOOT scores (+1), DRIBBLE loses the ball (-1)."""
    for i in range(kicks):
        kick = 1 if i % 2 else 2
        dqn.learn(Transition(states[i % len(states)], kick, 1.0 if kick == 1 else -1.0, None, None))
        dqn.end_episode()


def test_it_learns_which_kick_pays_and_restores_what_it_learned() -> None:
    """Whatever the state, after a few hundred kicks it values SHOOT above
    0.5 and DRIBBLE below -0.5; another learner of the same seed fed the same
    kicks has the same values, one of another seed other values; a fresh
    learner restored from its bytes values every state alike."""
    dqn = DoubleDqn(START)
    states = [tuple((i * 0.37 + f * 0.11) % 2 - 1 for f in range(6)) for i in range(50)]
    assert dqn.values(states[0], None) == [None] * 5, "values before it learned anything"
    one_kick_episodes(dqn, states, 400)
    assert dqn.updates == 400 - dqn.warmup + 1
    for state in states[:5]:
        q = dqn.values(state, None)
        assert q[0] is None and q[1] > 0.5 and q[2] < -0.5, q
    twin = DoubleDqn(START)
    one_kick_episodes(twin, states, 400)
    assert [twin.values(s, None) for s in states] == [dqn.values(s, None) for s in states]
    other = DoubleDqn(Start(2, 3, 0, 8, 6, START.actions))
    one_kick_episodes(other, states, 400)
    assert other.values(states[0], None) != dqn.values(states[0], None)
    again = DoubleDqn(Start(2, 3, 0, 99, 6, START.actions))
    again.restore(dqn.save())
    assert [again.values(s, None) for s in states] == [dqn.values(s, None) for s in states]
    assert (again.updates, again.decisions) == (dqn.updates, dqn.decisions)
    assert again.choose(states[0], None) in (1, 2, 3, 4)


def test_it_learns_beside_adhoc_td_in_process_and_a_seed_gives_one_run(tmp_path: Path) -> None:
    # One seed, the same files, whether its two runs play at once or in turn.
    for out, threads in (("a", 2), ("b", 1)):
        adhoc_advising.run(
            out=tmp_path / out,
            team=mixed_team(DoubleDqn),
            seed=3,
            save_agents=tmp_path / f"saved-{out}",
            **{**SMALL, "threads": threads},
        )
    assert_same_results(tmp_path / "a", tmp_path / "b", SMALL["runs"])
    config = json.loads((tmp_path / "a" / "config.json").read_text())
    recorded = config["config"]["team"][2]["plugin"]["learner"]
    assert recorded == "torch-double-dqn 1 (torch_dqn.DoubleDqn)"
    run = json.loads((tmp_path / "a" / "run-0.json").read_text())
    dqn = run["points"][-1]["agents"][2]
    # It asked, and it advised: its values spread only once it has trained.
    assert dqn["advice_requests"] > 0 and dqn["advice_given"] > 0, dqn
    # Its snapshots, the same for the same seed, hold a trained network...
    snapshots = [tmp_path / f"saved-{out}" / "run-0-agent-2.snapshot" for out in ("a", "b")]
    assert snapshots[0].read_bytes() == snapshots[1].read_bytes()
    trained = DoubleDqn(START)
    trained.restore(learner_bytes(snapshots[0].read_bytes()))
    assert trained.updates > 0 and trained.values((0.0,) * 6, None)[1] is not None
    # ...which a new run's agent starts from.
    restored: list[int] = []

    class Recording(DoubleDqn):
        def restore(self, state: bytes) -> None:
            super().restore(state)
            restored.append(self.updates)

    team = mixed_team(Recording)
    team[2]["load"] = str(snapshots[0])
    adhoc_advising.run(out=tmp_path / "loaded", team=team, **{**SMALL, "runs": 1})
    assert restored and set(restored) == {trained.updates}, restored
    # Another seed plays another run.
    adhoc_advising.run(out=tmp_path / "c", team=mixed_team(DoubleDqn), seed=4, **SMALL)
    other = json.loads((tmp_path / "c" / "run-0.json").read_text())
    assert without_times(other["points"]) != without_times(run["points"])


def test_it_learns_over_zenoh_as_a_learner_process(tmp_path: Path) -> None:
    command = json.dumps([sys.executable, str(EXAMPLE)])
    team = tmp_path / "team.toml"
    team.write_text(
        '[[agent]]\nalgorithm = "adhoc-td"\n\n[[agent]]\nalgorithm = "adhoc-td"\n\n'
        f'[[agent]]\nalgorithm = "adhoc-td"\n'
        f'learner = {{ command = {command}, source = "{EXAMPLE}" }}\n'
    )
    out, agents = tmp_path / "out", tmp_path / "agents"
    result = subprocess.run(
        [
            str(workspace_binary("coordinator")),
            "run",
            "--team",
            str(team),
            "--runs",
            "1",
            "--episodes",
            "200",
            "--eval-every",
            "100",
            "--eval-episodes",
            "20",
            "--transport",
            "zenoh",
            "--quiet",
            "--save-agents",
            str(agents),
            "--out",
            str(out),
        ],
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert result.returncode == 0, result.stderr
    config = json.loads((out / "config.json").read_text())
    learner = config["config"]["team"][2]["learner"]
    assert learner["command"][-1] == str(EXAMPLE) and len(learner["source_fnv64"]) == 16
    points = json.loads((out / "run-0.json").read_text())["points"]
    assert [p["episode"] for p in points] == [0, 100, 200], points
    last = points[-1]["agents"]
    assert last[2]["advice_requests"] > 0 and last[2]["advice_given"] > 0, last[2]
    assert sum(a["advice_replies_received"] for a in last[:2]) > 0
    # Its snapshot holds the framework's part and the learner's torch.save
    # bytes, which a fresh learner restores.
    restored = DoubleDqn(START)
    restored.restore(learner_bytes((agents / "run-0-agent-2.snapshot").read_bytes()))
    assert restored.updates > 0 and restored.values((0.0,) * 6, None)[1] is not None
