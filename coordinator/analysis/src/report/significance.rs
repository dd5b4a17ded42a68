//! Where methods differ significantly: against their baselines, with
//! Holm's correction, and between the advising methods.

use super::against::Against;
use super::markdown::{Markdown, intervals, p_value};
use crate::baselines::Pair;
use crate::stats::analysis::Comparison;
use crate::stats::holm::HolmComparison;
use crate::study::{EntryResults, Study};

/// Where every algorithm of `pairs` is significantly better or worse than
/// its baseline.
pub(super) fn significance_against(
    md: &mut Markdown,
    against: Against,
    pairs: &[Pair],
    comparisons: &[Comparison],
) {
    md.heading(2, &format!("Significance against {}", against.all()));
    md.paragraph(&format!(
        "Episodes where the algorithm's goal percentage is significantly higher or lower than {}'s.",
        against.each()
    ));
    let rows = pairs.iter().filter_map(|p| {
        let (entry, baseline) = (&p.entry.entry.name, p.baseline_name());
        let c = (comparisons.iter())
            .find(|c| c.a == *entry && c.b == baseline || c.a == baseline && c.b == *entry)?;
        let (better, worse) = if &c.a == entry {
            (&c.a_better, &c.b_better)
        } else {
            (&c.b_better, &c.a_better)
        };
        let row = vec![
            entry.clone(),
            intervals(better),
            intervals(worse),
            p_value(c.final_p),
        ];
        Some(against.row(row, baseline))
    });
    md.table(
        against.header(&[
            "algorithm",
            "better (episodes)",
            "worse (episodes)",
            "p at the end",
        ]),
        rows,
    );
}

/// The tests against the baselines with Holm's correction across
/// algorithms.
pub(super) fn holm_table(md: &mut Markdown, against: Against, holm: &[HolmComparison]) {
    let family = match against {
        Against::One(b) => format!("every algorithm against `{b}`"),
        Against::Several => "every algorithm against the same baseline".into(),
    };
    md.paragraph(&format!(
        "The same with Holm's correction: at every evaluation point, the p-values of {family} \
         adjusted together."
    ));
    md.table(
        against.header(&[
            "algorithm",
            "better (episodes, Holm)",
            "worse (episodes, Holm)",
            "p at the end (Holm)",
        ]),
        holm.iter().map(|h| {
            let row = vec![
                h.entry.clone(),
                intervals(&h.better),
                intervals(&h.worse),
                p_value(h.final_p),
            ];
            against.row(row, &h.baseline)
        }),
    );
}

/// Pairs of advising methods (the baselines aside) with at least one ad hoc
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
        !study.is_baseline(name) && kind(name).is_some_and(agent::Algorithm::communicates)
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
