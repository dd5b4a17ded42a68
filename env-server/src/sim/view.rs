//! What each attacker has looked at lately (spec 6.6): librcsc's
//! seen-direction counts, fed by rcssserver's see messages, and the neck and
//! view-width choices of HFO's agent that decide where those sees look.
//!
//! Everyone plays with full state, so no position depends on this; only
//! HFO's pass code reads it (`dirRangeCount` in `bhv_force_pass.cpp`). Angles
//! here are in degrees, as in librcsc, with its `AngleDeg` wrapping.

use crate::sim::geom::unit;
use crate::sim::params::PLAYER_DECAY;
use glam::DVec2;

/// Number of 5° direction bins (`WorldModel::DIR_CONF_DIVS`).
const DIRS: usize = 72;
/// Width of one direction bin, degrees (`WorldModel::DIR_STEP`).
const DIR_STEP: f64 = 5.0;
/// A count stops growing here (`WorldModel::update`).
const MAX_COUNT: u8 = 10;
/// rcssserver's neck range, degrees either side of the body.
const MAX_NECK: f64 = 90.0;

/// Visual ticks of rcssserver's synch-mode timer (a quarter of `send_step`,
/// 37.5 ms, against 100 ms cycles: 8 ticks per 3 cycles), per cycle of the
/// 3-cycle period: before the agents' think message, and after it.
const TICKS_BEFORE_THINK: [u8; 3] = [2, 2, 1];
const TICKS_AFTER_THINK: [u8; 3] = [1, 1, 1];

/// A view width without `synch_see` (HFO's agents do not ask for it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Width {
    Narrow,
    Normal,
    Wide,
}

impl Width {
    /// The view cone, degrees (`ViewWidth::width`: visible angle × 0.5, 1, 2).
    fn degrees(self) -> f64 {
        match self {
            Width::Narrow => 45.0,
            Width::Normal => 90.0,
            Width::Wide => 180.0,
        }
    }

    /// The unit vectors of a 5° step and of half the view cone, as the
    /// scan turns its cone (`unit` of those angles, computed once).
    fn step_and_half(self) -> (DVec2, DVec2) {
        static UNITS: std::sync::LazyLock<[(DVec2, DVec2); 3]> = std::sync::LazyLock::new(|| {
            [Width::Narrow, Width::Normal, Width::Wide].map(|w| {
                (
                    unit(DIR_STEP.to_radians()),
                    unit((w.degrees() * 0.5).to_radians()),
                )
            })
        });
        UNITS[self as usize]
    }

    /// Visual ticks between two sees (rcssserver's `visual_send_interval`).
    fn interval(self) -> u8 {
        match self {
            Width::Narrow => 2,
            Width::Normal => 4,
            Width::Wide => 8,
        }
    }
}

/// librcsc's estimate of when its sees arrive (`SeeState::SeeTiming`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum SeeTiming {
    At0,
    At50,
    At22,
    NoSynch,
}

impl SeeTiming {
    /// `SeeState::getNextTiming`: the timing of a see after one at `self`.
    fn next(self, width: Width) -> SeeTiming {
        use {SeeTiming::*, Width::*};
        match (self, width) {
            (At0, Wide) | (At50, Normal) | (At22, Narrow) => At0,
            (At0, Normal) | (At50, Wide) => At50,
            (At50, Narrow) | (At22, Wide) => At22,
            _ => NoSynch,
        }
    }
}

/// The neck action a behaviour leaves for the cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Neck {
    /// `Neck_ScanField` (also `Neck_TurnToBallOrScan`: with full state the
    /// ball's position count is 0).
    Scan,
    /// `Neck_TurnToBall`.
    TurnToBall,
    /// No neck command (`Neck_OffensiveInterceptNeck` before the agent's
    /// action chain exists).
    Keep,
}

/// One attacker's view: neck, width, see timing and seen-direction counts.
/// Like the agent's world model it survives episode resets. Only the neck
/// is public; the Debug output shows the rest.
#[derive(Clone, Debug, PartialEq)]
pub struct Sight {
    /// Neck angle relative to the body, degrees.
    pub neck: f64,
    width: Width,
    /// Visual ticks since the last see (rcssserver's send count).
    ticks: u8,
    timing: SeeTiming,
    /// `SeeState`'s cycles till the next see.
    cycles_till_see: u8,
    /// Whether a see arrived this cycle.
    seen: bool,
    /// Whether the agent has dribbled, which creates its action chain
    /// (`ActionChainHolder`); MOVE's intercept neck does nothing before.
    pub(crate) chain_ready: bool,
    /// Cycles since each 5° direction was last in view.
    counts: [u8; DIRS],
}

