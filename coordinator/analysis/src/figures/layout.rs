//! Where things go: the page's areas, the data ranges of a chart, tick
//! labels, the zoom window and the legend's size and place.

use super::data::{Series, SeriesPoint};

/// Width and height of every figure, in pixels.
pub const SIZE: (u32, u32) = (1000, 600);
/// Height of the header: the title, and the note below it.
pub(super) const HEADER_H: u32 = 64;
/// Margins around the chart (top, right, bottom, left).
pub(super) const MARGIN: (u32, u32, u32, u32) = (6, 30, 10, 12);
/// Height of the x tick labels and axis title.
pub(super) const X_LABELS_H: u32 = 54;
/// Width of the y tick labels and axis title.
pub(super) const Y_LABELS_W: u32 = 84;
/// Size of the plotting area.
pub(super) const PLOT: (u32, u32) = (
    SIZE.0 - MARGIN.1 - MARGIN.3 - Y_LABELS_W,
    SIZE.1 - HEADER_H - MARGIN.0 - MARGIN.2 - X_LABELS_H,
);
/// Tick labels on each axis, at most.
pub(super) const TICKS: usize = 11;
/// Height of the heading above a chart below the first.
pub(super) const HEADING_H: u32 = 30;

/// Legend text size (pixels).
pub(super) const LEGEND_TEXT: f64 = 15.0;
/// Legend line height (pixels).
pub(super) const LEGEND_LINE: i32 = 25;
/// Legend inner padding (pixels).
pub(super) const LEGEND_PAD: i32 = 10;
/// Width of a legend swatch (pixels).
pub(super) const LEGEND_SWATCH: i32 = 30;
/// Gap between a legend swatch and its text (pixels).
pub(super) const LEGEND_GAP: i32 = 9;
/// Distance of the legend from the plot's edges (pixels).
pub(super) const LEGEND_INSET: i32 = 12;

/// Share of the training episodes the zoomed figure shows.
const LAST_SHARE: f64 = 0.2;

/// How a figure's y range is chosen.
#[derive(Clone, Copy, Debug)]
pub(super) enum YRange {
    /// Always these bounds.
    Fixed(f64, f64),
    /// From zero to the largest value, with a margin.
    FromZero,
    /// Around the values with a margin, within zero and the ceiling.
    Fitted(Option<f64>),
    /// Around the values and this reference, with a margin, marked by a
    /// horizontal line (a difference's zero).
    Around(f64),
}

/// How the x axis maps its values to the page.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Scale {
    /// In proportion to the values.
    Linear,
    /// In proportion to their logarithms (positive values only).
    Log,
}

impl Scale {
    /// Where `x` lies along the axis, up to an affine map.
    fn of(self, x: f64) -> f64 {
        match self {
            Scale::Linear => x,
            Scale::Log => x.ln(),
        }
    }
}

/// Data ranges of a chart.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Ranges {
    /// Episodes, or whatever x is.
    pub x: (f64, f64),
    /// Metric values.
    pub y: (f64, f64),
    /// How x is drawn.
    pub x_scale: Scale,
}

impl Ranges {
    /// The x value `fraction` of the way along the axis.
    fn x_at(&self, fraction: f64) -> f64 {
        let (lo, hi) = (self.x_scale.of(self.x.0), self.x_scale.of(self.x.1));
        let at = lo + (hi - lo) * fraction;
        match self.x_scale {
            Scale::Linear => at,
            Scale::Log => at.exp(),
        }
    }
}

/// The legend's box in the plotting area, in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Legend {
    /// Width and height.
    pub size: (i32, i32),
    /// Top-left corner.
    pub place: (i32, i32),
}

/// Where a chart's data and legend go.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Layout {
    /// The data ranges of the axes.
    pub ranges: Ranges,
    /// The legend, `None` without curves.
    pub legend: Option<Legend>,
    /// The value of a horizontal reference line, if any.
    pub rule: Option<f64>,
    /// Size of the plotting area, in pixels.
    pub plot: (u32, u32),
}

impl Layout {
    /// The layout of the curves `shown` with y range rule `y` in a figure's
    /// plotting area ([`PLOT`]).
    pub(super) fn of(shown: &[Series], y: YRange) -> Self {
        Self::sized(shown, y, PLOT)
    }

