//! What the integration tests share: results compared byte for byte but
//! for the times they measured.

use std::path::Path;

/// A results file with the times it measured, and the build that played
/// it, masked: in `summary.json`, `wall_s` and `frames_per_sec`; in
/// `REPORT.md`, the cost table's last two columns and the line saying
/// what played the runs. Everything else must be identical for the same
/// configuration.
pub fn without_times(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut in_cost = false;
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        in_cost = line.starts_with("## Cost") || (in_cost && !line.starts_with("## "));
        let masked = if line.starts_with("Played with ") {
            "Played with <build>.".to_owned()
        } else if line.contains("\"wall_s\":") || line.contains("\"frames_per_sec\":") {
            format!("{}: <time>", line.split(':').next().unwrap_or_default())
        } else if in_cost && line.starts_with("| ") && !line.starts_with("| algorithm") {
            let cells: Vec<&str> = line.split('|').collect();
            format!(
                "{}| <time> | <time> |",
                cells[..cells.len().saturating_sub(3)].join("|")
            )
        } else {
            line.to_owned()
        };
        out.push_str(&masked);
        out.push('\n');
    }
    out
}