impl Default for Sight {
    /// A synchronised agent (the phase HFO's agents keep all game) about to
    /// see at the first tick of the period.
    fn default() -> Self {
        Sight {
            neck: 0.0,
            width: Width::Narrow,
            ticks: 1,
            timing: SeeTiming::At22,
            cycles_till_see: 1,
            seen: false,
            chain_ready: false,
            counts: [MAX_COUNT; DIRS],
        }
    }
}

/// What the agent's view and neck actions look at this cycle.
pub(crate) struct Outlook {
    /// The agent's position after this cycle's command (`queuedNextSelfPos`).
    pub(crate) next_pos: DVec2,
    /// Its body direction after the command, degrees (`queuedNextSelfBody`).
    pub(crate) next_body: f64,
    /// The ball's next position (`queuedNextBallPos`).
    pub(crate) next_ball: DVec2,
    /// Where the ball is when the first player reaches it.
    pub(crate) reach_point: DVec2,
    /// Distance from the ball to the nearest teammate and to the keeper.
    pub(crate) mate_ball_dist: f64,
    pub(crate) keeper_ball_dist: f64,
    /// Distance from the agent to the ball now.
    pub(crate) ball_dist: f64,
    /// The agent's position plus velocity (`calcAngleForWidePitchEdge`).
    pub(crate) drift_pos: DVec2,
}

impl Sight {
    /// A sight whose every direction was last seen `count` cycles ago.
    #[cfg(test)]
    pub(crate) fn with_counts(count: u8) -> Self {
        Sight {
            counts: [count; DIRS],
            ..Sight::default()
        }
    }

    /// Cycles since direction `angle` (degrees) was in view (`dirCount`).
    fn count(&self, angle: f64) -> u8 {
        self.counts[dir_index(angle)]
    }

    /// Maximum and (integer) average count over the `width`-degree range
    /// centred on `angle` (`dirRangeCount`).
    pub(crate) fn range_count(&self, angle: f64, width: f64) -> (u8, u8) {
        let mut dir = if width > DIR_STEP {
            angle - width * 0.5
        } else {
            angle
        };
        let (mut max, mut sum, mut n, mut added) = (0u8, 0u32, 0u32, 0.0);
        while added < width {
            let c = self.count(dir);
            max = max.max(c);
            sum += u32::from(c);
            added += DIR_STEP;
            dir += DIR_STEP;
            n += 1;
        }
        (max, (sum / n) as u8)
    }

    /// Start of a cycle: every count ages by one (`WorldModel::update`) and
    /// `SeeState` moves on (`setNewCycle`).
    fn new_cycle(&mut self) {
        for c in &mut self.counts {
            *c = (*c + 1).min(MAX_COUNT);
        }
        self.cycles_till_see = self.cycles_till_see.saturating_sub(1);
        self.seen = false;
    }

    fn is_synch(&self) -> bool {
        self.timing != SeeTiming::NoSynch
    }

    /// One visual tick of the server: a see when the send count reaches the
    /// width's interval. `face` is the body plus neck, degrees; `moved`
    /// whether the agent moved more than 0.5 m last cycle.
    fn tick(&mut self, face: f64, moved: bool) {
        self.ticks += 1;
        if self.ticks < self.width.interval() {
            return;
        }
        self.ticks = 0;
        // SeeState::updateBySee, then WorldModel::updateAfterSee (once a cycle).
        if self.seen {
            self.timing = SeeTiming::NoSynch;
            return;
        }
        self.seen = true;
        if self.is_synch() {
            if self.cycles_till_see > 0 {
                self.cycles_till_see = 0;
                self.set_view_mode();
            }
            self.timing = self.timing.next(self.width);
        }
        self.clear_view_cone(face, moved);
    }

