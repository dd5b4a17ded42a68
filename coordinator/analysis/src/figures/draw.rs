//! Drawing a laid-out figure with `plotters` (header, then one or more
//! charts with their axes, bands, lines and legend) as an SVG document, and
//! rasterising it to a PNG.

use plotters::coord::Shift;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::data::{Series, SeriesPoint};
use super::layout::{
    HEADER_H, HEADING_H, LEGEND_GAP, LEGEND_LINE, LEGEND_PAD, LEGEND_SWATCH, LEGEND_TEXT, Layout,
    Legend, MARGIN, PLOT, SIZE, Scale, TICKS, X_LABELS_H, Y_LABELS_W, decimals,
};
use super::log_axis::{LogAxis, tick_label};

/// Font families, first available wins (as env-server's pictures).
const FONT: &str = "DejaVu Sans, Liberation Sans, Arial, Helvetica, sans-serif";
/// Okabe-Ito colours, in an order where the first six are far apart
/// (yellow, poor on white, last).
pub(super) const PALETTE: [RGBColor; 8] = [
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

/// The x axis title of the figures over training.
pub(super) const EPISODES_AXIS: &str = "Training episodes";

/// A series as drawn: its colour, the points shown and its marks.
pub(super) struct Curve<'a> {
    /// Line and band colour.
    pub colour: RGBColor,
    /// The points shown.
    pub series: &'a Series,
    /// Points marked on the line.
    pub marks: &'a [Mark],
    /// How its points are drawn.
    pub style: Style,
}

/// How a curve's points are drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Style {
    /// A line through the means in a band of the intervals, with a legend.
    Line,
    /// Each mean a dot with its interval as a whisker, labelled beside it.
    Dots,
    /// Each mean a marker with its intervals as whiskers (on x too, where
    /// x is an estimate), the markers joined in order by a line, with a
    /// legend.
    Path(Marker),
}

/// The shape of a [`Style::Path`] curve's markers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Marker {
    /// A dot.
    Circle,
    /// A square.
    Square,
    /// A diamond.
    Diamond,
    /// A triangle pointing up.
    Triangle,
}

/// The markers, in the order curves take them once [`PALETTE`] is used up.
pub(super) const MARKERS: [Marker; 4] = [
    Marker::Circle,
    Marker::Square,
    Marker::Diamond,
    Marker::Triangle,
];

impl Marker {
    /// The corners of its polygon around its centre (pixels); a circle has
    /// none.
    fn corners(self) -> Vec<(i32, i32)> {
        match self {
            Marker::Circle => Vec::new(),
            Marker::Square => vec![(-4, -4), (4, -4), (4, 4), (-4, 4)],
            Marker::Diamond => vec![(0, -6), (6, 0), (0, 6), (-6, 0)],
            Marker::Triangle => vec![(0, -6), (6, 4), (-6, 4)],
        }
    }
}

/// Radius of a dot, and half the width of a whisker's caps (pixels).
const DOT: i32 = 5;

/// A marked point of a curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Mark {
    /// The x value (training episodes, or whatever x is).
    pub episode: f64,
    /// The value marked.
    pub value: f64,
    /// How it is marked.
    pub shape: MarkShape,
}

/// How a point is marked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum MarkShape {
    /// A triangle pointing up, in the curve's colour.
    Up,
    /// A triangle pointing down, in the curve's colour.
    Down,
    /// A dark ring around the point.
    Ring,
}

/// The texts of a figure above and below its charts.
pub(super) struct Captions<'a> {
    /// The title.
    pub title: &'a str,
    /// The subtitle below it.
    pub note: &'a str,
    /// The x axis title, below the last chart.
    pub x_axis: &'a str,
}

/// One chart of a figure: its curves as laid out, under a heading unless
/// it is the first.
pub(super) struct Panel<'a> {
    /// The curves, in legend order.
    pub curves: &'a [Curve<'a>],
    /// Where the data and the legend go.
    pub layout: Layout,
    /// The y axis title.
    pub y_axis: &'a str,
    /// The line above the chart (not drawn for the first, which has the
    /// title and note above it).
    pub heading: &'a str,
}

