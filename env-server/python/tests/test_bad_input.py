"""Bad input is a Python exception naming what is wrong, raised before
anything steps: never a Rust panic, never an action silently dropped."""

from __future__ import annotations

import numpy as np
import pytest

import halffield


@pytest.fixture
def env() -> halffield.HalfFieldOffenseParallelEnv:
    env = halffield.parallel_env(masked_action="raise")
    env.reset(seed=1)
    return env


def test_unknown_agent(env: halffield.HalfFieldOffenseParallelEnv) -> None:
    actions = {a: halffield.MOVE for a in env.agents}
    actions["offense_7"] = halffield.MOVE
    with pytest.raises(
        ValueError, match=r"unknown agent 'offense_7' \(agents: offense_0, offense_1, offense_2\)"
    ):
        env.step(actions)
    with pytest.raises(ValueError, match="unknown agent 'keeper'"):
        env.action_space("keeper")
    with pytest.raises(ValueError, match="unknown agent"):
        env.observation_space("offense_3")


def test_missing_agent(env: halffield.HalfFieldOffenseParallelEnv) -> None:
    with pytest.raises(ValueError, match="no action for offense_2"):
        env.step({"offense_0": 0, "offense_1": 0})


def test_actions_must_be_a_dict_of_integers(env: halffield.HalfFieldOffenseParallelEnv) -> None:
    with pytest.raises(TypeError, match="actions must be a dict"):
        env.step([0, 0, 0])
    with pytest.raises(TypeError, match=r"the action of offense_1 must be an integer, got 1\.0"):
        env.step({"offense_0": 0, "offense_1": 1.0, "offense_2": 0})
    # numpy integers are integers.
    env.step({a: np.int64(0) for a in env.agents})


@pytest.mark.parametrize("action", [-1, 5, 2**70])
def test_action_out_of_range(env: halffield.HalfFieldOffenseParallelEnv, action: int) -> None:
    actions = {a: halffield.MOVE for a in env.agents}
    actions["offense_1"] = action
    if action == 2**70:
        with pytest.raises(OverflowError):
            env.step(actions)
        return
    with pytest.raises(
        ValueError,
        match=rf"action {action} of offense_1 is out of range: "
        r"expected an integer from 0 \(MOVE\) to 4 \(PASS to teammate 1\)",
    ):
        env.step(actions)


def test_nothing_steps_when_an_action_is_refused(
    env: halffield.HalfFieldOffenseParallelEnv,
) -> None:
    before = env.state()
    with pytest.raises(ValueError):
        env.step({"offense_0": 0, "offense_1": 0, "offense_2": 9})
    np.testing.assert_array_equal(env.state(), before)
    _, _, _, _, infos = env.step({a: 0 for a in env.agents})
    assert infos["offense_0"]["frame"] == 1


def test_masked_actions_raise_when_asked(env: halffield.HalfFieldOffenseParallelEnv) -> None:
    actions = {a: halffield.MOVE for a in env.agents}
    actions["offense_2"] = halffield.SHOOT
    with pytest.raises(
        ValueError,
        match=r"offense_2 cannot kick, so MOVE \(0\) is its only allowed action, got 1 \(SHOOT\)",
    ):
        env.step(actions)


def _trajectory(
    masked_action: str, action: int, seed: int = 6, steps: int = 60
) -> list[np.ndarray]:
    env = halffield.parallel_env(masked_action=masked_action)
    observations, infos = env.reset(seed=seed)
    states = []
    for _ in range(steps):
        if not env.agents:
            break
        actions = {
            a: action if not infos[a]["action_mask"][1] else halffield.DRIBBLE for a in env.agents
        }
        observations, _, _, _, infos = env.step(actions)
        states.append(env.state())
    return states


def test_masked_actions_follow_the_documented_rule() -> None:
    """ "move" plays a masked action as MOVE; "hfo" plays it as HFO does,
    without a body command (the last-action feature says it failed)."""
    moved = _trajectory("move", halffield.SHOOT)
    np.testing.assert_array_equal(moved, _trajectory("hfo", halffield.MOVE))
    assert not np.array_equal(moved, _trajectory("hfo", halffield.SHOOT))
    env = halffield.parallel_env()
    env.reset(seed=6)
    observations, _, _, _, _ = env.step({a: halffield.SHOOT for a in env.agents})
    assert all(obs[-2] == -1.0 for obs in observations.values())
    observations, _, _, _, _ = env.step({a: halffield.MOVE for a in env.agents})
    assert all(obs[-2] == 1.0 for obs in observations.values())


