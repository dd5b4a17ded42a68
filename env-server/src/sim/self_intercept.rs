//! A player's own reach (spec 6.1.2): librcsc's `SelfInterceptV13`
//! (rcsc/player/self_intercept_v13.cpp). Unlike the estimate others make of
//! a player, it simulates the player's own turns and dashes: in the first
//! five cycles (`predictOneStep`, `predictShortStep`) along its body, its
//! back or sideways first (the omni-directional dash), the ball ending up
//! 0.15 m inside its control area; later (`predictLongStep`) full dashes
//! along the line to the ball after the turns it needs; and, when no cycle
//! qualifies, the ball's resting point (`predictFinal`). The control area is
//! the kickable area, or for the keeper (goalie mode) the catchable area
//! while the ball is in its penalty area.
//!
//! Stamina follows librcsc's save-recovery dashing (never below the recovery
//! threshold), so no entry is `EXHAUST`.

use crate::sim::geom::{angle_diff, asin_clamped, direction, normalize_angle, unit};
use crate::sim::kinematics::{DRIFT, dash_cycles, decay_pow, decay_sum};
use crate::sim::params::*;
use crate::sim::physics::{dash_dir, dash_dir_rate, kick_rate, update_stamina};
use crate::sim::world::{Ball, Player};
use glam::DVec2;
use std::f64::consts::{FRAC_PI_4, PI};

/// Longest prediction (librcsc `InterceptTable::MAX_CYCLE`).
const MAX_CYCLE: usize = 30;
/// Last cycle of the short-step prediction (`MAX_SHORT_STEP`).
pub(crate) const SHORT_STEPS: usize = 5;
/// How many cycles the long step looks on from its first reachable one
/// (`max_loop = cycle + 10`).
const LONG_WINDOW: usize = 10;
/// `control_area_buf`: how far inside the control area the ball must come.
const CONTROL_BUF: f64 = 0.15;
/// `MIN_TURN_THR` (12.5°): the smallest angle that needs a turn.
const MIN_TURN_THR: f64 = 12.5 * PI / 180.0;
/// The stamina kept back by save-recovery dashing (`recoverDecThrValue() + 1`).
const STAMINA_RESERVE: f64 = 0.3 * STAMINA_MAX + 1.0;

/// One way for a player to get the ball (librcsc `InterceptInfo`, one entry
/// of the self-interception cache).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Interception {
    /// Cycle at which the ball is reached.
    pub(crate) cycle: usize,
    /// Turns before the dashes.
    pub(crate) turns: usize,
    /// Dashes after the turns.
    pub(crate) dashes: usize,
    /// Power of the first dash (negative backwards, 0 with no dash).
    pub(crate) power: f64,
    /// Direction of the first dash relative to the body (radians; not 0
    /// only for the one-step and omni-directional dashes).
    pub(crate) dir: f64,
    /// Distance from the player's final position to the ball
    /// (`InterceptInfo::ballDist`).
    pub(crate) ball_dist: f64,
}

impl Interception {
    /// Whether the dashes go backwards.
    pub(crate) fn back(&self) -> bool {
        self.power < 0.0
    }
}

/// One way to reach the ball and the stamina left after it.
#[derive(Clone, Copy, Debug)]
struct Way {
    entry: Interception,
    stamina: f64,
}

/// The ways of one cycle's search, on the stack: a short step finds at
/// most 15 (two per turn-then-dash way, one per omni-directional dash
/// direction), a one-dash step at most 8.
struct Ways {
    ways: [Way; 16],
    len: usize,
}

impl Default for Ways {
    fn default() -> Self {
        let none = Way {
            entry: entry(0, 0, 0.0, 0.0, 0.0),
            stamina: 0.0,
        };
        Ways {
            ways: [none; 16],
            len: 0,
        }
    }
}

impl Ways {
    fn push(&mut self, way: Way) {
        self.ways[self.len] = way;
        self.len += 1;
    }

    fn clear(&mut self) {
        self.len = 0;
    }

    fn as_slice(&self) -> &[Way] {
        &self.ways[..self.len]
    }
}

/// Where [`reach`] found a player's earliest way, so that [`predict_from`]
/// need not search again what came before it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) enum Found {
    /// Not searched, or the ball is kickable now: nothing to skip.
    #[default]
    Nothing,
    /// The first short step that reaches the ball.
    Short(Interception),
    /// No short step does; the first long step is at this cycle.
    Long(usize),
    /// No short or long step does: the ball's resting point.
    Final,
}

/// The unit vector of the ball's direction of travel (the x axis for a
/// resting ball), which [`reach`] and [`predict_from`] take.
pub(crate) fn heading(ball: &Ball) -> DVec2 {
    unit(direction(ball.vel))
}