impl Panel<'_> {
    /// Height of the chart with its margins and x labels, in pixels.
    fn chart_height(&self) -> u32 {
        MARGIN.0 + self.layout.plot.1 + X_LABELS_H + MARGIN.2
    }
}

/// The figure of `panels` (one chart each, stacked, the x axis title below
/// the last) as an SVG document; the error says what plotters could not
/// draw. With one panel of [`PLOT`](super::layout::PLOT) size, the figure
/// is [`SIZE`].
pub(super) fn svg(captions: &Captions, panels: &[Panel]) -> Result<String, String> {
    let mut svg = String::new();
    draw(&mut svg, captions, panels).map_err(|e| e.to_string())?;
    Ok(svg)
}

/// Rasterises an SVG document to a PNG of its size, with the system's fonts
/// (without any, the PNG has no text); the error says why not.
pub(super) fn png(svg: &str) -> Result<Vec<u8>, String> {
    raster::png(svg).map_err(|e| e.to_string())
}

/// A text style of `px` pixels (plotters' SVG backend writes the size
/// divided by 1.24).
fn font(px: f64, colour: &RGBColor) -> TextStyle<'static> {
    (FONT, px * 1.24).into_font().color(colour)
}

/// Draws the figure into `svg`.
fn draw(
    svg: &mut String,
    captions: &Captions,
    panels: &[Panel],
) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
    let headings = panels.len().saturating_sub(1) as u32 * HEADING_H;
    let charts: u32 = panels.iter().map(Panel::chart_height).sum();
    let root =
        SVGBackend::with_string(svg, (SIZE.0, HEADER_H + headings + charts)).into_drawing_area();
    root.fill(&WHITE)?;
    let (head, mut rest) = root.split_vertically(HEADER_H);
    draw_header(&head, captions.title, captions.note)?;
    for (k, panel) in panels.iter().enumerate() {
        if k > 0 {
            let (heading, below) = rest.split_vertically(HEADING_H);
            draw_heading(&heading, panel.heading)?;
            rest = below;
        }
        let (area, below) = rest.split_vertically(panel.chart_height());
        let last = k + 1 == panels.len();
        draw_chart(&area, panel, last.then_some(captions.x_axis))?;
        rest = below;
    }
    root.present()
}

/// Draws the chart of `panel` on `area`, with the x axis title `x_axis`
/// if any.
fn draw_chart(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    panel: &Panel,
    x_axis: Option<&str>,
) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
    let ranges = panel.layout.ranges;
    let mut builder = ChartBuilder::on(area);
    builder
        .margin_top(MARGIN.0)
        .margin_right(MARGIN.1 + PLOT.0 - panel.layout.plot.0)
        .margin_bottom(MARGIN.2)
        .margin_left(MARGIN.3)
        .x_label_area_size(X_LABELS_H)
        .y_label_area_size(Y_LABELS_W);
    let y = ranges.y.0..ranges.y.1;
    let origin = match ranges.x_scale {
        Scale::Linear => {
            let chart = builder.build_cartesian_2d(ranges.x.0..ranges.x.1, y)?;
            let x_decimals = decimals(ranges.x.1 - ranges.x.0);
            plot(chart, panel, x_axis, &|x: &f64| format!("{x:.x_decimals$}"))?
        }
        Scale::Log => {
            let chart = builder.build_cartesian_2d(LogAxis(ranges.x.0..ranges.x.1), y)?;
            plot(chart, panel, x_axis, &|x: &f64| tick_label(*x))?
        }
    };
    // On the plotting area widened to the whole width: the legend may be
    // beside the plot.
    match &panel.layout.legend {
        Some(legend) => {
            let base = area.get_base_pixel();
            let at = (origin.0 - base.0, origin.1 - base.1);
            let room = area.clone().shrink(at, (PLOT.0, panel.layout.plot.1));
            draw_legend(&room, panel.curves, legend)
        }
        None => Ok(()),
    }
}

