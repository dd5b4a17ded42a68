//! Whether each swept method's result depends on the swept value.

use super::markdown::Markdown;
use crate::stats::gains::LAST_POINTS;
use crate::stats::sweeps::SweepTest;

/// The section "Sweeps" of `tests` at significance `alpha`; nothing
/// without a test.
pub(super) fn sweeps_section(md: &mut Markdown, tests: &[SweepTest], alpha: f64) {
    if tests.is_empty() {
        return;
    }
    md.heading(2, "Sweeps");
    md.paragraph(&format!(
        "Whether a group's result depends on the value swept: Friedman's test on each run's \
         mean goal % over the last {LAST_POINTS} evaluations, across the group's entries, paired \
         by run (the runs every entry played), Holm-adjusted across groups; \"yes\" where the \
         adjusted p is below {alpha:.2}. Each entry is named by its group and the value swept; the \
         means are over the paired runs."
    ));
    let rows = tests.iter().map(|t| {
        let values: Vec<String> = (t.entries.iter().zip(&t.means))
            .map(|(entry, mean)| {
                let value = entry
                    .strip_prefix(&format!("{}-", t.group))
                    .unwrap_or(entry);
                format!("{value}: {mean:.1}")
            })
            .collect();
        [
            t.group.clone(),
            values.join("; "),
            t.runs.to_string(),
            format!("{:.1}", t.spread()),
            format!("{:.2}", t.statistic),
            format!("{:.3}", t.p),
            format!("{:.3}", t.holm_p),
            if t.depends(alpha) { "yes" } else { "no" }.to_owned(),
        ]
    });
    md.table(
        [
            "group",
            &format!("value: goal %, last {LAST_POINTS}"),
            "runs",
            "spread",
            "Friedman χ²",
            "p",
            "Holm p",
            "depends on the value",
        ],
        rows,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_row_per_group_naming_each_value() {
        let test = SweepTest {
            group: "rcmp".into(),
            entries: vec![
                "rcmp-uncertainty_threshold-0.001".into(),
                "rcmp-uncertainty_threshold-0.01".into(),
            ],
            means: vec![40.0, 45.5],
            runs: 20,
            statistic: 7.2,
            p: 0.0073,
            holm_p: 0.0146,
        };
        let mut md = Markdown::default();
        sweeps_section(&mut md, &[test], 0.05);
        let text = md.finish();
        assert!(text.contains("## Sweeps"), "{text}");
        assert!(
            text.contains(
                "| rcmp | uncertainty_threshold-0.001: 40.0; uncertainty_threshold-0.01: 45.5 \
                 | 20 | 5.5 | 7.20 | 0.007 | 0.015 | yes |"
            ),
            "{text}"
        );
        let mut empty = Markdown::default();
        sweeps_section(&mut empty, &[], 0.05);
        assert!(empty.finish().is_empty());
    }
}
