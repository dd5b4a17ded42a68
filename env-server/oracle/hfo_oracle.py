#!/usr/bin/env python3
"""Real-HFO oracle: plays N episodes of a fixed high-level policy on the real
RoboCup Half Field Offense (3 offense agents vs agent2d's goalkeeper) and
writes one JSON object in the per-decision statistics schema shared with
`env-server rollout --json` (see README.md in this directory).

How it works, per batch of episodes:
  1. starts HFO's launcher (bin/HFO) with rcssserver's game and text logging
     switched on, logging into a temporary directory;
  2. starts the three offense agents (this same file in `agent` mode, using
     HFO's Python interface `hfo`); every agent records, per episode, the
     number of decisions it made and the high-level action it chose in every
     decision in which it could kick;
  3. once the batch is over, stream-parses the action log (.rcl: every
     player's commands per cycle, and the referee's messages), the game log
     (.rcg: ball and player positions every cycle) and rcssserver's .hfo
     episode log (start/end cycle and result of each trial), joins the kicks
     with the agents' choices and deletes the logs.
Batches are pipelined: batch k is parsed while batch k+1 is being played.

The harness itself needs only the Python standard library; the agents need
numpy and HFO's `hfo` module (ctypes wrapper over hfo/libhfo_c.so), so they and
HFO's launcher run with `--python`.

All processes talk over loopback only. Where `unshare` is usable the harness
re-executes itself in a fresh network namespace that has nothing but a
loopback interface (`--net auto`, the default), because rcssserver binds its
UDP ports on INADDR_ANY.  Every process it starts lives in its own process
group and is killed on exit, error, Ctrl-C or SIGTERM.
"""

import argparse
import json
import math
import os
import random
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

POLICIES = ("random", "shoot", "dribble", "pass", "uniform")
GOAL_X, GOAL_Y = 52.5, 0.0
SHOT_BINS = [(0, 10), (10, 15), (15, 20), (20, 25), (25, 30), (30, None)]
OUTCOMES = ("goal", "captured", "out_of_bounds", "out_of_time")
NEXT_KEYS = ("teammate", "same", "captured", "out_of_bounds", "goal", "out_of_time")
RESULT_MAP = {"GOAL": "goal", "CAPTURED_BY_DEFENSE": "captured",
              "OUT_OF_BOUNDS": "out_of_bounds", "OUT_OF_TIME": "out_of_time"}
# Action codes written by the agents (single letters keep the files small):
# S = SHOOT, D = DRIBBLE, N = PASS(nearest teammate), F = PASS(farthest),
# M = MOVE (a learned team's kicker may choose it).
# The codes of our actions by their index (halffield.PAPER_ACTIONS):
# move, shoot, dribble, pass-near, pass-far.
TEAM_CODES = "MSDNF"
ACTION_NAMES = {"M": "move", "S": "shoot", "D": "dribble", "N": "pass_near", "F": "pass_far"}
AGENT_STATUS = {"Goal": "GOAL", "CapturedByDefense": "CAPTURED_BY_DEFENSE",
                "OutOfBounds": "OUT_OF_BOUNDS", "OutOfTime": "OUT_OF_TIME"}


# ---------------------------------------------------------------------------
# Agent mode (runs under --python, inside HFO's tree, imports `hfo`)
# ---------------------------------------------------------------------------

