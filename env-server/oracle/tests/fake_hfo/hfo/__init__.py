"""A stand-in for HFO's Python interface `hfo`, for the harness's tests: the
agent of the connection order's uniform number (7, 8, 11) plays the schedule
the fake launcher (bin/HFO) wrote, seeing a high-level state in which it can
kick exactly at its kicks' cycles."""

import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
import fakegame  # noqa: E402

HIGH_LEVEL_FEATURE_SET = 1
IN_GAME, GOAL, CAPTURED_BY_DEFENSE, OUT_OF_BOUNDS, OUT_OF_TIME, SERVER_DOWN = range(6)
MOVE, SHOOT, PASS, DRIBBLE, QUIT = 8, 9, 10, 11, 14
_STATUS = {
    "GOAL": GOAL,
    "CAPTURED_BY_DEFENSE": CAPTURED_BY_DEFENSE,
    "OUT_OF_BOUNDS": OUT_OF_BOUNDS,
    "OUT_OF_TIME": OUT_OF_TIME,
}
_STRINGS = ["InGame", "Goal", "CapturedByDefense", "OutOfBounds", "OutOfTime", "ServerDown"]


class HFOEnvironment:
    def connectToServer(  # noqa: N802 (HFO's names)
        self, feature_set, config_dir, port, host, team, play_goalie
    ):
        rundir = os.environ["FAKE_HFO_RUNDIR"]
        path = os.path.join(rundir, "schedule-%d.json" % port)
        deadline = time.time() + 30
        while not os.path.exists(path) and time.time() < deadline:
            time.sleep(0.02)
        with open(path) as f:
            self.schedule = json.load(f)
        index = 0
        while True:  # the first free uniform number, taken atomically
            try:
                os.close(
                    os.open(
                        os.path.join(rundir, "ready-%d-%d" % (port, index)),
                        os.O_CREAT | os.O_EXCL | os.O_WRONLY,
                    )
                )
                break
            except FileExistsError:
                index += 1
        self.unum = fakegame.OFFENSE[index]
        self.trial, self.step_in_trial = 0, 0
        self.actions = []

    def getUnum(self):  # noqa: N802 (HFO's names)
        return self.unum

    def getNumTeammates(self):  # noqa: N802 (HFO's names)
        return len(fakegame.OFFENSE) - 1

    def _cycle(self):
        return self.schedule[self.trial]["start"] + 2 + self.step_in_trial

    def getState(self):  # noqa: N802 (HFO's names)
        state = [0.0] * 27
        if self.trial < len(self.schedule):
            state[5] = 1.0 if fakegame.can_kick(self.schedule, self.unum, self._cycle()) else -1.0
        else:
            state[5] = -1.0
        mates = [u for u in fakegame.OFFENSE if u != self.unum]
        for i, u in enumerate(mates):  # teammates' x, y and uniform number
            state[16 + 3 * i : 19 + 3 * i] = [0.1 * (i + 1), 0.0, float(u)]
        return state

    def act(self, action, *args):
        self.actions.append(action)

    def step(self):
        if self.trial >= len(self.schedule):
            return SERVER_DOWN
        t = self.schedule[self.trial]
        if self._cycle() == t["end"] - 1:
            self.trial, self.step_in_trial = self.trial + 1, 0
            return _STATUS[t["result"]]
        self.step_in_trial += 1
        return IN_GAME

    def statusToString(self, status):  # noqa: N802 (HFO's names)
        return _STRINGS[status]
