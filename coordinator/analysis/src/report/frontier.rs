//! The communication frontier: every entry's cost and gain with the Pareto
//! front, each method's gain at equal cost, and what a point of gain cost.

use super::against::Against;
use super::markdown::Markdown;
use crate::figures::{FRONTIER_BYTES, FRONTIER_MESSAGES};
use crate::stats::Estimate;
use crate::stats::frontier::{CostUnit, Frontier};
use crate::stats::gains::LAST_POINTS;

/// The section "Frontier" of `f`.
pub(super) fn frontier_section(md: &mut Markdown, f: &Frontier) {
    let against = Against::named(f.baseline.as_deref());
    let baseline = against.each();
    let rivals = match against {
        Against::One(_) => "no other entry",
        Against::Several => "no other entry of the same baseline",
    };
    md.heading(2, "Frontier");
    md.paragraph(&format!(
        "What each entry gains over {baseline} for what its agents send. Its group is the \
         study entry it was swept from (else its own name). Cost: the advising messages \
         (requests, replies, shared episodes), or their bytes, each agent sent per training \
         episode over the whole training (per run, the team's count at the last evaluation \
         divided by its agents and training episodes; mean over runs with its interval). Gain: \
         in goal % over the last {LAST_POINTS} evaluations and over the whole curve, paired by \
         run. On the front: {rivals}, nor {baseline} at its own cost and a gain of 0, \
         costs as little or less and gains as much or more over the last {LAST_POINTS}, one of \
         the two strictly (means)."
    ));
    for unit in CostUnit::ALL {
        md.heading(3, &format!("Gain against {}", unit.name()));
        let rows = f.points.iter().map(|p| {
            let row = vec![
                p.group.clone(),
                p.entry.clone(),
                cost_cell(p.cost(unit)),
                format!("{:.1}", p.last_ten_gain),
                format!("{:.1}", p.area_gain),
                if p.on_front(unit) { "yes" } else { "no" }.to_owned(),
            ];
            against.row(row, &p.baseline)
        });
        md.table(
            against.header(&[
                "group",
                "entry",
                &format!("{} / agent / episode", unit.name()),
                "gain: last ten",
                "gain: whole curve",
                "on the front",
            ]),
            rows,
        );
    }
    equal_cost(md, f);
    md.heading(3, "Messages per point of gain");
    md.paragraph(&format!(
        "The mean advising messages per agent per training episode divided by the mean gain \
         over the last {LAST_POINTS} evaluations: what one point of goal % cost. Only where the \
         gain's interval lies above 0; else –."
    ));
    md.table(
        ["group", "entry", "messages per point of gain"],
        f.points.iter().map(|p| {
            [
                p.group.clone(),
                p.entry.clone(),
                p.messages_per_point.map_or("–".to_owned(), significant),
            ]
        }),
    );
    md.paragraph(&format!(
        "Figures: [`{FRONTIER_MESSAGES}`](figures/{FRONTIER_MESSAGES}.svg), \
         [`{FRONTIER_BYTES}`](figures/{FRONTIER_BYTES}.svg)."
    ));
}

/// Each group of two or more entries at the frontier's message rates.
fn equal_cost(md: &mut Markdown, f: &Frontier) {
    md.heading(3, "Gain at equal cost");
    if f.equal_cost.is_empty() {
        md.paragraph("No group has entries at two message rates above 0.");
        return;
    }
    if f.rates.is_empty() {
        md.paragraph(
            "No rate of a tenth's step (1.0 to 9.9 in each decade) lies inside the ranges of \
             message rates of two groups (of the one, with one): the groups sent too \
             differently, or each group's entries about the same.",
        );
        return;
    }
    md.paragraph(&format!(
        "Each group's gain over the last {LAST_POINTS} evaluations at a few rates of advising \
         messages per agent per training episode (column \"at r\"), read off its curve: \
         interpolated linearly in log10(messages) between the two entries around the rate, \
         the mean and each bound of the interval alike. Groups of two or more entries that \
         sent messages; – outside a group's range."
    ));
    let header: Vec<String> = std::iter::once("group".to_owned())
        .chain(f.rates.iter().map(|r| format!("at {r}")))
        .collect();
    let rows = f.equal_cost.iter().map(|g| {
        std::iter::once(g.group.clone())
            .chain(
                (g.gains.iter())
                    .map(|e| e.as_ref().map_or("–".to_owned(), |e| format!("{e:.1}"))),
            )
            .collect::<Vec<String>>()
    });
    md.table(header, rows);
}

/// A cost with its interval, to three significant digits of its mean.
fn cost_cell(e: &Estimate) -> String {
    let digits = e.mean.map_or(2, decimals);
    format!("{e:.digits$}")
}

/// `x` to three significant digits.
fn significant(x: f64) -> String {
    let digits = decimals(x);
    format!("{x:.digits$}")
}

/// The decimals that show three significant digits of `x` (none past
/// the units).
fn decimals(x: f64) -> usize {
    if x == 0.0 || !x.is_finite() {
        return 2;
    }
    (2 - x.abs().log10().floor() as i32).max(0) as usize
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::frontier::{EqualCost, FrontierPoint};

    fn estimate(mean: f64, half: f64) -> Estimate {
        Estimate {
            n: 3,
            mean: Some(mean),
            ci_low: Some(mean - half),
            ci_high: Some(mean + half),
        }
    }

    #[test]
    fn the_section_tables_every_entry_and_each_group_at_equal_cost() {
        let point =
            |entry: &str, group: &str, messages: f64, gain: f64, front: bool| FrontierPoint {
                entry: entry.to_owned(),
                group: group.to_owned(),
                messages: estimate(messages, messages / 10.0),
                bytes: estimate(40.0 * messages, 4.0 * messages),
                last_ten_gain: estimate(gain, 1.0),
                area_gain: estimate(gain / 2.0, 1.0),
                baseline: "no-advice".to_owned(),
                front_messages: front,
                front_bytes: front,
                messages_per_point: (gain > 1.0).then(|| messages / gain),
            };
        let f = Frontier {
            baseline: Some("no-advice".to_owned()),
            points: vec![
                point("a-30", "a", 0.0123, 2.0, true),
                point("a-300", "a", 4.56, 3.0, true),
                point("b", "b", 789.0, 0.5, false),
            ],
            rates: vec![0.1, 1.0],
            equal_cost: vec![EqualCost {
                group: "a".to_owned(),
                gains: vec![Some(estimate(2.25, 1.0)), None],
            }],
        };
        let mut md = Markdown::default();
        frontier_section(&mut md, &f);
        let text = md.finish();
        for line in [
            "| a | a-30 | 0.0123 [0.0111, 0.0135] | 2.0 [1.0, 3.0] | 1.0 [0.0, 2.0] | yes |",
            "| b | b | 789 [710, 868] | 0.5 [-0.5, 1.5] | 0.2 [-0.8, 1.2] | no |",
            "| a | a-300 | 182 [164, 201] | 3.0 [2.0, 4.0] | 1.5 [0.5, 2.5] | yes |",
            "| group | at 0.1 | at 1 |",
            "| a | 2.2 [1.2, 3.2] | – |",
            "| a | a-300 | 1.52 |",
            "| b | b | – |",
            "[`frontier_bytes`](figures/frontier_bytes.svg)",
        ] {
            assert!(text.contains(line), "no line {line:?} in\n{text}");
        }
        assert_eq!(text.matches("### ").count(), 4, "{text}");
    }
}
