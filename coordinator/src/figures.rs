//! Figures of experiments in the style of the paper's: goal percentage with
//! a confidence band per algorithm (its Figures 3, 5, 7), time to goal
//! (Figure 2), spent budget (Figures 4a, 6a, 8a) and the goal percentage of
//! the last training episodes zoomed in (Figures 4b, 6b, 8b).
//!
//! Every figure is drawn as an SVG document with `plotters` and rasterised
//! to a PNG of the same size with `resvg` and the system's fonts (without
//! any, the PNG has no text). Unknown means (null in `summary.json`) leave
//! gaps in the lines; unknown interval bounds leave gaps in the bands.
//!
//! ```no_run
//! use coordinator::figures::{SeriesSet, write_figures};
//!
//! let sets = [
//!     SeriesSet::read("NoAdvice", "results/no-advice/summary.json".as_ref())?,
//!     SeriesSet::read("AdHocTD", "results/adhoc-td/summary.json".as_ref())?,
//! ];
//! for path in write_figures("results/figures".as_ref(), &sets)? {
//!     println!("{}", path.display());
//! }
//! # Ok::<(), coordinator::figures::FigureError>(())
//! ```

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use serde::Deserialize;

use crate::stats::Estimate;
use crate::summary::SummaryPoint;

/// Width and height of every figure, in pixels.
pub const SIZE: (u32, u32) = (1000, 600);

/// What a figure plots against the training episodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Metric {
    /// Percentage of evaluation episodes ending in a goal.
    GoalPct,
    /// Frames to a goal.
    TimeToGoal,
    /// Advice given, averaged over agents.
    SpentBudget,
}

impl Metric {
    /// The metric's estimate at `point`.
    fn of(self, point: &SummaryPoint) -> &Estimate {
        match self {
            Metric::GoalPct => &point.goal_pct,
            Metric::TimeToGoal => &point.time_to_goal,
            Metric::SpentBudget => &point.spent_budget,
        }
    }

    /// The figure title.
    fn title(self) -> &'static str {
        match self {
            Metric::GoalPct => "Goal percentage",
            Metric::TimeToGoal => "Time to goal",
            Metric::SpentBudget => "Spent budget",
        }
    }

    /// The y axis title, with the unit.
    fn axis(self) -> &'static str {
        match self {
            Metric::GoalPct => "Goal percentage (%)",
            Metric::TimeToGoal => "Time to goal (frames)",
            Metric::SpentBudget => "Spent budget (advice given, per agent)",
        }
    }
}

/// One evaluation point of a series: the mean and the interval bounds,
/// each `None` where unknown.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeriesPoint {
    /// Training episodes played before the evaluation.
    pub episode: f64,
    /// Mean over runs.
    pub mean: Option<f64>,
    /// Lower bound of the confidence interval.
    pub low: Option<f64>,
    /// Upper bound of the confidence interval.
    pub high: Option<f64>,
}

/// One algorithm's curve of one metric: a line with a band around it.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// The evaluation points, by episode.
    pub points: Vec<SeriesPoint>,
}

/// One algorithm's results, as read from its `summary.json`.
#[derive(Clone, Debug, PartialEq)]
pub struct SeriesSet {
    /// Legend label (the algorithm's name).
    pub label: String,
    /// Runs behind every mean.
    pub runs: u64,
    /// Confidence level of the intervals.
    pub ci_level: f64,
    /// Every evaluation point, in order.
    pub points: Vec<SummaryPoint>,
}

/// The part of `summary.json` the figures need.
#[derive(Deserialize)]
struct SummaryFile {
    runs: u64,
    ci_level: f64,
    eval_points: Vec<PointFile>,
}

/// One evaluation point of `summary.json`.
#[derive(Deserialize)]
struct PointFile {
    episode: u64,
    goal_pct: Estimate,
    time_to_goal: Estimate,
    spent_budget: Estimate,
}

impl SeriesSet {
    /// Parses the text of a `summary.json`.
    pub fn from_json(label: impl Into<String>, json: &str) -> Result<Self, serde_json::Error> {
        let file: SummaryFile = serde_json::from_str(json)?;
        Ok(Self {
            label: label.into(),
            runs: file.runs,
            ci_level: file.ci_level,
            points: file
                .eval_points
                .into_iter()
                .map(|p| SummaryPoint {
                    episode: p.episode,
                    goal_pct: p.goal_pct,
                    time_to_goal: p.time_to_goal,
                    spent_budget: p.spent_budget,
                })
                .collect(),
        })
    }

