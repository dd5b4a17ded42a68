//! Pictures on the half field as SVG documents: a recorded episode's paths
//! ([`record_episode`], [`Trace::to_svg`]), or an [`Env`] as it stands
//! ([`frame_svg`]). Writing them to a file, or as PNG, is the binary's job.
//!
//! The picture keeps the server's orientation (as rcssmonitor draws it): the
//! attacked goal is on the right, +y points down.

use crate::sim::config::MAX_OFFENSE;
use crate::sim::config::{EnvConfig, EnvConfigError};
use crate::sim::env::Env;
use crate::sim::formation::offense_unums;
use crate::sim::params::*;
use crate::sim::physics::Command;
use crate::sim::referee::Outcome;
use crate::tools::policy::{BaselinePolicy, play_episode, policy_rng};
use glam::DVec2;
use std::fmt::Write as _;

/// A player: who kicked, or whom a marker shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kicker {
    /// Offense agent `i` (in agent order).
    Offense(usize),
    /// The goalkeeper.
    Keeper,
}

/// One kick: the ball was kicked from its position in state `state`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Kick {
    /// Index (into the position lists) of the state the kick acted on.
    pub state: usize,
    /// The kicker.
    pub by: Kicker,
}

/// Everything drawn of one episode: positions of every state from the reset on.
#[derive(Clone, Debug, PartialEq)]
pub struct Trace {
    /// Policy that played it.
    pub policy: BaselinePolicy,
    /// Seed of the run.
    pub seed: u64,
    /// Episode number within the run (1-based).
    pub episode: u64,
    /// Ball position in every state.
    pub ball: Vec<DVec2>,
    /// Positions of each offense agent (outer index: agent).
    pub offense: Vec<Vec<DVec2>>,
    /// Goalkeeper position in every state.
    pub keeper: Vec<DVec2>,
    /// The kicks, in time order.
    pub kicks: Vec<Kick>,
    /// How the episode ended.
    pub outcome: Outcome,
    /// Agent decisions taken (the authors' "frames").
    pub frames: u32,
}

/// Why a picture could not be made.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// Bad simulator settings.
    #[error(transparent)]
    Config(#[from] EnvConfigError),
    /// Episodes are numbered from 1.
    #[error("episode must be at least 1")]
    EpisodeZero,
}

impl Trace {
    /// An empty trace of an `offense`-agent episode.
    fn new(policy: BaselinePolicy, seed: u64, episode: u64, offense: usize) -> Self {
        Trace {
            policy,
            seed,
            episode,
            ball: Vec::new(),
            offense: vec![Vec::new(); offense],
            keeper: Vec::new(),
            kicks: Vec::new(),
            outcome: Outcome::InGame,
            frames: 0,
        }
    }

    /// Records the state of `env` and the kicks that led to it.
    fn observe(&mut self, env: &Env) {
        let world = env.world();
        if let Some(state) = self.ball.len().checked_sub(1) {
            let n = world.offense.len();
            for (i, command) in env.last_commands().iter().enumerate() {
                if matches!(command, Command::Kick { .. }) {
                    let by = if i < n {
                        Kicker::Offense(i)
                    } else {
                        Kicker::Keeper
                    };
                    self.kicks.push(Kick { state, by });
                }
            }
        }
        self.ball.push(world.ball.pos);
        for (path, p) in self.offense.iter_mut().zip(&world.offense) {
            path.push(p.pos);
        }
        self.keeper.push(world.keeper.pos);
    }

    /// "goal after 104 frames" and the like.
    pub fn summary(&self) -> String {
        let what = match self.outcome {
            Outcome::InGame => "unfinished",
            ended => outcome_words(ended),
        };
        let s = if self.frames == 1 { "" } else { "s" };
        format!("{what} after {} frame{s}", self.frames)
    }

    /// The picture as an SVG document.
    pub fn to_svg(&self) -> String {
        let mut out = String::new();
        self.write_svg(&mut out)
            .expect("writing to a String cannot fail");
        out
    }

