//! The results store: the output layout, the claim/resume check and the one
//! atomic write every result file goes through.
//!
//! A directory is claimed by its identity file (`config.json` for an
//! experiment, `study.json` for a study): a directory holding another
//! identity, or files without one, is refused before anything is written;
//! the same identity resumes over its own files, with as many runs as it
//! now asks for. An experiment directory
//! gets `config.json` first, one `run-<k>.csv` per run written as it goes,
//! `run-<k>.json` when a run is complete and `summary.json` at the end.

use std::fs::{self, File};
use std::path::{Path, PathBuf};

use agent::Snapshot;
use node::files::TEMP_PREFIX;
use serde::Serialize;
use serde_json::Value;

use crate::error::Error;
use analysis::{AgentStats, EvalPoint, RunResult};

/// Name of an experiment directory's identity file.
pub const CONFIG_FILE: &str = "config.json";
/// Name of the summary in an experiment directory.
pub const SUMMARY_FILE: &str = "summary.json";

/// The file name of run `run`'s CSV.
pub fn run_file_name(run: u64) -> String {
    format!("run-{run}.csv")
}

/// The file name of run `run`'s complete results.
pub fn run_result_name(run: u64) -> String {
    format!("run-{run}.json")
}

/// The snapshot file of agent `agent` at the end of run `run`.
pub fn agent_file_name(run: u64, agent: usize) -> String {
    format!("run-{run}-agent-{agent}.snapshot")
}

/// Writes `bytes` to `path` atomically and durably (see
/// [`node::files::write_atomically`]).
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    node::files::write_atomically(path, bytes).map_err(|e| Error::io("write", path, e))
}

/// Creates directory `dir` and its parents, as needed.
pub fn create_dir(dir: &Path) -> Result<(), Error> {
    fs::create_dir_all(dir).map_err(|e| Error::io("create", dir, e))
}

/// Writes `value` as pretty JSON with a final newline, atomically.
pub fn write_json(path: &Path, value: &impl Serialize) -> Result<(), Error> {
    let mut bytes = serde_json::to_vec_pretty(value).expect("results serialise");
    bytes.push(b'\n');
    write_atomically(path, &bytes)
}

/// Checks that `dir` may hold the results identified by `identity` in its
/// file `name`: `dir` is absent, holds nothing (but leftover temporary
/// files), or holds the same identity. Writes nothing.
pub fn check_claim(dir: &Path, name: &str, identity: &Value) -> Result<(), Error> {
    let other = |reason: String| Error::OtherResults {
        dir: dir.to_path_buf(),
        reason,
    };
    if dir.exists() && !dir.is_dir() {
        return Err(Error::NotADirectory(dir.to_path_buf()));
    }
    let path = dir.join(name);
    let compare = |bytes: Vec<u8>| {
        let mut theirs: Value = serde_json::from_slice(&bytes)
            .map_err(|e| other(format!("its {name} is unreadable: {e}")))?;
        todays_spellings(&mut theirs);
        match first_difference(&comparable(identity), &comparable(&theirs), "") {
            Some(diff) => Err(other(format!("{name} differs at {diff}"))),
            None => Ok(()),
        }
    };
    let read = || match fs::read(&path) {
        Ok(bytes) => Ok(Some(bytes)),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(Error::io("read", &path, e)),
    };
    if let Some(bytes) = read()? {
        return compare(bytes);
    }
    if !dir.is_dir() {
        return Ok(());
    }
    let entries = fs::read_dir(dir).map_err(|e| Error::io("read", dir, e))?;
    for entry in entries {
        let entry = entry.map_err(|e| Error::io("read", dir, e))?;
        let file = entry.file_name().to_string_lossy().into_owned();
        if !file.starts_with(TEMP_PREFIX) {
            // The identity is written before anything else: another process
            // (a concurrent shard) may have claimed the directory meanwhile.
            return match read()? {
                Some(bytes) => compare(bytes),
                None => Err(other(format!("it has {file} but no {name}"))),
            };
        }
    }
    Ok(())
}

/// An identity without its count of runs: a directory resumes with more
/// runs (a run's seeds depend only on its index, so those played stay
/// valid) or reports on fewer; the identity file then says the new count.
fn without_runs(identity: &Value) -> Value {
    let mut identity = identity.clone();
    if let Some(map) = identity.as_object_mut() {
        map.remove("runs");
        if let Some(config) = map.get_mut("config").and_then(Value::as_object_mut) {
            config.remove("runs");
        }
    }
    identity
}