def agent_main(argv):
    p = argparse.ArgumentParser(prog="hfo_oracle.py agent")
    p.add_argument("--port", type=int, required=True)
    p.add_argument("--policy", choices=POLICIES + ("team",), required=True)
    p.add_argument("--snapshot", help="with --policy team: this agent's snapshot file")
    p.add_argument("--seed", type=int, required=True)
    p.add_argument("--config-dir", required=True)
    p.add_argument("--out", required=True)
    a = p.parse_args(argv)
    import hfo  # HFO's own interface, from PYTHONPATH=<hfo-dir>

    learner = None
    if a.policy == "team":
        import halffield  # our package, installed in this interpreter
        learner = halffield.GreedyAgent(a.snapshot)

    rng = random.Random(a.seed)
    env = hfo.HFOEnvironment()
    env.connectToServer(hfo.HIGH_LEVEL_FEATURE_SET, a.config_dir, a.port,
                        "localhost", "base_left", False)
    ntm = env.getNumTeammates()
    # High-level feature layout (src/highlevel_feature_extractor.cpp), T teammates:
    #   0 x, 1 y (normalised), 5 able to kick (+1/-1),
    #   10+3T+3i .. : teammate i's x, y (normalised) and uniform number.
    tm_base = 10 + 3 * ntm
    half_len, half_wid = 52.5, 34.0
    tol_x, tol_y = 0.1 * half_len, 0.1 * half_wid

    def unnorm(v, lo, hi):
        return lo + (v + 1.0) * 0.5 * (hi - lo)

    def teammates(s):
        me_x = unnorm(s[0], -tol_x, half_len + tol_x)
        me_y = unnorm(s[1], -half_wid - tol_y, half_wid + tol_y)
        out = []
        for i in range(ntm):
            x, y, u = s[tm_base + 3 * i], s[tm_base + 3 * i + 1], s[tm_base + 3 * i + 2]
            if u <= 0 or x < -1.5 or y < -1.5:  # FEAT_INVALID = -2
                continue
            tx = unnorm(x, -tol_x, half_len + tol_x)
            ty = unnorm(y, -half_wid - tol_y, half_wid + tol_y)
            out.append((math.hypot(tx - me_x, ty - me_y), int(round(u))))
        out.sort()
        return out

    def paper_state(s):
        """The paper's 6 features as our simulator computes them (its
        `features::paper_state`), from today's HFO high-level set: able to
        kick (5); the distance to the goal centre (6: norm(r, 0, maxR) with
        maxR = |(52.5, 68)|), renormalised as the authors' set does (0 to
        62.548, clamped); the angle to it (7) and the goal opening (8), as
        they are; the nearest then the farthest teammate's goal opening
        (10, 11: HFO lists teammates nearest first)."""
        max_r = math.hypot(half_len, 2 * half_wid)
        dist = (s[6] + 1.0) * 0.5 * max_r
        authors_max = math.hypot(half_len, half_wid)
        return [s[5], 2.0 * min(dist, authors_max) / authors_max - 1.0, s[7], s[8],
                s[10], s[11]]

    choices = {"random": "DDSSFN", "shoot": "S", "dribble": "D", "pass": "N",
               "uniform": "SDNF", "team": ""}[a.policy]
    out = open(a.out, "w", buffering=1 << 16)
    out.write("U %d\n" % env.getUnum())
    episode = 0
    status = hfo.IN_GAME
    while status != hfo.SERVER_DOWN:
        step = 0
        status = hfo.IN_GAME
        while status == hfo.IN_GAME:
            s = env.getState()
            if s[5] > 0.5:
                if learner is not None:
                    c = TEAM_CODES[learner.act(paper_state(s), True)]
                else:
                    c = choices[rng.randrange(len(choices))]
                target = 0
                if c == "M":
                    env.act(hfo.MOVE)
                elif c == "S":
                    env.act(hfo.SHOOT)
                elif c == "D":
                    env.act(hfo.DRIBBLE)
                else:
                    tms = teammates(s)  # (distance, unum), nearest first
                    if tms:
                        target = tms[0][1] if c == "N" else tms[-1][1]
                    env.act(hfo.PASS, float(target))
                out.write("D %d %d %s %d\n" % (episode, step, c, target))
            else:
                env.act(hfo.MOVE)
            status = env.step()
            step += 1
        out.write("E %d %d %s\n" % (episode, step, env.statusToString(status)))
        episode += 1
    out.close()
    try:
        env.act(hfo.QUIT)
    except Exception:
        pass
    return 0


# ---------------------------------------------------------------------------
# Process management
# ---------------------------------------------------------------------------

class Procs:
    """Processes started by the harness, each the leader of its own process
    group (so that rcssserver and the NPCs started by HFO's launcher go with
    it). `kill_all` ends exactly these groups."""

    def __init__(self):
        self.items = []

    def start(self, cmd, **kw):
        p = subprocess.Popen(cmd, start_new_session=True, **kw)
        self.items.append(p)
        return p

    def kill_all(self, grace=1.0):
        for p in self.items:
            self._signal(p, signal.SIGTERM)
        deadline = time.time() + grace
        for p in self.items:
            try:
                p.wait(timeout=max(0.0, deadline - time.time()))
            except subprocess.TimeoutExpired:
                pass
        for p in self.items:
            self._signal(p, signal.SIGKILL)
            try:
                p.wait(timeout=5)
            except subprocess.TimeoutExpired:
                pass
        self.items = []

    @staticmethod
    def _signal(p, sig):
        # The group outlives its leader when children remain, so signal the
        # group even if the leader has exited; a group id cannot be reused
        # while any member is alive.
        try:
            os.killpg(p.pid, sig)
        except (ProcessLookupError, PermissionError):
            pass