/// Every way `SelfInterceptV13::predict` finds for player `p` (the keeper
/// if `goalie`), who cannot kick the ball now, on the ball path `path`
/// (whose first point is `ball`'s position and whose heading is
/// `heading`), earliest first: the best of each short step, the long-step
/// cycles from the first reachable one for 10 cycles, and the ball's
/// resting point when no long step reaches it. `found` is what [`reach`]
/// returned on the same arguments: the search it already made is skipped.
pub(crate) fn predict_from(
    p: &Player,
    ball: &Ball,
    heading: DVec2,
    path: &[DVec2],
    goalie: bool,
    found: Found,
) -> Vec<Interception> {
    let max_cycle = MAX_CYCLE.min(path.len());
    // At most the five short steps and the long step's window.
    let mut cache = Vec::with_capacity(SHORT_STEPS + LONG_WINDOW);
    let mut t = match found {
        Found::Nothing | Found::Short(_) => {
            let lateral = lateral_offset(p, ball, heading);
            let (known, after) = match found {
                Found::Short(first) => (Some(first), first.cycle),
                _ => (None, 0),
            };
            cache.extend(known);
            cache.extend(short_steps(p, ball, lateral, max_cycle, goalie, after));
            long_start(lateral)
        }
        Found::Long(first) => first,
        Found::Final => return vec![final_point(p, ball, max_cycle, goalie)],
    };
    let before = cache.len();
    let mut end = max_cycle;
    let mut runs = Runs::new(p);
    while t < end {
        if let Some(way) = long_step(p, ball, path[t], t, goalie, &mut runs) {
            if cache.len() == before {
                end = max_cycle.min(t + LONG_WINDOW);
            }
            cache.push(way);
        }
        t += 1;
    }
    if cache.len() == before {
        cache.push(final_point(p, ball, max_cycle, goalie));
    }
    cache
}

/// The own reach cycle (`self_min`) and where it was found: 0 if the player
/// can kick the ball by its own test (1.03 m), else the earliest way of
/// [`predict_from`].
pub(crate) fn reach(
    p: &Player,
    ball: &Ball,
    heading: DVec2,
    path: &[DVec2],
    goalie: bool,
) -> (usize, Found) {
    if p.pos.distance(ball.pos) <= AGENT_KICKABLE_AREA {
        return (0, Found::Nothing);
    }
    let max_cycle = MAX_CYCLE.min(path.len());
    let lateral = lateral_offset(p, ball, heading);
    if let Some(first) = short_steps(p, ball, lateral, max_cycle, goalie, 0).next() {
        return (first.cycle, Found::Short(first));
    }
    let mut runs = Runs::new(p);
    (long_start(lateral)..max_cycle)
        .find_map(|t| {
            let way = long_step(p, ball, path[t], t, goalie, &mut runs)?;
            Some((way.cycle, Found::Long(t)))
        })
        .unwrap_or_else(|| (final_point(p, ball, max_cycle, goalie).cycle, Found::Final))
}

/// The player's distance from the ball's line of travel, whose direction is
/// `heading`.
fn lateral_offset(p: &Player, ball: &Ball, heading: DVec2) -> f64 {
    in_frame(p.pos - ball.pos, heading).y.abs()
}

/// The first cycle `predictLongStep` tries: after the short steps, and not
/// before the player can cover its offset `lateral` from the ball's line.
fn long_start(lateral: f64) -> usize {
    let start = libm::ceil((lateral - KICKABLE_AREA - 0.2) / REAL_SPEED_MAX);
    if start <= SHORT_STEPS as f64 {
        SHORT_STEPS + 1
    } else {
        start as usize
    }
}

/// `predictLongStep` at cycle `t` (the ball at `ball_pos`):
/// `canReachAfterTurnDash`; `runs` holds player `p`'s dashes.
#[inline(always)]
fn long_step(
    p: &Player,
    ball: &Ball,
    ball_pos: DVec2,
    t: usize,
    goalie: bool,
    runs: &mut Runs,
) -> Option<Interception> {
    let control = if goalie && in_penalty_area(ball_pos) {
        KEEPER_CONTROL_AREA
    } else {
        KICKABLE_AREA
    };
    if control + REAL_SPEED_MAX * (t as f64) < p.pos.distance(ball_pos) {
        return None;
    }
    long_step_near(p, ball, ball_pos, t, control, goalie, runs)
}

/// [`long_step`] past its distance test (which most cycles fail, so it is
/// inlined into the loops and this is not).
#[inline(never)]
fn long_step_near(
    p: &Player,
    ball: &Ball,
    ball_pos: DVec2,
    t: usize,
    control: f64,
    goalie: bool,
    runs: &mut Runs,
) -> Option<Interception> {
    let (n_turn, dash_angle, back) = long_turns(p, ball, ball_pos, t, control, goalie);
    if n_turn > t {
        return None;
    }
    let run = runs.get(n_turn, back);
    reach_after_dash(p, ball, ball_pos, run, t - n_turn, control, dash_angle)
}

/// `predictTurnCycle`: the turns (each at most 162°, the largest moment less
/// its noise) until the body, or its back where `canBackDashChase` allows,
/// points at the ball within max(12.5°, asin((control - 0.25) / distance));
/// returns them, the dash direction and whether the dashes go backwards.
fn long_turns(
    p: &Player,
    ball: &Ball,
    ball_pos: DVec2,
    t: usize,
    control: f64,
    goalie: bool,
) -> (usize, f64, bool) {
    let rel = ball_pos - p.drift(t as u32);
    let (dist, target) = (rel.length(), direction(rel));
    let signed = normalize_angle(target - p.body);
    let mut diff = signed.abs();
    let buf = (control - 0.25).max(0.5);
    let margin = if buf < dist {
        asin_clamped(buf / dist)
    } else {
        PI
    }
    .max(MIN_TURN_THR);
    let mut dash_angle = p.body;
    let back = back_dash_allowed(p, ball, t, diff, goalie);
    if back {
        dash_angle = normalize_angle(p.body + PI);
        diff = PI - diff;
    }
    let mut n_turn = 0;
    let mut speed = p.vel.length();
    while diff > margin {
        diff -= 0.9 * PI / (1.0 + INERTIA_MOMENT * speed);
        speed *= PLAYER_DECAY;
        n_turn += 1;
    }
    if n_turn > 0 {
        // librcsc measures the sign before a back dash flips the angle.
        let left = diff.max(0.0);
        dash_angle = if signed > 0.0 {
            target + left
        } else {
            target - left
        };
    }
    (n_turn, dash_angle, back)
}

