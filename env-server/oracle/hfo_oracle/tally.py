"""The join of one HFO run's logs with its agents' choices into the
per-decision statistics, added up over runs (README.md, "How the
per-decision statistics are obtained").

A kick is a ``(kick ...)`` command of an offense player in the ``.rcl``
sent in a cycle in which the ``.rcg`` shows the ball within that player's
kickable area; it is released when the next cycle shows the ball out of
it. The agent's choice behind it is found by aligning the agent's
decisions of each episode so that its last one is at the trial's end cycle
- 1. The first trial of every run is a warm-up and is not counted (the
agents were already acting when the game started, so it lacks the two
idle cycles every later trial has).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any, NamedTuple

from hfo_oracle import logs, stats
from hfo_oracle.schema import (
    ACTION_NAMES,
    GOAL_X,
    GOAL_Y,
    NEXT_KEYS,
    OUTCOMES,
    SHOT_BINS,
    STATUS_OUTCOMES,
    shot_bin,
)

# The consistency counters of the join. All but the informational `kicks`,
# `shots_not_released`, `passes_not_released` and `choices_without_kick`
# should stay 0 (README.md, "checks").
CHECKS = (
    "kicks",
    "kick_commands_not_kickable",
    "kicks_without_choice",
    "kick_count_mismatches",
    "shots_not_released",
    "passes_not_released",
    "trainer_outcome_mismatches",
    "referee_outcome_mismatches",
    "agent_frames_mismatches",
    "agent_outcome_mismatches",
    "choices_without_kick",
    "batches_replayed",
)


class Kick(NamedTuple):
    """A kick that took effect: its cycle, the kicker, the kicker's choice
    (None if none was found), the ball's distance to the goal centre when
    kicked (m), and whether the ball left the kicker's reach."""

    cycle: int
    unum: int
    code: str | None
    distance: float
    released: bool


