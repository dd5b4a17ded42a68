//! The authors' published results (f-leno/AdHoc_AAMAS-17, `ProcessedFiles/`)
//! read as runs, and each algorithm's gain over a baseline computed as a
//! study's (`gains`), but unpaired: the authors' runs of two algorithms
//! share nothing, so the interval of a gain is Welch's.

use std::path::Path;

use crate::error::Error;
use crate::files;
use crate::results::{EvalPoint, RunResult};
use crate::stats::gains::{Gain, area, first, last_ten};
use crate::stats::{difference_of_means, estimate};

/// The runs of one algorithm's directory: every `_0_<run>_AGENT_1_RESULTS_eval`
/// file (the team's outcomes; the other agents' files repeat them), with
/// its evaluation points (`trial,goal_percentage,...` rows), sorted by run.
pub fn read_runs(dir: &Path) -> Result<Vec<RunResult>, Error> {
    let mut runs = Vec::new();
    for (path, text) in files::read_matching(dir, |name| name.ends_with("_AGENT_1_RESULTS_eval"))? {
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default();
        let Some(run) = (name.strip_prefix("_0_"))
            .and_then(|rest| rest.strip_suffix("_AGENT_1_RESULTS_eval"))
            .and_then(|run| run.parse::<u64>().ok())
        else {
            continue;
        };
        let points = parse_points(&text).map_err(|problem| Error::invalid(&path, problem))?;
        runs.push(RunResult {
            joins: Vec::new(),
            played_with: None,
            restarts: Vec::new(),
            simulator_restarts: Vec::new(),
            advice_matrix: Vec::new(),
            run,
            points,
            timing: Default::default(),
            advice_rtt_ms: Vec::new(),
        });
    }
    if runs.is_empty() {
        return Err(Error::invalid(dir, "no _0_<run>_AGENT_1_RESULTS_eval file"));
    }
    runs.sort_by_key(|r| r.run);
    Ok(runs)
}

/// The evaluation points of one file: a header, then `trial,goal_percentage,...`.
fn parse_points(text: &str) -> Result<Vec<EvalPoint>, String> {
    let mut points = Vec::new();
    for (i, line) in text.lines().enumerate().skip(1) {
        let mut fields = line.split(',');
        let mut number = |what: &str| -> Result<f64, String> {
            (fields.next().and_then(|f| f.trim().parse::<f64>().ok()))
                .ok_or_else(|| format!("line {}: expected a number for {what}", i + 1))
        };
        let (trial, goal_pct) = (number("trial")?, number("goal_percentage")?);
        points.push(EvalPoint {
            episode: trial as u64,
            episodes: 100,
            goals: goal_pct.round() as u64,
            goal_pct,
            time_to_goal: None,
            agents: Vec::new(),
            spent_budget: 0.0,
            actions_timed_out: 0,
        });
    }
    Ok(points)
}

/// The gain of every algorithm in `algorithms` over `baseline`, each a
/// directory of `results`, with Welch's intervals at `level`.
pub fn published_gains(
    results: &Path,
    baseline: &str,
    algorithms: &[String],
    level: f64,
) -> Result<Vec<Gain>, Error> {
    let base = read_runs(&results.join(baseline))?;
    let values = |runs: &[RunResult], metric: fn(&RunResult) -> Option<f64>| -> Vec<f64> {
        runs.iter().filter_map(metric).collect()
    };
    algorithms
        .iter()
        .map(|name| {
            let runs = read_runs(&results.join(name))?;
            let of = |metric| estimate(&values(&runs, metric), level);
            let gain =
                |metric| difference_of_means(&values(&runs, metric), &values(&base, metric), level);
            Ok(Gain {
                entry: name.clone(),
                baseline: baseline.to_owned(),
                last_ten: of(last_ten),
                last_ten_gain: gain(last_ten),
                area: of(area),
                area_gain: gain(area),
                first: of(first),
                first_gain: gain(first),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write_run(dir: &Path, run: u64, goals: &[f64]) {
        let mut text = "trial,goal_percentage,avg_goal_time,used_budget\n".to_owned();
        for (i, g) in goals.iter().enumerate() {
            text.push_str(&format!("{},{g:.2},50.00,0\n", 20 * i));
        }
        std::fs::create_dir_all(dir).unwrap();
        std::fs::write(dir.join(format!("_0_{run}_AGENT_1_RESULTS_eval")), text).unwrap();
        std::fs::write(
            dir.join(format!("_0_{run}_AGENT_2_RESULTS_eval")),
            "ignored",
        )
        .unwrap();
    }

    #[test]
    fn gains_of_published_runs() {
        let tmp = tempfile::tempdir().unwrap();
        let (base, alg) = (tmp.path().join("SARSATile"), tmp.path().join("AdHocTD"));
        for run in 1..=3 {
            write_run(&base, run, &[0.0, 10.0 * run as f64]);
            write_run(&alg, run, &[0.0, 10.0 * run as f64 + 6.0]);
        }
        let runs = read_runs(&alg).unwrap();
        assert_eq!(runs.iter().map(|r| r.run).collect::<Vec<_>>(), [1, 2, 3]);
        assert_eq!(runs[0].points[1].goal_pct, 16.0);
        let gains = published_gains(tmp.path(), "SARSATile", &["AdHocTD".into()], 0.9).unwrap();
        // Last ten: both points; the runs average 8, 13, 18 against 5, 10, 15.
        assert_eq!(gains[0].last_ten.mean, Some(13.0));
        assert_eq!(gains[0].last_ten_gain.mean, Some(3.0));
        assert_eq!(gains[0].area_gain.mean, Some(3.0));
        let e = read_runs(&tmp.path().join("missing"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("missing"), "{e}");
        write_run(&tmp.path().join("Bad"), 1, &[]);
        std::fs::write(tmp.path().join("Bad/_0_1_AGENT_1_RESULTS_eval"), "h\n0,x\n").unwrap();
        let e = read_runs(&tmp.path().join("Bad")).unwrap_err().to_string();
        assert!(
            e.contains("line 2: expected a number for goal_percentage"),
            "{e}"
        );
    }
}