def free_port():
    """A base port P with P, P+1, P+2 free on UDP loopback (rcssserver's player,
    coach and online-coach ports)."""
    for _ in range(200):
        base = random.SystemRandom().randrange(20000, 60000)
        socks = []
        try:
            for off in range(3):
                s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
                socks.append(s)
                s.bind(("127.0.0.1", base + off))
            return base
        except OSError:
            continue
        finally:
            for s in socks:
                s.close()
    raise RuntimeError("no free UDP port triple found")


def wait_for_line(path, needle, proc, timeout):
    deadline = time.time() + timeout
    while time.time() < deadline:
        try:
            with open(path, "r", errors="replace") as f:
                if needle in f.read():
                    return True
        except FileNotFoundError:
            pass
        if proc.poll() is not None:
            return False
        time.sleep(0.05)
    return False


class Batch:
    def __init__(self, index, episodes, seed, workdir, attempt=0):
        self.index = index
        self.episodes = episodes
        self.seed = seed
        self.dir = os.path.join(workdir, "batch%04d-%d" % (index, attempt))
        self.logdir = os.path.join(self.dir, "log")
        os.makedirs(self.logdir)
        self.hfo_out = os.path.join(self.dir, "hfo.out")
        self.agent_files = [os.path.join(self.dir, "agent%d.txt" % i) for i in range(3)]
        self.launcher = None
        self.agents = []