def test_an_action_for_a_finished_episode() -> None:
    env = halffield.parallel_env()
    env.reset(seed=1)
    while env.agents:
        _, _, _, _, infos = env.step({a: halffield.MOVE for a in env.agents})
    status, frame = infos["offense_0"]["status"], infos["offense_0"]["frame"]
    with pytest.raises(ValueError, match="offense_0 is not playing: its episode has ended"):
        env.step({"offense_0": 0})
    with pytest.raises(
        RuntimeError, match=rf"the episode has ended \({status} at frame {frame}\): call reset\(\)"
    ):
        env.step({})
    gym = halffield.HalfFieldOffenseEnv(teammates="shoot")
    gym.reset(seed=1)
    done = False
    while not done:
        _, _, terminated, truncated, _ = gym.step(halffield.MOVE)
        done = terminated or truncated
    with pytest.raises(RuntimeError, match="the episode has ended"):
        gym.step(halffield.MOVE)


def test_step_before_reset() -> None:
    with pytest.raises(RuntimeError, match=r"no episode has started: call reset\(\) first"):
        halffield.parallel_env().step({})
    with pytest.raises(RuntimeError, match="call reset"):
        halffield.HalfFieldOffenseEnv().step(0)
    with pytest.raises(RuntimeError, match="call reset"):
        halffield.BatchEnv(2).step(np.zeros((2, 3), dtype=np.int64))
    with pytest.raises(RuntimeError, match="call reset"):
        halffield.parallel_env().state()


@pytest.mark.parametrize("shape", [(4,), (4, 2), (3, 3), (4, 3, 1), (12,)])
def test_wrong_shaped_batch(shape: tuple[int, ...]) -> None:
    batch = halffield.BatchEnv(4)
    batch.reset(seed=1)
    with pytest.raises(
        ValueError, match=r"actions must have shape \(envs, agents\) = \(4, 3\), got \["
    ):
        batch.step(np.zeros(shape, dtype=np.int64))


def test_bad_batch_actions_name_the_environment() -> None:
    batch = halffield.BatchEnv(4, masked_action="raise")
    _, infos = batch.reset(seed=1)
    actions = np.zeros((4, 3), dtype=np.int64)
    actions[2, 1] = 7
    with pytest.raises(ValueError, match=r"environment 2: action 7 of offense_1 is out of range"):
        batch.step(actions)
    actions[2, 1] = halffield.SHOOT
    with pytest.raises(ValueError, match=r"environment 2: offense_1 cannot kick"):
        batch.step(actions)
    with pytest.raises(TypeError, match="actions must be integers, got an array of dtype float64"):
        batch.step(np.zeros((4, 3)))
    # Refused steps left every environment where it was.
    observations, _, _, _, step_infos = batch.step(np.zeros((4, 3), dtype=np.int64))
    assert (step_infos["frame"] == 1).all()


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"offense": 0}, "offense must be between 1 and 4, got 0"),
        ({"offense": 5}, "offense must be between 1 and 4, got 5"),
        ({"offense": -1}, "offense must be a non-negative integer, got -1"),
        (
            {"observation": "pixels"},
            r"unknown observation \"pixels\" \(expected one of: hfo, authors, paper\)",
        ),
        (
            {"masked_action": "ignore"},
            r"unknown masked_action \"ignore\" \(expected one of: hfo, move, raise\)",
        ),
        ({"frames_per_trial": 0}, "frames_per_trial must be at least 1"),
        (
            {"render_mode": "human"},
            r"unknown render_mode 'human' \(expected None or one of: rgb_array, svg\)",
        ),
    ],
)
def test_bad_settings(kwargs: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        halffield.parallel_env(**kwargs)


def test_bad_seeds_and_policies() -> None:
    env = halffield.parallel_env()
    with pytest.raises(ValueError, match=r"seed must be in \[0, 2\*\*64\), got -1"):
        env.reset(seed=-1)
    with pytest.raises(TypeError, match="seed must be an integer, got 1.5"):
        env.reset(seed=1.5)
    with pytest.raises(
        ValueError,
        match=r"unknown policy 'best' \(expected one of: random, shoot, dribble, pass, uniform\)",
    ):
        halffield.ScriptedPolicy("best", 1)
    with pytest.raises(ValueError, match="unknown policy"):
        halffield.HalfFieldOffenseEnv(teammates="best")
    with pytest.raises(TypeError, match="teammates must be a scripted policy's name or a function"):
        halffield.HalfFieldOffenseEnv(teammates=3)
    with pytest.raises(ValueError, match="num_envs must be an integer from 1 to 1048576, got 0"):
        halffield.BatchEnv(0)
    with pytest.raises(ValueError, match="from 1 to 1048576, got 1000000000000"):
        halffield.BatchEnv(10**12)
    with pytest.raises(ValueError, match="threads must be a positive integer or None, got 0"):
        halffield.BatchEnv(2, threads=0)
    lone = halffield.parallel_env(offense=1)
    lone.reset(seed=1)
    policy = halffield.ScriptedPolicy("pass", 1)
    with pytest.raises(ValueError, match="passed, which a lone attacker cannot do"):
        for _ in range(10_000):
            if not lone.agents:
                lone.reset()
            lone.step(policy(lone))