    /// Reads a `summary.json`.
    pub fn read(label: impl Into<String>, path: &Path) -> Result<Self, FigureError> {
        let text = std::fs::read_to_string(path).map_err(|source| FigureError::Read {
            path: path.to_owned(),
            source,
        })?;
        Self::from_json(label, &text).map_err(|source| FigureError::Parse {
            path: path.to_owned(),
            source,
        })
    }

    /// The curve of `metric`; non-finite values count as unknown.
    pub fn series(&self, metric: Metric) -> Series {
        let known = |v: Option<f64>| v.filter(|v| v.is_finite());
        Series {
            label: self.label.clone(),
            points: self
                .points
                .iter()
                .map(|p| {
                    let e = metric.of(p);
                    SeriesPoint {
                        episode: p.episode as f64,
                        mean: known(e.mean),
                        low: known(e.ci_low),
                        high: known(e.ci_high),
                    }
                })
                .collect(),
        }
    }
}

/// Why figures could not be made.
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    /// A summary could not be read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A summary is not valid `summary.json`.
    #[error("cannot parse {}: {source}", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: serde_json::Error,
    },
    /// Plotting failed.
    #[error("cannot draw figure {name}: {message}")]
    Draw {
        /// The figure.
        name: &'static str,
        /// What went wrong.
        message: String,
    },
    /// The SVG could not be rasterised.
    #[error("cannot rasterise figure {name}: {message}")]
    Raster {
        /// The figure.
        name: &'static str,
        /// What went wrong.
        message: String,
    },
    /// Writing a file or creating the directory failed.
    #[error("cannot write {}: {source}", path.display())]
    Write {
        /// The file or directory.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}

/// Writes every figure of `sets` (one colour per set, in order) into `dir`,
/// creating it: `goal_pct`, `time_to_goal`, `spent_budget` and
/// `goal_pct_last`, each as `.svg` and `.png`, every file atomically.
/// Returns the paths written.
pub fn write_figures(dir: &Path, sets: &[SeriesSet]) -> Result<Vec<PathBuf>, FigureError> {
    std::fs::create_dir_all(dir).map_err(|source| FigureError::Write {
        path: dir.to_owned(),
        source,
    })?;
    let note = note(sets);
    let mut written = Vec::new();
    for figure in &FIGURES {
        let series: Vec<Series> = sets.iter().map(|s| s.series(figure.metric)).collect();
        let svg = figure.svg(&series, &note)?;
        let png = node::files::svg_to_png(&svg).map_err(|e| FigureError::Raster {
            name: figure.name,
            message: e.to_string(),
        })?;
        for (extension, bytes) in [("svg", svg.as_bytes()), ("png", &png)] {
            let path = dir.join(format!("{}.{extension}", figure.name));
            write_atomically(&path, bytes)?;
            written.push(path);
        }
    }
    Ok(written)
}

/// Writes `<path>.tmp` beside `path`, then renames it over `path`.
fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), FigureError> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".tmp");
    let tmp = PathBuf::from(tmp);
    std::fs::write(&tmp, bytes)
        .and_then(|()| std::fs::rename(&tmp, path))
        .map_err(|source| {
            let _ = std::fs::remove_file(&tmp);
            FigureError::Write {
                path: path.to_owned(),
                source,
            }
        })
}

/// The subtitle: runs behind the means and the level of the bands.
fn note(sets: &[SeriesSet]) -> String {
    let (Some(min), Some(max)) = (
        sets.iter().map(|s| s.runs).min(),
        sets.iter().map(|s| s.runs).max(),
    ) else {
        return String::new();
    };
    let runs = match (min == max, max) {
        (true, 1) => "1 run".to_owned(),
        (true, n) => format!("{n} runs"),
        (false, _) => format!("{min}\u{2013}{max} runs"),
    };
    let level = sets[0].ci_level;
    let band = if sets.iter().all(|s| s.ci_level == level) {
        format!("{}% confidence interval", (level * 1e4).round() / 100.0)
    } else {
        "confidence interval".to_owned()
    };
    format!("Mean over {runs}; shaded: {band}")
}

// ---------------------------------------------------------------------------
// Layout and style.