    fn write_svg(&self, s: &mut String) -> std::fmt::Result {
        let w = write_svg_start(s)?;
        self.write_header(s, w)?;
        write_field(s)?;
        // Paths: keeper first, then the offense, the ball on top.
        write_path(s, &self.keeper, KEEPER_COLOUR, 2.4, 1.0)?;
        for (i, path) in self.offense.iter().enumerate() {
            write_path(s, path, colour(Kicker::Offense(i)), 2.4, 1.0)?;
        }
        write_path(s, &self.ball, "#111", 4.6, 0.45)?;
        write_path(s, &self.ball, BALL_COLOUR, 2.0, 1.0)?;
        for path in self.offense.iter().chain([&self.keeper, &self.ball]) {
            write_ticks(s, path)?;
        }
        for kick in &self.kicks {
            if let Some(&p) = self.ball.get(kick.state) {
                write_star(s, p, colour(kick.by))?;
            }
        }
        // Start markers under the end markers.
        let players = self
            .offense
            .iter()
            .enumerate()
            .map(|(i, p)| (p, Kicker::Offense(i)));
        let players: Vec<_> = players
            .chain([(&self.keeper, Kicker::Keeper)])
            .map(|(path, who)| (path, colour(who), label(self.offense.len(), who)))
            .collect();
        for (path, colour, label) in &players {
            if let Some(&p) = path.first() {
                write_start(s, p, colour, label)?;
            }
        }
        if let Some(&p) = self.ball.first() {
            let (x, y) = px(p);
            writeln!(
                s,
                r#"<circle cx="{x:.1}" cy="{y:.1}" r="8.5" fill="none" stroke="{BALL_COLOUR}" stroke-width="2"/>"#
            )?;
        }
        for (path, colour, label) in &players {
            if let Some(&p) = path.last() {
                write_end(s, p, colour, label)?;
            }
        }
        if let Some(&p) = self.ball.last() {
            let (x, y) = px(p);
            writeln!(
                s,
                r##"<circle cx="{x:.1}" cy="{y:.1}" r="5" fill="{BALL_COLOUR}" stroke="#111" stroke-width="1.5"/>"##
            )?;
        }
        writeln!(s, "</svg>")
    }

    /// The title band: outcome, run, legend.
    fn write_header(&self, s: &mut String, w: f64) -> std::fmt::Result {
        let n = self.offense.len();
        let detail = format!(
            "policy {} · {n} offense vs keeper · seed {} · episode {} · {} kick{}",
            self.policy,
            self.seed,
            self.episode,
            self.kicks.len(),
            if self.kicks.len() == 1 { "" } else { "s" }
        );
        write_title(s, w, &self.summary(), self.outcome, &detail)?;
        // Legend, one row.
        let y = 86.0;
        let mut x = 18.0;
        let mut items: Vec<_> = (0..n)
            .map(|i| {
                (
                    colour(Kicker::Offense(i)),
                    format!("#{}", label(n, Kicker::Offense(i))),
                )
            })
            .collect();
        items.push((KEEPER_COLOUR, "keeper".to_owned()));
        for (colour, label) in &items {
            writeln!(
                s,
                r#"<line x1="{x}" y1="{y}" x2="{}" y2="{y}" stroke="{colour}" stroke-width="3" stroke-linecap="round"/>"#,
                x + 18.0
            )?;
            x = legend_text(s, x + 24.0, y, label)?;
        }
        writeln!(
            s,
            r##"<line x1="{x}" y1="{y}" x2="{}" y2="{y}" stroke="#111" stroke-opacity="0.6" stroke-width="4.6" stroke-linecap="round"/>"##,
            x + 18.0
        )?;
        writeln!(
            s,
            r#"<line x1="{x}" y1="{y}" x2="{}" y2="{y}" stroke="{BALL_COLOUR}" stroke-width="2" stroke-linecap="round"/>"#,
            x + 18.0
        )?;
        x = legend_text(s, x + 24.0, y, "ball")?;
        x += 14.0;
        write_start_at(s, x + 7.0, y, "#e8efe8", "")?;
        x = legend_text(s, x + 20.0, y, "start")?;
        write_end_at(s, x + 7.0, y, "#e8efe8", "")?;
        x = legend_text(s, x + 20.0, y, "end")?;
        write_star_at(s, x + 7.0, y, "#e8efe8")?;
        x = legend_text(s, x + 20.0, y, "kick")?;
        write_tick_at(s, x + 5.0, y)?;
        legend_text(s, x + 14.0, y, "every 10 frames")?;
        Ok(())
    }
}