    /// The view cone's left edge, and the limits of the directions well
    /// inside it (a buffer of half a direction step, one degree more after a
    /// move): `(left, left_limit, right_limit)`.
    fn cone_limits(&self, face: f64, moved: bool) -> (f64, f64, f64) {
        let half = self.width.degrees() * 0.5;
        let buf = if moved {
            DIR_STEP * 0.5 + 1.0
        } else {
            DIR_STEP * 0.5
        };
        (
            deg_norm(face - half),
            deg_norm(face - half + buf),
            deg_norm(face + half - buf),
        )
    }

    /// `WorldModel::updateDirCount`: zero the count of every direction well
    /// inside the view cone.
    fn clear_view_cone(&mut self, face: f64, moved: bool) {
        let (left, left_limit, right_limit) = self.cone_limits(face, moved);
        // The directions tried are whole multiples of 5°, `5 * step` (-36 to
        // 36), exact in floating point; `deg_norm` wraps them from 180° to
        // -175°, and their bin is `step + 35`, 0 for -180°.
        let mut step = dir_index(left) as i32 - 36;
        let mut dir = DIR_STEP * f64::from(step);
        let next = |step: i32| if step == 36 { -35 } else { step + 1 };
        while is_left_of(dir, left_limit) {
            step = next(step);
            dir = DIR_STEP * f64::from(step);
        }
        while is_left_of(dir, right_limit) {
            self.counts[(step + 35).max(0) as usize] = 0;
            step = next(step);
            dir = DIR_STEP * f64::from(step);
        }
    }

    /// [`Sight::clear_view_cone`] as librcsc writes it: the reference the
    /// tests compare with.
    #[cfg(test)]
    fn clear_view_cone_by_angles(&mut self, face: f64, moved: bool) {
        let (left, left_limit, right_limit) = self.cone_limits(face, moved);
        let mut dir = deg_norm(-180.0 + DIR_STEP * dir_index(left) as f64);
        while is_left_of(dir, left_limit) {
            dir = deg_norm(dir + DIR_STEP);
        }
        while is_left_of(dir, right_limit) {
            self.counts[dir_index(dir)] = 0;
            dir = deg_norm(dir + DIR_STEP);
        }
    }

    /// `SeeState::setViewMode` after a see this cycle: when the next see is due.
    fn set_view_mode(&mut self) {
        if !self.seen {
            return;
        }
        use {SeeTiming::*, Width::*};
        self.cycles_till_see = match (self.timing, self.width) {
            (_, Wide) => 3,
            (At0, Normal) | (At50 | At22 | NoSynch, Narrow) => 1,
            (At50 | NoSynch, Normal) => 2,
            // "illegal" pairs leave the count as it is.
            (At0, Narrow) | (At22, Normal) => self.cycles_till_see,
        };
    }

    /// `PlayerAgent::doChangeView` under `SeeState`'s rules.
    fn change_view(&mut self, width: Width) {
        if self.is_synch() && !self.can_change_view_to(width) {
            return;
        }
        self.width = width;
    }

    /// `SeeState::canChangeViewTo`.
    fn can_change_view_to(&self, width: Width) -> bool {
        self.seen
            && match width {
                Width::Narrow => self.timing != SeeTiming::At0,
                Width::Normal => matches!(self.timing, SeeTiming::At0 | SeeTiming::At50),
                Width::Wide => true,
            }
    }

    /// HFO's `View_Tactical` for an attacker (`doDefault`).
    fn tactical_width(&self, o: &Outlook) -> Width {
        let ball_dist = o.next_pos.distance(o.reach_point);
        if ball_dist > 40.0 {
            return Width::Wide;
        }
        if ball_dist > 20.0 {
            return Width::Normal;
        }
        if ball_dist > 10.0
            && deg_norm(dir_deg(o.next_ball - o.next_pos) - o.next_body).abs() > 120.0
        {
            return Width::Wide;
        }
        if o.mate_ball_dist > 5.0
            && o.keeper_ball_dist > 5.0
            && ball_dist > 10.0
            && o.ball_dist > 10.0
        {
            return Width::Normal;
        }
        // View_Synch; unsynchronised in server synch mode: doTimerSynchView.
        if self.is_synch() && self.timing == SeeTiming::At0 {
            Width::Normal
        } else {
            Width::Narrow
        }
    }

    /// `Neck_ScanField` with the next view width: the face direction, degrees.
    fn scan_field(&self, o: &Outlook, face: f64) -> f64 {
        if self.width == Width::Wide
            && let Some(angle) = wide_pitch_edge(o.drift_pos)
        {
            return angle;
        }
        let angle = self.scan_angle(o, true);
        if deg_norm(angle - face).abs() < 5.0 {
            self.scan_angle(o, false)
        } else {
            angle
        }
    }