def start_batch(batch, args, procs):
    port = free_port()
    env = dict(os.environ, PYTHONPATH=args.hfo_dir + os.pathsep + os.environ.get("PYTHONPATH", ""))
    cmd = [args.python, "-u", os.path.join(args.hfo_dir, "bin", "HFO"),
           "--offense-agents=3", "--defense-npcs=1", "--fullstate", "--headless",
           "--frames-per-trial=200", "--trials=%d" % (batch.episodes + 1),
           "--port=%d" % port, "--log-dir=%s" % batch.logdir,
           "--seed=%d" % (batch.seed % 2147483647)]
    with open(batch.hfo_out, "w") as out:
        batch.launcher = procs.start(cmd, cwd=args.hfo_dir, env=env, stdout=out,
                                     stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
    config_dir = os.path.join(args.hfo_dir, "bin", "teams", "base", "config", "formations-dt")
    for i in range(3):
        if not wait_for_line(batch.hfo_out, "Waiting for player-controlled agent base_left-%d" % i,
                             batch.launcher, 60):
            raise BatchStuck("batch %d: HFO did not ask for agent %d" % (batch.index, i))
        acmd = [args.python, os.path.abspath(__file__), "agent", "--port=%d" % port,
                "--policy=%s" % args.policy, "--seed=%d" % (batch.seed * 7 + 1000 * i + 1),
                "--config-dir=%s" % config_dir, "--out=%s" % batch.agent_files[i]]
        if args.team:
            acmd.append("--snapshot=%s" % args.team[i])
        with open(os.path.join(batch.dir, "agent%d.err" % i), "w") as err:
            batch.agents.append(procs.start(acmd, cwd=args.hfo_dir, env=env,
                                            stdout=subprocess.DEVNULL, stderr=err,
                                            stdin=subprocess.DEVNULL))


def finish_batch(batch, stall=30.0):
    """Waits for the batch to end.

    rcssserver quits by itself after the last trial and then renames its
    logs from incomplete.rcg/.rcl to their final names.  HFO's trainer
    (bin/Trainer.py) can miss that: right after the last trial it asks the
    server for the connected players and, the server being gone, retries for
    ever.  So the batch is over when every trial has been reported and the
    logs are closed, whether or not the launcher has exited (kill_all ends
    it).  A trial lasts at most ~200 cycles, well under a second of wall
    time: if HFO reports nothing new for `stall` seconds the batch is stuck.
    """
    trials = batch.episodes + 1
    ended = 0
    last_size, last_change = -1, time.time()
    while batch.launcher.poll() is None:
        try:
            size = os.path.getsize(batch.hfo_out)
        except OSError:
            size = 0
        now = time.time()
        if size != last_size:
            last_size, last_change = size, now
            with open(batch.hfo_out, errors="replace") as f:
                ended = sum(1 for line in f if line.startswith("EndOfTrial:"))
        if ended >= trials and logs_closed(batch.logdir):
            break
        if now - last_change > stall:
            raise BatchStuck("batch %d: no progress for %.0f s" % (batch.index, stall))
        time.sleep(0.2)
    if not logs_closed(batch.logdir):
        raise BatchStuck("batch %d: HFO ended before rcssserver closed its logs" % batch.index)
    for p in batch.agents:
        try:
            p.wait(timeout=stall)
        except subprocess.TimeoutExpired:
            raise BatchStuck("batch %d: an agent did not exit after the server quit" % batch.index)


def logs_closed(logdir):
    names = os.listdir(logdir)
    return (not any(n.startswith("incomplete.rc") for n in names)
            and any(n.endswith(".rcg") for n in names) and any(n.endswith(".rcl") for n in names))


class BatchStuck(RuntimeError):
    pass


# ---------------------------------------------------------------------------
# Log parsing
# ---------------------------------------------------------------------------

REF_END = re.compile(r"\(referee (GOAL|CAPTURED_BY_DEFENSE|OUT_OF_BOUNDS|OUT_OF_TIME)")
KICK_LINE = re.compile(r"^(\d+),\d+\tRecv base_left_(\d+): .*?\(kick ")


def parse_hfo_log(logdir):
    files = [f for f in os.listdir(logdir) if f.endswith(".hfo")]
    if len(files) != 1:
        raise RuntimeError("expected one .hfo log in %s, found %r" % (logdir, files))
    eps = []
    with open(os.path.join(logdir, files[0])) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            num, start, end, _dur, res = line.split("\t")
            eps.append((int(start), int(end), res.strip().split("-")[0]))
    return eps


def parse_rcl(path, offense):
    """Kick commands of the offense players by cycle, and the referee's
    end-of-trial messages (cycle, result)."""
    kicks = {}
    ends = []
    with open(path, "rb") as f:
        for raw in f:
            if b"(kick " in raw:
                line = raw.decode("ascii", "replace")
                m = KICK_LINE.match(line)
                if m and int(m.group(2)) in offense:
                    kicks.setdefault(int(m.group(1)), []).append(int(m.group(2)))
            elif b"(referee " in raw:
                line = raw.decode("ascii", "replace")
                m = REF_END.search(line)
                if m:
                    ends.append((int(line[:line.index(",")]), m.group(1)))
    return kicks, ends


def iter_rcg(path, wanted):
    """Yields (cycle, ball_xy, {key: (x, y, player_type, kick_count)}) for
    every show line (rcg version 5, rcssserver's logger.cpp); wanted = the
    player keys to keep, such as 'l 7'.  At the server_param line it yields
    (None, ball_size, kick_area) once, kick_area being a dict type id ->
    (kickable_margin, player_size) that fills up as the player_type lines
    (which precede the first show) are read."""
    kick_area = {}
    ball_size = 0.085
    with open(path, "rb") as f:
        for raw in f:
            if raw.startswith(b"(show "):
                line = raw.decode("ascii", "replace")
                chunks = line.split("((")
                cycle = int(chunks[0].split()[1])
                b = chunks[1].split()  # "b)", x, y, vx, vy)
                ball = (float(b[1]), float(b[2]))
                players = {}
                for ch in chunks[2:]:
                    key = ch[:ch.index(")")]
                    if key not in wanted:
                        continue
                    t = ch.split()
                    # t: side, "unum)", type, state, x, y, vx, vy, body, neck, ...
                    ci = t.index("(c")
                    players[key] = (float(t[4]), float(t[5]), int(t[2]), int(t[ci + 1]))
                yield cycle, ball, players
            elif raw.startswith(b"(player_type "):
                line = raw.decode("ascii", "replace")
                pid = int(re.search(r"\(id (\d+)\)", line).group(1))
                km = float(re.search(r"\(kickable_margin ([-\d.e+]+)\)", line).group(1))
                ps = float(re.search(r"\(player_size ([-\d.e+]+)\)", line).group(1))
                kick_area[pid] = (km, ps)
            elif raw.startswith(b"(server_param "):
                m = re.search(rb"\(ball_size ([-\d.e+]+)\)", raw)
                if m:
                    ball_size = float(m.group(1))
                yield None, ball_size, kick_area


def read_agent_file(path):
    unum, decisions, episodes = None, {}, []
    with open(path) as f:
        for line in f:
            t = line.split()
            if not t:
                continue
            if t[0] == "D":
                decisions[(int(t[1]), int(t[2]))] = t[3]
            elif t[0] == "E":
                episodes.append((int(t[2]), t[3]))
            elif t[0] == "U":
                unum = int(t[1])
    return unum, decisions, episodes


class Stats:
    def __init__(self):
        self.episodes = 0
        self.outcomes = {k: 0 for k in OUTCOMES}
        self.frames = []
        self.frames_goal = []
        self.shots = [[0, 0] for _ in SHOT_BINS]
        self.after = {"PASS": {k: 0 for k in NEXT_KEYS}, "DRIBBLE": {k: 0 for k in NEXT_KEYS}}
        self.possessions = []
        # The kickers' choices, every decision with the ball.
        self.actions = {name: 0 for name in ACTION_NAMES.values()}
        self.checks = {k: 0 for k in (
            "kicks", "kick_commands_not_kickable", "kicks_without_choice",
            "kick_count_mismatches", "shots_not_released",
            "passes_not_released", "trainer_outcome_mismatches",
            "referee_outcome_mismatches", "agent_frames_mismatches",
            "agent_outcome_mismatches", "choices_without_kick", "batches_replayed")}

    def add_batch(self, batch, verbose=False):
        c = self.checks
        hfo_eps = parse_hfo_log(batch.logdir)
        # Trial 0 of every HFO run is a warm-up and is not counted: the agents
        # were already stepping when the game started, so it lacks the two
        # idle cycles every later trial has.
        if len(hfo_eps) != batch.episodes + 1:
            raise RuntimeError("batch %d: %d trials in the .hfo log, expected %d"
                               % (batch.index, len(hfo_eps), batch.episodes + 1))
        # Trainer's EndOfTrial lines: "EndOfTrial: <goals> / <trial> <frame> <STATUS>-<unum>"
        trainer = []
        with open(batch.hfo_out, errors="replace") as f:
            for line in f:
                if line.startswith("EndOfTrial:"):
                    t = line.split()
                    trainer.append((int(t[4]), t[5].split("-")[0]))
        for (s, e, r), tr in zip(hfo_eps, trainer):
            if tr != (e, r):
                c["trainer_outcome_mismatches"] += 1
        c["trainer_outcome_mismatches"] += abs(len(trainer) - len(hfo_eps))

        agents = [read_agent_file(p) for p in batch.agent_files]
        offense = {a[0] for a in agents}
        # Map (unum, cycle) -> action code, aligning each agent's episode e
        # (n_e decisions, the last one answered by the terminal status) so that
        # its last decision is at cycle end_e - 1 (the agent's first decision
        # is at reset + 2, after the two idle cycles).
        choice = {}
        for unum, decisions, aeps in agents:
            if len(aeps) < len(hfo_eps):
                raise RuntimeError("agent %d saw %d episodes, HFO played %d"
                                   % (unum, len(aeps), len(hfo_eps)))
            for ep, ((s, e, r), (n, st)) in enumerate(zip(hfo_eps, aeps)):
                first = e - n
                if ep > 0 and first != s + 2:
                    c["agent_frames_mismatches"] += 1
                if AGENT_STATUS.get(st) != r:
                    c["agent_outcome_mismatches"] += 1
            for (ep, step), code in decisions.items():
                if ep >= len(hfo_eps):
                    continue
                if ep > 0:  # trial 0 is the warm-up
                    self.actions[ACTION_NAMES[code]] += 1
                if code == "M":
                    continue  # no kick to join
                s, e, r = hfo_eps[ep]
                choice[(unum, e - aeps[ep][0] + step)] = code

        rcl = [f for f in os.listdir(batch.logdir) if f.endswith(".rcl")]
        rcg = [f for f in os.listdir(batch.logdir) if f.endswith(".rcg")]
        if len(rcl) != 1 or len(rcg) != 1:
            raise RuntimeError("expected one .rcg and one .rcl in %s" % batch.logdir)
        kick_cmds, ref_ends = parse_rcl(os.path.join(batch.logdir, rcl[0]), offense)
        for (s, e, r), (rc, rr) in zip(hfo_eps, ref_ends):
            if (e, r) != (rc, rr):
                c["referee_outcome_mismatches"] += 1
        c["referee_outcome_mismatches"] += abs(len(ref_ends) - len(hfo_eps))

        # Episode index of every cycle.
        ep_of = {}
        for ep, (s, e, r) in enumerate(hfo_eps):
            for cyc in range(s, e + 1):
                ep_of[cyc] = ep
        ep_kicks = [[] for _ in hfo_eps]  # (cycle, unum, code, dist, released)

        wanted = {"l %d" % u for u in offense}
        kick_area = {}
        ball_size = 0.085
        prev = None  # (cycle, ball, players)
        pending = []  # kicks at prev cycle awaiting the next show: (unum, code, dist, key)
        for cyc, ball, players in iter_rcg(os.path.join(batch.logdir, rcg[0]), wanted):
            if cyc is None:
                ball_size, kick_area = ball, players
                continue
            if prev is not None and cyc == prev[0]:
                prev = (cyc, ball, players)
                continue
            if prev is not None and pending:
                pcyc, pball, pplayers = prev
                for unum, code, dist, key in pending:
                    me = players.get(key)
                    area = self._area(kick_area, ball_size, me[2])
                    released = math.hypot(ball[0] - me[0], ball[1] - me[1]) > area
                    if me[3] != pplayers[key][3] + 1:
                        c["kick_count_mismatches"] += 1
                    ep = ep_of.get(pcyc)
                    if ep is not None and pcyc < hfo_eps[ep][1]:
                        ep_kicks[ep].append((pcyc, unum, code, dist, released))
                pending = []
            # Kick commands issued at this cycle take effect in the step to
            # cycle+1 if the ball is kickable now.
            for unum in kick_cmds.get(cyc, ()):
                key = "l %d" % unum
                me = players[key]
                area = self._area(kick_area, ball_size, me[2])
                if math.hypot(ball[0] - me[0], ball[1] - me[1]) > area:
                    c["kick_commands_not_kickable"] += 1
                    continue
                code = choice.get((unum, cyc))
                pending.append((unum, code, math.hypot(ball[0] - GOAL_X, ball[1] - GOAL_Y), key))
            prev = (cyc, ball, players)

        # Decisions under which a kickable agent chose a kicking action but no
        # kick followed (e.g. DRIBBLE dashing, PASS with no safe pass).
        kicked = {(u, cyc) for ks in ep_kicks for (cyc, u, _, _, _) in ks}
        c["choices_without_kick"] += sum(1 for k in choice if k not in kicked)

        for ep, (s, e, r) in enumerate(hfo_eps):
            if ep == 0:
                continue  # warm-up trial
            outcome = RESULT_MAP[r]
            self.episodes += 1
            self.outcomes[outcome] += 1
            frames = e - s - 2
            self.frames.append(frames)
            if outcome == "goal":
                self.frames_goal.append(frames)
            ks = sorted(ep_kicks[ep])
            runs = 0
            last = None
            for i, (cyc, unum, code, dist, released) in enumerate(ks):
                c["kicks"] += 1
                if unum != last:
                    runs += 1
                    last = unum
                if code is None:
                    c["kicks_without_choice"] += 1
                    continue
                nxt = ks[i + 1] if i + 1 < len(ks) else None
                if nxt is None:
                    follow = outcome
                else:
                    follow = "same" if nxt[1] == unum else "teammate"
                if code == "S":
                    if not released:
                        c["shots_not_released"] += 1
                        continue
                    b = self._bin(dist)
                    self.shots[b][0] += 1
                    if nxt is None and outcome == "goal":
                        self.shots[b][1] += 1
                elif code in ("N", "F"):
                    if not released:
                        c["passes_not_released"] += 1
                        continue
                    self.after["PASS"][follow] += 1
                elif code == "D":
                    self.after["DRIBBLE"][follow] += 1
            self.possessions.append(runs)

    @staticmethod
    def _area(kick_area, ball_size, ptype):
        km, ps = kick_area.get(ptype, (0.7, 0.3))
        return km + ps + ball_size

    @staticmethod
    def _bin(dist):
        for i, (lo, hi) in enumerate(SHOT_BINS):
            if dist >= lo and (hi is None or dist < hi):
                return i
        return len(SHOT_BINS) - 1

    def result(self, policy, seed):
        def mean(xs):
            return sum(xs) / len(xs) if xs else None

        def sd(xs):
            if len(xs) < 2:
                return None
            m = mean(xs)
            return math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1))

        n = self.episodes
        return {
            "simulator": "hfo",
            "policy": policy,
            "episodes": n,
            "seed": seed,
            "goal_pct": 100.0 * self.outcomes["goal"] / n if n else None,
            "mean_frames": mean(self.frames),
            "mean_frames_to_goal": mean(self.frames_goal),
            "outcomes": dict(self.outcomes),
            "decisions": {
                "shots": [{"from_m": lo, "to_m": hi, "released": r, "goals": g}
                          for (lo, hi), (r, g) in zip(SHOT_BINS, self.shots)],
                "after_pass": dict(self.after["PASS"]),
                "after_dribble": dict(self.after["DRIBBLE"]),
                "possessions_per_episode": mean(self.possessions),
            },
            # Extra: the kickers' choices (every decision with the ball).
            "actions": dict(self.actions),
            # Extras (not in the shared schema): standard deviations for the
            # confidence intervals of compare.py, and the log-join checks.
            "sd": {"frames": sd(self.frames), "frames_to_goal": sd(self.frames_goal),
                   "possessions_per_episode": sd(self.possessions)},
            "checks": dict(self.checks),
        }