/// `canBackDashChase`: a ball at least 100° off the body, before cycle 5 for
/// an attacker; for the keeper before cycle 15 while the ball is then
/// within 21 m of its goal; and stamina for full backward dashes.
fn back_dash_allowed(p: &Player, ball: &Ball, t: usize, diff: f64, goalie: bool) -> bool {
    if diff < 100f64.to_radians() {
        return false;
    }
    if t >= 5 && (!goalie || t >= 15) {
        return false;
    }
    if goalie && t >= 5 {
        let at = ball.pos + ball.vel * decay_sum(BALL_DECAY, t as u32);
        if at.distance(GOAL_CENTER) > 21.0 {
            return false;
        }
    }
    let left = p.stamina - 2.0 * MAX_DASH_POWER * t as f64
        + STAMINA_INC_MAX * p.recovery * (t as f64 - 1.0);
    left >= 0.3 * STAMINA_MAX + 205.0
}

/// The full dashes a player makes after some turns, as its stamina allows
/// them (half the power backwards); librcsc's speed-limit branch never acts
/// for this player type (100 · 0.006 < 1.05 · 0.6).
struct DashRun {
    turns: usize,
    back: bool,
    /// The player after the dashes so far.
    me: Player,
    /// The first dash's power (0 before it).
    first: f64,
    /// Each dash's acceleration along the dash line.
    accel: [f64; MAX_CYCLE],
    len: usize,
    /// Without turns, the unit vector of the dash line (the body's or its
    /// back's, the same at every cycle), once computed.
    line: Option<DVec2>,
}

impl DashRun {
    fn new(p: &Player, turns: usize, back: bool) -> Self {
        let mut me = *p;
        for _ in 0..turns {
            update_stamina(&mut me);
        }
        DashRun {
            turns,
            back,
            me,
            first: 0.0,
            accel: [0.0; MAX_CYCLE],
            len: 0,
            line: None,
        }
    }

    /// Simulates the dashes up to the `n`th.
    fn extend(&mut self, n: usize) {
        let share = if self.back { 0.5 } else { 1.0 };
        while self.len < n {
            let me = &mut self.me;
            let power = (available(me.stamina) * share).clamp(0.0, MAX_DASH_POWER);
            if self.len == 0 {
                self.first = power;
            }
            self.accel[self.len] = power * DASH_POWER_RATE * me.effort;
            spend(me, if self.back { -power } else { power });
            self.len += 1;
        }
    }
}

/// One player's runs, kept while its long steps are predicted: each long
/// step's dashes depend only on the turns before them and their direction.
struct Runs {
    player: Player,
    runs: Vec<DashRun>,
}

thread_local! {
    /// The storage of the last [`Runs`] dropped, reused by the next.
    static RUNS: std::cell::Cell<Vec<DashRun>> = const { std::cell::Cell::new(Vec::new()) };
}

impl Runs {
    fn new(p: &Player) -> Self {
        let mut runs = RUNS.take();
        runs.clear();
        Runs { player: *p, runs }
    }

    /// The run after `turns` turns, backwards if `back`.
    fn get(&mut self, turns: usize, back: bool) -> &mut DashRun {
        let i = match self
            .runs
            .iter()
            .position(|r| r.turns == turns && r.back == back)
        {
            Some(i) => i,
            None => {
                self.runs.push(DashRun::new(&self.player, turns, back));
                self.runs.len() - 1
            }
        };
        &mut self.runs[i]
    }
}

impl Drop for Runs {
    fn drop(&mut self) {
        RUNS.set(std::mem::take(&mut self.runs));
    }
}

/// `canReachAfterDash`: `n_dash` dashes of `run` along `dash_angle` after
/// its turns; the player reaches the ball once its run along that line
/// passes the ball's point there (plus half its noise), or if after the
/// dashes the ball is within max(control - 0.225, control - 0.2 - noise).
fn reach_after_dash(
    p: &Player,
    ball: &Ball,
    ball_pos: DVec2,
    run: &mut DashRun,
    n_dash: usize,
    control: f64,
    dash_angle: f64,
) -> Option<Interception> {
    run.extend(n_dash);
    let (n_turn, back) = (run.turns, run.back);
    // Without turns the dash angle is the body's (or its back's) at every cycle.
    let u = if n_turn == 0 {
        *run.line.get_or_insert_with(|| unit(dash_angle))
    } else {
        unit(dash_angle)
    };
    let inertia = p.drift((n_turn + n_dash) as u32);
    let ball_rel = in_frame(ball_pos - p.pos, u);
    let ball_noise = ball.pos.distance(ball_pos) * BALL_RAND * 0.5;
    let noised_x = ball_rel.x + ball_noise;
    let mut pos = in_frame(p.vel * DRIFT[n_turn.min(DRIFT.len() - 1)], u);
    let mut vel = in_frame(p.vel * decay_pow(PLAYER_DECAY, n_turn as u32), u);
    let first = (n_dash > 0).then_some(run.first);
    for &accel in &run.accel[..n_dash] {
        vel.x += accel;
        pos += vel;
        vel *= PLAYER_DECAY;
        if pos.x * (1.0 - PLAYER_RAND * 0.01) + 0.1 > noised_x {
            let mut end = p.pos + u * pos.x + u.perp() * pos.y;
            if inertia.distance_squared(end) > 0.01 {
                let line = (end - inertia).normalize();
                end = inertia + line * (ball_pos - inertia).dot(line);
            }
            let power = first.unwrap_or(0.0);
            return Some(entry(
                n_turn,
                n_dash,
                if back { -power } else { power },
                0.0,
                end.distance(ball_pos),
            ));
        }
    }
    let travel = pos.length();
    let buf = 0.2 + travel * PLAYER_RAND * 0.5 + ball_noise;
    let last = ball_rel.distance(pos);
    (last < (control - 0.225).max(control - buf)).then(|| {
        let end = p.pos + u * pos.x + u.perp() * pos.y;
        let power = first.unwrap_or(0.0);
        entry(
            n_turn,
            n_dash,
            if back { -power } else { power },
            0.0,
            end.distance(ball_pos),
        )
    })
}