/// Plays the `episode`-th episode (1-based) of the run `env-server rollout
/// --seed seed` would play with `config` and `policy`, and records it.
pub fn record_episode(
    config: EnvConfig,
    policy: BaselinePolicy,
    seed: u64,
    episode: u64,
) -> Result<Trace, RenderError> {
    if episode == 0 {
        return Err(RenderError::EpisodeZero);
    }
    let offense = config.offense;
    let mut env = Env::new(config, seed)?;
    let mut rng = policy_rng(seed);
    for _ in 1..episode {
        play_episode(&mut env, policy, &mut rng, |_, _| {});
    }
    let mut trace = Trace::new(policy, seed, episode, offense);
    let (outcome, frames) = play_episode(&mut env, policy, &mut rng, |env, _| trace.observe(env));
    trace.outcome = outcome;
    trace.frames = frames;
    Ok(trace)
}

/// A picture of `env` as it stands: every player (labelled, with a tick
/// along its body direction) and the ball on the half field, the frame and
/// the outcome so far in the title band.
pub fn frame_svg(env: &Env) -> String {
    let mut out = String::new();
    write_frame(&mut out, env).expect("writing to a String cannot fail");
    out
}

fn write_frame(s: &mut String, env: &Env) -> std::fmt::Result {
    let w = write_svg_start(s)?;
    let world = env.world();
    let n = world.offense.len();
    let title = match env.outcome() {
        Outcome::InGame => format!("in play at frame {}", env.frame()),
        ended => format!("{} at frame {}", outcome_words(ended), env.frame()),
    };
    write_title(
        s,
        w,
        &title,
        env.outcome(),
        &format!("{n} offense vs keeper"),
    )?;
    write_field(s)?;
    let players = world.offense.iter().enumerate();
    let players = players.map(|(i, p)| (p, Kicker::Offense(i)));
    for (p, who) in players.chain([(&world.keeper, Kicker::Keeper)]) {
        let (x, y) = px(p.pos);
        let (tx, ty) = px(p.pos + (MARKER + 5.0) / SCALE * DVec2::from_angle(p.body));
        writeln!(
            s,
            r#"<line x1="{x:.1}" y1="{y:.1}" x2="{tx:.1}" y2="{ty:.1}" stroke="{}" stroke-width="3" stroke-linecap="round"/>"#,
            colour(who)
        )?;
        write_end(s, p.pos, colour(who), &label(n, who))?;
    }
    let (x, y) = px(world.ball.pos);
    writeln!(
        s,
        r##"<circle cx="{x:.1}" cy="{y:.1}" r="5" fill="{BALL_COLOUR}" stroke="#111" stroke-width="1.5"/>"##
    )?;
    writeln!(s, "</svg>")
}

// ---------------------------------------------------------------------------
// Drawing.

/// Pixels per metre.
const SCALE: f64 = 14.0;
/// Height of the title band above the field.
const HEADER: f64 = 104.0;
/// Field region shown (metres): the HFO area with a margin and the goal.
const VIEW_X: (f64, f64) = (-3.0, PITCH_HALF_LENGTH + GOAL_DEPTH + 2.56);
const VIEW_Y: (f64, f64) = (-PITCH_HALF_WIDTH - 3.0, PITCH_HALF_WIDTH + 3.0);

