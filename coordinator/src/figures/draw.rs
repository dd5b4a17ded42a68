//! Drawing a laid-out figure with `plotters` (header, axes, bands, lines,
//! legend) as an SVG document, and rasterising it to a PNG.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::data::{Series, SeriesPoint};
use super::layout::{
    HEADER_H, LEGEND_GAP, LEGEND_LINE, LEGEND_PAD, LEGEND_SWATCH, LEGEND_TEXT, Layout, Legend,
    MARGIN, PLOT, SIZE, TICKS, X_LABELS_H, Y_LABELS_W, decimals,
};

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
}

/// A marked point of a curve: a triangle pointing up or down.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Mark {
    /// Training episodes (the x value).
    pub episode: f64,
    /// The value marked.
    pub value: f64,
    /// Up (else down).
    pub up: bool,
}

/// The texts of a figure besides its legend.
pub(super) struct Captions<'a> {
    /// The title.
    pub title: &'a str,
    /// The subtitle below it.
    pub note: &'a str,
    /// The x axis title.
    pub x_axis: &'a str,
    /// The y axis title.
    pub y_axis: &'a str,
}

/// The figure of `curves` laid out by `layout`, as an SVG document; the
/// error says what plotters could not draw.
pub(super) fn svg(
    captions: &Captions,
    curves: &[Curve],
    layout: &Layout,
) -> Result<String, String> {
    let mut svg = String::new();
    draw(&mut svg, captions, curves, layout).map_err(|e| e.to_string())?;
    Ok(svg)
}

/// Rasterises an SVG document to a PNG of its size, with the system's fonts
/// (without any, the PNG has no text); the error says why not.
pub(super) fn png(svg: &str) -> Result<Vec<u8>, String> {
    node::files::svg_to_png(svg).map_err(|e| e.to_string())
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
    curves: &[Curve],
    layout: &Layout,
) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
    let ranges = layout.ranges;
    let root = SVGBackend::with_string(svg, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let (head, body) = root.split_vertically(HEADER_H);
    draw_header(&head, captions.title, captions.note)?;

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
        .x_desc(captions.x_axis)
        .y_desc(captions.y_axis)
        .axis_desc_style(font(16.0, &INK))
        .label_style(font(14.0, &MUTED))
        .axis_style(AXIS)
        .bold_line_style(GRID)
        .light_line_style(TRANSPARENT)
        .x_labels(TICKS)
        .y_labels(TICKS)
        .x_label_formatter(&|x| format!("{x:.x_decimals$}"))
        .y_label_formatter(&|y| format!("{y:.y_decimals$}"))
        .draw()?;

    if let Some(y) = layout.rule {
        let rule = vec![(ranges.x.0, y), (ranges.x.1, y)];
        chart.draw_series([PathElement::new(rule, INK.stroke_width(1))])?;
    }
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
    for c in curves {
        // A triangle outlined in white, centred on the mark.
        let triangle = |m: &Mark| {
            let (tip, base) = if m.up { (-7, 4) } else { (7, -4) };
            let corners = vec![(0, tip), (6, base), (-6, base)];
            let outline = vec![(0, tip), (6, base), (-6, base), (0, tip)];
            EmptyElement::at((m.episode, m.value))
                + Polygon::new(corners, c.colour.filled())
                + PathElement::new(outline, WHITE.stroke_width(1))
        };
        chart.draw_series(c.marks.iter().map(triangle))?;
    }
    if let Some(legend) = &layout.legend {
        let area = chart.plotting_area().strip_coord_spec();
        draw_legend(&area, curves, legend)?;
    }
    root.present()
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
