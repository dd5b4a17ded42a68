"""The agent's reading of HFO's high-level features (hfo_oracle.agent),
without HFO: states built by hand in its layout; and the factory of a
learned team's agents, found by its name."""

import math
import os.path

import pytest

from hfo_oracle import agent
from hfo_oracle.schema import ACTION_CODES, POLICIES


def normalise(v, lo, hi):
    return 2 * (v - lo) / (hi - lo) - 1


def state_with(me, mates):
    """A 27-feature state (2 teammates) with own position ``me`` and
    teammates ``(x, y, unum)`` (None: invalid, -2 as HFO marks it)."""
    s = [0.0] * 27
    s[0], s[1] = normalise(me[0], *agent.X_RANGE), normalise(me[1], *agent.Y_RANGE)
    for i, mate in enumerate(mates):
        if mate is None:
            s[16 + 3 * i : 19 + 3 * i] = [-2.0, -2.0, -2.0]
        else:
            x, y, u = mate
            s[16 + 3 * i : 19 + 3 * i] = [
                normalise(x, *agent.X_RANGE),
                normalise(y, *agent.Y_RANGE),
                float(u),
            ]
    return s


def test_the_ranges_are_hfo_s_area_plus_ten_percent():
    assert agent.X_RANGE == (-5.25, 57.75)
    assert agent.Y_RANGE == pytest.approx((-37.4, 37.4))
    assert agent.unnormalise(-1, 0, 10) == 0 and agent.unnormalise(1, 0, 10) == 10


def test_teammates_nearest_first():
    s = state_with((30, 0), [(30, 20, 11), (34, 3, 8)])
    near = agent.teammates(s, 2)
    assert [u for _, u in near] == [8, 11]
    assert near[0][0] == pytest.approx(5.0)
    assert near[1][0] == pytest.approx(20.0)
    assert agent.pass_target(s, 2, "N") == 8
    assert agent.pass_target(s, 2, "F") == 11


def test_teammates_hfo_does_not_show_are_left_out():
    s = state_with((30, 0), [None, (34, 3, 8)])
    assert [u for _, u in agent.teammates(s, 2)] == [8]
    assert agent.pass_target(state_with((30, 0), [None, None]), 2, "N") == 0


def test_paper_state_from_hfo_s_features():
    s = [0.0] * 27
    s[5], s[7], s[8], s[10], s[11] = 1.0, 0.25, -0.5, 0.125, -0.75
    max_r = math.hypot(52.5, 68)
    authors_max = math.hypot(52.5, 34)
    s[6] = normalise(20.0, 0, max_r)  # 20 m from the goal centre
    assert agent.paper_state(s) == pytest.approx(
        [1.0, 2 * 20.0 / authors_max - 1, 0.25, -0.5, 0.125, -0.75]
    )
    s[6] = 1.0  # farther than the authors' range: clamped
    assert agent.paper_state(s)[1] == pytest.approx(1.0)


def test_every_policy_draws_known_actions():
    assert set(agent.POLICY_CODES) == set(POLICIES)
    for codes in agent.POLICY_CODES.values():
        assert set(codes) <= set(ACTION_CODES) - {"M"}


def test_a_team_factory_is_found_by_module_and_dotted_name():
    assert agent.split_factory("os.path:join") == ("os.path", "join")
    assert agent.load_factory("os.path:join") is os.path.join
    assert agent.load_factory("math:inf.__class__") is float
    for bad in ("os.path", "os.path:", ":join", "os path:join", "os.path:join()", "os:path:join"):
        with pytest.raises(ValueError, match="is not MODULE:CALLABLE"):
            agent.split_factory(bad)


def test_a_team_agent_needs_its_snapshot_and_factory(capsys):
    common = ["--port", "1", "--seed", "1", "--config-dir", "c", "--out", "o", "--policy", "team"]
    with pytest.raises(SystemExit):
        agent.parse_args(common + ["--snapshot", "a.snapshot"])
    assert "--policy team needs --snapshot and --team-factory" in capsys.readouterr().err
    a = agent.parse_args(common + ["--snapshot", "a.snapshot", "--team-factory", "m:f"])
    assert (a.snapshot, a.team_factory) == ("a.snapshot", "m:f")
