"""The parsers of hfo_oracle.logs on small excerpts of each file."""

import pytest

from hfo_oracle import logs

HFO_LOG = """\
# Trial\tStart\tEnd\tDuration\tStatus
0\t0\t57\t57\tGOAL-11

1\t60\t94\t34\tCAPTURED_BY_DEFENSE-1
2\t97\t297\t200\tOUT_OF_TIME-0
"""

TRAINER_OUTPUT = """\
[start.py] Starting server
Waiting for player-controlled agent base_left-0
EndOfTrial: 1 / 1 57 GOAL-11
Some other line: EndOfTrial: 9 / 9 9 GOAL
EndOfTrial: 1 / 2 94 CAPTURED_BY_DEFENSE-1
"""

RCL = """\
0,0\t(referee before_kick_off)
12,0\tRecv base_left_7: (dash 100 0)(turn_neck 10)
12,0\tRecv base_left_7: (kick 100 0)
12,0\tRecv base_left_8: (turn_neck 10)(kick 50 30)
12,0\tRecv base_right_1: (kick 100 0)
13,0\tRecv base_left_9: (kick 100 0)
13,1\tRecv base_left_11: (say "kick")(kick 20 -10)
57,0\t(referee GOAL)
94,0\t(referee CAPTURED_BY_DEFENSE)
97,0\t(referee play_on)
297,0\t(referee OUT_OF_TIME)
"""

RCG = """\
ULG5
(server_param (ball_size 0.1)(goal_width 14.02)(kickable_margin 0.7))
(player_param (player_types 18))
(player_type (id 0)(player_speed_max 1.05)(kickable_margin 0.7)(player_size 0.3))
(player_type (id 3)(player_speed_max 1.05)(kickable_margin 0.95)(player_size 0.3))
(playmode 1 play_on)
(team 1 base_left base_right 0 0)
(show 1 ((b) 10.5 -2.25 0.1 0) ((l 7) 3 0x1 10 -2 0.2 0 45 0 (v h 90) (s 8000 1 1 130600) \
(c 4 12 3 0 1 4 0 0 0 0 0)) ((l 9) 0 0x1 20 5 0 0 0 0 (v h 90) (s 8000 1 1 130600) \
(c 0 0 0 0 0 0 0 0 0 0 0)) ((r 1) 1 0x9 50 0 0 0 180 0 (v h 90) (s 8000 1 1 130600) \
(c 0 0 0 3 0 0 0 0 0 0 0)))
(show 2 ((b) 12 -2 1.5 0) ((l 7) 3 0x1 10.1 -2 0.1 0 45 0 (v h 90) (s 8000 1 1 130600) \
(c 5 12 3 0 1 4 0 0 0 0 0)) ((r 1) 1 0x9 50 0 0 0 180 0 (v h 90) (s 8000 1 1 130600) \
(c 0 0 0 3 0 0 0 0 0 0 0)))
"""


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def test_parse_hfo_log(tmp_path):
    trials = logs.parse_hfo_log(write(tmp_path, "x.hfo", HFO_LOG))
    assert trials == [(0, 57, "GOAL"), (60, 94, "CAPTURED_BY_DEFENSE"), (97, 297, "OUT_OF_TIME")]
    assert trials[1].start == 60 and trials[1].end == 94
    assert trials[2].result == "OUT_OF_TIME"


def test_parse_trainer_output_reads_only_end_of_trial_lines(tmp_path):
    ends = logs.parse_trainer_output(write(tmp_path, "hfo.out", TRAINER_OUTPUT))
    assert ends == [(57, "GOAL"), (94, "CAPTURED_BY_DEFENSE")]


def test_parse_rcl_keeps_the_offense_kicks_and_the_trial_ends(tmp_path):
    kicks, ends = logs.parse_rcl(write(tmp_path, "x.rcl", RCL), {7, 8, 11})
    # 9 is not of the offense given, base_right never is.
    assert kicks == {12: [7, 8], 13: [11]}
    assert ends == [(57, "GOAL"), (94, "CAPTURED_BY_DEFENSE"), (297, "OUT_OF_TIME")]


def test_iter_rcg_reads_the_shows_and_the_kick_areas(tmp_path):
    areas = logs.KickAreas()
    shows = list(logs.iter_rcg(write(tmp_path, "x.rcg", RCG), {"l 7", "l 8"}, areas))
    assert [s.cycle for s in shows] == [1, 2]
    first = shows[0]
    assert first.ball == (10.5, -2.25)
    # Only the players asked for, and only those the show lists.
    assert first.players == {"l 7": logs.PlayerShow(10.0, -2.0, 3, 4)}
    assert shows[1].players["l 7"].kicks == 5
    assert areas.ball_size == 0.1
    assert areas.by_type == {0: (0.7, 0.3), 3: (0.95, 0.3)}
    assert areas.radius(3) == pytest.approx(0.95 + 0.3 + 0.1)
    # A type the log does not list: rcssserver's defaults.
    assert areas.radius(17) == pytest.approx(0.7 + 0.3 + 0.1)


def test_kick_areas_default_to_rcssserver_s_ball():
    assert logs.KickAreas().radius(0) == pytest.approx(0.7 + 0.3 + 0.085)


def test_agent_files_read_back_what_the_agent_writes(tmp_path):
    text = (
        logs.unum_line(7)
        + logs.decision_line(0, 3, "S", 0)
        + logs.decision_line(0, 5, "N", 8)
        + logs.episode_line(0, 12, "Goal")
        + "\n"
        + logs.decision_line(1, 0, "M", 0)
        + logs.episode_line(1, 1, "ServerDown")
    )
    assert text.splitlines()[:3] == ["U 7", "D 0 3 S 0", "D 0 5 N 8"]
    record = logs.read_agent_file(write(tmp_path, "agent0.txt", text))
    assert record.unum == 7
    assert record.decisions == {(0, 3): "S", (0, 5): "N", (1, 0): "M"}
    assert record.episodes == [(12, "Goal"), (1, "ServerDown")]


def test_find_log_wants_exactly_one_file(tmp_path):
    write(tmp_path, "a.rcg", "")
    write(tmp_path, "a.rcl", "")
    write(tmp_path, "b.rcl", "")
    assert logs.find_log(str(tmp_path), ".rcg") == str(tmp_path / "a.rcg")
    with pytest.raises(RuntimeError, match="expected one .rcl log"):
        logs.find_log(str(tmp_path), ".rcl")
    with pytest.raises(RuntimeError, match="expected one .hfo log"):
        logs.find_log(str(tmp_path), ".hfo")