# ---------------------------------------------------------------------------
# Harness
# ---------------------------------------------------------------------------

def maybe_enter_netns(args):
    """Re-executes this harness inside a new user+network namespace whose only
    interface is loopback (so nothing rcssserver binds is reachable from
    outside). Returns normally if that is not wanted or not possible."""
    if args.net == "host" or os.environ.get("HFO_ORACLE_NETNS") == "1":
        return
    unshare, ip = shutil.which("unshare"), shutil.which("ip")
    ok = False
    if unshare and ip:
        ok = subprocess.run([unshare, "-rn", ip, "link", "set", "lo", "up"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode == 0
    if not ok:
        if args.net == "isolated":
            sys.exit("--net isolated: cannot create a network namespace (unshare -rn)")
        print("note: no network namespace available; processes use 127.0.0.1 only, "
              "but rcssserver binds its ports on all interfaces", file=sys.stderr)
        return
    os.environ["HFO_ORACLE_NETNS"] = "1"
    sys.stdout.flush()
    sys.stderr.flush()
    os.execvp(unshare, [unshare, "-rn", "sh", "-c", ip + ' link set lo up && exec "$@"', "sh",
                        sys.executable, os.path.abspath(__file__)] + sys.argv[1:])


def harness_main(argv):
    p = argparse.ArgumentParser(
        description="Play N episodes of a fixed policy on the real HFO (3 offense agents vs "
                    "agent2d's goalie) and write per-decision statistics as JSON.")
    p.add_argument("--hfo-dir", default=os.environ.get("HFO_DIR"),
                   help="built HFO tree (bin/HFO, bin/rcssserver, hfo/libhfo_c.so); default $HFO_DIR")
    p.add_argument("--python", default=sys.executable,
                   help="Python interpreter with numpy, for HFO's launcher and the agents")
    who = p.add_mutually_exclusive_group(required=True)
    who.add_argument("--policy", choices=POLICIES)
    who.add_argument("--team", nargs=3, metavar="SNAPSHOT",
                     help="a learned team: our agents' snapshot files (coordinator run "
                          "--save-agents), played greedily as our evaluations play; --python "
                          "must have the halffield package")
    p.add_argument("--episodes", type=int, required=True)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--out", required=True, help="output JSON file")
    p.add_argument("--batch", type=int, default=500,
                   help="episodes per HFO run (the logs of one run are parsed and deleted "
                        "while the next one plays); default 500")
    p.add_argument("--net", choices=("auto", "isolated", "host"), default="auto",
                   help="auto: run in a loopback-only network namespace when possible")
    p.add_argument("--tmp", default=None, help="parent directory for the temporary logs")
    p.add_argument("--keep-logs", action="store_true", help="do not delete the logs (debugging)")
    args = p.parse_args(argv)
    if not args.hfo_dir or not os.path.exists(os.path.join(args.hfo_dir, "bin", "HFO")):
        p.error("--hfo-dir (or $HFO_DIR) must point at a built HFO tree containing bin/HFO")
    args.hfo_dir = os.path.abspath(args.hfo_dir)
    if args.team:
        args.team = [os.path.abspath(f) for f in args.team]
        missing = [f for f in args.team if not os.path.isfile(f)]
        if missing:
            p.error("--team: no such file: %s" % ", ".join(missing))
        args.policy = "team"
    if args.episodes <= 0:
        p.error("--episodes must be positive")
    maybe_enter_netns(args)

    def on_term(signum, frame):
        raise KeyboardInterrupt("signal %d" % signum)
    signal.signal(signal.SIGTERM, on_term)
    signal.signal(signal.SIGHUP, on_term)

    procs = Procs()
    workdir = tempfile.mkdtemp(prefix="hfo-oracle-", dir=args.tmp)
    stats = Stats()
    t0 = time.time()
    sizes = []
    left = args.episodes
    while left > 0:
        sizes.append(min(args.batch, left))
        left -= sizes[-1]
    try:
        prev = None
        for i, n in enumerate(sizes):
            attempt = 0
            while True:
                b = Batch(i, n, args.seed * 1000 + i + 100000 * attempt, workdir, attempt)
                try:
                    start_batch(b, args, procs)
                    if prev is not None:
                        parse_and_drop(prev, stats, args)
                        prev = None
                    finish_batch(b)
                    procs.kill_all(grace=0.2)  # nothing should be left; make sure
                    break
                except BatchStuck as e:
                    # A run that hangs (seen rarely: a client never joins or
                    # the game stops advancing) is discarded as a whole and
                    # replayed with another port and seed.
                    procs.kill_all()
                    report_stuck(b, e)
                    if not args.keep_logs:
                        shutil.rmtree(b.dir, ignore_errors=True)
                    stats.checks["batches_replayed"] += 1
                    attempt += 1
                    if attempt > 3:
                        raise
            prev = b
            print("[hfo_oracle] %s: %d/%d episodes played, %.0f s"
                  % (args.policy, sum(sizes[:i + 1]), args.episodes, time.time() - t0),
                  file=sys.stderr, flush=True)
        parse_and_drop(prev, stats, args)
        res = stats.result(args.policy, args.seed)
        if args.team:
            res["team"] = args.team
        res["wall_seconds"] = round(time.time() - t0, 1)
        tmp_out = args.out + ".tmp"
        with open(tmp_out, "w") as f:
            json.dump(res, f, indent=2)
            f.write("\n")
        os.replace(tmp_out, args.out)
        print("[hfo_oracle] %s: goal %.2f%%, mean frames %.1f, wrote %s (%.0f s)"
              % (args.policy, res["goal_pct"], res["mean_frames"], args.out, time.time() - t0),
              file=sys.stderr, flush=True)
        return 0
    finally:
        procs.kill_all()
        if not args.keep_logs:
            shutil.rmtree(workdir, ignore_errors=True)


def report_stuck(batch, err):
    print("[hfo_oracle] %s; replaying it. Last lines of its output:" % err, file=sys.stderr)
    for path in [batch.hfo_out] + [os.path.join(batch.dir, "agent%d.err" % i) for i in range(3)]:
        try:
            with open(path, errors="replace") as f:
                tail = f.readlines()[-8:]
        except OSError:
            continue
        print("  --- %s" % os.path.basename(path), file=sys.stderr)
        for line in tail:
            print("  " + line.rstrip()[:200], file=sys.stderr)
    sys.stderr.flush()


def parse_and_drop(batch, stats, args):
    stats.add_batch(batch)
    if not args.keep_logs:
        shutil.rmtree(batch.dir, ignore_errors=True)


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "agent":
        return agent_main(sys.argv[2:])
    return harness_main(sys.argv[1:])


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        print("[hfo_oracle] interrupted; all started processes were stopped", file=sys.stderr)
        sys.exit(130)