/// `predictFinal`: the ball's resting point, after the turns and the dashes
/// that cover the distance less the control area (0.15 m less for the
/// keeper's catch), and not before the end of the ball's path.
fn final_point(p: &Player, ball: &Ball, max_cycle: usize, goalie: bool) -> Interception {
    let me_final = p.final_drift();
    let ball_final = ball.pos + ball.vel / (1.0 - BALL_DECAY);
    let control = if goalie && in_penalty_area(ball_final) {
        KEEPER_CONTROL_AREA - 0.15
    } else {
        KICKABLE_AREA
    };
    let (n_turn, _, _) = long_turns(p, ball, ball_final, 100, control, goalie);
    let n_dash =
        dash_cycles(me_final.distance(ball_final) - control).max(max_cycle.saturating_sub(n_turn));
    entry(n_turn, n_dash, MAX_DASH_POWER, 0.0, 0.0)
}

/// The best way to reach the ball at each reachable cycle after `after`
/// up to 5, in order and computed only as far as they are taken, for player
/// `p`, who cannot kick the ball now and stands `lateral` off the ball's
/// line, the keeper if `goalie`; `max_cycle` bounds the cycles as the ball
/// cache's length does (`min(MAX_CYCLE, cache size)`).
fn short_steps<'a>(
    p: &'a Player,
    ball: &'a Ball,
    lateral: f64,
    max_cycle: usize,
    goalie: bool,
    after: usize,
) -> impl Iterator<Item = Interception> + 'a {
    let one_step_control = match goalie && in_penalty_area(ball.pos + ball.vel) {
        true => KEEPER_CONTROL_AREA,
        false => KICKABLE_AREA,
    };
    let first = std::iter::once_with(move || one_step(p, ball, one_step_control, goalie))
        .take(usize::from(after == 0))
        .flatten()
        .map(|w| w.entry);
    let max_loop = SHORT_STEPS.min(max_cycle);
    // The cycles needed to cover the player's distance from the ball's line.
    let min_cycle = libm::ceil((lateral - KICKABLE_AREA) / REAL_SPEED_MAX);
    let cycles = if min_cycle >= max_loop as f64 {
        0..0
    } else {
        (min_cycle.max(2.0) as usize).max(after + 1)..max_loop + 1
    };
    let mut positions = [ball.pos; SHORT_STEPS + 1];
    let (mut ball_pos, mut ball_vel) = (ball.pos, ball.vel);
    for slot in positions.iter_mut().skip(1) {
        ball_pos += ball_vel;
        ball_vel *= BALL_DECAY;
        *slot = ball_pos;
    }
    // Made by the first cycle that needs it.
    let mut ways = None;
    let later = cycles
        .filter_map(move |cycle| short_step(p, ball, cycle, positions[cycle], goalie, &mut ways));
    first.chain(later)
}

/// `predictShortStep` at cycle `cycle` (2 to 5), the ball then at
/// `ball_pos`: the best of the turn-then-dash ways (forward and backward,
/// each with two turn margins) and, up to cycle 2, the omni-directional
/// dashes; `ways` is scratch space, made by the first cycle that needs it.
fn short_step(
    p: &Player,
    ball: &Ball,
    cycle: usize,
    ball_pos: DVec2,
    goalie: bool,
    ways: &mut Option<Ways>,
) -> Option<Interception> {
    // Goalie mode inside the area less 0.5 m.
    let deep =
        ball_pos.x > PENALTY_AREA_X + 0.5 && ball_pos.y.abs() < PENALTY_AREA_HALF_WIDTH - 0.5;
    let control = if goalie && deep {
        KEEPER_CONTROL_AREA
    } else {
        KICKABLE_AREA
    };
    let reach = control + REAL_SPEED_MAX * cycle as f64;
    if reach * reach < p.pos.distance_squared(ball_pos) {
        return None;
    }
    let inertia = p.drift(cycle as u32);
    let rel = ball_pos - inertia;
    let c = Chase {
        p,
        ball_pos,
        cycle,
        control,
        inertia,
        target_dist: rel.length(),
        target_angle: direction(rel),
    };
    let turn_margins = [control - 0.4, control - CONTROL_BUF].map(|m| c.turn_margin(m.max(0.1)));
    let ways = ways.get_or_insert_with(Ways::default);
    ways.clear();
    for back in [false, true] {
        for turn_margin in turn_margins {
            c.turn_dash(back, turn_margin, ways);
        }
    }
    if cycle <= 2 {
        c.omni_dash(ways);
    }
    let safety = (control - 0.2 - ball.pos.distance(ball_pos) * BALL_RAND)
        .max(PLAYER_SIZE + BALL_SIZE + KICKABLE_MARGIN * 0.4);
    pick_short(ways.as_slice(), safety).map(|w| w.entry)
}