    /// The layout of `shown` with y range rule `y` and no legend (each
    /// curve labelled where it is drawn).
    pub(super) fn unlabelled(shown: &[Series], y: YRange) -> Self {
        Self {
            ranges: Ranges {
                x: x_range(shown),
                y: y_range(y, shown),
                x_scale: Scale::Linear,
            },
            legend: None,
            rule: match y {
                YRange::Around(reference) => Some(reference),
                _ => None,
            },
            plot: PLOT,
        }
    }

    /// The layout of the curves `shown` with y range rule `y` in a plotting
    /// area of `plot` pixels: the legend where it covers the least data; if
    /// it covers some and the range is not fixed, the y range grows to make
    /// room above the data.
    pub(super) fn sized(shown: &[Series], y: YRange, plot: (u32, u32)) -> Self {
        let ranges = Ranges {
            x: x_range(shown),
            y: y_range(y, shown),
            x_scale: Scale::Linear,
        };
        Self::placed(shown, y, ranges, plot)
    }

    /// The layout of `shown`, whose x values are positive and span orders
    /// of magnitude, on a logarithmic x axis, with y range rule `y`, in a
    /// figure's plotting area ([`PLOT`]); the legend placed as
    /// [`Layout::sized`] places it.
    pub(super) fn log_x(shown: &[Series], y: YRange) -> Self {
        let ranges = Ranges {
            x: log_range(shown),
            y: y_range(y, shown),
            x_scale: Scale::Log,
        };
        Self::placed(shown, y, ranges, PLOT)
    }

    /// The layout of `shown` in `ranges` with the legend where it covers
    /// the least data (see [`Layout::sized`]); a legend too tall to make
    /// room above the data without squashing it to less than half the
    /// height goes beside the plotting area, which narrows, if it fits
    /// there in half the width.
    fn placed(shown: &[Series], y: YRange, mut ranges: Ranges, mut plot: (u32, u32)) -> Self {
        let legend = legend_size(shown).map(|size| {
            let (place, covered) = best_place(shown, ranges, size, plot);
            if covered == 0 || matches!(y, YRange::Fixed(..)) {
                return Legend { size, place };
            }
            let tall = size.1 + 2 * LEGEND_INSET;
            let fits_beside = tall <= plot.1 as i32 && 2 * beside_width(size.0) >= plot.0;
            if 2 * tall > plot.1 as i32 && fits_beside {
                plot.0 = beside_width(size.0);
                return Legend::beside(size, plot.0);
            }
            let free = f64::from(plot.1) - f64::from(size.1 + 2 * LEGEND_INSET);
            let (lo, hi) = ranges.y;
            ranges.y.1 = lo + (hi - lo) * f64::from(plot.1) / free.max(1.0);
            Legend {
                size,
                place: best_place(shown, ranges, size, plot).0,
            }
        });
        let rule = match y {
            YRange::Around(reference) => Some(reference),
            _ => None,
        };
        Self {
            ranges,
            legend,
            rule,
            plot,
        }
    }
}

impl Legend {
    /// A legend of `size` beside a plotting area `width` pixels wide, at
    /// its top.
    fn beside(size: (i32, i32), width: u32) -> Self {
        Self {
            size,
            place: (width as i32 + LEGEND_INSET, LEGEND_INSET),
        }
    }
}

/// The width of a figure's plotting area with a legend `width` pixels
/// wide beside it.
fn beside_width(width: i32) -> u32 {
    PLOT.0.saturating_sub((width + LEGEND_INSET) as u32)
}

/// Lays out charts stacked over one x axis alike: when one has its legend
/// beside its plotting area, every one has, and their plotting areas are
/// as wide as the widest legend leaves.
pub(super) fn align(layouts: &mut [&mut Layout]) {
    let beside = |l: &Layout| l.legend.is_some_and(|g| g.place.0 >= l.plot.0 as i32);
    if !layouts.iter().any(|l| beside(l)) {
        return;
    }
    let widest = (layouts.iter().filter_map(|l| l.legend))
        .map(|g| g.size.0)
        .max()
        .unwrap_or_default();
    for layout in layouts {
        layout.plot.0 = beside_width(widest);
        layout.legend = (layout.legend).map(|g| Legend::beside(g.size, layout.plot.0));
    }
}