/// Font families, first available wins (as env-server's pictures).
const FONT: &str = "DejaVu Sans, Liberation Sans, Arial, Helvetica, sans-serif";
/// Okabe-Ito colours, in an order where the first six are far apart
/// (yellow, poor on white, last).
const PALETTE: [RGBColor; 8] = [
    RGBColor(0x00, 0x72, 0xB2),
    RGBColor(0xD5, 0x5E, 0x00),
    RGBColor(0x00, 0x9E, 0x73),
    RGBColor(0xCC, 0x79, 0xA7),
    RGBColor(0x00, 0x00, 0x00),
    RGBColor(0xE6, 0x9F, 0x00),
    RGBColor(0x56, 0xB4, 0xE9),
    RGBColor(0xF0, 0xE4, 0x42),
];
/// Titles and axis titles.
const INK: RGBColor = RGBColor(0x22, 0x22, 0x22);
/// Tick labels and the subtitle.
const MUTED: RGBColor = RGBColor(0x5A, 0x5A, 0x5A);
/// Axes.
const AXIS: RGBColor = RGBColor(0x88, 0x88, 0x88);
/// Grid lines.
const GRID: RGBColor = RGBColor(0xE6, 0xE6, 0xE6);
/// Legend frame.
const FRAME: RGBColor = RGBColor(0xC8, 0xC8, 0xC8);
/// Opacity of the confidence bands.
const BAND_ALPHA: f64 = 0.2;
/// Width of the mean lines.
const LINE_WIDTH: u32 = 2;

/// Height of the header: the title, and the note below it.
const HEADER_H: u32 = 64;
/// Margins around the chart (top, right, bottom, left).
const MARGIN: (u32, u32, u32, u32) = (6, 30, 10, 12);
/// Height of the x tick labels and axis title.
const X_LABELS_H: u32 = 54;
/// Width of the y tick labels and axis title.
const Y_LABELS_W: u32 = 84;
/// Size of the plotting area.
const PLOT: (u32, u32) = (
    SIZE.0 - MARGIN.1 - MARGIN.3 - Y_LABELS_W,
    SIZE.1 - HEADER_H - MARGIN.0 - MARGIN.2 - X_LABELS_H,
);

/// Legend: text size, line height, inner padding, swatch width, gap to the
/// text, distance from the plot's edges (pixels).
const LEGEND_TEXT: f64 = 15.0;
const LEGEND_LINE: i32 = 25;
const LEGEND_PAD: i32 = 10;
const LEGEND_SWATCH: i32 = 30;
const LEGEND_GAP: i32 = 9;
const LEGEND_INSET: i32 = 12;

/// Share of the training episodes the zoomed figure shows.
const LAST_SHARE: f64 = 0.2;

/// A text style of `px` pixels (plotters' SVG backend writes the size
/// divided by 1.24).
fn font(px: f64, colour: &RGBColor) -> TextStyle<'static> {
    (FONT, px * 1.24).into_font().color(colour)
}

/// Decimals that tell apart ticks over a range of `span`.
fn decimals(span: f64) -> usize {
    if span >= 10.0 {
        0
    } else if span >= 1.0 {
        1
    } else {
        2
    }
}

// ---------------------------------------------------------------------------
// The figures.

/// How a figure's y range is chosen.
#[derive(Clone, Copy)]
enum YRange {
    /// Always these bounds.
    Fixed(f64, f64),
    /// From zero to the largest value, with a margin.
    FromZero,
    /// Around the values with a margin, within zero and the ceiling.
    Fitted(Option<f64>),
}

/// One figure: what it plots, how, and its file name.
struct Figure {
    /// File name without extension.
    name: &'static str,
    /// The metric plotted.
    metric: Metric,
    /// Only the last [`LAST_SHARE`] of the episodes.
    last: bool,
    /// How the y range is chosen.
    y: YRange,
    /// Curves that are zero throughout are named in the note instead of
    /// drawn (algorithms that never advise, in the spent budget).
    skip_zero: bool,
}

/// Every figure written.
const FIGURES: [Figure; 4] = [
    Figure {
        name: "goal_pct",
        metric: Metric::GoalPct,
        last: false,
        y: YRange::Fixed(0.0, 100.0),
        skip_zero: false,
    },
    Figure {
        name: "time_to_goal",
        metric: Metric::TimeToGoal,
        last: false,
        y: YRange::Fitted(None),
        skip_zero: false,
    },
    Figure {
        name: "spent_budget",
        metric: Metric::SpentBudget,
        last: false,
        y: YRange::FromZero,
        skip_zero: true,
    },
    Figure {
        name: "goal_pct_last",
        metric: Metric::GoalPct,
        last: true,
        y: YRange::Fitted(Some(100.0)),
        skip_zero: false,
    },
];

/// A series as drawn: its colour and the points shown.
struct Curve {
    /// Line and band colour.
    colour: RGBColor,
    /// The points in the figure's episodes.
    series: Series,
}