const FONT: &str = "DejaVu Sans, Liberation Sans, Arial, Helvetica, sans-serif";
const HEADER_COLOUR: &str = "#17301a";
const GRASS: [&str; 2] = ["#3d8b3d", "#37823a"];
const LINE_COLOUR: &str = "#f4f8f4";
const BALL_COLOUR: &str = "#ffffff";
const KEEPER_COLOUR: &str = "#ff4b4b";
const OFFENSE_COLOURS: [&str; MAX_OFFENSE] = ["#ffd23f", "#45c4f5", "#c39bff", "#ff9f1c"];
/// Radius of the start and end markers (pixels).
const MARKER: f64 = 9.0;

fn px_x(x: f64) -> f64 {
    (x - VIEW_X.0) * SCALE
}

fn px_y(y: f64) -> f64 {
    HEADER + (y - VIEW_Y.0) * SCALE
}

fn px(p: DVec2) -> (f64, f64) {
    (px_x(p.x), px_y(p.y))
}

/// The opening `<svg>` tag; returns the picture's width.
fn write_svg_start(s: &mut String) -> Result<f64, std::fmt::Error> {
    let (w, h) = (px_x(VIEW_X.1).round(), px_y(VIEW_Y.1).round());
    writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="{FONT}">"#
    )?;
    Ok(w)
}

/// The title band of a `w`-pixel wide picture: `title` (capitalised) in the
/// colour of `outcome`, and a line of `detail` below it.
fn write_title(
    s: &mut String,
    w: f64,
    title: &str,
    outcome: Outcome,
    detail: &str,
) -> std::fmt::Result {
    writeln!(
        s,
        r#"<rect width="{w}" height="{HEADER}" fill="{HEADER_COLOUR}"/>"#
    )?;
    let colour = match outcome {
        Outcome::Goal => "#8ef58e",
        Outcome::Captured => "#ff8080",
        Outcome::OutOfBounds => "#ffc266",
        Outcome::OutOfTime | Outcome::InGame => "#d8d8d8",
    };
    let mut title = title.to_owned();
    title[..1].make_ascii_uppercase();
    writeln!(
        s,
        r#"<text x="18" y="34" font-size="23" font-weight="bold" fill="{colour}">{title}</text>"#
    )?;
    writeln!(
        s,
        r##"<text x="18" y="58" font-size="14" fill="#e8efe8">{detail}</text>"##
    )
}

/// How an episode ended, in words.
fn outcome_words(outcome: Outcome) -> &'static str {
    match outcome {
        Outcome::Goal => "goal",
        Outcome::Captured => "captured by the keeper",
        Outcome::OutOfBounds => "ball out of bounds",
        Outcome::OutOfTime => "out of time",
        Outcome::InGame => "in play",
    }
}

/// The colour of a player.
fn colour(who: Kicker) -> &'static str {
    match who {
        Kicker::Offense(i) => OFFENSE_COLOURS[i % OFFENSE_COLOURS.len()],
        Kicker::Keeper => KEEPER_COLOUR,
    }
}

/// The label of a player among `offense` attackers: its uniform number,
/// "GK" for the keeper.
fn label(offense: usize, who: Kicker) -> String {
    match who {
        Kicker::Offense(i) => {
            let unums = offense_unums(offense.min(MAX_OFFENSE));
            unums
                .get(i)
                .map_or_else(|| (i + 1).to_string(), u8::to_string)
        }
        Kicker::Keeper => "GK".to_owned(),
    }
}

/// Grass, the darker surround outside the HFO area, the lines and the goal.
fn write_field(s: &mut String) -> std::fmt::Result {
    write_grass(s)?;
    write_goal(s)?;
    write_pitch_lines(s)?;
    write_coordinates(s)?;
    for post in GOAL_POSTS {
        let (x, y) = px(post);
        writeln!(
            s,
            r##"<circle cx="{x:.1}" cy="{y:.1}" r="3" fill="white" stroke="#333" stroke-width="0.8"/>"##
        )?;
    }
    Ok(())
}

