"""A scripted game written in the formats of one HFO run's files (the
``.hfo``, ``.rcl`` and ``.rcg`` logs, the trainer's output and the agents'
choice files), for the tests and for the fake HFO tree in ``fake_hfo/``.

A schedule is a list of trials (JSON-able dicts): ``start`` and ``end``
cycle, HFO's ``result`` status name, ``kicks`` as ``[cycle, unum, code,
released]`` (``code`` the kicker's choice, None for a kick without one),
and optionally ``choices`` without a kick as ``[cycle, unum, code]`` and
``commands``, kick commands sent out of reach, as ``[cycle, unum]``.
"""

from __future__ import annotations

import os

OFFENSE = (7, 8, 11)
# Where each offense player stands all game long, and where the ball rests
# when no one has it.
POSITION = {7: (40.0, 0.0), 8: (40.0, -8.0), 11: (30.0, 10.0)}
BALL_AWAY = (0.0, 30.0)
STATUS_STRINGS = {
    "GOAL": "Goal",
    "CAPTURED_BY_DEFENSE": "CapturedByDefense",
    "OUT_OF_BOUNDS": "OutOfBounds",
    "OUT_OF_TIME": "OutOfTime",
}

RCG_HEADER = (
    "ULG5\n"
    "(server_param (ball_size 0.085)(goal_width 14.02)(kickable_margin 0.7))\n"
    "(player_param (player_types 18))\n"
    "(player_type (id 0)(player_speed_max 1.05)(kickable_margin 0.7)(player_size 0.3))\n"
    "(player_type (id 1)(player_speed_max 1.05)(kickable_margin 0.9)(player_size 0.3))\n"
)


def _kicks_at(schedule: list[dict]) -> dict[int, tuple[int, bool]]:
    return {k[0]: (k[1], k[3]) for t in schedule for k in t["kicks"]}


def ball_at(schedule: list[dict], cycle: int) -> tuple[float, float]:
    """Beside the kicker in a kick's cycle, and in the next one when the
    kick did not release it; away from everyone otherwise."""
    kicks = _kicks_at(schedule)
    kicker = None
    if cycle in kicks:
        kicker = kicks[cycle][0]
    elif cycle - 1 in kicks and not kicks[cycle - 1][1]:
        kicker = kicks[cycle - 1][0]
    if kicker is None:
        return BALL_AWAY
    x, y = POSITION[kicker]
    return x + 0.3, y


def can_kick(schedule: list[dict], unum: int, cycle: int) -> bool:
    """Whether ``unum`` kicks (so could kick) at ``cycle``."""
    kicks = _kicks_at(schedule)
    return cycle in kicks and kicks[cycle][0] == unum


def write_logs(logdir: str, schedule: list[dict], name: str = "20260101-base_left_0") -> None:
    """rcssserver's three logs of ``schedule`` in ``logdir``."""
    with open(os.path.join(logdir, name + ".hfo"), "w") as f:
        f.write("# Trial\tStart\tEnd\tDuration\tStatus\n")
        for i, t in enumerate(schedule):
            f.write(
                "%d\t%d\t%d\t%d\t%s-7\n"
                % (i, t["start"], t["end"], t["end"] - t["start"], t["result"])
            )
    with open(os.path.join(logdir, name + ".rcl"), "w") as f:
        for t in schedule:
            commands = [(k[0], k[1]) for k in t["kicks"]] + [
                tuple(c) for c in t.get("commands", [])
            ]
            for cycle in range(t["start"], t["end"] + 1):
                f.write("%d,0\tRecv base_right_1: (catch 0)\n" % cycle)
                for c, unum in sorted(commands):
                    if c == cycle:
                        f.write(
                            "%d,0\tRecv base_left_%d: (turn_neck 10)(kick 100 0)\n" % (cycle, unum)
                        )
                f.write("%d,0\tRecv base_left_7: (dash 100 0)\n" % cycle)
            f.write("%d,0\t(referee %s)\n" % (t["end"], t["result"]))
    with open(os.path.join(logdir, name + ".rcg"), "w") as f:
        f.write(RCG_HEADER)
        for t in schedule:
            for cycle in range(t["start"], t["end"] + 1):
                f.write(show_line(schedule, cycle))


def show_line(schedule: list[dict], cycle: int) -> str:
    """The ``(show ...)`` line of ``cycle``: the ball, the offense players
    (type 0, kick counters as rcssserver counts them) and the goalie."""
    bx, by = ball_at(schedule, cycle)
    parts = ["(show %d ((b) %.4f %.4f 0 0)" % (cycle, bx, by)]
    for unum in OFFENSE:
        x, y = POSITION[unum]
        kicks = sum(1 for t in schedule for k in t["kicks"] if k[1] == unum and k[0] < cycle)
        parts.append(
            "((l %d) 0 0x1 %.4f %.4f 0 0 0 0 (v h 90) (s 8000 1 1 130600) "
            "(c %d 12 3 0 1 4 0 0 0 0 0))" % (unum, x, y, kicks)
        )
    parts.append(
        "((r 1) 1 0x9 50 0 0 0 180 0 (v h 90) (s 8000 1 1 130600) (c 0 0 0 3 0 0 0 0 0 0 0))"
    )
    return " ".join(parts) + ")\n"


def trainer_output(schedule: list[dict]) -> str:
    """The launcher's output: HFO's trainer's ``EndOfTrial:`` lines among
    others."""
    lines = ["[start.py] Starting server\n"]
    goals = 0
    for i, t in enumerate(schedule):
        goals += t["result"] == "GOAL"
        lines.append("EndOfTrial: %d / %d %d %s-7\n" % (goals, i + 1, t["end"], t["result"]))
    return "".join(lines)


def agent_file(schedule: list[dict], unum: int) -> str:
    """The choice file the agent ``unum`` writes for ``schedule``."""
    lines = ["U %d\n" % unum]
    for i, t in enumerate(schedule):
        first = t["start"] + 2
        decisions = [(k[0], k[2]) for k in t["kicks"] if k[1] == unum and k[2] is not None]
        decisions += [(c[0], c[2]) for c in t.get("choices", []) if c[1] == unum]
        for cycle, code in sorted(decisions):
            lines.append("D %d %d %s 0\n" % (i, cycle - first, code))
        lines.append("E %d %d %s\n" % (i, t["end"] - first, STATUS_STRINGS[t["result"]]))
    lines.append("E %d 1 ServerDown\n" % len(schedule))
    return "".join(lines)


def write_batch(directory: str, schedule: list[dict]) -> tuple[str, str, list[str]]:
    """Every file of one run in ``directory``: returns the log directory,
    the launcher's output and the agents' choice files."""
    logdir = os.path.join(directory, "log")
    os.makedirs(logdir, exist_ok=True)
    write_logs(logdir, schedule)
    out = os.path.join(directory, "hfo.out")
    with open(out, "w") as f:
        f.write(trainer_output(schedule))
    files = []
    for unum in OFFENSE:
        path = os.path.join(directory, "agent-%d.txt" % unum)
        with open(path, "w") as f:
            f.write(agent_file(schedule, unum))
        files.append(path)
    return logdir, out, files


def simple_schedule(trials: int) -> list[dict]:
    """Every trial: 7 shoots and releases the ball at start + 4; the odd
    trials end in a goal, the even ones out of bounds, 8 frames each."""
    schedule = []
    for i in range(trials):
        start = 1 + 20 * i
        schedule.append(
            {
                "start": start,
                "end": start + 10,
                "result": "GOAL" if i % 2 else "OUT_OF_BOUNDS",
                "kicks": [[start + 4, 7, "S", True]],
            }
        )
    return schedule