    /// `Neck_ScanField::calcAngleDefault`: the view cone reachable by a neck
    /// turn that holds the most aged directions (the window of counts skips
    /// one bin after its first position, as in librcsc).
    fn scan_angle(&self, o: &Outlook, consider_pitch: bool) -> f64 {
        let view = self.width.degrees();
        let left_start = o.next_body - MAX_NECK - view * 0.5;
        let scan_range = 2.0 * MAX_NECK + view;
        let shrunk = view - DIR_STEP * 1.5;
        let mut best = deg_norm(left_start + scan_range * 0.5);
        let size = (shrunk / DIR_STEP).round_ties_even() as usize;
        // The window's counts as a ring, with their running sum.
        let mut window = [0u8; DIRS];
        let mut dir = left_start;
        for c in &mut window[..size] {
            *c = self.count(dir);
            dir += DIR_STEP;
        }
        let mut sum: u32 = window[..size].iter().map(|&c| u32::from(c)).sum();
        let (mut best_sum, mut front, mut added) = (0, 0, shrunk);
        // The cone's centre as a unit vector, turned 5° a step.
        let mut facing = unit((dir - shrunk * 0.5).to_radians());
        let (step, half) = self.width.step_and_half();
        loop {
            let angle = dir - shrunk * 0.5;
            if sum > best_sum && (!consider_pitch || faces_pitch(o.next_pos, facing, half)) {
                best = deg_norm(angle);
                best_sum = sum;
            }
            facing = step.rotate(facing);
            added += DIR_STEP;
            dir += DIR_STEP;
            let next = self.count(dir);
            sum = sum - u32::from(window[front]) + u32::from(next);
            window[front] = next;
            front = if front + 1 == size { 0 } else { front + 1 };
            if added > scan_range {
                return best;
            }
        }
    }

    /// Advances the view by one cycle up to the agent's decision: counts
    /// age, and the sees due before the think message arrive. `face` is the
    /// body plus neck, degrees; `moved` whether the agent moved over 0.5 m
    /// last cycle.
    pub(crate) fn before_decision(&mut self, phase: u8, face: f64, moved: bool) {
        self.new_cycle();
        for _ in 0..TICKS_BEFORE_THINK[phase as usize] {
            self.tick(face, moved);
        }
        // PlayerAgent::action: a see missed while synchronised breaks the synch.
        if self.is_synch() && self.cycles_till_see == 0 && !self.seen {
            self.timing = SeeTiming::NoSynch;
        }
    }

    /// The view and neck actions after the agent's body command, then the
    /// sees due after the think message (still with this cycle's face).
    /// `body` is the body direction now, degrees; the new neck takes effect
    /// with the server's step.
    pub(crate) fn act(&mut self, phase: u8, neck: Neck, o: &Outlook, body: f64, moved: bool) {
        let face = deg_norm(body + self.neck);
        let width = self.tactical_width(o);
        self.change_view(width);
        self.set_view_mode();
        let target = match neck {
            Neck::Keep => None,
            Neck::Scan => Some(self.scan_field(o, face)),
            Neck::TurnToBall => Some(dir_deg(o.next_ball - o.next_pos)),
        };
        for _ in 0..TICKS_AFTER_THINK[phase as usize] {
            self.tick(face, moved);
        }
        if let Some(target) = target {
            self.turn_neck(deg_norm(target - o.next_body - self.neck));
        }
    }

    /// librcsc's `setTurnNeck` (a whole-degree moment that keeps the neck,
    /// wrapped as an angle, inside its range) and the server's turn_neck.
    fn turn_neck(&mut self, moment: f64) {
        let mut moment = moment.clamp(-180.0, 180.0).round_ties_even();
        let next = deg_norm(self.neck + moment);
        if next > MAX_NECK {
            moment = (MAX_NECK - self.neck).round_ties_even();
        } else if next < -MAX_NECK {
            moment = (-MAX_NECK - self.neck).round_ties_even();
        }
        self.neck = (self.neck + moment).clamp(-MAX_NECK, MAX_NECK);
    }
}