/// The grass with its mowing stripes, darker outside the HFO area.
fn write_grass(s: &mut String) -> std::fmt::Result {
    let (top, bottom) = (px_y(VIEW_Y.0), px_y(VIEW_Y.1));
    let (left, right) = (px_x(VIEW_X.0), px_x(VIEW_X.1));
    writeln!(
        s,
        r#"<rect x="{left}" y="{top}" width="{}" height="{}" fill="{}"/>"#,
        right - left,
        bottom - top,
        GRASS[0]
    )?;
    // Mowing stripes every 5.25 m from the half-way line.
    let stripe = PITCH_HALF_LENGTH / 10.0;
    let mut k = (VIEW_X.0 / stripe).floor() as i32;
    while f64::from(k) * stripe < VIEW_X.1 {
        if k.rem_euclid(2) == 1 {
            let x0 = px_x(f64::from(k) * stripe).max(left);
            let x1 = px_x(f64::from(k + 1) * stripe).min(right);
            writeln!(
                s,
                r#"<rect x="{x0:.1}" y="{top}" width="{:.1}" height="{}" fill="{}"/>"#,
                x1 - x0,
                bottom - top,
                GRASS[1]
            )?;
        }
        k += 1;
    }
    // Darken what lies outside the HFO area.
    let (ax0, ay0) = px(DVec2::new(0.0, -PITCH_HALF_WIDTH));
    let (ax1, ay1) = px(DVec2::new(PITCH_HALF_LENGTH, PITCH_HALF_WIDTH));
    writeln!(
        s,
        r#"<path d="M{left},{top}H{right}V{bottom}H{left}Z M{ax0:.1},{ay0:.1}V{ay1:.1}H{ax1:.1}V{ay0:.1}Z" fill="black" fill-opacity="0.16" fill-rule="evenodd"/>"#
    )
}

/// The goal: its net behind the line and its outline.
fn write_goal(s: &mut String) -> std::fmt::Result {
    let (gx0, gy0) = px(DVec2::new(PITCH_HALF_LENGTH, -GOAL_HALF_WIDTH));
    let (gx1, gy1) = px(DVec2::new(PITCH_HALF_LENGTH + GOAL_DEPTH, GOAL_HALF_WIDTH));
    writeln!(
        s,
        r#"<rect x="{gx0:.1}" y="{gy0:.1}" width="{:.1}" height="{:.1}" fill="white" fill-opacity="0.18"/>"#,
        gx1 - gx0,
        gy1 - gy0
    )?;
    writeln!(
        s,
        r#"<g stroke="white" stroke-opacity="0.45" stroke-width="0.8">"#
    )?;
    let mesh = 0.5 * SCALE;
    let mut x = gx0 + mesh;
    while x < gx1 - 1.0 {
        writeln!(
            s,
            r#"<line x1="{x:.1}" y1="{gy0:.1}" x2="{x:.1}" y2="{gy1:.1}"/>"#
        )?;
        x += mesh;
    }
    let mut y = gy0 + mesh;
    while y < gy1 - 1.0 {
        writeln!(
            s,
            r#"<line x1="{gx0:.1}" y1="{y:.1}" x2="{gx1:.1}" y2="{y:.1}"/>"#
        )?;
        y += mesh;
    }
    writeln!(s, "</g>")?;
    writeln!(
        s,
        r#"<path d="M{gx0:.1},{gy0:.1}H{gx1:.1}V{gy1:.1}H{gx0:.1}" fill="none" stroke="{LINE_COLOUR}" stroke-width="2.5"/>"#
    )
}