/// The first episode a zoomed figure shows: the start of the last
/// [`LAST_SHARE`] of the episodes of `series`; `None` without points.
pub(super) fn zoom_start(series: &[Series]) -> Option<f64> {
    let episodes = || {
        series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.episode))
    };
    let first = episodes().min_by(f64::total_cmp)?;
    let last = episodes().max_by(f64::total_cmp)?;
    Some(last - LAST_SHARE * (last - first))
}

/// Decimals that tell apart ticks over a range of `span`.
pub(super) fn decimals(span: f64) -> usize {
    if span >= 10.0 {
        0
    } else if span >= 1.0 {
        1
    } else {
        2
    }
}

/// From the first episode shown to the last.
fn x_range(shown: &[Series]) -> (f64, f64) {
    let episodes = shown
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.episode));
    let lo = episodes.clone().min_by(f64::total_cmp).unwrap_or(0.0);
    let hi = episodes.max_by(f64::total_cmp).unwrap_or(1.0);
    if hi > lo {
        (lo, hi)
    } else {
        (lo - 1.0, lo + 1.0)
    }
}

/// Share of the decades shown left free at each end of a logarithmic axis.
const LOG_MARGIN: f64 = 0.06;

/// The least ratio of the ends of a logarithmic axis.
const LOG_LEAST: f64 = 3.0;

/// From the least positive x shown (a point's or its interval's) to the
/// greatest, on a logarithmic axis: spanning a ratio of at least
/// [`LOG_LEAST`], with a margin; 1 to 10 without any.
fn log_range(shown: &[Series]) -> (f64, f64) {
    let xs = (shown.iter().flat_map(|s| &s.points))
        .flat_map(|p| {
            let (lo, hi) = p.x_interval.unzip();
            [Some(p.episode), lo, hi]
        })
        .flatten()
        .filter(|x| *x > 0.0 && x.is_finite());
    let (Some(lo), Some(hi)) = (xs.clone().min_by(f64::total_cmp), xs.max_by(f64::total_cmp))
    else {
        return (1.0, 10.0);
    };
    let (lo, hi) = (lo.log10(), hi.log10());
    let span = (hi - lo).max(LOG_LEAST.log10());
    let half = span / 2.0 + span * LOG_MARGIN;
    let middle = (lo + hi) / 2.0;
    (10f64.powf(middle - half), 10f64.powf(middle + half))
}

/// The y range by `rule` over every known value shown.
fn y_range(rule: YRange, shown: &[Series]) -> (f64, f64) {
    let values = shown
        .iter()
        .flat_map(|s| &s.points)
        .flat_map(|p| [p.mean, p.low, p.high])
        .flatten();
    let lo = values.clone().min_by(f64::total_cmp);
    let hi = values.max_by(f64::total_cmp);
    match rule {
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
        YRange::Around(reference) => {
            let min = lo.map_or(reference, |lo| lo.min(reference));
            let max = hi.map_or(reference, |hi| hi.max(reference));
            let margin = ((max - min) * 0.08).max(0.5);
            (min - margin, max + margin)
        }
    }
}

/// Size of the legend of `shown` in pixels, `None` without curves.
fn legend_size(shown: &[Series]) -> Option<(i32, i32)> {
    // A generous average glyph width: DejaVu Sans is wide.
    let chars = shown.iter().map(|s| s.label.chars().count()).max()?;
    let text = (chars as f64 * 0.62 * LEGEND_TEXT).ceil() as i32;
    Some((
        2 * LEGEND_PAD + LEGEND_SWATCH + LEGEND_GAP + text,
        2 * LEGEND_PAD + LEGEND_LINE * (shown.len() as i32 - 1) + 18,
    ))
}

/// Where a legend of `size` may go in a plotting area of `plot` pixels
/// (its top-left pixel), best first: the upper left, upper right, lower
/// right and lower left corners, then down the left and right edges, then
/// along the top and bottom edges (a gap between clusters of points).
fn legend_places(size: (i32, i32), plot: (u32, u32)) -> Vec<(i32, i32)> {
    let left = LEGEND_INSET;
    let right = plot.0 as i32 - LEGEND_INSET - size.0;
    let top = LEGEND_INSET;
    let bottom = plot.1 as i32 - LEGEND_INSET - size.1;
    let mut places = vec![(left, top), (right, top), (right, bottom), (left, bottom)];
    for y in (top..bottom).step_by(10).skip(1) {
        places.extend([(left, y), (right, y)]);
    }
    for x in (left..right).step_by(10).skip(1) {
        places.extend([(x, top), (x, bottom)]);
    }
    places
}