/// Whether an agent moving at `vel` (after the server's decay) moved more
/// than 0.5 m last cycle (`lastMove`, for `updateDirCount`'s margin).
pub(crate) fn moved(vel: DVec2) -> bool {
    vel.length() / PLAYER_DECAY > 0.5
}

/// `calcAngleForWidePitchEdge`: near a goal line a wide view looks back to
/// (26.25, 0). (Its touchline rule needs |y| > 42.5: never on this pitch.)
fn wide_pitch_edge(drift_pos: DVec2) -> Option<f64> {
    (drift_pos.x.abs() > 52.5 - 15.0).then(|| dir_deg(DVec2::new(26.25, 0.0) - drift_pos))
}

/// `calcAngleDefault`'s pitch test: facing a point 20 m away on the pitch or
/// in the goal area, with both cone edges inside the pitch grown by 3 m.
/// `facing` is the unit vector of the cone's centre, `half` that of half
/// the view width.
fn faces_pitch(from: DVec2, facing: DVec2, half: DVec2) -> bool {
    let inside = |p: DVec2, grow: f64| p.x.abs() <= 52.5 + grow && p.y.abs() <= 34.0 + grow;
    let goal_area = |p: DVec2| (49.5..=59.5).contains(&p.x) && p.y.abs() <= 15.0;
    let edge = |u: DVec2| {
        let p = from + 20.0 * u;
        inside(p, 3.0) || goal_area(p)
    };
    let centre = from + 20.0 * facing;
    (inside(centre, 0.0) || goal_area(centre))
        && edge(DVec2::new(half.x, -half.y).rotate(facing))
        && edge(half.rotate(facing))
}

/// librcsc's direction bin of `angle` (degrees).
fn dir_index(angle: f64) -> usize {
    // In [-0.1, 71.9]: truncating through i32 is the saturating `as usize`
    // (0 below zero), and cheaper.
    let bin = (deg_norm(angle) - 0.5 + 180.0) / DIR_STEP;
    (bin as i32 as usize).min(DIRS - 1)
}

/// `AngleDeg::normalize`: into [-180, 180].
fn deg_norm(a: f64) -> f64 {
    let a = if a.abs() > 360.0 { a % 360.0 } else { a };
    if a < -180.0 {
        a + 360.0
    } else if a > 180.0 {
        a - 360.0
    } else {
        a
    }
}

/// `AngleDeg::isLeftOf`: `a` is less than 180° below `b`, wrapping.
fn is_left_of(a: f64, b: f64) -> bool {
    let diff = b - a;
    (0.0 < diff && diff < 180.0) || diff < -180.0
}