/// The HFO area's lines: its boundary, the penalty and goal areas, the
/// centre circle's attacking half, the penalty arc and the two spots.
fn write_pitch_lines(s: &mut String) -> std::fmt::Result {
    writeln!(
        s,
        r#"<g fill="none" stroke="{LINE_COLOUR}" stroke-width="2" stroke-opacity="0.92">"#
    )?;
    let rect = |s: &mut String, x0: f64, half: f64| {
        let (a, b) = px(DVec2::new(x0, -half));
        let (c, d) = px(DVec2::new(PITCH_HALF_LENGTH, half));
        writeln!(
            s,
            r#"<rect x="{a:.1}" y="{b:.1}" width="{:.1}" height="{:.1}"/>"#,
            c - a,
            d - b
        )
    };
    rect(s, 0.0, PITCH_HALF_WIDTH)?;
    rect(s, PENALTY_AREA_X, PENALTY_AREA_HALF_WIDTH)?;
    rect(
        s,
        PITCH_HALF_LENGTH - GOAL_AREA_LENGTH,
        GOAL_AREA_HALF_WIDTH,
    )?;
    // Centre circle (its attacking half) and the penalty arc outside the box.
    let r = CIRCLE_RADIUS * SCALE;
    let (cx, cy) = px(DVec2::ZERO);
    writeln!(
        s,
        r#"<path d="M{cx:.1},{:.1}A{r:.1},{r:.1} 0 0 1 {cx:.1},{:.1}"/>"#,
        cy - r,
        cy + r
    )?;
    let spot = PITCH_HALF_LENGTH - PENALTY_SPOT_DISTANCE;
    let half_chord = (CIRCLE_RADIUS.powi(2) - (spot - PENALTY_AREA_X).powi(2)).sqrt();
    let (ax, ay0) = px(DVec2::new(PENALTY_AREA_X, -half_chord));
    let ay1 = px_y(half_chord);
    writeln!(
        s,
        r#"<path d="M{ax:.1},{ay0:.1}A{r:.1},{r:.1} 0 0 0 {ax:.1},{ay1:.1}"/>"#
    )?;
    writeln!(s, "</g>")?;
    let (sx, sy) = px(DVec2::new(spot, 0.0));
    writeln!(
        s,
        r#"<circle cx="{cx:.1}" cy="{cy:.1}" r="2.5" fill="{LINE_COLOUR}"/>"#
    )?;
    writeln!(
        s,
        r#"<circle cx="{sx:.1}" cy="{sy:.1}" r="2.5" fill="{LINE_COLOUR}"/>"#
    )
}