/// Draws `panel` but its legend on `chart`, whose x axis is labelled by
/// `x_format`; the plotting area's top-left pixel.
fn plot<X>(
    mut chart: ChartContext<'_, SVGBackend<'_>, Cartesian2d<X, RangedCoordf64>>,
    panel: &Panel,
    x_axis: Option<&str>,
    x_format: &dyn Fn(&f64) -> String,
) -> Result<(i32, i32), DrawingAreaErrorKind<std::io::Error>>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let (layout, curves) = (&panel.layout, panel.curves);
    let ranges = layout.ranges;
    debug_assert_eq!(chart.plotting_area().dim_in_pixel(), layout.plot);
    let y_decimals = decimals(ranges.y.1 - ranges.y.0);
    let y_format = |y: &f64| format!("{y:.y_decimals$}");
    let mut mesh = chart.configure_mesh();
    mesh.y_desc(panel.y_axis)
        .axis_desc_style(font(16.0, &INK))
        .label_style(font(14.0, &MUTED))
        .axis_style(AXIS)
        .bold_line_style(GRID)
        .light_line_style(TRANSPARENT)
        .x_labels(TICKS)
        .y_labels(y_ticks(layout.plot.1))
        .x_label_formatter(x_format)
        .y_label_formatter(&y_format);
    if let Some(x_axis) = x_axis {
        mesh.x_desc(x_axis);
    }
    mesh.draw()?;

    if let Some(y) = layout.rule {
        let rule = vec![(ranges.x.0, y), (ranges.x.1, y)];
        chart.draw_series([PathElement::new(rule, INK.stroke_width(1))])?;
    }
    let clamp = |y: f64| y.clamp(ranges.y.0, ranges.y.1);
    let clamp_x = |x: f64| x.clamp(ranges.x.0, ranges.x.1);
    let lines: Vec<&Curve> = curves.iter().filter(|c| c.style == Style::Line).collect();
    let dots: Vec<&Curve> = curves.iter().filter(|c| c.style == Style::Dots).collect();
    let paths: Vec<&Curve> = (curves.iter())
        .filter(|c| matches!(c.style, Style::Path(_)))
        .collect();
    for c in &lines {
        for run in runs(&c.series.points, |p| p.low.zip(p.high)) {
            let upper = run.iter().map(|&(x, (_, hi))| (x, clamp(hi)));
            let lower = run.iter().rev().map(|&(x, (lo, _))| (x, clamp(lo)));
            let outline: Vec<_> = upper.chain(lower).collect();
            let fill = c.colour.mix(BAND_ALPHA).filled();
            chart.draw_series([Polygon::new(outline, fill)])?;
        }
    }
    for c in &lines {
        for run in runs(&c.series.points, |p| p.mean) {
            if let [point] = run[..] {
                chart.draw_series([Circle::new(point, 3, c.colour.filled())])?;
            } else {
                let style = c.colour.stroke_width(LINE_WIDTH);
                chart.draw_series([PathElement::new(run, style)])?;
            }
        }
    }
    for c in &paths {
        for run in runs(&c.series.points, |p| p.mean) {
            let run: Vec<(f64, f64)> = run.into_iter().map(|(x, y)| (x, clamp(y))).collect();
            chart.draw_series([PathElement::new(run, c.colour.stroke_width(LINE_WIDTH))])?;
        }
    }
    for c in curves {
        // A triangle outlined in white, centred on the mark.
        let triangle = |m: &Mark, up: bool| {
            let (tip, base) = if up { (-7, 4) } else { (7, -4) };
            let corners = vec![(0, tip), (6, base), (-6, base)];
            let outline = vec![(0, tip), (6, base), (-6, base), (0, tip)];
            EmptyElement::at((m.episode, m.value))
                + Polygon::new(corners, c.colour.filled())
                + PathElement::new(outline, WHITE.stroke_width(1))
        };
        let (rings, triangles): (Vec<&Mark>, Vec<&Mark>) =
            c.marks.iter().partition(|m| m.shape == MarkShape::Ring);
        chart
            .draw_series((triangles.into_iter()).map(|m| triangle(m, m.shape == MarkShape::Up)))?;
        chart.draw_series(rings.into_iter().map(|m| {
            let at = (clamp_x(m.episode), clamp(m.value));
            EmptyElement::at(at) + Circle::new((0, 0), DOT + 5, INK.stroke_width(2))
        }))?;
    }
    // Each dot's label beside it, moved down where it would cover another.
    let at = |p: &SeriesPoint| {
        p.mean
            .map(|mean| chart.backend_coord(&(p.episode, clamp(mean))))
    };
    let labelled: Vec<((i32, i32), &str)> = (dots.iter())
        .flat_map(|c| {
            c.series
                .points
                .iter()
                .map(move |p| (p, c.series.label.as_str()))
        })
        .filter_map(|(p, label)| Some((at(p)?, label)))
        .collect();
    let mut shifts = label_shifts(&labelled).into_iter();
    for c in dots.iter().chain(&paths) {
        let stroke = c.colour.stroke_width(2);
        for p in &c.series.points {
            if let (Some(low), Some(high)) = (p.low, p.high) {
                let whisker = |y: f64| (p.episode, clamp(y));
                let cap = |y: f64| {
                    EmptyElement::at(whisker(y))
                        + PathElement::new(vec![(-DOT, 0), (DOT, 0)], stroke)
                };
                let line = PathElement::new(vec![whisker(low), whisker(high)], stroke);
                chart.draw_series([line])?;
                chart.draw_series([cap(low), cap(high)])?;
            }
            if let (Some((low, high)), Some(mean)) = (p.x_interval, p.mean) {
                let whisker = |x: f64| (clamp_x(x), clamp(mean));
                let cap = |x: f64| {
                    EmptyElement::at(whisker(x))
                        + PathElement::new(vec![(0, -DOT), (0, DOT)], stroke)
                };
                let line = PathElement::new(vec![whisker(low), whisker(high)], stroke);
                chart.draw_series([line])?;
                chart.draw_series([cap(low), cap(high)])?;
            }
        }
    }
    for c in &paths {
        let Style::Path(marker) = c.style else {
            continue;
        };
        for p in &c.series.points {
            if let Some(mean) = p.mean {
                let at = (p.episode, clamp(mean));
                draw_marker(chart.plotting_area(), at, marker, c.colour)?;
            }
        }
    }
    for c in &dots {
        let label = font(14.0, &c.colour).pos(Pos::new(HPos::Left, VPos::Center));
        for p in &c.series.points {
            if let Some(mean) = p.mean {
                let shift = shifts.next().unwrap_or_default();
                let dot = EmptyElement::at((p.episode, clamp(mean)))
                    + Circle::new((0, 0), DOT, c.colour.filled())
                    + Text::new(c.series.label.clone(), (DOT + 4, shift), label.clone());
                chart.draw_series([dot])?;
            }
        }
    }
    Ok(chart.plotting_area().get_base_pixel())
}

