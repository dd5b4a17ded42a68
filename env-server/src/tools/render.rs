//! Pictures on the half field as SVG documents: a recorded episode's paths
//! ([`record_episode`], [`Trace::to_svg`]) or its animation
//! ([`Trace::to_animated_svg`]), or an [`Env`] as it stands
//! ([`frame_svg`]). Writing them to a file, or as PNG, is the binary's job.
//!
//! The documents are built element by element with the `svg` crate, which
//! writes and escapes them; coordinates are rounded to a tenth of a pixel.
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
use crate::tools::scripted::{ScriptedPolicy, play_episode, policy_rng};
use glam::DVec2;
use svg::node::element::path::Data;
use svg::node::element::{AnimateTransform, Circle, Group, Line, Path, Polyline, Rectangle, Text};
use svg::{Document, Node as _};

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
    /// Who played it, as the title says it: `policy random`, `team adhoc-td`.
    pub played_by: String,
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
    /// An empty trace of an `offense`-agent episode played by `played_by`;
    /// [`observe`](Self::observe) records its states.
    pub fn new(played_by: String, seed: u64, episode: u64, offense: usize) -> Self {
        Trace {
            played_by,
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

    /// Records the state of `env` and the kicks that led to it; at the
    /// episode's end, its outcome and frames.
    pub fn observe(&mut self, env: &Env) {
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
        self.outcome = env.outcome();
        self.frames = env.frame();
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
        self.picture().to_string()
    }

    /// The episode as an animation (SVG's own, which browsers and notebooks
    /// play): every player and the ball moving over their faint paths, ten
    /// frames a second as the server plays them, then again.
    pub fn to_animated_svg(&self) -> String {
        let (mut doc, w) = canvas();
        let n = self.offense.len();
        let detail = format!(
            "{} · {n} offense vs keeper · seed {} · episode {} · 10 frames/s",
            self.played_by, self.seed, self.episode
        );
        title(&mut doc, w, &self.summary(), self.outcome, &detail);
        field(&mut doc);
        let players = (self.offense.iter().enumerate())
            .map(|(i, p)| (p, Kicker::Offense(i)))
            .chain([(&self.keeper, Kicker::Keeper)]);
        let duration = format!("{:.1}s", self.ball.len().max(1) as f64 / 10.0);
        for (points, who) in players {
            if let Some(line) = path(points, colour(who), 2.0, 0.35) {
                doc.append(line);
            }
            let mut marker = Group::new();
            end_marker(&mut marker, (0.0, 0.0), colour(who), &label(n, who));
            doc.append(moving(marker, points, &duration));
        }
        let mut ball_marker = Group::new();
        ball_marker.append(ball((0.0, 0.0)));
        doc.append(moving(ball_marker, &self.ball, &duration));
        doc.to_string()
    }

    /// The picture: title band, field, paths, kicks and markers.
    fn picture(&self) -> Document {
        let (mut doc, w) = canvas();
        self.header(&mut doc, w);
        field(&mut doc);
        // Paths: keeper first, then the offense, the ball on top.
        let players = self.offense.iter().enumerate();
        let players = players.map(|(i, points)| path(points, colour(Kicker::Offense(i)), 2.4, 1.0));
        let lines = [path(&self.keeper, KEEPER_COLOUR, 2.4, 1.0)]
            .into_iter()
            .chain(players)
            .chain([
                path(&self.ball, "#111", 4.6, 0.45),
                path(&self.ball, BALL_COLOUR, 2.0, 1.0),
            ]);
        for line in lines.flatten() {
            doc.append(line);
        }
        for points in self.offense.iter().chain([&self.keeper, &self.ball]) {
            for &p in points.iter().skip(10).step_by(10) {
                doc.append(tick(px(p)));
            }
        }
        for kick in &self.kicks {
            if let Some(&p) = self.ball.get(kick.state) {
                doc.append(star(px(p), colour(kick.by)));
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
                start_marker(&mut doc, px(p), colour, label);
            }
        }
        if let Some(&p) = self.ball.first() {
            let ring = circle(px(p), 8.5)
                .set("fill", "none")
                .set("stroke", BALL_COLOUR)
                .set("stroke-width", 2);
            doc.append(ring);
        }
        for (path, colour, label) in &players {
            if let Some(&p) = path.last() {
                end_marker(&mut doc, px(p), colour, label);
            }
        }
        if let Some(&p) = self.ball.last() {
            doc.append(ball(px(p)));
        }
        doc
    }

    /// The title band: outcome, run, legend.
    fn header(&self, doc: &mut Document, w: f64) {
        let n = self.offense.len();
        let detail = format!(
            "{} · {n} offense vs keeper · seed {} · episode {} · {} kick{}",
            self.played_by,
            self.seed,
            self.episode,
            self.kicks.len(),
            if self.kicks.len() == 1 { "" } else { "s" }
        );
        title(doc, w, &self.summary(), self.outcome, &detail);
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
        let swatch = |x: f64, colour: &str, width: f64| {
            line((x, y), (x + 18.0, y))
                .set("stroke", colour)
                .set("stroke-width", width)
                .set("stroke-linecap", "round")
        };
        for (colour, label) in &items {
            doc.append(swatch(x, colour, 3.0));
            x = legend_text(doc, x + 24.0, y, label);
        }
        doc.append(swatch(x, "#111", 4.6).set("stroke-opacity", 0.6));
        doc.append(swatch(x, BALL_COLOUR, 2.0));
        x = legend_text(doc, x + 24.0, y, "ball");
        x += 14.0;
        start_marker(doc, (x + 7.0, y), "#e8efe8", "");
        x = legend_text(doc, x + 20.0, y, "start");
        end_marker(doc, (x + 7.0, y), "#e8efe8", "");
        x = legend_text(doc, x + 20.0, y, "end");
        doc.append(star((x + 7.0, y), "#e8efe8"));
        x = legend_text(doc, x + 20.0, y, "kick");
        doc.append(tick((x + 5.0, y)));
        legend_text(doc, x + 14.0, y, "every 10 frames");
    }
}

/// Plays the `episode`-th episode (1-based) of the run `env-server rollout
/// --seed seed` would play with `config` and `policy`, and records it.
pub fn record_episode(
    config: EnvConfig,
    policy: ScriptedPolicy,
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
    let mut trace = Trace::new(format!("policy {policy}"), seed, episode, offense);
    play_episode(&mut env, policy, &mut rng, |env, _| trace.observe(env));
    Ok(trace)
}

/// A picture of `env` as it stands: every player (labelled, with a tick
/// along its body direction) and the ball on the half field, the frame and
/// the outcome so far in the title band.
pub fn frame_svg(env: &Env) -> String {
    frame_picture(env).to_string()
}

fn frame_picture(env: &Env) -> Document {
    let (mut doc, w) = canvas();
    let world = env.world();
    let n = world.offense.len();
    let heading = match env.outcome() {
        Outcome::InGame => format!("in play at frame {}", env.frame()),
        ended => format!("{} at frame {}", outcome_words(ended), env.frame()),
    };
    let detail = format!("{n} offense vs keeper");
    title(&mut doc, w, &heading, env.outcome(), &detail);
    field(&mut doc);
    let players = world.offense.iter().enumerate();
    let players = players.map(|(i, p)| (p, Kicker::Offense(i)));
    for (p, who) in players.chain([(&world.keeper, Kicker::Keeper)]) {
        let facing = p.pos + (MARKER + 5.0) / SCALE * DVec2::from_angle(p.body);
        let body = line(px(p.pos), px(facing))
            .set("stroke", colour(who))
            .set("stroke-width", 3)
            .set("stroke-linecap", "round");
        doc.append(body);
        end_marker(&mut doc, px(p.pos), colour(who), &label(n, who));
    }
    doc.append(ball(px(world.ball.pos)));
    doc
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

/// A point in pixels: x to the right, y down.
type Px = (f64, f64);

fn px_x(x: f64) -> f64 {
    (x - VIEW_X.0) * SCALE
}

fn px_y(y: f64) -> f64 {
    HEADER + (y - VIEW_Y.0) * SCALE
}

fn px(p: DVec2) -> Px {
    (px_x(p.x), px_y(p.y))
}

/// A coordinate rounded to a tenth of a pixel, finer than the eye sees,
/// which keeps the documents short.
fn tenth(v: f64) -> f64 {
    (v * 10.0).round() / 10.0
}

/// An empty picture of the field's size, and its width.
fn canvas() -> (Document, f64) {
    let (w, h) = (px_x(VIEW_X.1).round(), px_y(VIEW_Y.1).round());
    let doc = Document::new()
        .set("width", w)
        .set("height", h)
        .set("viewBox", (0, 0, w, h))
        .set("font-family", FONT);
    (doc, w)
}

/// A circle of radius `r` (pixels) centred at `centre`.
fn circle(centre: Px, r: f64) -> Circle {
    Circle::new()
        .set("cx", tenth(centre.0))
        .set("cy", tenth(centre.1))
        .set("r", r)
}

/// A line from `from` to `to`.
fn line(from: Px, to: Px) -> Line {
    Line::new()
        .set("x1", tenth(from.0))
        .set("y1", tenth(from.1))
        .set("x2", tenth(to.0))
        .set("y2", tenth(to.1))
}

/// The rectangle between the corners `from` (top left) and `to`.
fn rectangle(from: Px, to: Px) -> Rectangle {
    Rectangle::new()
        .set("x", tenth(from.0))
        .set("y", tenth(from.1))
        .set("width", tenth(to.0 - from.0))
        .set("height", tenth(to.1 - from.1))
}

/// `content` written from `at` (its baseline).
fn text(at: Px, content: &str) -> Text {
    Text::new(content)
        .set("x", tenth(at.0))
        .set("y", tenth(at.1))
}

/// Path data starting at `at`.
fn start_at(at: Px) -> Data {
    Data::new().move_to((tenth(at.0), tenth(at.1)))
}

/// The title band of a `w`-pixel wide picture: `heading` (capitalised) in
/// the colour of `outcome`, and a line of `detail` below it.
fn title(doc: &mut Document, w: f64, heading: &str, outcome: Outcome, detail: &str) {
    doc.append(rectangle((0.0, 0.0), (w, HEADER)).set("fill", HEADER_COLOUR));
    let colour = match outcome {
        Outcome::Goal => "#8ef58e",
        Outcome::Captured => "#ff8080",
        Outcome::OutOfBounds => "#ffc266",
        Outcome::OutOfTime | Outcome::InGame => "#d8d8d8",
    };
    let mut heading = heading.to_owned();
    heading[..1].make_ascii_uppercase();
    doc.append(
        text((18.0, 34.0), &heading)
            .set("font-size", 23)
            .set("font-weight", "bold")
            .set("fill", colour),
    );
    doc.append(
        text((18.0, 58.0), detail)
            .set("font-size", 14)
            .set("fill", "#e8efe8"),
    );
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
fn field(doc: &mut Document) {
    grass(doc);
    goal(doc);
    pitch_lines(doc);
    doc.append(coordinates());
    for post in GOAL_POSTS {
        let post = circle(px(post), 3.0)
            .set("fill", "white")
            .set("stroke", "#333")
            .set("stroke-width", 0.8);
        doc.append(post);
    }
}

/// The grass with its mowing stripes, darker outside the HFO area.
fn grass(doc: &mut Document) {
    let (top, bottom) = (px_y(VIEW_Y.0), px_y(VIEW_Y.1));
    let (left, right) = (px_x(VIEW_X.0), px_x(VIEW_X.1));
    doc.append(rectangle((left, top), (right, bottom)).set("fill", GRASS[0]));
    // Mowing stripes every 5.25 m from the half-way line.
    let stripe = PITCH_HALF_LENGTH / 10.0;
    let mut k = (VIEW_X.0 / stripe).floor() as i32;
    while f64::from(k) * stripe < VIEW_X.1 {
        if k.rem_euclid(2) == 1 {
            let x0 = px_x(f64::from(k) * stripe).max(left);
            let x1 = px_x(f64::from(k + 1) * stripe).min(right);
            doc.append(rectangle((x0, top), (x1, bottom)).set("fill", GRASS[1]));
        }
        k += 1;
    }
    // Darken what lies outside the HFO area: the view minus the area.
    let (ax0, ay0) = px(DVec2::new(0.0, -PITCH_HALF_WIDTH));
    let (ax1, ay1) = px(DVec2::new(PITCH_HALF_LENGTH, PITCH_HALF_WIDTH));
    let outside = start_at((left, top))
        .horizontal_line_to(tenth(right))
        .vertical_line_to(tenth(bottom))
        .horizontal_line_to(tenth(left))
        .close()
        .move_to((tenth(ax0), tenth(ay0)))
        .vertical_line_to(tenth(ay1))
        .horizontal_line_to(tenth(ax1))
        .vertical_line_to(tenth(ay0))
        .close();
    let outside = Path::new()
        .set("d", outside)
        .set("fill", "black")
        .set("fill-opacity", 0.16)
        .set("fill-rule", "evenodd");
    doc.append(outside);
}

/// The goal: its net behind the line and its outline.
fn goal(doc: &mut Document) {
    let (gx0, gy0) = px(DVec2::new(PITCH_HALF_LENGTH, -GOAL_HALF_WIDTH));
    let (gx1, gy1) = px(DVec2::new(PITCH_HALF_LENGTH + GOAL_DEPTH, GOAL_HALF_WIDTH));
    let inside = rectangle((gx0, gy0), (gx1, gy1))
        .set("fill", "white")
        .set("fill-opacity", 0.18);
    doc.append(inside);
    let mut net = Group::new()
        .set("stroke", "white")
        .set("stroke-opacity", 0.45)
        .set("stroke-width", 0.8);
    let mesh = 0.5 * SCALE;
    let mut x = gx0 + mesh;
    while x < gx1 - 1.0 {
        net.append(line((x, gy0), (x, gy1)));
        x += mesh;
    }
    let mut y = gy0 + mesh;
    while y < gy1 - 1.0 {
        net.append(line((gx0, y), (gx1, y)));
        y += mesh;
    }
    doc.append(net);
    let outline = start_at((gx0, gy0))
        .horizontal_line_to(tenth(gx1))
        .vertical_line_to(tenth(gy1))
        .horizontal_line_to(tenth(gx0));
    let outline = Path::new()
        .set("d", outline)
        .set("fill", "none")
        .set("stroke", LINE_COLOUR)
        .set("stroke-width", 2.5);
    doc.append(outline);
}

/// The HFO area's lines: its boundary, the penalty and goal areas, the
/// centre circle's attacking half, the penalty arc and the two spots.
fn pitch_lines(doc: &mut Document) {
    let mut lines = Group::new()
        .set("fill", "none")
        .set("stroke", LINE_COLOUR)
        .set("stroke-width", 2)
        .set("stroke-opacity", 0.92);
    // The boxes, each from its x to the goal line, `half` wide each side.
    for (x0, half) in [
        (0.0, PITCH_HALF_WIDTH),
        (PENALTY_AREA_X, PENALTY_AREA_HALF_WIDTH),
        (PITCH_HALF_LENGTH - GOAL_AREA_LENGTH, GOAL_AREA_HALF_WIDTH),
    ] {
        let from = px(DVec2::new(x0, -half));
        let to = px(DVec2::new(PITCH_HALF_LENGTH, half));
        lines.append(rectangle(from, to));
    }
    // Centre circle (its attacking half) and the penalty arc outside the box.
    let r = tenth(CIRCLE_RADIUS * SCALE);
    let (cx, cy) = px(DVec2::ZERO);
    let centre =
        start_at((cx, cy - r)).elliptical_arc_to((r, r, 0, 0, 1, tenth(cx), tenth(cy + r)));
    lines.append(Path::new().set("d", centre));
    let spot = PITCH_HALF_LENGTH - PENALTY_SPOT_DISTANCE;
    let half_chord = (CIRCLE_RADIUS.powi(2) - (spot - PENALTY_AREA_X).powi(2)).sqrt();
    let (ax, ay0) = px(DVec2::new(PENALTY_AREA_X, -half_chord));
    let ay1 = px_y(half_chord);
    let arc = start_at((ax, ay0)).elliptical_arc_to((r, r, 0, 0, 0, tenth(ax), tenth(ay1)));
    lines.append(Path::new().set("d", arc));
    doc.append(lines);
    for at in [DVec2::ZERO, DVec2::new(spot, 0.0)] {
        doc.append(circle(px(at), 2.5).set("fill", LINE_COLOUR));
    }
}

/// Coordinates in the margin: x below the field, y left of it.
fn coordinates() -> Group {
    let mut labels = Group::new()
        .set("font-size", 11)
        .set("fill", "white")
        .set("fill-opacity", 0.65)
        .set("text-anchor", "middle");
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
        labels.append(text((px_x(x), below), &x.to_string()));
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
        labels.append(text((left, px_y(y) + 4.0), &y.to_string()));
    }
    labels
}

/// Radius of the centre circle and the penalty arc.
const CIRCLE_RADIUS: f64 = 9.15;
/// Distance of the penalty spot from the goal line.
const PENALTY_SPOT_DISTANCE: f64 = 11.0;

/// A line through `points` (none through fewer than two).
fn path(points: &[DVec2], colour: &str, width: f64, opacity: f64) -> Option<Polyline> {
    if points.len() < 2 {
        return None;
    }
    let points: Vec<Px> = (points.iter())
        .map(|&p| (tenth(px(p).0), tenth(px(p).1)))
        .collect();
    let line = Polyline::new()
        .set("class", "path")
        .set("fill", "none")
        .set("stroke", colour)
        .set("stroke-width", width)
        .set("stroke-opacity", opacity)
        .set("stroke-linejoin", "round")
        .set("stroke-linecap", "round")
        .set("points", points);
    Some(line)
}

/// A small dot, drawn every 10 frames along a path.
fn tick(at: Px) -> Circle {
    circle(at, 2.2)
        .set("fill", "#f4f8f4")
        .set("stroke", "#111")
        .set("stroke-width", 0.8)
}

/// The ball where it is: a white disc.
fn ball(at: Px) -> Circle {
    circle(at, 5.0)
        .set("fill", BALL_COLOUR)
        .set("stroke", "#111")
        .set("stroke-width", 1.5)
}

/// The radius of a marker: smaller without a label (in the legend).
fn marker_radius(label: &str) -> f64 {
    if label.is_empty() {
        MARKER - 2.0
    } else {
        MARKER
    }
}

/// A hollow ring at a player's start, its label inside.
fn start_marker(doc: &mut Document, at: Px, colour: &str, label: &str) {
    let ring = circle(at, marker_radius(label))
        .set("class", "start")
        .set("fill", "black")
        .set("fill-opacity", 0.3)
        .set("stroke", colour)
        .set("stroke-width", 2.5);
    doc.append(ring);
    marker_label(doc, at, label, "#ffffff");
}

/// `group` (drawn around the origin) following `points`, one a frame over
/// `duration`, again and again.
fn moving(group: Group, points: &[DVec2], duration: &str) -> Group {
    let values: Vec<String> = (points.iter())
        .map(|&p| {
            let (x, y) = px(p);
            format!("{} {}", tenth(x), tenth(y))
        })
        .collect();
    let (x, y) = points.first().map_or((0.0, 0.0), |&p| px(p));
    let motion = AnimateTransform::new()
        .set("attributeName", "transform")
        .set("type", "translate")
        .set("values", values.join(";"))
        .set("dur", duration)
        .set("repeatCount", "indefinite");
    group
        .set("transform", format!("translate({} {})", tenth(x), tenth(y)))
        .add(motion)
}

/// A filled disc at a player's end, its label inside.
fn end_marker(doc: &mut impl svg::Node, at: Px, colour: &str, label: &str) {
    let disc = circle(at, marker_radius(label))
        .set("class", "end")
        .set("fill", colour)
        .set("stroke", "#111")
        .set("stroke-width", 1.5);
    doc.append(disc);
    marker_label(doc, at, label, "#111");
}

/// A marker's label, centred on it (none if empty).
fn marker_label(doc: &mut impl svg::Node, (x, y): Px, label: &str, colour: &str) {
    if label.is_empty() {
        return;
    }
    let size = if label.len() > 1 { 9.5 } else { 11.0 };
    let label = text((x, y + 0.36 * size), label)
        .set("font-size", size)
        .set("font-weight", "bold")
        .set("text-anchor", "middle")
        .set("fill", colour);
    doc.append(label);
}

/// A five-pointed star where the ball was kicked.
fn star((x, y): Px, colour: &str) -> Path {
    let corner = |k: i32| {
        let r = if k % 2 == 0 { 6.5 } else { 2.8 };
        let a = -std::f64::consts::FRAC_PI_2 + f64::from(k) * std::f64::consts::PI / 5.0;
        (tenth(x + r * a.cos()), tenth(y + r * a.sin()))
    };
    let outline = (1..10)
        .fold(Data::new().move_to(corner(0)), |d, k| d.line_to(corner(k)))
        .close();
    Path::new()
        .set("class", "kick")
        .set("fill", colour)
        .set("stroke", "#111")
        .set("stroke-width", 1)
        .set("stroke-linejoin", "round")
        .set("d", outline)
}

/// Legend text at `x`; returns where the next item starts.
fn legend_text(doc: &mut Document, x: f64, y: f64, content: &str) -> f64 {
    let label = text((x, y + 4.5), content)
        .set("font-size", 13)
        .set("fill", "#e8efe8");
    doc.append(label);
    // DejaVu Sans at 13 px averages about 7.6 px per character.
    x + 7.6 * content.chars().count() as f64 + 16.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use proto::Action;
    use std::collections::HashMap;
    use svg::node::element::tag::Type;
    use svg::parser::Event;

    fn trace(seed: u64, episode: u64) -> Trace {
        record_episode(EnvConfig::default(), ScriptedPolicy::Random, seed, episode).unwrap()
    }

    /// An element of a picture as read back: its name, attributes and text.
    struct Element {
        name: String,
        attributes: HashMap<String, String>,
        text: String,
    }

    impl Element {
        fn get(&self, attribute: &str) -> &str {
            self.attributes.get(attribute).map_or("", String::as_str)
        }

        fn number(&self, attribute: &str) -> f64 {
            let value = self.get(attribute);
            value
                .parse()
                .unwrap_or_else(|_| panic!("{}'s {attribute} is {value:?}", self.name))
        }

        fn class(&self) -> &str {
            self.get("class")
        }
    }

    /// Every element of `svg` in document order, read back with the svg
    /// crate's parser; panics unless it is one well-formed `<svg>` element.
    fn read(svg: &str) -> Vec<Element> {
        let mut elements: Vec<Element> = Vec::new();
        let mut open = Vec::new();
        for event in svg::read(svg).unwrap() {
            match event {
                Event::Tag(name, kind, attributes) => {
                    if kind == Type::End {
                        assert_eq!(open.pop(), Some(name.to_owned()), "unbalanced");
                        continue;
                    }
                    if kind == Type::Start {
                        open.push(name.to_owned());
                    }
                    elements.push(Element {
                        name: name.to_owned(),
                        attributes: (attributes.iter())
                            .map(|(k, v)| (k.clone(), v.to_string()))
                            .collect(),
                        text: String::new(),
                    });
                }
                Event::Text(text) => {
                    assert!(!open.is_empty(), "text outside the document");
                    elements.last_mut().unwrap().text.push_str(text.trim());
                }
                Event::Error(e) => panic!("{e}"),
                _ => {}
            }
        }
        assert!(open.is_empty(), "unclosed: {open:?}");
        assert_eq!(elements[0].name, "svg");
        assert!(elements[1..].iter().all(|e| e.name != "svg"));
        elements
    }

    /// The texts of `elements`.
    fn texts(elements: &[Element]) -> Vec<&str> {
        (elements.iter())
            .filter(|e| e.name == "text")
            .map(|e| e.text.as_str())
            .collect()
    }

    #[test]
    fn the_animation_moves_every_player_and_the_ball_through_every_state() {
        let trace = trace(3, 1);
        let elements = read(&trace.to_animated_svg());
        let moves: Vec<&Element> = (elements.iter())
            .filter(|e| e.name == "animateTransform")
            .collect();
        // Three attackers, the keeper, then the ball.
        assert_eq!(moves.len(), 5);
        let duration = format!("{:.1}s", trace.ball.len() as f64 / 10.0);
        let paths = trace.offense.iter().chain([&trace.keeper, &trace.ball]);
        for (motion, path) in moves.iter().zip(paths) {
            assert_eq!(motion.get("dur"), duration);
            let values: Vec<(f64, f64)> = (motion.get("values").split(';'))
                .map(|v| {
                    let (x, y) = v.split_once(' ').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect();
            let expected: Vec<(f64, f64)> = path.iter().map(|&p| at(p)).collect();
            assert_eq!(values, expected);
        }
        let said = |what: &str| texts(&elements).iter().any(|t| t.contains(what));
        assert!(said("policy random") && said(&format!("{} frames", trace.frames)));
    }

    /// The elements of `elements` of class `class`.
    fn of_class<'a>(elements: &'a [Element], class: &str) -> Vec<&'a Element> {
        elements.iter().filter(|e| e.class() == class).collect()
    }

    /// A point of the field in the picture, as written.
    fn at(p: DVec2) -> (f64, f64) {
        (tenth(px(p).0), tenth(px(p).1))
    }

    /// The centre of a circle.
    fn centre(e: &Element) -> (f64, f64) {
        (e.number("cx"), e.number("cy"))
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
        assert!(
            !t.kicks.is_empty(),
            "a random episode has at least the first kick"
        );
        let svg = t.to_svg();
        let elements = read(&svg);
        // The keeper, three agents and the ball (drawn twice: underlay and
        // line), each through every state, from its start to its end.
        let paths = of_class(&elements, "path");
        let drawn = [
            &t.keeper,
            &t.offense[0],
            &t.offense[1],
            &t.offense[2],
            &t.ball,
            &t.ball,
        ];
        assert_eq!(paths.len(), drawn.len());
        for (path, states) in paths.iter().zip(drawn) {
            let numbers: Vec<f64> = (path.get("points").split([' ', ',']))
                .map(|n| n.parse().unwrap())
                .collect();
            let points: Vec<(f64, f64)> = numbers.chunks(2).map(|p| (p[0], p[1])).collect();
            let expected: Vec<(f64, f64)> = states.iter().map(|&p| at(p)).collect();
            assert_eq!(points, expected);
        }
        // Every kick where the ball was, and one in the legend.
        let kicks = of_class(&elements, "kick");
        assert_eq!(kicks.len(), t.kicks.len() + 1);
        // Each player's start and end, labelled, and one of each in the legend.
        let starts = of_class(&elements, "start");
        let ends = of_class(&elements, "end");
        assert_eq!((starts.len(), ends.len()), (1 + 4, 1 + 4));
        let players = [&t.offense[0], &t.offense[1], &t.offense[2], &t.keeper];
        for ((start, end), states) in starts[1..].iter().zip(&ends[1..]).zip(players) {
            assert_eq!(centre(start), at(states[0]));
            assert_eq!(centre(end), at(*states.last().unwrap()));
        }
        let texts = texts(&elements);
        for label in ["7", "8", "11", "GK"] {
            let n = texts.iter().filter(|&&t| t == label).count();
            assert_eq!(n, 2, "{label}: {texts:?}");
        }
        let mut summary = t.summary();
        summary[..1].make_ascii_uppercase();
        assert!(texts.contains(&summary.as_str()), "{texts:?}");
        let kicks = t.kicks.len();
        let detail =
            format!("policy random · 3 offense vs keeper · seed 1 · episode 2 · {kicks} kicks");
        assert!(texts.contains(&detail.as_str()), "{texts:?}");
        for legend in ["#7", "#8", "#11", "keeper", "ball", "start", "end", "kick"] {
            assert!(texts.contains(&legend), "{legend}");
        }
    }

    #[test]
    fn everything_drawn_is_inside_the_picture() {
        let elements = read(&trace(7, 3).to_svg());
        let (w, h) = (elements[0].number("width"), elements[0].number("height"));
        assert_eq!(elements[0].get("viewBox"), format!("0 0 {w} {h}"));
        assert!(w > 800.0 && h > 1000.0, "{w}x{h}");
        let mut numbers = 0;
        for e in &elements[1..] {
            let xs = ["cx", "x", "x1", "x2"].map(|a| (a, w));
            let ys = ["cy", "y", "y1", "y2"].map(|a| (a, h));
            for (attribute, most) in xs.into_iter().chain(ys) {
                if e.attributes.contains_key(attribute) {
                    let v = e.number(attribute);
                    assert!((0.0..=most).contains(&v), "{} {attribute}={v}", e.name);
                    numbers += 1;
                }
            }
        }
        assert!(numbers > 100, "{numbers}");
    }

    #[test]
    fn a_frame_draws_every_player_where_it_stands() {
        let mut env = Env::new(EnvConfig::default(), 5).unwrap();
        env.reset();
        let elements = read(&frame_svg(&env));
        let written = texts(&elements);
        assert!(written.contains(&"In play at frame 0"), "{written:?}");
        assert!(written.contains(&"3 offense vs keeper"), "{written:?}");
        for label in ["7", "8", "11", "GK"] {
            assert!(written.contains(&label), "{label}");
        }
        let ends = of_class(&elements, "end");
        let world = env.world();
        let players: Vec<_> = world.players().map(|p| at(p.pos)).collect();
        assert_eq!(ends.len(), players.len());
        for end in ends {
            assert!(players.contains(&centre(end)), "{:?}", centre(end));
        }
        // The picture follows the episode to its end.
        let mut rng = policy_rng(5);
        let mut actions = [Action::Move; 3];
        while !env.step(&actions).is_terminal() {
            for (i, a) in actions.iter_mut().enumerate() {
                *a = ScriptedPolicy::Shoot.choose(env.can_kick(i), &mut rng);
            }
        }
        let end = read(&frame_svg(&env));
        let mut title = format!("{} at frame {}", outcome_words(env.outcome()), env.frame());
        title[..1].make_ascii_uppercase();
        assert!(texts(&end).contains(&title.as_str()), "{title}");
    }

    #[test]
    fn follows_the_rollout_sequence() {
        let config = EnvConfig::default();
        let summary =
            crate::tools::rollout::rollout(config.clone(), ScriptedPolicy::Random, 4, 7).unwrap();
        let mut counts = crate::tools::tally::OutcomeCounts::default();
        let mut frames = 0;
        for k in 1..=4 {
            let t = record_episode(config.clone(), ScriptedPolicy::Random, 7, k).unwrap();
            counts.add(t.outcome);
            frames += u64::from(t.frames);
        }
        assert_eq!(counts, summary.outcomes);
        assert_eq!(frames, summary.frames);
        assert!(matches!(
            record_episode(config, ScriptedPolicy::Random, 7, 0),
            Err(RenderError::EpisodeZero)
        ));
    }
}