/// `predictOneStep`: the ball comes to the player by itself, or one dash
/// (in any of the eight dash directions) brings it there.
fn one_step(p: &Player, ball: &Ball, control: f64, goalie: bool) -> Option<Way> {
    let too_far = BALL_SPEED_MAX + REAL_SPEED_MAX + control;
    if p.pos.distance(ball.pos) > too_far {
        return None;
    }
    no_dash(p, ball, control, goalie).or_else(|| one_dash(p, ball, control))
}

/// `predictNoDash`: the ball's next position is well inside the control
/// area and (unless the keeper catches it) one kick can still stop it.
fn no_dash(p: &Player, ball: &Ball, control: f64, goalie: bool) -> Option<Way> {
    let me_next = Player {
        pos: p.pos + p.vel,
        ..*p
    };
    let ball_next = ball.pos + ball.vel;
    let dist = me_next.pos.distance(ball_next);
    if dist > control - CONTROL_BUF - ball.vel.length() * BALL_RAND {
        return None;
    }
    let next_speed = ball.vel.length() * BALL_DECAY;
    let catchable = goalie && control == KEEPER_CONTROL_AREA;
    if !catchable
        && dist > PLAYER_SIZE + BALL_SIZE
        && MAX_KICK_POWER * kick_rate(&me_next, ball_next) <= next_speed * BALL_DECAY * 1.1
    {
        return None; // it might not be stopped
    }
    let mut rested = *p;
    update_stamina(&mut rested);
    Some(Way {
        entry: entry(1, 0, 0.0, 0.0, dist),
        stamina: rested.stamina,
    })
}

/// `predictOneDash`: of the dash directions after which the ball is
/// controllable, the one leaving it nearest (or, when several leave it safe,
/// the one sparing the most stamina).
fn one_dash(p: &Player, ball: &Ball, control: f64) -> Option<Way> {
    let forward = (p.stamina - STAMINA_RESERVE).clamp(0.0, MAX_DASH_POWER);
    let back = ((p.stamina - STAMINA_RESERVE) * -0.5).clamp(-MAX_DASH_POWER, 0.0);
    let full = (forward - MAX_DASH_POWER).abs() < 1.0 && (back + MAX_DASH_POWER).abs() < 1.0;
    let mut ways = Ways::default();
    for dir in dash_dirs() {
        let u = unit(p.body + dir);
        let rate = p.effort * DASH_POWER_RATE * dash_dir_rate(dir);
        let powers: &[(f64, f64)] = if full {
            &[(forward, back)]
        } else {
            &[(forward, back), (MAX_DASH_POWER, -MAX_DASH_POWER)]
        };
        let way = powers.iter().find_map(|&(f, b)| {
            // `u * r` is `polar(r, angle)` bit for bit.
            let max_forward = limit_accel(p.vel, u * (f * rate));
            let max_back = limit_accel(p.vel, u * (b * rate));
            one_dash_adjust(p, ball, dir, u, max_forward, max_back, control)
        });
        if let Some(w) = way {
            ways.push(w);
        }
    }
    let safety = (control - 0.2 - ball.vel.length() * BALL_RAND)
        .max(PLAYER_SIZE + BALL_SIZE + KICKABLE_MARGIN * 0.4);
    let ways = ways.as_slice();
    let mut best = *ways.first()?;
    for &w in &ways[1..] {
        let both_safe = best.entry.ball_dist < safety && w.entry.ball_dist < safety;
        let nearer = best.entry.ball_dist > w.entry.ball_dist
            || ((best.entry.ball_dist - w.entry.ball_dist).abs() < 0.001
                && best.stamina < w.stamina);
        if (both_safe && best.stamina < w.stamina) || (!both_safe && nearer) {
            best = w;
        }
    }
    Some(best)
}

/// `predictOneDashAdjust`: the dash power along `dir` (relative to the body;
/// `u` its global unit vector) that leaves the ball controllable, between
/// the largest backward and forward accelerations.
fn one_dash_adjust(
    p: &Player,
    ball: &Ball,
    dir: f64,
    u: DVec2,
    max_forward: DVec2,
    max_back: DVec2,
    control: f64,
) -> Option<Way> {
    let control = control - 0.075;
    let ball_next = ball.pos + ball.vel;
    let ball_rel = in_frame(ball_next - (p.pos + p.vel), u);
    let (f, b) = (in_frame(max_forward, u), in_frame(max_back, u));
    let rate = p.effort * DASH_POWER_RATE * dash_dir_rate(dir);
    if ball_rel.y.abs() > control || segment_distance(f, b, ball_rel) > control {
        return None;
    }
    let between = b.x < ball_rel.x && ball_rel.x < f.x;
    let power = between
        .then(|| one_step_dash_power(p, p.body + dir, ball_rel, f.x, b.x))
        .flatten()
        .or_else(|| (f.x < ball_rel.x && ball_rel.distance(f) < control).then(|| f.x / rate))
        .or_else(|| (ball_rel.x < b.x && ball_rel.distance(b) < control).then(|| b.x / rate))
        .or_else(|| between.then(|| ball_rel.x / rate))?;
    let pos = p.pos + p.vel + u * (power * rate);
    let mut after = *p;
    spend(&mut after, power);
    Some(Way {
        entry: entry(0, 1, power, dash_dir(dir), pos.distance(ball_next)),
        stamina: after.stamina,
    })
}