/// How far down (pixels) to draw each label of `labelled` (a dot's centre
/// and its label, in drawing order) so that none covers another: the
/// highest placed first, each moved down a line at a time while it would.
fn label_shifts(labelled: &[((i32, i32), &str)]) -> Vec<i32> {
    const LINE: i32 = 16;
    // A generous average glyph width: DejaVu Sans is wide.
    let boxed = |((x, y), label): ((i32, i32), &str), shift: i32| {
        let left = x + DOT + 4;
        let width = 8 * label.chars().count() as i32;
        (
            left,
            y + shift - LINE / 2,
            left + width,
            y + shift + LINE / 2,
        )
    };
    let overlap = |a: (i32, i32, i32, i32), b: (i32, i32, i32, i32)| {
        a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
    };
    let mut order: Vec<usize> = (0..labelled.len()).collect();
    order.sort_by_key(|&i| labelled[i].0.1);
    let mut shifts = vec![0; labelled.len()];
    let mut placed = Vec::new();
    for i in order {
        let mut shift = 0;
        while placed
            .iter()
            .any(|&b| overlap(boxed(labelled[i], shift), b))
        {
            shift += LINE;
        }
        shifts[i] = shift;
        placed.push(boxed(labelled[i], shift));
    }
    shifts
}

/// Tick labels on the y axis of a plotting area `height` pixels high: at
/// most [`TICKS`], at least about 40 pixels apart.
fn y_ticks(height: u32) -> usize {
    TICKS.min(height as usize / 40 + 1)
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

/// Draws the heading of a panel below the first, aligned with its plotting
/// area.
fn draw_heading(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    heading: &str,
) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
    let left = (MARGIN.3 + Y_LABELS_W) as i32;
    let style = (FONT, 15.0 * 1.24, FontStyle::Bold)
        .into_font()
        .color(&INK)
        .pos(Pos::new(HPos::Left, VPos::Center));
    area.draw(&Text::new(heading, (left, HEADING_H as i32 / 2 + 2), style))
}

