//! The report's Markdown, and the cells its tables share.

use crate::results::{AgentStats, EvalPoint};
use crate::study::{Entry, EntryResults};

/// Markdown written block by block (headings, paragraphs, tables), each
/// followed by a blank line.
#[derive(Default)]
pub(super) struct Markdown(pub(super) String);

impl Markdown {
    /// A heading of `level` (1 for `#`).
    pub(super) fn heading(&mut self, level: usize, text: &str) {
        self.paragraph(&format!("{} {text}", "#".repeat(level)));
    }

    /// A paragraph, or any block of lines.
    pub(super) fn paragraph(&mut self, text: &str) {
        self.0.push_str(text);
        self.0.push_str("\n\n");
    }

    /// A table: its header, then one line per row (as many cells).
    pub(super) fn table<H: AsRef<str>, R: AsRef<[String]>>(
        &mut self,
        header: impl AsRef<[H]>,
        rows: impl IntoIterator<Item = R>,
    ) {
        let header: Vec<&str> = header.as_ref().iter().map(AsRef::as_ref).collect();
        let line = |cells: &[&str]| format!("| {} |\n", cells.join(" | "));
        self.0.push_str(&line(&header));
        self.0
            .push_str(&format!("|{}\n", "---|".repeat(header.len())));
        for row in rows {
            let cells: Vec<&str> = row.as_ref().iter().map(String::as_str).collect();
            self.0.push_str(&line(&cells));
        }
        self.0.push('\n');
    }

    /// The document, ending with one newline.
    pub(super) fn finish(mut self) -> String {
        if self.0.ends_with("\n\n") {
            self.0.pop();
        }
        self.0
    }
}

/// `value [low, high]` with `digits` decimals.
pub(super) fn interval(value: f64, [low, high]: [f64; 2], digits: usize) -> String {
    format!("{value:.digits$} [{low:.digits$}, {high:.digits$}]")
}

/// Episode intervals as `a–b, c`, or `none`.
pub(super) fn intervals(v: &[(u64, u64)]) -> String {
    if v.is_empty() {
        return "none".into();
    }
    v.iter()
        .map(|(a, b)| {
            if a == b {
                a.to_string()
            } else {
                format!("{a}–{b}")
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// A p-value with three decimals, or `< 0.001`.
pub(super) fn p_value(p: Option<f64>) -> String {
    p.map_or("-".into(), |p| {
        if p < 0.001 {
            "< 0.001".into()
        } else {
            format!("{p:.3}")
        }
    })
}

/// An entry's label: its name, marked when it has an expert.
pub(super) fn label(e: &Entry) -> String {
    let mut s = e.name.clone();
    if e.expert {
        s.push_str(" (expert)");
    }
    s
}

/// The mean over runs of `f` of each run's last point; `None` without runs.
pub(super) fn mean_at_end(e: &EntryResults, f: &dyn Fn(&EvalPoint) -> f64) -> Option<f64> {
    let ends: Vec<f64> = (e.results.iter())
        .filter_map(|r| r.points.last())
        .map(f)
        .collect();
    (!ends.is_empty()).then(|| ends.iter().sum::<f64>() / ends.len() as f64)
}

/// A counter at `p` summed over the agents, per agent, and per training
/// episode when `per_episode`.
pub(super) fn per_agent(p: &EvalPoint, f: fn(&AgentStats) -> u64, per_episode: bool) -> f64 {
    let total = p.agents.iter().map(f).sum::<u64>() as f64;
    let episodes = if per_episode {
        p.episode.max(1) as f64
    } else {
        1.0
    };
    total / p.agents.len().max(1) as f64 / episodes
}