/// `getOneStepDashPower`: the weakest dash that traps the ball at the best
/// control distance in front of or behind the player. As librcsc, the rate
/// reads the dash's global angle where the relative one was meant.
fn one_step_dash_power(
    p: &Player,
    dash_angle: f64,
    ball_rel: DVec2,
    max_forward_x: f64,
    max_back_x: f64,
) -> Option<f64> {
    let rate = p.effort * DASH_POWER_RATE * dash_dir_rate(normalize_angle(dash_angle));
    let best_forward = PLAYER_SIZE + 0.5 * KICKABLE_MARGIN + BALL_SIZE;
    let best_backward = PLAYER_SIZE + 0.3 * KICKABLE_MARGIN + BALL_SIZE;
    if ball_rel.y.abs() > best_forward {
        return Some(ball_rel.x / rate); // just put the ball at the side
    }
    let y2 = ball_rel.y * ball_rel.y;
    let forward_trap = ball_rel.x - (best_forward * best_forward - y2).sqrt();
    // NaN when the ball is beside the backward circle: then no step is tried.
    let backward_trap = ball_rel.x + (best_backward * best_backward - y2).sqrt();
    let step = (backward_trap - forward_trap) / 5.0;
    let mut best: Option<f64> = None;
    let mut accel_x = forward_trap;
    while accel_x < backward_trap + 0.01 {
        let feasible = if accel_x >= 0.0 {
            max_forward_x > accel_x
        } else {
            max_back_x < accel_x
        };
        let power = accel_x / rate;
        if feasible && best.is_none_or(|b| power.abs() < b.abs()) {
            best = Some(power);
        }
        accel_x += step;
    }
    best
}

/// One cycle of `predictShortStep`: the player and where the ball will be.
struct Chase<'a> {
    p: &'a Player,
    ball_pos: DVec2,
    cycle: usize,
    /// The control area at that cycle.
    control: f64,
    /// Where the player drifts to by then, and the ball's distance and
    /// direction from there.
    inertia: DVec2,
    target_dist: f64,
    target_angle: f64,
}

impl Chase<'_> {
    /// The largest angle off the ball that needs no turn, for a ball
    /// `margin` off the body's line.
    fn turn_margin(&self, margin: f64) -> f64 {
        if margin < self.target_dist {
            MIN_TURN_THR.max(asin_clamped(margin / self.target_dist))
        } else {
            PI
        }
    }

    /// `predictTurnDashShort`: turn (if the ball is more than `turn_margin`
    /// off), then dash along the body or its back.
    fn turn_dash(&self, back: bool, turn_margin: f64, ways: &mut Ways) {
        let (p, target_angle) = (self.p, self.target_angle);
        let body = if back {
            normalize_angle(p.body + PI)
        } else {
            p.body
        };
        let mut diff = angle_diff(target_angle, body);
        let mut n_turn = 0;
        let mut speed = p.vel.length();
        while diff > turn_margin {
            diff -= PI / (1.0 + INERTIA_MOMENT * speed);
            speed *= PLAYER_DECAY;
            n_turn += 1;
        }
        let dash_angle = match n_turn {
            0 => body,
            _ if normalize_angle(target_angle - body) > 0.0 => target_angle - diff.max(0.0),
            _ => target_angle + diff.max(0.0),
        };
        if n_turn <= self.cycle {
            self.dash_cycle(n_turn, dash_angle, back, ways);
        }
    }

    /// `predictDashCycleShort`: after `n_turn` turns, the dashes along
    /// `dash_angle` that stop the player at the ball, if they get there.
    fn dash_cycle(&self, n_turn: usize, dash_angle: f64, back: bool, ways: &mut Ways) {
        let (p, ball_pos, cycle) = (self.p, self.ball_pos, self.cycle);
        let max_dash = cycle - n_turn;
        let inertia = self.inertia;
        let mut me = *p;
        for _ in 0..n_turn {
            update_stamina(&mut me);
        }
        let control2 = (self.control - CONTROL_BUF).powi(2);
        if inertia.distance_squared(ball_pos) < control2 {
            let mut waited = me;
            for _ in 0..max_dash {
                update_stamina(&mut waited);
            }
            ways.push(Way {
                entry: entry(n_turn, max_dash, 0.0, 0.0, inertia.distance(ball_pos)),
                stamina: waited.stamina,
            });
        }
        if angle_diff(self.target_angle, dash_angle) > PI / 2.0 {
            return;
        }
        me.pos = p.drift(n_turn as u32);
        me.vel = p.vel * decay_pow(PLAYER_DECAY, n_turn as u32);
        let first = dash_to(&mut me, ball_pos, unit(dash_angle), back, max_dash);
        if me.pos.distance_squared(ball_pos) < control2
            || p.pos.distance_squared(me.pos) > p.pos.distance_squared(ball_pos)
        {
            ways.push(Way {
                entry: entry(n_turn, max_dash, first, 0.0, me.pos.distance(ball_pos)),
                stamina: me.stamina,
            });
        }
    }

    /// `predictOmniDashShort` (cycles 1-2, forward): up to two dashes sideways
    /// onto the ball's line along the body, then dashes along the body.
    fn omni_dash(&self, ways: &mut Ways) {
        let (p, ball_pos, cycle) = (self.p, self.ball_pos, self.cycle);
        let body = unit(p.body);
        let line_dist = |q: DVec2| body.perp_dot(q - ball_pos).abs();
        if line_dist(self.inertia) < self.control - 0.4 {
            return;
        }
        for dir in dash_dirs().filter(|&d| d != 0.0) {
            if angle_diff(p.body + dir, self.target_angle) > 91f64.to_radians() {
                continue;
            }
            let mut me = *p;
            let u = unit(p.body + dir);
            let rate = p.effort * DASH_POWER_RATE * dash_dir_rate(dir);
            let mut first = 0.0;
            let mut n_omni = None;
            for n in 1..=cycle.min(2) {
                let first_speed = first_term(line_dist(me.pos).max(0.0), cycle - n + 1);
                let required = first_speed - me.vel.dot(u);
                if required.abs() < 0.01 {
                    n_omni = Some(n - 1);
                    break;
                }
                let power = (required / rate)
                    .clamp(0.0, MAX_DASH_POWER)
                    .min(available(me.stamina));
                if n == 1 {
                    first = power;
                }
                me.vel += u * (power.abs() * rate);
                me.pos += me.vel;
                me.vel *= PLAYER_DECAY;
                spend(&mut me, power);
                if line_dist(me.pos + me.vel * DRIFT[cycle - n]) < self.control - CONTROL_BUF {
                    n_omni = Some(n);
                    break;
                }
            }
            let Some(n_omni) = n_omni.filter(|&n| n > 0) else {
                continue;
            };
            let ahead = me.pos + me.vel * DRIFT[cycle - n_omni];
            if (ball_pos - ahead).dot(body) < 0.0 {
                continue; // the ball would be behind
            }
            dash_to(&mut me, ball_pos, body, false, cycle - n_omni);
            let moved = me.pos - p.pos;
            let reaches_line = moved.length()
                > in_frame(ball_pos - p.pos, moved.normalize_or_zero())
                    .x
                    .abs();
            if me.pos.distance_squared(ball_pos) < (self.control - CONTROL_BUF).powi(2)
                || reaches_line
            {
                ways.push(Way {
                    entry: entry(0, cycle, first, dash_dir(dir), me.pos.distance(ball_pos)),
                    stamina: me.stamina,
                });
            }
        }
    }
}

