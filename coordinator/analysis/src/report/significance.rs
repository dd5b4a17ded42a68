//! Where methods differ significantly: against the baseline, with Holm's
//! correction, and between the advising methods.

use super::markdown::{Markdown, intervals, p_value};
use crate::stats::analysis::Comparison;
use crate::stats::holm::HolmComparison;
use crate::study::{EntryResults, Study};

/// Where every algorithm is significantly better or worse than `baseline`.
pub(super) fn significance_against(md: &mut Markdown, baseline: &str, comparisons: &[Comparison]) {
    md.heading(2, &format!("Significance against `{baseline}`"));
    md.paragraph(&format!(
        "Episodes where the algorithm's goal percentage is significantly higher or lower than `{baseline}`'s."
    ));
    let rows = comparisons
        .iter()
        .filter(|c| c.a == baseline || c.b == baseline)
        .map(|c| {
            let (other, better, worse) = if c.a == baseline {
                (&c.b, &c.b_better, &c.a_better)
            } else {
                (&c.a, &c.a_better, &c.b_better)
            };
            [
                other.clone(),
                intervals(better),
                intervals(worse),
                p_value(c.final_p),
            ]
        });
    md.table(
        [
            "algorithm",
            "better (episodes)",
            "worse (episodes)",
            "p at the end",
        ],
        rows,
    );
}

/// The tests against `baseline` with Holm's correction across algorithms.
pub(super) fn holm_table(md: &mut Markdown, baseline: &str, holm: &[HolmComparison]) {
    md.paragraph(&format!(
        "The same with Holm's correction: at every evaluation point, the p-values of every \
         algorithm against `{baseline}` adjusted together."
    ));
    md.table(
        [
            "algorithm",
            "better (episodes, Holm)",
            "worse (episodes, Holm)",
            "p at the end (Holm)",
        ],
        holm.iter().map(|h| {
            [
                h.entry.clone(),
                intervals(&h.better),
                intervals(&h.worse),
                p_value(h.final_p),
            ]
        }),
    );
}

/// Pairs of advising methods (the baseline aside) with at least one ad hoc
/// method among them; nothing without such a pair.
pub(super) fn significance_between_advising(
    md: &mut Markdown,
    study: &Study,
    entries: &[EntryResults],
    comparisons: &[Comparison],
) {
    let kind = |name: &str| {
        entries
            .iter()
            .find(|e| e.entry.name == name)
            .map(|e| e.entry.algorithm)
    };
    let advising = |name: &str| {
        Some(name) != study.baseline.as_deref()
            && kind(name).is_some_and(agent::Algorithm::communicates)
    };
    // The paper's methods, `adhoc-visit` and `adhoc-td`.
    let ad_hoc = |name: &str| kind(name).is_some_and(|a| a.name().starts_with("adhoc-"));
    let between: Vec<&Comparison> = comparisons
        .iter()
        .filter(|c| advising(&c.a) && advising(&c.b) && (ad_hoc(&c.a) || ad_hoc(&c.b)))
        .collect();
    if between.is_empty() {
        return;
    }
    md.heading(
        2,
        "Significance between the ad hoc methods and the other advising methods",
    );
    md.table(
        [
            "A",
            "B",
            "A better (episodes)",
            "B better (episodes)",
            "p at the end",
        ],
        between.iter().map(|c| {
            [
                c.a.clone(),
                c.b.clone(),
                intervals(&c.a_better),
                intervals(&c.b_better),
                p_value(c.final_p),
            ]
        }),
    );
}