/// Data ranges of a chart.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Ranges {
    /// Episodes.
    x: (f64, f64),
    /// Metric values.
    y: (f64, f64),
}

impl Figure {
    /// The figure of `series` (coloured in order) as an SVG document.
    fn svg(&self, series: &[Series], note: &str) -> Result<String, FigureError> {
        let from = self.first_episode(series);
        let mut skipped = Vec::new();
        let mut curves = Vec::new();
        for (s, &colour) in series.iter().zip(PALETTE.iter().cycle()) {
            let points: Vec<SeriesPoint> = s
                .points
                .iter()
                .filter(|p| from.is_none_or(|from| p.episode >= from))
                .copied()
                .collect();
            let zero = |v: Option<f64>| v.is_none_or(|v| v == 0.0);
            let known = points.iter().any(|p| p.mean.is_some());
            if self.skip_zero && known && points.iter().all(|p| zero(p.mean) && zero(p.high)) {
                skipped.push(s.label.as_str());
                continue;
            }
            let label = s.label.clone();
            curves.push(Curve {
                colour,
                series: Series { label, points },
            });
        }
        let mut note = note.to_owned();
        if !skipped.is_empty() {
            let sep = if note.is_empty() { "" } else { ". " };
            note = format!(
                "{note}{sep}Zero throughout, not drawn: {}",
                skipped.join(", ")
            );
        }

        let mut ranges = Ranges {
            x: self.x_range(&curves),
            y: self.y_range(&curves),
        };
        let legend = legend_size(&curves).map(|size| {
            let (place, covered) = best_place(&curves, ranges, size);
            if covered == 0 || matches!(self.y, YRange::Fixed(..)) {
                return (size, place);
            }
            // Make room above the data.
            let free = f64::from(PLOT.1) - f64::from(size.1 + 2 * LEGEND_INSET);
            let (lo, hi) = ranges.y;
            ranges.y.1 = lo + (hi - lo) * f64::from(PLOT.1) / free.max(1.0);
            (size, best_place(&curves, ranges, size).0)
        });
        let mut svg = String::new();
        self.draw(&mut svg, &curves, ranges, &note, legend)
            .map_err(|e| FigureError::Draw {
                name: self.name,
                message: e.to_string(),
            })?;
        Ok(svg)
    }

    /// The title.
    fn title(&self) -> String {
        if self.last {
            format!("{} in the last training episodes", self.metric.title())
        } else {
            format!("{} during training", self.metric.title())
        }
    }

    /// The first episode shown by a zoomed figure: the first evaluation in
    /// the last [`LAST_SHARE`] of the episodes. `None` for the others.
    fn first_episode(&self, series: &[Series]) -> Option<f64> {
        if !self.last {
            return None;
        }
        let episodes = || {
            series
                .iter()
                .flat_map(|s| s.points.iter().map(|p| p.episode))
        };
        let first = episodes().min_by(f64::total_cmp)?;
        let last = episodes().max_by(f64::total_cmp)?;
        Some(last - LAST_SHARE * (last - first))
    }

    /// From the first episode shown to the last.
    fn x_range(&self, curves: &[Curve]) -> (f64, f64) {
        let episodes = curves
            .iter()
            .flat_map(|c| c.series.points.iter().map(|p| p.episode));
        let lo = episodes.clone().min_by(f64::total_cmp).unwrap_or(0.0);
        let hi = episodes.max_by(f64::total_cmp).unwrap_or(1.0);
        if hi > lo {
            (lo, hi)
        } else {
            (lo - 1.0, lo + 1.0)
        }
    }

    /// The y range of the figure's kind over every known value.
    fn y_range(&self, curves: &[Curve]) -> (f64, f64) {
        let values = curves
            .iter()
            .flat_map(|c| &c.series.points)
            .flat_map(|p| [p.mean, p.low, p.high])
            .flatten();
        let lo = values.clone().min_by(f64::total_cmp);
        let hi = values.max_by(f64::total_cmp);
        match self.y {
            YRange::Fixed(lo, hi) => (lo, hi),
            YRange::FromZero => {
                let hi = hi.unwrap_or(0.0) * 1.08;
                (0.0, if hi > 0.0 { hi } else { 1.0 })
            }
            YRange::Fitted(ceiling) => {
                let (Some(min), Some(max)) = (lo, hi) else {
                    return (0.0, ceiling.unwrap_or(1.0));
                };
                let margin = ((max - min) * 0.08).max(0.5);
                let lo = (min - margin).max(0.0);
                let hi = max + margin;
                (lo, ceiling.map_or(hi, |c| hi.min(c).max(lo + 1.0)))
            }
        }
    }