/// The first of the [`legend_places`] in a plotting area of `plot` pixels
/// where a legend of `size` covers the least data, and how much it covers
/// (samples of lines and bands under it).
fn best_place(
    shown: &[Series],
    ranges: Ranges,
    size: (i32, i32),
    plot: (u32, u32),
) -> ((i32, i32), usize) {
    let (w, h) = (f64::from(plot.0), f64::from(plot.1));
    let to_x = |px: i32| ranges.x_at(f64::from(px) / w);
    let to_y = |px: i32| ranges.y.1 - (ranges.y.1 - ranges.y.0) * f64::from(px) / h;
    // Pixels kept free above and below the legend.
    const CLEAR: i32 = 8;
    legend_places(size, plot)
        .into_iter()
        .map(|(left, top)| {
            let (x0, x1) = (to_x(left), to_x(left + size.0));
            let (y0, y1) = (to_y(top + size.1 + CLEAR), to_y(top - CLEAR));
            let covered = (0..=32)
                .map(|i| x0 + (x1 - x0) * f64::from(i) / 32.0)
                .flat_map(|x| {
                    (shown.iter()).filter_map(move |s| extent_at(&s.points, x, ranges.x_scale))
                })
                .filter(|&(lo, hi)| lo <= y1 && hi >= y0)
                .count();
            ((left, top), covered)
        })
        .min_by_key(|&(_, covered)| covered)
        .expect("four corners at least")
}