/// Draws the legend of `curves` in its box on `area`.
fn draw_legend(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    curves: &[Curve],
    legend: &Legend,
) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
    let ((left, top), size) = (legend.place, legend.size);
    let frame = [(left, top), (left + size.0, top + size.1)];
    area.draw(&Rectangle::new(frame, WHITE.mix(0.9).filled()))?;
    area.draw(&Rectangle::new(frame, FRAME.stroke_width(1)))?;
    let text = font(LEGEND_TEXT, &INK).pos(Pos::new(HPos::Left, VPos::Center));
    for (i, c) in curves.iter().enumerate() {
        let y = top + LEGEND_PAD + 9 + LEGEND_LINE * i as i32;
        let x = left + LEGEND_PAD;
        let line = vec![(x, y), (x + LEGEND_SWATCH, y)];
        if let Style::Path(marker) = c.style {
            area.draw(&PathElement::new(line, c.colour.stroke_width(LINE_WIDTH)))?;
            draw_marker(area, (x + LEGEND_SWATCH / 2, y), marker, c.colour)?;
        } else {
            let band = [(x, y - 7), (x + LEGEND_SWATCH, y + 7)];
            area.draw(&Rectangle::new(band, c.colour.mix(BAND_ALPHA).filled()))?;
            let style = c.colour.stroke_width(LINE_WIDTH + 1);
            area.draw(&PathElement::new(line, style))?;
        }
        let at = (x + LEGEND_SWATCH + LEGEND_GAP, y);
        area.draw(&Text::new(c.series.label.as_str(), at, text.clone()))?;
    }
    Ok(())
}

/// Draws `marker` in `colour` centred at `at` on `area`.
fn draw_marker<CT: CoordTranslate>(
    area: &DrawingArea<SVGBackend<'_>, CT>,
    at: CT::From,
    marker: Marker,
    colour: RGBColor,
) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
    let corners = marker.corners();
    if corners.is_empty() {
        area.draw(&(EmptyElement::at(at) + Circle::new((0, 0), DOT, colour.filled())))
    } else {
        area.draw(&(EmptyElement::at(at) + Polygon::new(corners, colour.filled())))
    }
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

    #[test]
    fn labels_that_would_cover_one_another_move_down_a_line() {
        // Two dots at the same place, a third far away, a fourth just below.
        let labelled = [
            ((100, 200), "adhoc-td"),
            ((100, 200), "psaf"),
            ((600, 200), "torrey"),
            ((102, 210), "advice-reuse"),
        ];
        assert_eq!(label_shifts(&labelled), vec![0, 16, 0, 32]);
    }

    use super::super::data::Metric;
    use super::super::fixtures::set;
    use super::*;

    #[test]
    fn unknown_means_split_the_line() {
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
        assert!(runs(&series.points[2..3], |p| p.mean).is_empty());
    }

    #[test]
    fn rasterises_to_a_png_and_rejects_what_is_not_svg() {
        let svg = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\"/>",
            SIZE.0, SIZE.1
        );
        assert!(png(&svg).unwrap().starts_with(b"\x89PNG\r\n\x1a\n"));
        assert!(png("not svg").is_err());
    }
}