    /// Draws the figure into `svg`, with the legend of the given size in
    /// its corner.
    fn draw(
        &self,
        svg: &mut String,
        curves: &[Curve],
        ranges: Ranges,
        note: &str,
        legend: Option<((i32, i32), (i32, i32))>,
    ) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
        let root = SVGBackend::with_string(svg, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        let (head, body) = root.split_vertically(HEADER_H);
        draw_header(&head, &self.title(), note)?;

        let mut chart = ChartBuilder::on(&body)
            .margin_top(MARGIN.0)
            .margin_right(MARGIN.1)
            .margin_bottom(MARGIN.2)
            .margin_left(MARGIN.3)
            .x_label_area_size(X_LABELS_H)
            .y_label_area_size(Y_LABELS_W)
            .build_cartesian_2d(ranges.x.0..ranges.x.1, ranges.y.0..ranges.y.1)?;
        debug_assert_eq!(chart.plotting_area().dim_in_pixel(), PLOT);
        let x_decimals = decimals(ranges.x.1 - ranges.x.0);
        let y_decimals = decimals(ranges.y.1 - ranges.y.0);
        chart
            .configure_mesh()
            .x_desc("Training episodes")
            .y_desc(self.metric.axis())
            .axis_desc_style(font(16.0, &INK))
            .label_style(font(14.0, &MUTED))
            .axis_style(AXIS)
            .bold_line_style(GRID)
            .light_line_style(TRANSPARENT)
            .x_labels(11)
            .y_labels(11)
            .x_label_formatter(&|x| format!("{x:.x_decimals$}"))
            .y_label_formatter(&|y| format!("{y:.y_decimals$}"))
            .draw()?;

        let clamp = |y: f64| y.clamp(ranges.y.0, ranges.y.1);
        for c in curves {
            for run in runs(&c.series.points, |p| p.low.zip(p.high)) {
                let upper = run.iter().map(|&(x, (_, hi))| (x, clamp(hi)));
                let lower = run.iter().rev().map(|&(x, (lo, _))| (x, clamp(lo)));
                let outline: Vec<_> = upper.chain(lower).collect();
                let fill = c.colour.mix(BAND_ALPHA).filled();
                chart.draw_series([Polygon::new(outline, fill)])?;
            }
        }
        for c in curves {
            for run in runs(&c.series.points, |p| p.mean) {
                if let [point] = run[..] {
                    chart.draw_series([Circle::new(point, 3, c.colour.filled())])?;
                } else {
                    let style = c.colour.stroke_width(LINE_WIDTH);
                    chart.draw_series([PathElement::new(run, style)])?;
                }
            }
        }
        if let Some((size, place)) = legend {
            let area = chart.plotting_area().strip_coord_spec();
            draw_legend(&area, curves, size, place)?;
        }
        root.present()
    }
}

/// Draws the title and, below it, the note, aligned with the plotting area.
fn draw_header(
    head: &DrawingArea<SVGBackend<'_>, Shift>,
    title: &str,
    note: &str,
) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
    let left = (MARGIN.3 + Y_LABELS_W) as i32;
    let anchor = Pos::new(HPos::Left, VPos::Center);
    let title_style = (FONT, 20.0 * 1.24, FontStyle::Bold)
        .into_font()
        .color(&INK)
        .pos(anchor);
    head.draw(&Text::new(title, (left, 22), title_style))?;
    head.draw(&Text::new(note, (left, 47), font(14.0, &MUTED).pos(anchor)))
}

/// Size of the legend of `curves` in pixels, `None` without curves.
fn legend_size(curves: &[Curve]) -> Option<(i32, i32)> {
    // A generous average glyph width: DejaVu Sans is wide.
    let chars = curves
        .iter()
        .map(|c| c.series.label.chars().count())
        .max()?;
    let text = (chars as f64 * 0.62 * LEGEND_TEXT).ceil() as i32;
    Some((
        2 * LEGEND_PAD + LEGEND_SWATCH + LEGEND_GAP + text,
        2 * LEGEND_PAD + LEGEND_LINE * (curves.len() as i32 - 1) + 18,
    ))
}

/// Where a legend of `size` may go in the plotting area (its top-left
/// pixel), best first: the upper left, upper right, lower right and lower
/// left corners, then down the left and right edges.
fn legend_places(size: (i32, i32)) -> Vec<(i32, i32)> {
    let left = LEGEND_INSET;
    let right = PLOT.0 as i32 - LEGEND_INSET - size.0;
    let top = LEGEND_INSET;
    let bottom = PLOT.1 as i32 - LEGEND_INSET - size.1;
    let mut places = vec![(left, top), (right, top), (right, bottom), (left, bottom)];
    for y in (top..bottom).step_by(10).skip(1) {
        places.extend([(left, y), (right, y)]);
    }
    places
}