/// Dashes along `u` (the body or its back) that would bring `me` level with
/// `ball_pos` along `u` in `n_dash` cycles, each as strong as the stamina
/// allows; returns the first dash's power (0 if there is none).
fn dash_to(me: &mut Player, ball_pos: DVec2, u: DVec2, back: bool, n_dash: usize) -> f64 {
    let mut first_power = 0.0;
    for n in 1..=n_dash {
        let first_speed = first_term((ball_pos - me.pos).dot(u), n_dash - n + 1);
        let rate = me.effort * DASH_POWER_RATE;
        let required = (first_speed - me.vel.dot(u)) / rate;
        let power = if back {
            (-required)
                .clamp(-MAX_DASH_POWER, 0.0)
                .max(available(me.stamina) * -0.5)
        } else {
            required
                .clamp(0.0, MAX_DASH_POWER)
                .min(available(me.stamina))
        };
        if n == 1 {
            first_power = power;
        }
        me.vel += u * (power.abs() * rate);
        me.pos += me.vel;
        me.vel *= PLAYER_DECAY;
        spend(me, power);
    }
    first_power
}

/// `predictShortStep`'s choice among one cycle's ways: when both are safely
/// inside the kickable area, fewer turns, then more stamina; otherwise the
/// nearer ball among ways with no more turns.
fn pick_short(ways: &[Way], safety: f64) -> Option<Way> {
    let mut best = *ways.first()?;
    for &w in &ways[1..] {
        let (b, e) = (best.entry, w.entry);
        let better = if b.ball_dist < safety && e.ball_dist < safety {
            b.turns > e.turns || (b.turns == e.turns && best.stamina < w.stamina)
        } else {
            b.turns >= e.turns
                && (b.ball_dist > e.ball_dist
                    || ((b.ball_dist - e.ball_dist).abs() < 0.001 && best.stamina < w.stamina))
        };
        if better {
            best = w;
        }
    }
    Some(best)
}

/// An interception at cycle `turns + dashes` whose first dash has `power`
/// along `dir`.
fn entry(turns: usize, dashes: usize, power: f64, dir: f64, ball_dist: f64) -> Interception {
    Interception {
        cycle: turns + dashes,
        turns,
        dashes,
        power,
        dir,
        ball_dist,
    }
}

/// The eight dash directions relative to the body, -180° to 135°.
fn dash_dirs() -> impl Iterator<Item = f64> {
    (-4..4).map(|k| f64::from(k) * FRAC_PI_4)
}

/// `v` in the frame whose x axis is the unit vector `u`.
fn in_frame(v: DVec2, u: DVec2) -> DVec2 {
    DVec2::new(v.dot(u), u.perp_dot(v))
}