class Tally:
    """The statistics of the runs added so far."""

    def __init__(self) -> None:
        self.episodes = 0
        self.outcomes = dict.fromkeys(OUTCOMES, 0)
        self.frames: list[int] = []
        self.frames_goal: list[int] = []
        self.shots = [[0, 0] for _ in SHOT_BINS]  # [released, goals] per bin
        self.after = {"PASS": dict.fromkeys(NEXT_KEYS, 0), "DRIBBLE": dict.fromkeys(NEXT_KEYS, 0)}
        self.possessions: list[int] = []
        # The kickers' choices, every decision with the ball.
        self.actions = dict.fromkeys(ACTION_NAMES.values(), 0)
        self.checks = dict.fromkeys(CHECKS, 0)

    def add_batch(
        self, logdir: str, trainer_output: str, agent_files: Sequence[str], trials: int
    ) -> None:
        """Adds one HFO run of ``trials`` trials (the warm-up included):
        rcssserver's logs in ``logdir``, the launcher's output
        ``trainer_output`` and the agents' choice files."""
        trial_log = logs.parse_hfo_log(logs.find_log(logdir, ".hfo"))
        if len(trial_log) != trials:
            raise RuntimeError(
                "%s: %d trials in the .hfo log, expected %d" % (logdir, len(trial_log), trials)
            )
        self._check_ends(
            "trainer_outcome_mismatches", trial_log, logs.parse_trainer_output(trainer_output)
        )
        agents = [logs.read_agent_file(p) for p in agent_files]
        offense = {a.unum for a in agents}
        choices = self._choices(trial_log, agents)
        kick_commands, referee_ends = logs.parse_rcl(logs.find_log(logdir, ".rcl"), offense)
        self._check_ends("referee_outcome_mismatches", trial_log, referee_ends)
        kicks = self._kicks(
            logs.find_log(logdir, ".rcg"), trial_log, offense, kick_commands, choices
        )
        # Decisions in which an agent that could kick chose a kicking action
        # but no kick followed (e.g. DRIBBLE dashing, PASS with no safe pass).
        kicked = {(k.unum, k.cycle) for ks in kicks for k in ks}
        self.checks["choices_without_kick"] += sum(1 for k in choices if k not in kicked)
        for trial, (t, ks) in enumerate(zip(trial_log, kicks)):
            if trial > 0:  # trial 0 is the warm-up
                self._add_episode(t, ks)

    def _check_ends(
        self, counter: str, trial_log: list[logs.Trial], ends: list[tuple[int, str]]
    ) -> None:
        """Counts the trials whose (end cycle, result) another source
        reports otherwise, and the trials it reports too many or too few."""
        for t, end in zip(trial_log, ends):
            if (t.end, t.result) != end:
                self.checks[counter] += 1
        self.checks[counter] += abs(len(ends) - len(trial_log))

    def _choices(
        self, trial_log: list[logs.Trial], agents: list[logs.AgentRecord]
    ) -> dict[tuple[int, int], str]:
        """The kicking choices by ``(unum, cycle)``, each agent's episode e
        (n decisions, the last one answered by the terminal status) aligned
        so that its last decision is at cycle end - 1 (its first is then at
        start + 2, after the two idle cycles); counts the choices of the
        counted trials."""
        choice = {}
        for unum, decisions, episodes in agents:
            if len(episodes) < len(trial_log):
                raise RuntimeError(
                    "agent %d saw %d episodes, HFO played %d"
                    % (unum, len(episodes), len(trial_log))
                )
            for trial, (t, (steps, status)) in enumerate(zip(trial_log, episodes)):
                if trial > 0 and t.end - steps != t.start + 2:
                    self.checks["agent_frames_mismatches"] += 1
                if logs.AGENT_STATUS.get(status) != t.result:
                    self.checks["agent_outcome_mismatches"] += 1
            for (trial, step), code in decisions.items():
                if trial >= len(trial_log):
                    continue
                if trial > 0:
                    self.actions[ACTION_NAMES[code]] += 1
                if code == "M":
                    continue  # no kick to join
                choice[(unum, trial_log[trial].end - episodes[trial][0] + step)] = code
        return choice

    def _kicks(
        self,
        rcg: str,
        trial_log: list[logs.Trial],
        offense: set[int],
        kick_commands: dict[int, list[int]],
        choices: dict[tuple[int, int], str],
    ) -> list[list[Kick]]:
        """The kicks of each trial, in the order of the game log."""
        trial_of = {}
        for trial, t in enumerate(trial_log):
            for cycle in range(t.start, t.end + 1):
                trial_of[cycle] = trial
        kicks: list[list[Kick]] = [[] for _ in trial_log]
        areas = logs.KickAreas()
        prev = None
        pending = []  # kicks sent at prev's cycle: (unum, code, distance, key)
        for show in logs.iter_rcg(rcg, {"l %d" % u for u in offense}, areas):
            if prev is not None and show.cycle == prev.cycle:
                prev = show
                continue
            # A kick sent at a cycle takes effect in the step to the next one.
            for unum, code, distance, key in pending:
                me, before = show.players[key], prev.players[key]
                released = _ball_distance(show.ball, me) > areas.radius(me.player_type)
                if me.kicks != before.kicks + 1:
                    self.checks["kick_count_mismatches"] += 1
                trial = trial_of.get(prev.cycle)
                if trial is not None and prev.cycle < trial_log[trial].end:
                    kicks[trial].append(Kick(prev.cycle, unum, code, distance, released))
            pending = []
            for unum in kick_commands.get(show.cycle, ()):
                key = "l %d" % unum
                me = show.players[key]
                if _ball_distance(show.ball, me) > areas.radius(me.player_type):
                    self.checks["kick_commands_not_kickable"] += 1
                    continue
                distance = math.hypot(show.ball[0] - GOAL_X, show.ball[1] - GOAL_Y)
                pending.append((unum, choices.get((unum, show.cycle)), distance, key))
            prev = show
        return kicks

    def _add_episode(self, trial: logs.Trial, kicks: list[Kick]) -> None:
        """Counts one trial: its outcome and length, its shots, what
        followed its passes and dribbles, and its possessions."""
        outcome = STATUS_OUTCOMES[trial.result]
        self.episodes += 1
        self.outcomes[outcome] += 1
        frames = trial.end - trial.start - 2
        self.frames.append(frames)
        if outcome == "goal":
            self.frames_goal.append(frames)
        kicks = sorted(kicks)
        possessions = 0
        last = None
        for i, kick in enumerate(kicks):
            self.checks["kicks"] += 1
            if kick.unum != last:
                possessions += 1
                last = kick.unum
            if kick.code is None:
                self.checks["kicks_without_choice"] += 1
                continue
            following = kicks[i + 1] if i + 1 < len(kicks) else None
            if following is None:
                follow = outcome
            else:
                follow = "same" if following.unum == kick.unum else "teammate"
            if kick.code == "S":
                if not kick.released:
                    self.checks["shots_not_released"] += 1
                    continue
                b = shot_bin(kick.distance)
                self.shots[b][0] += 1
                if following is None and outcome == "goal":
                    self.shots[b][1] += 1
            elif kick.code in ("N", "F"):
                if not kick.released:
                    self.checks["passes_not_released"] += 1
                    continue
                self.after["PASS"][follow] += 1
            elif kick.code == "D":
                self.after["DRIBBLE"][follow] += 1
        self.possessions.append(possessions)

    def result(self, policy: str, seed: int) -> dict[str, Any]:
        """The statistics object (the schema of ``env-server rollout
        --json``, with the extras ``actions``, ``sd`` and ``checks``)."""
        n = self.episodes
        return {
            "simulator": "hfo",
            "policy": policy,
            "episodes": n,
            "seed": seed,
            "goal_pct": 100.0 * self.outcomes["goal"] / n if n else None,
            "mean_frames": stats.mean(self.frames),
            "mean_frames_to_goal": stats.mean(self.frames_goal),
            "outcomes": dict(self.outcomes),
            "decisions": {
                "shots": [
                    {"from_m": lo, "to_m": hi, "released": r, "goals": g}
                    for (lo, hi), (r, g) in zip(SHOT_BINS, self.shots)
                ],
                "after_pass": dict(self.after["PASS"]),
                "after_dribble": dict(self.after["DRIBBLE"]),
                "possessions_per_episode": stats.mean(self.possessions),
            },
            # Extra: the kickers' choices (every decision with the ball).
            "actions": dict(self.actions),
            # Extras (not in the shared schema): standard deviations for the
            # confidence intervals of compare.py, and the log-join checks.
            "sd": {
                "frames": stats.sample_sd(self.frames),
                "frames_to_goal": stats.sample_sd(self.frames_goal),
                "possessions_per_episode": stats.sample_sd(self.possessions),
            },
            "checks": dict(self.checks),
        }


def _ball_distance(ball: tuple[float, float], player: logs.PlayerShow) -> float:
    return math.hypot(ball[0] - player.x, ball[1] - player.y)