/// The vertical extent of a series' line and band at episode `x`,
/// interpolated between the evaluations around it along an axis of
/// `scale`; `None` outside the series' span.
fn extent_at(points: &[SeriesPoint], x: f64, scale: Scale) -> Option<(f64, f64)> {
    let i = points.iter().position(|p| p.episode >= x)?;
    let b = &points[i];
    let a = if b.episode == x {
        b
    } else {
        &points[i.checked_sub(1)?]
    };
    let t = if b.episode > a.episode {
        (scale.of(x) - scale.of(a.episode)) / (scale.of(b.episode) - scale.of(a.episode))
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

#[cfg(test)]
mod tests {
    use super::super::data::Metric;
    use super::super::fixtures::{RISING, estimate, set};
    use super::*;

    /// The goal percentage curve of a set with `goal`, labelled "Curve".
    fn goal(goal: &[Option<f64>]) -> Series {
        set("Curve", goal).series(Metric::GoalPct)
    }

    #[test]
    fn zoom_window_is_the_last_fifth_with_a_fitted_range() {
        let series = [goal(&RISING)];
        assert_eq!(zoom_start(&series), Some(400.0));
        assert_eq!(zoom_start(&[]), None);
        let shown = [Series {
            label: "A".to_owned(),
            points: series[0].points[4..].to_vec(),
        }];
        let (lo, hi) = y_range(YRange::Fitted(Some(100.0)), &shown);
        assert!(
            lo > 30.0 && lo < 35.0 && hi > 47.0 && hi < 50.0,
            "{lo}..{hi}"
        );
        assert_eq!(x_range(&shown), (400.0, 500.0));
    }

    #[test]
    fn legend_avoids_the_data() {
        let ranges = Ranges {
            x: (0.0, 300.0),
            y: (0.0, 100.0),
            x_scale: Scale::Linear,
        };
        // Rising curves leave the upper left free.
        let rising = [goal(&[Some(0.0), Some(50.0), Some(90.0), Some(95.0)])];
        let size = legend_size(&rising).unwrap();
        let places = legend_places(size, PLOT);
        assert_eq!(best_place(&rising, ranges, size, PLOT), (places[0], 0));
        // High ones leave the bottom free.
        let high = [goal(&[Some(90.0); 4])];
        assert_eq!(best_place(&high, ranges, size, PLOT), (places[2], 0));
        // High and low ones, the middle of the left edge.
        let both = [goal(&[Some(90.0); 4]), goal(&[Some(5.0); 4])];
        let size = legend_size(&both).unwrap();
        let ((left, top), covered) = best_place(&both, ranges, size, PLOT);
        assert_eq!((left, covered), (LEGEND_INSET, 0));
        assert!(top > LEGEND_INSET && top + size.1 < PLOT.1 as i32 - LEGEND_INSET);
        // Covering the height at both ends: the gap between them.
        let apart = [band(0.0, 60.0), band(240.0, 300.0)];
        let ((left, _), covered) = best_place(&apart, ranges, size, PLOT);
        assert_eq!(covered, 0);
        assert!(left > LEGEND_INSET && left + size.0 < PLOT.0 as i32 - LEGEND_INSET);
        // Covering everything, the first corner.
        let wide = [wide_band()];
        let (place, covered) = best_place(&wide, ranges, size, PLOT);
        assert_eq!(place, legend_places(size, PLOT)[0]);
        assert!(covered > 0);
    }

    #[test]
    fn a_covering_legend_makes_room_above_the_data_unless_fixed() {
        let wide = [wide_band()];
        let grown = Layout::of(&wide, YRange::FromZero);
        assert_eq!(grown.ranges.y.0, 0.0);
        assert!(grown.ranges.y.1 > 100.0 * 1.08, "{grown:?}");
        let fixed = Layout::of(&wide, YRange::Fixed(0.0, 100.0));
        assert_eq!(fixed.ranges.y, (0.0, 100.0));
        assert_eq!(Layout::of(&[], YRange::FromZero).legend, None);
    }

    #[test]
    fn a_tall_covering_legend_goes_beside_and_stacked_charts_follow() {
        let many: Vec<Series> = (0..12).map(|_| wide_band()).collect();
        let mut main = Layout::of(&many, YRange::FromZero);
        let legend = main.legend.unwrap();
        assert_eq!(main.ranges.y, y_range(YRange::FromZero, &many));
        assert_eq!(
            main.plot,
            (PLOT.0 - (legend.size.0 + LEGEND_INSET) as u32, PLOT.1)
        );
        assert_eq!(legend.place.0 as u32, main.plot.0 + LEGEND_INSET as u32);
        // A chart below keeps the same width, its legend beside as well.
        let mut below = Layout::sized(&[wide_band()], YRange::FromZero, (PLOT.0, 200));
        assert_eq!(below.plot.0, PLOT.0);
        align(&mut [&mut main, &mut below]);
        assert_eq!(below.plot.0, main.plot.0);
        assert_eq!(below.legend.unwrap().place, legend.place);
    }

    #[test]
    fn a_log_axis_spans_the_decades_shown_with_a_margin() {
        let at = |x: f64, across: Option<(f64, f64)>| SeriesPoint {
            x_interval: across,
            ..SeriesPoint::at(x, &estimate(Some(1.0)))
        };
        let shown = |points| {
            [Series {
                label: "A".to_owned(),
                points,
            }]
        };
        // From 0.5 (an interval's end) to 100: 2.3 decades, 6 % more each side.
        let (lo, hi) = log_range(&shown(vec![at(1.0, Some((0.5, 2.0))), at(100.0, None)]));
        let margin = 0.06 * 200f64.log10();
        assert!(
            (lo.log10() - (0.5f64.log10() - margin)).abs() < 1e-12,
            "{lo}"
        );
        assert!((hi.log10() - (2.0 + margin)).abs() < 1e-12, "{hi}");
        // Nothing positive shown: 1 to 10; one value: a factor 3 around it.
        assert_eq!(
            log_range(&shown(vec![at(0.0, Some((-1.0, 0.0)))])),
            (1.0, 10.0)
        );
        let (lo, hi) = log_range(&shown(vec![at(2.0, None)]));
        assert!((hi / lo - 3f64.powf(1.12)).abs() < 1e-9 && (lo * hi - 4.0).abs() < 1e-9);
        // The legend's place is judged on the same axis: half way across a
        // log axis from 1 to 100 is 10.
        let ranges = Ranges {
            x: (1.0, 100.0),
            y: (0.0, 1.0),
            x_scale: Scale::Log,
        };
        assert!((ranges.x_at(0.5) - 10.0).abs() < 1e-12);
    }

    /// A band from 0 to 100 over episodes 0 to 300.
    fn wide_band() -> Series {
        band(0.0, 300.0)
    }

    /// A band from 0 to 100 over episodes `from` to `to`.
    fn band(from: f64, to: f64) -> Series {
        let point = |episode| SeriesPoint {
            episode,
            mean: Some(50.0),
            low: Some(0.0),
            high: Some(100.0),
            x_interval: None,
        };
        Series {
            label: "Wide".to_owned(),
            points: vec![point(from), point(to)],
        }
    }
}