/// Direction of `v`, degrees.
fn dir_deg(v: DVec2) -> f64 {
    crate::sim::geom::direction(v).to_degrees()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outlook(next_pos: DVec2, ball: DVec2) -> Outlook {
        Outlook {
            next_pos,
            next_body: 0.0,
            next_ball: ball,
            reach_point: ball,
            mate_ball_dist: 20.0,
            keeper_ball_dist: 20.0,
            ball_dist: next_pos.distance(ball),
            drift_pos: next_pos,
        }
    }

    #[test]
    fn the_cone_steps_are_the_bins_of_their_directions() {
        for step in -36..=36 {
            let dir = DIR_STEP * f64::from(step);
            assert_eq!(dir_index(dir), (step + 35).max(0) as usize, "{dir}");
            assert_eq!(
                deg_norm(-180.0 + DIR_STEP * f64::from(step + 36)),
                dir.max(-180.0)
            );
        }
    }

    proptest::proptest! {
        #[test]
        fn a_cone_clears_the_bins_librcsc_clears(
            face in -1000.0..1000.0f64,
            width in 0..3usize,
            moved: bool,
            fill in 1..11u8,
        ) {
            let width = [Width::Narrow, Width::Normal, Width::Wide][width];
            let mut ours = Sight { width, counts: [fill; DIRS], ..Sight::default() };
            let mut reference = ours.clone();
            ours.clear_view_cone(face, moved);
            reference.clear_view_cone_by_angles(face, moved);
            proptest::prop_assert_eq!(ours.counts, reference.counts);
            for edge in [-180.0, 180.0, -177.5, 177.5, 0.0, 2.5, -2.5] {
                for delta in [-1e-9, 0.0, 1e-9] {
                    let face = edge + delta + [22.5, 45.0, 90.0][width as usize];
                    let mut ours = Sight { width, counts: [fill; DIRS], ..Sight::default() };
                    let mut reference = ours.clone();
                    ours.clear_view_cone(face, moved);
                    reference.clear_view_cone_by_angles(face, moved);
                    proptest::prop_assert_eq!(ours.counts, reference.counts);
                }
            }
        }

        #[test]
        fn dir_index_is_the_saturating_bin(angle in -1000.0..1000.0f64) {
            let bin = (deg_norm(angle) - 0.5 + 180.0) / DIR_STEP;
            proptest::prop_assert_eq!(dir_index(angle), (bin as usize).min(DIRS - 1));
        }
    }

    #[test]
    fn a_see_clears_the_directions_well_inside_the_cone() {
        let mut s = Sight {
            width: Width::Normal,
            ..Sight::default()
        };
        s.clear_view_cone(0.0, false);
        // 90° cone less 2.5° each side: bins from -42.5° to 42.5°.
        assert_eq!(s.count(0.0), 0);
        assert_eq!(s.count(-40.0), 0);
        assert_eq!(s.count(40.0), 0);
        assert_eq!(s.count(-47.0), MAX_COUNT);
        assert_eq!(s.count(47.0), MAX_COUNT);
        assert_eq!(s.count(180.0), MAX_COUNT);
        assert_eq!(s.range_count(0.0, 20.0), (0, 0));
        assert_eq!(s.range_count(45.0, 20.0), (MAX_COUNT, 5));
    }

    #[test]
    fn an_agent_that_moved_keeps_a_wider_margin_inside_the_cone() {
        let cleared = |moved| {
            let mut s = Sight {
                width: Width::Normal,
                ..Sight::default()
            };
            s.clear_view_cone(2.0, moved);
            s.count(-42.0)
        };
        assert_eq!(cleared(false), 0);
        assert_eq!(cleared(true), MAX_COUNT);
    }

    #[test]
    fn the_neck_turns_the_short_way_and_stops_at_its_limit() {
        let mut s = Sight::default();
        s.turn_neck(120.4);
        assert_eq!(s.neck, 90.0);
        // 90 + 179 wraps to -91: librcsc stops the moment at -90.
        s.turn_neck(179.0);
        assert_eq!(s.neck, -90.0);
        s.turn_neck(30.6);
        assert_eq!(s.neck, -59.0);
    }

    #[test]
    fn a_synchronised_agent_near_the_ball_sees_every_cycle_narrow_narrow_normal() {
        let mut s = Sight::default();
        let o = outlook(DVec2::new(10.0, 0.0), DVec2::new(10.5, 0.0));
        let mut widths = Vec::new();
        for cycle in 0..300u32 {
            let phase = (cycle % 3) as u8;
            s.before_decision(phase, 0.0, false);
            assert!(s.seen, "cycle {cycle}: no see");
            s.act(phase, Neck::Scan, &o, 0.0, false);
            widths.push(s.width);
        }
        assert!(s.is_synch());
        assert_eq!(
            &widths[297..],
            &[Width::Normal, Width::Narrow, Width::Narrow]
        );
    }

    #[test]
    fn the_neck_scan_sweeps_towards_the_oldest_directions() {
        let mut s = Sight::default();
        let o = outlook(DVec2::new(10.0, 0.0), DVec2::new(10.5, 0.0));
        s.counts = [0; DIRS];
        for a in [60.0, 65.0, 70.0, 75.0, 80.0, 85.0] {
            s.counts[dir_index(a)] = 10;
        }
        let face = s.scan_field(&o, 0.0);
        assert!((55.0..=90.0).contains(&face), "{face}");
    }

    #[test]
    fn an_agent_kept_far_from_the_ball_stays_synchronised_on_a_wide_view() {
        let mut s = Sight::default();
        let o = outlook(DVec2::new(0.0, 0.0), DVec2::new(45.0, 0.0));
        let mut sees = 0;
        for cycle in 0..300u32 {
            let phase = (cycle % 3) as u8;
            s.before_decision(phase, 0.0, false);
            sees += u32::from(s.seen);
            s.act(phase, Neck::Scan, &o, 0.0, false);
        }
        assert_eq!(s.width, Width::Wide);
        assert!(s.is_synch());
        assert!((99..=102).contains(&sees), "{sees}");
    }
}
