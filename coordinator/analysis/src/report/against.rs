//! What the report's methods are compared with: one baseline, named in the
//! text, or several, each method's named in a column `baseline`.

use crate::baselines::{Pair, common_baseline};
use crate::stats::aggregates::Aggregates;

/// The baseline, or that there are several.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Against<'a> {
    /// Every method has this one.
    One(&'a str),
    /// Methods have different baselines.
    Several,
}

impl<'a> Against<'a> {
    /// What `pairs` compare with; none without a pair.
    pub(super) fn of(pairs: &[Pair<'a>]) -> Option<Self> {
        (!pairs.is_empty()).then(|| Self::named(common_baseline(pairs)))
    }

    /// One named baseline, or several (none named).
    pub(super) fn named(baseline: Option<&'a str>) -> Self {
        baseline.map_or(Self::Several, Self::One)
    }

    /// A method's baseline as a sentence names it: `` `no-advice` ``, or
    /// "its baseline".
    pub(super) fn each(self) -> String {
        match self {
            Self::One(b) => format!("`{b}`"),
            Self::Several => "its baseline".into(),
        }
    }

    /// The baselines as a heading names them: `` `no-advice` ``, or "the
    /// baselines".
    pub(super) fn all(self) -> String {
        match self {
            Self::One(b) => format!("`{b}`"),
            Self::Several => "the baselines".into(),
        }
    }

    /// A method's baseline as a figure names it: `no-advice`, or "its
    /// baseline".
    pub(super) fn plain(self) -> &'a str {
        match self {
            Self::One(b) => b,
            Self::Several => "its baseline",
        }
    }

    /// `header` with the column `baseline` after its first, with several.
    pub(super) fn header(self, header: &[&str]) -> Vec<String> {
        self.row(header.iter().map(|h| h.to_string()).collect(), "baseline")
    }

    /// `row` with `baseline` (a cell) after its first, with several.
    pub(super) fn row(self, mut row: Vec<String>, baseline: &str) -> Vec<String> {
        if self == Self::Several {
            row.insert(1, baseline.to_owned());
        }
        row
    }
}

/// The cell `baseline` of `entry` (as `a` holds it): its baseline's name,
/// *baseline* for a baseline, `-` for an entry compared with none.
pub(super) fn baseline_cell(a: &Aggregates, entry: &str) -> String {
    let own = (a.entries.iter())
        .find(|e| e.entry == entry)
        .and_then(|e| e.baseline.clone());
    let is_baseline = (a.entries.iter()).any(|e| e.baseline.as_deref() == Some(entry));
    match own {
        Some(b) => b,
        None if is_baseline => "*baseline*".into(),
        None => "-".into(),
    }
}