/// The first of the [`legend_places`] where a legend of `size` covers the
/// least data, and how much it covers (samples of lines and bands under it).
fn best_place(curves: &[Curve], ranges: Ranges, size: (i32, i32)) -> ((i32, i32), usize) {
    let (w, h) = (f64::from(PLOT.0), f64::from(PLOT.1));
    let to_x = |px: i32| ranges.x.0 + (ranges.x.1 - ranges.x.0) * f64::from(px) / w;
    let to_y = |px: i32| ranges.y.1 - (ranges.y.1 - ranges.y.0) * f64::from(px) / h;
    // Pixels kept free above and below the legend.
    const CLEAR: i32 = 8;
    legend_places(size)
        .into_iter()
        .map(|(left, top)| {
            let (x0, x1) = (to_x(left), to_x(left + size.0));
            let (y0, y1) = (to_y(top + size.1 + CLEAR), to_y(top - CLEAR));
            let covered = (0..=32)
                .map(|i| x0 + (x1 - x0) * f64::from(i) / 32.0)
                .flat_map(|x| {
                    curves
                        .iter()
                        .filter_map(move |c| extent_at(&c.series.points, x))
                })
                .filter(|&(lo, hi)| lo <= y1 && hi >= y0)
                .count();
            ((left, top), covered)
        })
        .min_by_key(|&(_, covered)| covered)
        .expect("four corners at least")
}

/// The vertical extent of a series' line and band at episode `x`,
/// interpolated between the evaluations around it.
fn extent_at(points: &[SeriesPoint], x: f64) -> Option<(f64, f64)> {
    let i = points.iter().position(|p| p.episode >= x)?;
    let b = &points[i];
    let a = if b.episode == x || i == 0 {
        b
    } else {
        &points[i - 1]
    };
    let t = if b.episode > a.episode {
        (x - a.episode) / (b.episode - a.episode)
    } else {
        0.0
    };
    let at = |f: fn(&SeriesPoint) -> Option<f64>| Some(f(a)? + (f(b)? - f(a)?) * t);
    let known = [at(|p| p.mean), at(|p| p.low), at(|p| p.high)]
        .into_iter()
        .flatten();
    let lo = known.clone().min_by(f64::total_cmp)?;
    let hi = known.max_by(f64::total_cmp)?;
    Some((lo, hi))
}

/// Draws the legend of `curves` (`size` pixels, top left at `place`) on
/// `area`.
fn draw_legend(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    curves: &[Curve],
    size: (i32, i32),
    (left, top): (i32, i32),
) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
    let frame = [(left, top), (left + size.0, top + size.1)];
    area.draw(&Rectangle::new(frame, WHITE.mix(0.9).filled()))?;
    area.draw(&Rectangle::new(frame, FRAME.stroke_width(1)))?;
    let text = font(LEGEND_TEXT, &INK).pos(Pos::new(HPos::Left, VPos::Center));
    for (i, c) in curves.iter().enumerate() {
        let y = top + LEGEND_PAD + 9 + LEGEND_LINE * i as i32;
        let x = left + LEGEND_PAD;
        let band = [(x, y - 7), (x + LEGEND_SWATCH, y + 7)];
        area.draw(&Rectangle::new(band, c.colour.mix(BAND_ALPHA).filled()))?;
        let line = vec![(x, y), (x + LEGEND_SWATCH, y)];
        area.draw(&PathElement::new(
            line,
            c.colour.stroke_width(LINE_WIDTH + 1),
        ))?;
        let at = (x + LEGEND_SWATCH + LEGEND_GAP, y);
        area.draw(&Text::new(c.series.label.as_str(), at, text.clone()))?;
    }
    Ok(())
}