/// An identity as compared: without its count of runs, and without the
/// keys that say nothing (null, or false), which versions before 0.3 wrote
/// and later ones leave out.
fn comparable(identity: &Value) -> Value {
    fn strip(value: &mut Value) {
        match value {
            Value::Object(map) => {
                map.retain(|_, v| !(v.is_null() || *v == Value::Bool(false)));
                map.values_mut().for_each(strip);
            }
            Value::Array(items) => items.iter_mut().for_each(strip),
            _ => {}
        }
    }
    let mut identity = without_runs(identity);
    strip(&mut identity);
    identity
}

/// Rewrites the keys an earlier version wrote under another name as they
/// are spelled today (CHANGELOG.md), so its results still resume: a team
/// entry's `strategy` is `algorithm` since 0.2.0, the zenoh transport's
/// `checkpoint_every` is `snapshot_every` since 0.3.
fn todays_spellings(value: &mut Value) {
    match value {
        Value::Object(map) => {
            for (old, new) in [
                ("strategy", "algorithm"),
                ("checkpoint_every", "snapshot_every"),
            ] {
                if let Some(v) = map.remove(old) {
                    map.insert(new.to_owned(), v);
                }
            }
            map.values_mut().for_each(todays_spellings);
        }
        Value::Array(items) => items.iter_mut().for_each(todays_spellings),
        _ => {}
    }
}

/// Creates `dir` and writes its identity file `name`.
pub fn claim(dir: &Path, name: &str, identity: &Value) -> Result<(), Error> {
    create_dir(dir)?;
    write_json(&dir.join(name), identity)
}

/// An experiment's directory, checked to accept its results.
#[derive(Clone, Debug)]
pub struct ExperimentDir {
    dir: PathBuf,
    record: Value,
}

impl ExperimentDir {
    /// Checks that `dir` may hold the results of the experiment whose
    /// `config.json` is `record` (see [`check_claim`]). Writes nothing.
    pub fn check(dir: &Path, record: &impl Serialize) -> Result<Self, Error> {
        let record = serde_json::to_value(record).expect("a record serialises");
        check_claim(dir, CONFIG_FILE, &record)?;
        Ok(Self {
            dir: dir.to_path_buf(),
            record,
        })
    }

    /// The directory.
    pub fn path(&self) -> &Path {
        &self.dir
    }

    /// Creates the directory and writes `config.json`.
    pub fn create(&self) -> Result<(), Error> {
        claim(&self.dir, CONFIG_FILE, &self.record)
    }

    /// Starts run `run`'s CSV for a team of `agents`, replacing any old one.
    pub fn run_writer(&self, run: u64, agents: usize) -> Result<RunWriter, Error> {
        RunWriter::create(&self.dir.join(run_file_name(run)), agents)
    }

    /// The results of run `run` if an earlier invocation finished it.
    pub fn finished_run(&self, run: u64) -> Option<RunResult> {
        let bytes = fs::read(self.dir.join(run_result_name(run))).ok()?;
        serde_json::from_slice::<RunResult>(&bytes)
            .ok()
            .filter(|r| r.run == run)
    }

    /// Marks run `result.run` finished by writing its results.
    pub fn write_run_result(&self, result: &RunResult) -> Result<(), Error> {
        let bytes = serde_json::to_vec(result).expect("a run result serialises");
        write_atomically(&self.dir.join(run_result_name(result.run)), &bytes)
    }

    /// Writes `summary.json`.
    pub fn write_summary(&self, summary: &impl Serialize) -> Result<(), Error> {
        write_json(&self.dir.join(SUMMARY_FILE), summary)
    }
}

/// Saves every agent's snapshot at the end of run `run` into `dir`, as
/// [`agent_file_name`].
pub fn write_agents(dir: &Path, run: u64, snapshots: &[Snapshot]) -> Result<(), Error> {
    for (i, s) in snapshots.iter().enumerate() {
        let path = dir.join(agent_file_name(run, i));
        let bytes = s
            .encode()
            .map_err(|e| Error::io("write", &path, std::io::Error::other(e.to_string())))?;
        write_atomically(&path, &bytes)?;
    }
    Ok(())
}