/// Distance from `q` to the segment from `a` to `b`.
fn segment_distance(a: DVec2, b: DVec2, q: DVec2) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((q - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    q.distance(a + ab * t)
}

/// `PlayerType::normalizeAccel`: shortens a dash's acceleration so the
/// player's speed stays within its limit.
fn limit_accel(vel: DVec2, accel: DVec2) -> DVec2 {
    if (vel + accel).length_squared() <= PLAYER_SPEED_MAX * PLAYER_SPEED_MAX + 0.0001 {
        return accel;
    }
    let u = accel.normalize_or_zero();
    let rel = in_frame(vel, u);
    u * ((PLAYER_SPEED_MAX * PLAYER_SPEED_MAX - rel.y * rel.y).sqrt() - rel.x)
}

/// First term of a series decaying by the player's decay that sums to
/// `sum` over `len` terms (`calc_first_term_geom_series`).
fn first_term(sum: f64, len: usize) -> f64 {
    sum * (1.0 - PLAYER_DECAY) / (1.0 - decay_pow(PLAYER_DECAY, len as u32))
}

/// The dash power the stamina allows under save-recovery dashing.
fn available(stamina: f64) -> f64 {
    (stamina - STAMINA_RESERVE).max(0.0)
}

/// librcsc's `StaminaModel::simulateDash`.
fn spend(p: &mut Player, power: f64) {
    let cost = if power >= 0.0 { power } else { -2.0 * power };
    p.stamina = (p.stamina - cost).max(0.0);
    update_stamina(p);
}

/// [`predict_from`] searching everything again: the reference the tests
/// compare with.
#[cfg(test)]
pub(crate) fn predict(p: &Player, ball: &Ball, path: &[DVec2], goalie: bool) -> Vec<Interception> {
    predict_from(p, ball, heading(ball), path, goalie, Found::Nothing)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::world::World;

    fn world(ball: (f64, f64, f64, f64), me: (f64, f64, f64, f64), body_deg: f64) -> World {
        let mut w = World::new(1);
        w.ball.pos = DVec2::new(ball.0, ball.1);
        w.ball.vel = DVec2::new(ball.2, ball.3);
        w.offense[0] = Player::new(DVec2::new(me.0, me.1), body_deg.to_radians());
        w.offense[0].vel = DVec2::new(me.2, me.3);
        w.keeper = Player::new(DVec2::new(50.0, 2.8), FRAC_PI_4 * 2.0);
        w
    }

    /// The ball's path without kicks over the longest prediction, as the
    /// analysis of a ball that keeps moving has it.
    fn path(ball: &Ball) -> Vec<DVec2> {
        let (mut pos, mut vel) = (ball.pos, ball.vel);
        (0..=MAX_CYCLE)
            .map(|_| {
                let at = pos;
                pos += vel;
                vel *= BALL_DECAY;
                at
            })
            .collect()
    }

    /// The own reach cycle of attacker 0 in `w` on the path `path`.
    fn own_reach(w: &World, path: &[DVec2]) -> usize {
        reach(&w.offense[0], &w.ball, heading(&w.ball), path, false).0
    }

    #[test]
    fn a_ball_kicked_on_beside_the_body_takes_five_cycles_as_in_hfo() {
        // A state from HFO's logs where its dribbler's self_min was 5: the
        // ball 1.1 m ahead at 0.68 m/cycle, 21° off the body. Dashing along
        // the body leaves it too far to the side, so the player turns first
        // and gets there at cycle 5 (the others' estimate, running straight
        // at it, says 2 cycles or fewer: the analysis tests).
        let w = world(
            (44.6709, 5.4471, 0.6549, 0.1775),
            (43.5482, 5.2586, 0.1476, -0.0176),
            -6.261,
        );
        let path = path(&w.ball);
        assert_eq!(own_reach(&w, &path), 5);
        let steps: Vec<_> = short_steps(
            &w.offense[0],
            &w.ball,
            lateral_offset(&w.offense[0], &w.ball, heading(&w.ball)),
            path.len(),
            false,
            0,
        )
        .collect();
        assert_eq!(steps.len(), 1);
        assert_eq!((steps[0].cycle, steps[0].turns), (5, 1));
    }

    #[test]
    fn a_far_ball_is_reached_when_the_run_passes_it_as_in_hfo() {
        // A pass rolling 10 m from a teammate, from HFO's logs: its agent
        // printed self_min 14 (the straight-run rule with a 0.2 m margin
        // said 13).
        let w = world(
            (28.41, 5.26, 0.27, -0.15),
            (20.35, 12.11, 0.14, -0.11),
            -41.0,
        );
        let path = path(&w.ball);
        assert_eq!(own_reach(&w, &path), 14);
        let cache = predict(&w.offense[0], &w.ball, &path, false);
        assert_eq!(cache[0].cycle, 14);
        assert!(cache.windows(2).all(|c| c[1].cycle == c[0].cycle + 1));
        assert!(cache.len() <= LONG_WINDOW);
    }

    #[test]
    fn a_ball_rolling_into_the_kickable_area_needs_no_dash() {
        let w = world((10.0, 0.0, -1.0, 0.0), (8.5, 0.0, 0.0, 0.0), 0.0);
        let entry = one_step(&w.offense[0], &w.ball, KICKABLE_AREA, false)
            .expect("reachable")
            .entry;
        assert_eq!((entry.cycle, entry.turns, entry.dashes), (1, 1, 0));
        assert!((entry.ball_dist - 0.5).abs() < 1e-9);
    }

    #[test]
    fn one_sideways_dash_reaches_a_ball_beside_the_player() {
        // The ball rests 1.2 m to the left: out of reach without a dash and
        // after a forward one, within reach after a sideways dash.
        let w = world((0.0, 1.2, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0), 0.0);
        assert!(no_dash(&w.offense[0], &w.ball, KICKABLE_AREA, false).is_none());
        let entry = one_dash(&w.offense[0], &w.ball, KICKABLE_AREA)
            .expect("one dash")
            .entry;
        assert_eq!((entry.cycle, entry.dashes), (1, 1));
        assert!(entry.ball_dist < KICKABLE_AREA - 0.075);
    }

    #[test]
    fn a_ball_behind_is_chased_by_dashing_backwards() {
        let w = world((-2.5, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0), 0.0);
        let first = short_steps(
            &w.offense[0],
            &w.ball,
            lateral_offset(&w.offense[0], &w.ball, heading(&w.ball)),
            30,
            false,
            0,
        )
        .next()
        .expect("reachable");
        assert!(first.back() && first.turns == 0, "{first:?}");
    }
}