/// The maximal runs of consecutive points where `value` is known, as
/// `(episode, value)`: a gap wherever it is not.
fn runs<T>(
    points: &[SeriesPoint],
    value: impl Fn(&SeriesPoint) -> Option<T>,
) -> Vec<Vec<(f64, T)>> {
    let mut runs = Vec::new();
    let mut run = Vec::new();
    for p in points {
        match value(p) {
            Some(v) => run.push((p.episode, v)),
            None if !run.is_empty() => runs.push(std::mem::take(&mut run)),
            None => {}
        }
    }
    if !run.is_empty() {
        runs.push(run);
    }
    runs
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An estimate of `mean` ± 5, or all unknown.
    fn estimate(mean: Option<f64>) -> Estimate {
        Estimate {
            n: 3,
            mean,
            ci_low: mean.map(|m| m - 5.0),
            ci_high: mean.map(|m| m + 5.0),
        }
    }

    /// A set whose goal percentage is `goal` at episodes 0, 100, 200, ...
    fn set(label: &str, goal: &[Option<f64>]) -> SeriesSet {
        SeriesSet {
            label: label.to_owned(),
            runs: 3,
            ci_level: 0.95,
            points: goal
                .iter()
                .enumerate()
                .map(|(i, &g)| SummaryPoint {
                    episode: 100 * i as u64,
                    goal_pct: estimate(g),
                    time_to_goal: estimate(g.map(|g| 120.0 - g)),
                    spent_budget: estimate(Some(10.0 * i as f64)),
                })
                .collect(),
        }
    }

    #[test]
    fn writes_every_figure_as_svg_and_png() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("figures");
        let sets = [
            set("NoAdvice", &[Some(5.0), Some(20.0), Some(30.0), Some(35.0)]),
            set("AdHocTD", &[Some(5.0), Some(25.0), Some(40.0), Some(45.0)]),
        ];
        let written = write_figures(&out, &sets).unwrap();
        let names = ["goal_pct", "time_to_goal", "spent_budget", "goal_pct_last"];
        assert_eq!(written.len(), 2 * names.len());
        for (name, axis) in names.iter().zip([
            "Goal percentage (%)",
            "Time to goal (frames)",
            "Spent budget (advice given, per agent)",
            "Goal percentage (%)",
        ]) {
            let svg_path = out.join(format!("{name}.svg"));
            let png_path = out.join(format!("{name}.png"));
            assert!(written.contains(&svg_path) && written.contains(&png_path));
            let svg = std::fs::read_to_string(&svg_path).unwrap();
            for text in ["NoAdvice", "AdHocTD", "Training episodes", axis] {
                assert!(svg.contains(text), "{name}.svg lacks {text:?}");
            }
            let png = std::fs::read(&png_path).unwrap();
            assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"), "{name}.png");
            assert!(!out.join(format!("{name}.png.tmp")).exists());
        }
    }

    #[test]
    fn unknown_means_leave_gaps_not_zeros() {
        let s = set(
            "Gappy",
            &[Some(40.0), Some(50.0), None, Some(60.0), Some(70.0)],
        );
        let series = s.series(Metric::GoalPct);
        assert_eq!(
            runs(&series.points, |p| p.mean),
            [
                vec![(0.0, 40.0), (100.0, 50.0)],
                vec![(300.0, 60.0), (400.0, 70.0)]
            ]
        );
        let svg = FIGURES[0].svg(&[series], "").unwrap();
        // Two lines of two points each, all above the 35% level.
        let y_at = |v: f64| f64::from(HEADER_H + MARGIN.0 + PLOT.1) - v / 100.0 * f64::from(PLOT.1);
        let lines: Vec<Vec<f64>> = svg
            .lines()
            .filter(|l| {
                l.starts_with("<polyline") && l.contains("stroke=\"#0072B2\" stroke-width=\"2\"")
            })
            .map(|l| {
                let points = l
                    .split("points=\"")
                    .nth(1)
                    .unwrap()
                    .split('"')
                    .next()
                    .unwrap();
                let ys = points
                    .split_whitespace()
                    .map(|xy| xy.split(',').nth(1).unwrap());
                ys.map(|y| y.parse().unwrap()).collect()
            })
            .collect();
        assert_eq!(lines.len(), 2, "{lines:?}");
        for y in lines.iter().flatten() {
            assert!(*y < y_at(35.0), "{y} is below 35%: {lines:?}");
        }
    }

    #[test]
    fn reads_summary_json_with_nulls() {
        let json = r#"{"format":1,"seed":1,"runs":2,"ci_level":0.9,"config":{},
            "eval_points":[{"episode":0,
              "goal_pct":{"n":2,"mean":0.0,"ci_low":0.0,"ci_high":0.0},
              "time_to_goal":{"n":0,"mean":null,"ci_low":null,"ci_high":null},
              "spent_budget":{"n":2,"mean":1.5,"ci_low":null,"ci_high":null}}]}"#;
        let set = SeriesSet::from_json("X", json).unwrap();
        assert_eq!((set.runs, set.ci_level), (2, 0.9));
        let point = |m| set.series(m).points[0];
        assert_eq!(point(Metric::TimeToGoal).mean, None);
        assert_eq!(point(Metric::GoalPct).mean, Some(0.0));
        assert_eq!(point(Metric::SpentBudget).high, None);
        assert_eq!(
            note(&[set]),
            "Mean over 2 runs; shaded: 90% confidence interval"
        );
    }

    #[test]
    fn zoomed_figure_shows_the_last_episodes_fitted() {
        let s = set(
            "A",
            &[
                Some(0.0),
                Some(10.0),
                Some(20.0),
                Some(30.0),
                Some(40.0),
                Some(42.0),
            ],
        );
        let series = [s.series(Metric::GoalPct)];
        let zoom = &FIGURES[3];
        assert_eq!(zoom.first_episode(&series), Some(400.0));
        assert_eq!(FIGURES[0].first_episode(&series), None);
        let shown: Vec<_> = series[0].points[4..].to_vec();
        let (lo, hi) = zoom.y_range(&[curve("A", shown)]);
        assert!(
            lo > 30.0 && lo < 35.0 && hi > 47.0 && hi < 50.0,
            "{lo}..{hi}"
        );
        // Drawn, the zoomed figure's x axis starts at episode 400.
        let svg = zoom.svg(&series, "").unwrap();
        assert!(svg.contains(">\n400\n</text>") && !svg.contains(">\n300\n</text>"));
    }

    #[test]
    fn never_advising_curves_are_named_not_drawn() {
        let mut silent = set("NoAdvice", &[Some(1.0), Some(2.0), Some(3.0)]);
        for p in &mut silent.points {
            p.spent_budget = Estimate {
                n: 3,
                mean: Some(0.0),
                ci_low: Some(0.0),
                ci_high: Some(0.0),
            };
        }
        let advising = set("AdHocTD", &[Some(1.0), Some(2.0), Some(3.0)]);
        let series = [
            silent.series(Metric::SpentBudget),
            advising.series(Metric::SpentBudget),
        ];
        let svg = FIGURES[2].svg(&series, "Mean over 3 runs").unwrap();
        assert!(svg.contains("Mean over 3 runs. Zero throughout, not drawn: NoAdvice"));
        assert!(!svg.contains("#0072B2"), "the first colour is not drawn");
        assert!(svg.contains("#D55E00"), "the second keeps its colour");
        // In the goal percentage, both are drawn.
        let series = [
            silent.series(Metric::GoalPct),
            advising.series(Metric::GoalPct),
        ];
        assert!(FIGURES[0].svg(&series, "").unwrap().contains("#0072B2"));
    }

    /// A curve in the first colour.
    fn curve(label: &str, points: Vec<SeriesPoint>) -> Curve {
        let label = label.to_owned();
        Curve {
            colour: PALETTE[0],
            series: Series { label, points },
        }
    }

    #[test]
    fn legend_avoids_the_data() {
        let goal = |g: &[Option<f64>]| curve("Curve", set("", g).series(Metric::GoalPct).points);
        let ranges = Ranges {
            x: (0.0, 300.0),
            y: (0.0, 100.0),
        };
        // Rising curves leave the upper left free.
        let rising = [goal(&[Some(0.0), Some(50.0), Some(90.0), Some(95.0)])];
        let size = legend_size(&rising).unwrap();
        let places = legend_places(size);
        assert_eq!(best_place(&rising, ranges, size), (places[0], 0));
        // High ones leave the bottom free.
        let high = [goal(&[Some(90.0); 4])];
        assert_eq!(best_place(&high, ranges, size), (places[2], 0));
        // High and low ones, the middle of the left edge.
        let both = [goal(&[Some(90.0); 4]), goal(&[Some(5.0); 4])];
        let size = legend_size(&both).unwrap();
        let ((left, top), covered) = best_place(&both, ranges, size);
        assert_eq!((left, covered), (LEGEND_INSET, 0));
        assert!(top > LEGEND_INSET && top + size.1 < PLOT.1 as i32 - LEGEND_INSET);
        // Covering everything, the first corner.
        let wide = [curve(
            "Wide",
            vec![
                SeriesPoint {
                    episode: 0.0,
                    mean: Some(50.0),
                    low: Some(0.0),
                    high: Some(100.0),
                },
                SeriesPoint {
                    episode: 300.0,
                    mean: Some(50.0),
                    low: Some(0.0),
                    high: Some(100.0),
                },
            ],
        )];
        let (place, covered) = best_place(&wide, ranges, size);
        assert_eq!(place, legend_places(size)[0]);
        assert!(covered > 0);
    }
}