/// Coordinates in the margin: x below the field, y left of it.
fn write_coordinates(s: &mut String) -> std::fmt::Result {
    writeln!(
        s,
        r#"<g font-size="11" fill="white" fill-opacity="0.65" text-anchor="middle">"#
    )?;
    let below = px_y(PITCH_HALF_WIDTH) + 18.0;
    for x in [
        0.0,
        10.0,
        20.0,
        30.0,
        PENALTY_AREA_X,
        40.0,
        PITCH_HALF_LENGTH,
    ] {
        writeln!(s, r#"<text x="{:.1}" y="{below:.1}">{x}</text>"#, px_x(x))?;
    }
    let left = px_x(0.0) - 20.0;
    for y in [
        -PITCH_HALF_WIDTH,
        -20.0,
        -10.0,
        0.0,
        10.0,
        20.0,
        PITCH_HALF_WIDTH,
    ] {
        writeln!(
            s,
            r#"<text x="{left:.1}" y="{:.1}">{y}</text>"#,
            px_y(y) + 4.0
        )?;
    }
    writeln!(s, "</g>")
}

/// Radius of the centre circle and the penalty arc.
const CIRCLE_RADIUS: f64 = 9.15;
/// Distance of the penalty spot from the goal line.
const PENALTY_SPOT_DISTANCE: f64 = 11.0;

/// A polyline through `points`.
fn write_path(
    s: &mut String,
    points: &[DVec2],
    colour: &str,
    width: f64,
    opacity: f64,
) -> std::fmt::Result {
    if points.len() < 2 {
        return Ok(());
    }
    write!(
        s,
        r#"<polyline class="path" fill="none" stroke="{colour}" stroke-width="{width}" stroke-opacity="{opacity}" stroke-linejoin="round" stroke-linecap="round" points=""#
    )?;
    for (i, &p) in points.iter().enumerate() {
        let (x, y) = px(p);
        write!(s, "{}{x:.1},{y:.1}", if i == 0 { "" } else { " " })?;
    }
    writeln!(s, r#""/>"#)
}

/// A small dot every 10 frames along `points` (the first at frame 10).
fn write_ticks(s: &mut String, points: &[DVec2]) -> std::fmt::Result {
    for &p in points.iter().skip(10).step_by(10) {
        let (x, y) = px(p);
        write_tick_at(s, x, y)?;
    }
    Ok(())
}

fn write_tick_at(s: &mut String, x: f64, y: f64) -> std::fmt::Result {
    writeln!(
        s,
        r##"<circle cx="{x:.1}" cy="{y:.1}" r="2.2" fill="#f4f8f4" stroke="#111" stroke-width="0.8"/>"##
    )
}

/// A hollow ring at a player's start, its label inside.
fn write_start(s: &mut String, p: DVec2, colour: &str, label: &str) -> std::fmt::Result {
    let (x, y) = px(p);
    write_start_at(s, x, y, colour, label)
}

fn write_start_at(s: &mut String, x: f64, y: f64, colour: &str, label: &str) -> std::fmt::Result {
    let r = if label.is_empty() {
        MARKER - 2.0
    } else {
        MARKER
    };
    writeln!(
        s,
        r#"<circle class="start" cx="{x:.1}" cy="{y:.1}" r="{r}" fill="black" fill-opacity="0.3" stroke="{colour}" stroke-width="2.5"/>"#
    )?;
    write_label(s, x, y, label, "#ffffff")
}

/// A filled disc at a player's end, its label inside.
fn write_end(s: &mut String, p: DVec2, colour: &str, label: &str) -> std::fmt::Result {
    let (x, y) = px(p);
    write_end_at(s, x, y, colour, label)
}

fn write_end_at(s: &mut String, x: f64, y: f64, colour: &str, label: &str) -> std::fmt::Result {
    let r = if label.is_empty() {
        MARKER - 2.0
    } else {
        MARKER
    };
    writeln!(
        s,
        r##"<circle class="end" cx="{x:.1}" cy="{y:.1}" r="{r}" fill="{colour}" stroke="#111" stroke-width="1.5"/>"##
    )?;
    write_label(s, x, y, label, "#111")
}

fn write_label(s: &mut String, x: f64, y: f64, label: &str, colour: &str) -> std::fmt::Result {
    if label.is_empty() {
        return Ok(());
    }
    let size = if label.len() > 1 { 9.5 } else { 11.0 };
    writeln!(
        s,
        r#"<text x="{x:.1}" y="{:.1}" font-size="{size}" font-weight="bold" text-anchor="middle" fill="{colour}">{label}</text>"#,
        y + 0.36 * size
    )
}

/// A five-pointed star where the ball was kicked.
fn write_star(s: &mut String, p: DVec2, colour: &str) -> std::fmt::Result {
    let (x, y) = px(p);
    write_star_at(s, x, y, colour)
}

fn write_star_at(s: &mut String, x: f64, y: f64, colour: &str) -> std::fmt::Result {
    write!(
        s,
        r##"<path class="kick" fill="{colour}" stroke="#111" stroke-width="1" stroke-linejoin="round" d=""##
    )?;
    for k in 0..10 {
        let r = if k % 2 == 0 { 6.5 } else { 2.8 };
        let a = -std::f64::consts::FRAC_PI_2 + f64::from(k) * std::f64::consts::PI / 5.0;
        write!(
            s,
            "{}{:.1},{:.1}",
            if k == 0 { "M" } else { "L" },
            x + r * a.cos(),
            y + r * a.sin()
        )?;
    }
    writeln!(s, r#"Z"/>"#)
}

/// Legend text at `x`; returns where the next item starts.
fn legend_text(s: &mut String, x: f64, y: f64, text: &str) -> Result<f64, std::fmt::Error> {
    writeln!(
        s,
        r##"<text x="{x:.1}" y="{:.1}" font-size="13" fill="#e8efe8">{text}</text>"##,
        y + 4.5
    )?;
    // DejaVu Sans at 13 px averages about 7.6 px per character.
    Ok(x + 7.6 * text.chars().count() as f64 + 16.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proto::Action;

    fn trace(seed: u64, episode: u64) -> Trace {
        record_episode(EnvConfig::default(), BaselinePolicy::Random, seed, episode).unwrap()
    }

    #[test]
    fn records_every_state_and_draws_every_path() {
        let t = trace(1, 2);
        assert_eq!(t.ball.len(), t.frames as usize + 1);
        assert!(
            t.offense
                .iter()
                .chain([&t.keeper])
                .all(|p| p.len() == t.ball.len())
        );
        assert!(t.outcome.is_terminal());
        let svg = t.to_svg();
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        // Three agents, the keeper and the ball (drawn twice: underlay and line).
        assert_eq!(svg.matches(r#"class="path""#).count(), 3 + 1 + 2);
        assert_eq!(svg.matches(r#"class="kick""#).count(), t.kicks.len() + 1);
        assert!(svg.contains(&t.summary()[1..]), "{}", t.summary());
        assert!(svg.contains("seed 1 · episode 2"));
        for label in [">7<", ">8<", ">11<", ">GK<"] {
            assert!(svg.contains(label), "{label}");
        }
        assert!(
            !t.kicks.is_empty(),
            "a random episode has at least the first kick"
        );
    }

    #[test]
    fn a_frame_draws_every_player_where_it_stands() {
        let mut env = Env::new(EnvConfig::default(), 5).unwrap();
        env.reset();
        let svg = frame_svg(&env);
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        assert!(svg.contains(">In play at frame 0<"), "{svg}");
        assert!(svg.contains("3 offense vs keeper"));
        assert_eq!(svg.matches(r#"class="end""#).count(), 3 + 1);
        for label in [">7<", ">8<", ">11<", ">GK<"] {
            assert!(svg.contains(label), "{label}");
        }
        let world = env.world();
        for p in world.players() {
            let (x, y) = px(p.pos);
            assert!(svg.contains(&format!(r#"cx="{x:.1}" cy="{y:.1}""#)));
        }
        // The picture follows the episode to its end.
        let mut rng = policy_rng(5);
        let mut actions = [Action::Move; 3];
        while !env.step(&actions).is_terminal() {
            for (i, a) in actions.iter_mut().enumerate() {
                *a = BaselinePolicy::Shoot.choose(env.can_kick(i), &mut rng);
            }
        }
        let end = frame_svg(&env);
        let title = format!("{} at frame {}<", outcome_words(env.outcome()), env.frame());
        assert!(end.contains(&title[1..]), "{title}");
    }

    #[test]
    fn follows_the_rollout_sequence() {
        let config = EnvConfig::default();
        let summary =
            crate::tools::rollout::rollout(config.clone(), BaselinePolicy::Random, 4, 7).unwrap();
        let mut counts = crate::tools::tally::OutcomeCounts::default();
        let mut frames = 0;
        for k in 1..=4 {
            let t = record_episode(config.clone(), BaselinePolicy::Random, 7, k).unwrap();
            counts.add(t.outcome);
            frames += u64::from(t.frames);
        }
        assert_eq!(counts, summary.outcomes);
        assert_eq!(frames, summary.frames);
        assert!(matches!(
            record_episode(config, BaselinePolicy::Random, 7, 0),
            Err(RenderError::EpisodeZero)
        ));
    }
}