/// The path of the first value that differs between two JSON documents.
fn first_difference(ours: &Value, theirs: &Value, at: &str) -> Option<String> {
    match (ours, theirs) {
        (Value::Object(a), Value::Object(b)) => {
            let keys: std::collections::BTreeSet<&String> = a.keys().chain(b.keys()).collect();
            keys.into_iter().find_map(|k| {
                let path = if at.is_empty() {
                    k.clone()
                } else {
                    format!("{at}.{k}")
                };
                match (a.get(k), b.get(k)) {
                    (Some(x), Some(y)) => first_difference(x, y, &path),
                    _ => Some(path),
                }
            })
        }
        (Value::Array(a), Value::Array(b)) if a.len() == b.len() => a
            .iter()
            .zip(b)
            .enumerate()
            .find_map(|(i, (x, y))| first_difference(x, y, &format!("{at}[{i}]"))),
        _ if ours == theirs => None,
        _ => Some(format!("`{at}` (this run: {ours}, on disk: {theirs})")),
    }
}

/// A column of a run's CSV, or a group of them: header and value come from
/// one entry, so that they stay in step.
enum Column {
    /// A value of the evaluation point.
    Point(&'static str, fn(&EvalPoint) -> String),
    /// `<name>_<i>` for every agent `i`.
    EachAgent(&'static str, fn(&AgentStats) -> u64),
    /// The team's total so far.
    Team(&'static str, fn(&AgentStats) -> u64),
}

/// The columns of a run's CSV, in order.
const COLUMNS: &[Column] = &[
    Column::Point("episode", |p| p.episode.to_string()),
    Column::Point("goal_pct", |p| p.goal_pct.to_string()),
    // Empty without a goal.
    Column::Point("time_to_goal", |p| {
        p.time_to_goal.map(|t| t.to_string()).unwrap_or_default()
    }),
    Column::EachAgent("give_spent", |a| a.give_spent),
    Column::EachAgent("ask_spent", |a| a.ask_spent),
    Column::Team("advice_requests", |a| a.advice_requests),
    Column::Team("advice_given", |a| a.advice_given),
    // The give budget spent, averaged over agents.
    Column::Point("spent_budget", |p| p.spent_budget.to_string()),
    Column::Team("advice_replies_received", |a| a.advice_replies_received),
    Column::Team("messages_sent", |a| a.messages_sent),
    Column::Team("bytes_sent", |a| a.bytes_sent),
    Column::Team("messages_received", |a| a.messages_received),
    Column::Team("bytes_received", |a| a.bytes_received),
    // 0 in process.
    Column::Team("messages_dropped", |a| a.messages_dropped),
    // Awaited actions that missed the step timeout and were played as Move,
    // over the run so far (0 in process).
    Column::Point("actions_timed_out", |p| p.actions_timed_out.to_string()),
    // Advice requests, replies and shared episodes sent (in process: as
    // the zenoh transport would encode them).
    Column::Team("advising_messages", |a| a.advising_messages),
    Column::Team("advising_bytes", |a| a.advising_bytes),
    // What became of the requests (format 5).
    Column::Team("answered_requests", |a| a.answered_requests),
    Column::Team("declined_requests", |a| a.declined_requests),
    Column::Team("futile_requests", |a| a.futile_requests),
    Column::Team("lost_requests", |a| a.lost_requests),
    Column::Team("reused_advice", |a| a.reused_advice),
];

impl Column {
    fn names(&self, agents: usize) -> Vec<String> {
        match self {
            Column::Point(name, _) | Column::Team(name, _) => vec![(*name).to_owned()],
            Column::EachAgent(name, _) => (0..agents).map(|i| format!("{name}_{i}")).collect(),
        }
    }

    fn values(&self, p: &EvalPoint) -> Vec<String> {
        match self {
            Column::Point(_, value) => vec![value(p)],
            Column::EachAgent(_, value) => p.agents.iter().map(|a| value(a).to_string()).collect(),
            Column::Team(_, value) => vec![p.agents.iter().map(value).sum::<u64>().to_string()],
        }
    }
}

/// One run's CSV: a header, then one row per evaluation point, flushed as
/// soon as it is written. The columns are those of `COLUMNS`: the point's
/// goal percentage and time to goal, every agent's spent budgets, then the
/// team's advice and communication so far.
#[derive(Debug)]
pub struct RunWriter {
    path: PathBuf,
    csv: csv::Writer<File>,
    agents: usize,
}

impl RunWriter {
    fn create(path: &Path, agents: usize) -> Result<Self, Error> {
        let file = File::create(path).map_err(|e| Error::io("create", path, e))?;
        let mut w = Self {
            path: path.to_path_buf(),
            csv: csv::Writer::from_writer(file),
            agents,
        };
        let header: Vec<String> = COLUMNS.iter().flat_map(|c| c.names(agents)).collect();
        w.write_row(&header)?;
        Ok(w)
    }

    /// Appends one evaluation point and flushes it to the file.
    pub fn write_point(&mut self, p: &EvalPoint) -> Result<(), Error> {
        debug_assert_eq!(p.agents.len(), self.agents);
        let row: Vec<String> = COLUMNS.iter().flat_map(|c| c.values(p)).collect();
        self.write_row(&row)
    }

    fn write_row(&mut self, row: &[String]) -> Result<(), Error> {
        let to_io = |e: csv::Error| match e.into_kind() {
            csv::ErrorKind::Io(e) => e,
            other => std::io::Error::other(format!("{other:?}")),
        };
        self.csv
            .write_record(row)
            .map_err(to_io)
            .and_then(|()| self.csv.flush())
            .map_err(|e| Error::io("write", &self.path, e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use analysis::Timing;
    use serde_json::json;

    #[test]
    fn leftover_temporary_files_never_block_a_directory() {
        let tmp = tempfile::tempdir().unwrap();
        let identity = json!({"a": 1});
        fs::write(tmp.path().join(format!("{TEMP_PREFIX}x")), b"half").unwrap();
        check_claim(tmp.path(), "id.json", &identity).unwrap();
        fs::write(tmp.path().join("notes.txt"), b"mine").unwrap();
        let err = check_claim(tmp.path(), "id.json", &identity).unwrap_err();
        assert!(err.to_string().contains("notes.txt"), "{err}");
        let file = tmp.path().join("notes.txt");
        let err = check_claim(&file, "id.json", &identity).unwrap_err();
        assert!(err.to_string().contains("not a directory"), "{err}");
    }

    #[test]
    fn results_written_with_an_old_spelling_resume() {
        let tmp = tempfile::tempdir().unwrap();
        let old = json!({"config": {"team": [{"strategy": "torrey", "v_a": 0.5}]}});
        fs::write(tmp.path().join("config.json"), old.to_string()).unwrap();
        let today = json!({"config": {"team": [{"algorithm": "torrey", "v_a": 0.5}]}});
        check_claim(tmp.path(), "config.json", &today).unwrap();
        let other = json!({"config": {"team": [{"algorithm": "random", "v_a": 0.5}]}});
        check_claim(tmp.path(), "config.json", &other).unwrap_err();
    }

    #[test]
    fn differences_are_located() {
        let a = json!({"config": {"runs": 5, "team": [{"strategy": "torrey"}]}});
        let b = json!({"config": {"runs": 5, "team": [{"strategy": "random"}]}});
        let d = first_difference(&a, &b, "").unwrap();
        assert!(d.contains("config.team[0].strategy"), "{d}");
        assert_eq!(first_difference(&a, &a, ""), None);
        let c = json!({"config": {"runs": 5}});
        assert_eq!(first_difference(&a, &c, "").as_deref(), Some("config.team"));
    }

    #[test]
    fn same_config_is_accepted_other_is_refused_and_untouched() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("out");
        let ours = json!({"format": 1, "config": {"runs": 2}});
        let out = ExperimentDir::check(&dir, &ours).unwrap();
        assert!(!dir.exists(), "check writes nothing");
        out.create().unwrap();
        let mut w = out.run_writer(0, 2).unwrap();
        w.write_point(&EvalPoint {
            episode: 20,
            episodes: 10,
            goals: 0,
            goal_pct: 0.0,
            time_to_goal: None,
            agents: vec![AgentStats::default(); 2],
            spent_budget: 0.0,
            actions_timed_out: 4,
        })
        .unwrap();
        let csv = fs::read_to_string(dir.join("run-0.csv")).unwrap();
        assert_eq!(
            csv,
            "episode,goal_pct,time_to_goal,give_spent_0,give_spent_1,ask_spent_0,ask_spent_1,\
             advice_requests,advice_given,spent_budget,advice_replies_received,messages_sent,\
             bytes_sent,messages_received,bytes_received,messages_dropped,actions_timed_out,\
             advising_messages,advising_bytes,answered_requests,declined_requests,\
             futile_requests,lost_requests,reused_advice\n\
             20,0,,0,0,0,0,0,0,0,0,0,0,0,0,0,4,0,0,0,0,0,0,0\n"
        );
        ExperimentDir::check(&dir, &ours).unwrap();
        // More runs (or fewer) resume the same experiment.
        ExperimentDir::check(&dir, &json!({"format": 1, "config": {"runs": 9}})).unwrap();
        let theirs = json!({"format": 1, "config": {"runs": 2, "episodes": 3}});
        let err = ExperimentDir::check(&dir, &theirs).unwrap_err().to_string();
        assert!(
            err.contains("config.episodes") && err.contains("out"),
            "{err}"
        );
        assert_eq!(fs::read_to_string(dir.join("run-0.csv")).unwrap(), csv);

        // Results without a config.json are someone else's too.
        fs::remove_file(dir.join(CONFIG_FILE)).unwrap();
        let err = ExperimentDir::check(&dir, &ours).unwrap_err().to_string();
        assert!(err.contains("run-0.csv"), "{err}");
    }

    #[test]
    fn a_finished_run_reads_back_bit_for_bit() {
        let tmp = tempfile::tempdir().unwrap();
        let out = ExperimentDir::check(tmp.path(), &json!({})).unwrap();
        out.create().unwrap();
        // Means whose shortest decimal form the default float parser of
        // serde_json reads back one ulp off.
        let awkward = [
            1.271_006_919_926_564_1,
            2.542_013_839_853_128_2,
            7.887_090_078_870_901_5,
            9.132_420_091_324_201,
            10.377_750_103_777_501,
        ];
        let result = RunResult {
            joins: Vec::new(),
            played_with: None,
            restarts: Vec::new(),
            simulator_restarts: Vec::new(),
            advice_matrix: Vec::new(),
            run: 3,
            points: awkward
                .iter()
                .map(|&x| EvalPoint {
                    episode: 20,
                    episodes: 97,
                    goals: 7,
                    goal_pct: x,
                    time_to_goal: Some(x * 3.3),
                    agents: vec![AgentStats::default(); 2],
                    spent_budget: x / 7.0,
                    actions_timed_out: 0,
                })
                .collect(),
            timing: Timing {
                training_frames: 5,
                training_s: 0.1,
                evaluation_frames: 7,
                evaluation_s: 1.0 / 3.0,
            },
            advice_rtt_ms: vec![vec![0.1, 1.0 / 3.0, 2.7e-3]],
        };
        out.write_run_result(&result).unwrap();
        let back = out.finished_run(3).expect("the run is finished");
        for (a, b) in back.points.iter().zip(&result.points) {
            assert_eq!(a.goal_pct.to_bits(), b.goal_pct.to_bits());
            assert_eq!(
                a.time_to_goal.map(f64::to_bits),
                b.time_to_goal.map(f64::to_bits)
            );
            assert_eq!(a.spent_budget.to_bits(), b.spent_budget.to_bits());
        }
        assert_eq!(back.advice_rtt_ms, result.advice_rtt_ms);
        assert_eq!(back.timing, result.timing);
    }

    #[test]
    fn summary_is_written_atomically() {
        let tmp = tempfile::tempdir().unwrap();
        let out = ExperimentDir::check(tmp.path(), &json!({})).unwrap();
        out.create().unwrap();
        out.write_summary(&json!({"a": 1})).unwrap();
        out.write_summary(&json!({"a": 2})).unwrap();
        let mut names: Vec<_> = fs::read_dir(tmp.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        assert_eq!(names, ["config.json", "summary.json"]);
        let text = fs::read_to_string(tmp.path().join(SUMMARY_FILE)).unwrap();
        assert_eq!(text, "{\n  \"a\": 2\n}\n");
    }
}
