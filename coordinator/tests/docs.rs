//! The docs that say what the files and settings are, kept true:
//! docs/results.md names every file, CSV column and JSON key that a run and
//! a study write, and docs/settings.md every command-line option, team-file
//! key and study-file key.
//!
//! A name counts as documented when the doc has it as inline code
//! (`` `name` ``), or as one component of a dotted path in inline code
//! (`` `cost.wall_s` `` names `cost` and `wall_s`). Names that are data
//! become patterns first: the digits of `run-3.csv`, `give_spent_2` and
//! `run-3-agent-2.snapshot` become `<k>` (a run) and `<i>` (an agent), an
//! entry's directory `<entry>/`. The keys come from what the binaries write
//! and from the code's own types, never from a list kept here.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use agent::{
    AdHoc, AgentConfig, Algorithm, LearnerSettings, NetworkConditions, Profile, Reachable,
};
use analysis::{AgentStats, EvalPoint, RunResult, Timing};
use coordinator::config::ChildSpec;
use coordinator::experiment::Record;
use coordinator::membership::MembershipEvent;
use coordinator::plugin::PluginSpec;
use coordinator::study::{PRESETS, StudyConfig};
use coordinator::{AgentSpec, ExperimentConfig, Transport, ZenohSettings, summarize};
use serde_json::Value;

fn coordinator<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_coordinator"))
        .args(args)
        .env_remove("RUST_LOG")
        .output()
        .expect("the binary runs")
}

fn ok(output: &Output) {
    assert!(
        output.status.success(),
        "exit {:?}, stderr: {}",
        output.status.code(),
        String::from_utf8_lossy(&output.stderr)
    );
}

/// The doc `docs/<name>`.
fn doc(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../docs")
        .join(name);
    fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Every name `markdown` gives as inline code, outside fenced blocks: each
/// span, and each component of a dotted path without its brackets
/// (`[transport.zenoh]` names `transport` and `zenoh`, `team[].load` names
/// `team` and `load`, `[[entry]]` names `entry`).
fn names_in(markdown: &str) -> BTreeSet<String> {
    let bare = |part: &str| {
        let part = part.trim_start_matches('[').trim_end_matches(']');
        part.split('[').next().unwrap_or_default().to_owned()
    };
    let mut names = BTreeSet::new();
    let mut fenced = false;
    for line in markdown.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        for span in line.split('`').skip(1).step_by(2) {
            names.insert(span.to_owned());
            if !span.contains(' ') {
                names.extend(span.split('.').map(bare));
            }
        }
    }
    names
}

/// The part of `markdown` under the first heading that contains `title`,
/// down to the next heading of the same or a higher level; none without
/// such a heading.
fn section(markdown: &str, title: &str) -> Option<String> {
    let level = |line: &str| {
        let hashes = line.chars().take_while(|&c| c == '#').count();
        (hashes > 0 && line[hashes..].starts_with(' ')).then_some(hashes)
    };
    let mut lines = markdown.lines();
    let depth = lines.find_map(|l| level(l).filter(|_| l.contains(title)))?;
    let body: Vec<&str> = lines
        .take_while(|l| level(l).is_none_or(|d| d > depth))
        .collect();
    Some(body.join("\n"))
}

/// `name` with its data made a pattern: a whole number that is a
/// `-`/`_`/`.`-separated part becomes `<k>` after `run-`, `<i>` elsewhere
/// (`give_spent_2`, `run-3-agent-2.snapshot`); `p99` stays.
fn pattern(name: &str) -> String {
    let mut out = String::new();
    let mut rest = name;
    while let Some(c) = rest.chars().next() {
        let digits = rest.chars().take_while(char::is_ascii_digit).count();
        let after = rest[digits..].chars().next();
        let at_start = out.is_empty() || out.ends_with(['-', '_', '.']);
        if digits > 0 && at_start && after.is_none_or(|c| matches!(c, '-' | '_' | '.')) {
            out.push_str(if out.ends_with("run-") { "<k>" } else { "<i>" });
            rest = &rest[digits..];
        } else {
            out.push(c);
            rest = &rest[c.len_utf8()..];
        }
    }
    out
}

/// What a doc must name: every name, with the first place it was found.
#[derive(Default)]
struct Names {
    /// Name (as a pattern) -> (what it is, where it was found).
    found: BTreeMap<String, (&'static str, String)>,
    /// Names that are data, and the pattern they stand for (entry names
    /// and algorithm names -> `<entry>`).
    data: BTreeMap<String, String>,
}

impl Names {
    fn add(&mut self, name: &str, kind: &'static str, at: String) {
        let name = self
            .data
            .get(name)
            .cloned()
            .unwrap_or_else(|| pattern(name));
        self.found.entry(name).or_insert((kind, at));
    }

    /// Every file and directory under `dir` (shown as `label`), every
    /// column of its CSVs and every key of its JSON files.
    fn files(&mut self, dir: &Path, label: &str) {
        let mut entries: Vec<PathBuf> = fs::read_dir(dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.unwrap().path())
            .collect();
        entries.sort();
        for path in entries {
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            let at = format!("{label}/{name}");
            if path.is_dir() {
                self.add(&format!("{name}/"), "directory", at.clone());
                self.files(&path, &at);
                continue;
            }
            if label.ends_with("figures") {
                // A figure is named by its name, without `.svg` or `.png`.
                let stem = path.file_stem().unwrap().to_string_lossy();
                self.add(&stem, "figure", at);
                continue;
            }
            self.add(&name, "file", at.clone());
            match path.extension().and_then(|e| e.to_str()) {
                Some("csv") => {
                    let text = fs::read_to_string(&path).unwrap();
                    let header = text.lines().next().unwrap_or_default();
                    for column in header.split(',') {
                        self.add(column, "column", at.clone());
                    }
                }
                Some("json") => {
                    let value: Value = serde_json::from_slice(&fs::read(&path).unwrap())
                        .unwrap_or_else(|e| panic!("{at}: {e}"));
                    self.keys(&value, &at, "");
                }
                _ => {}
            }
        }
    }

    /// Every object key of `value` (in `file`, at the path `at`), arrays'
    /// items included.
    fn keys(&mut self, value: &Value, file: &str, at: &str) {
        match value {
            Value::Object(map) => {
                for (key, v) in map {
                    let path = if at.is_empty() {
                        key.clone()
                    } else {
                        format!("{at}.{key}")
                    };
                    self.add(key, "key", format!("{file}: {path}"));
                    self.keys(v, file, &path);
                }
            }
            Value::Array(items) => {
                for item in items {
                    self.keys(item, file, &format!("{at}[]"));
                }
            }
            _ => {}
        }
    }

    /// Panics naming every name `doc` (read as `doc_name`) lacks.
    fn assert_named_in(&self, doc: &str, doc_name: &str) {
        let named = names_in(doc);
        let missing: Vec<String> = (self.found.iter())
            .filter(|(name, _)| !named.contains(*name))
            .map(|(name, (kind, at))| format!("  {kind} `{name}` (found in {at})"))
            .collect();
        assert!(
            missing.is_empty(),
            "docs/{doc_name} does not name these; add each as `name`, with its unit and \
             meaning:\n{}",
            missing.join("\n")
        );
    }
}

/// A study that writes every kind of file a study writes: a pretraining
/// and its expert, a baseline, network conditions.
const STUDY: &str = r#"
name = "docs"
description = "Every kind of file a study writes, small"
runs = 2
episodes = 20
eval_every = 10
eval_episodes = 2
seed = 1
transport = "in-process"
baseline = "no-advice"

[pretrain]
algorithm = "no-advice"
episodes = 10
expert = 2

[[entry]]
name = "no-advice"
algorithm = "no-advice"

[[entry]]
name = "adhoc-td-lossy"
algorithm = "adhoc-td"
network = { latency = "uniform:1,2", loss = 0.2 }

[[entry]]
name = "torrey-expert"
algorithm = "torrey"
expert = true
"#;

/// The data names of a study's files: its entries' and the algorithms'.
fn data_names(entries: &[&str]) -> BTreeMap<String, String> {
    let algorithms = Algorithm::all().map(|a| a.name());
    (entries.iter().copied().chain(algorithms))
        .map(|name| (name.to_owned(), "<entry>".to_owned()))
        .chain((entries.iter()).map(|name| (format!("{name}/"), "<entry>/".to_owned())))
        .collect()
}

/// What a run over zenoh writes that an in-process run does not, with
/// every optional key of a team entry: `config.json` and `summary.json` of
/// such a run, made by the code that writes them.
fn zenoh_record_and_summary() -> (Value, Value) {
    let mut config = ExperimentConfig {
        runs: 1,
        episodes: 10,
        eval_every: 10,
        eval_episodes: 1,
        transport: Transport::Zenoh(ZenohSettings::default()),
        ..ExperimentConfig::default()
    };
    let ad_hoc = |reachable| {
        let mut c = AgentConfig {
            network: Some(NetworkConditions::default()),
            ..AgentConfig::of("adhoc-td".parse().unwrap(), Profile::Paper)
        };
        c.algorithm.get_mut::<AdHoc>().unwrap().reachable = reachable;
        c
    };
    config.team[0].config = ad_hoc(Reachable::Agents(vec![1, 2]));
    config.team[0].load = Some("expert.snapshot".into());
    config.team[0].keep_counters = true;
    config.team[1].config = ad_hoc(Reachable::WithinDistance(20.0));
    config.team[2].learner = Some(ChildSpec {
        command: vec!["python3".into(), "learner.py".into()],
        dir: Some("learners".into()),
        source: Some("learner.py".into()),
        source_fnv64: Some("0123456789abcdef".into()),
    });
    config.events = vec![MembershipEvent {
        episode: 1,
        slot: 2,
        newcomer: Some(config.team[1].clone()),
    }];
    let record = Record {
        format: coordinator::experiment::RESULTS_FORMAT_VERSION,
        config: &config,
        snapshot_digests: vec![Some("0123456789abcdef".into()), None, None],
    };
    let points = config
        .eval_points()
        .into_iter()
        .map(|episode| EvalPoint {
            episode,
            episodes: 1,
            goals: 1,
            goal_pct: 100.0,
            time_to_goal: Some(50.0),
            agents: vec![AgentStats::default(); 3],
            spent_budget: 0.0,
            actions_timed_out: 0,
        })
        .collect();
    let results = [RunResult {
        run: 0,
        points,
        timing: Timing::default(),
        advice_rtt_ms: vec![vec![1.5]; 3],
        joins: Vec::new(),
        played_with: None,
        restarts: Vec::new(),
        simulator_restarts: Vec::new(),
        advice_matrix: Vec::new(),
    }];
    let summary = summarize(&record, &results);
    (
        serde_json::to_value(&record).unwrap(),
        serde_json::to_value(&summary).unwrap(),
    )
}

#[test]
fn a_run_writes_only_what_results_md_names() {
    let tmp = tempfile::tempdir().unwrap();
    let (out, agents) = (tmp.path().join("out"), tmp.path().join("agents"));
    ok(&coordinator(&[
        "run",
        "--algorithm",
        "adhoc-td",
        "--runs",
        "2",
        "--episodes",
        "20",
        "--eval-every",
        "10",
        "--eval-episodes",
        "2",
        "--transport",
        "in-process",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
        "--save-agents",
        agents.to_str().unwrap(),
    ]));
    let mut names = Names {
        data: data_names(&[]),
        ..Names::default()
    };
    names.files(&out, "run --out");
    names.files(&agents, "run --save-agents");
    let (record, summary) = zenoh_record_and_summary();
    names.keys(&record, "config.json of a zenoh run (in memory)", "");
    names.keys(&summary, "summary.json of a zenoh run (in memory)", "");
    names.assert_named_in(&doc("results.md"), "results.md");
}

#[test]
fn a_study_writes_only_what_results_md_names() {
    let tmp = tempfile::tempdir().unwrap();
    let (file, out) = (tmp.path().join("docs.toml"), tmp.path().join("out"));
    fs::write(&file, STUDY).unwrap();
    ok(&coordinator(&[
        "study",
        "--config",
        file.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]));
    let mut names = Names {
        data: data_names(&["no-advice", "adhoc-td-lossy", "torrey-expert"]),
        ..Names::default()
    };
    names.files(&out, "study --out");
    names.assert_named_in(&doc("results.md"), "results.md");
}

/// The subcommands a `--help` lists (but `help`).
fn subcommands(help: &str) -> Vec<String> {
    (help.lines())
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| !l.trim().is_empty())
        .filter_map(|l| l.split_whitespace().next())
        .filter(|&c| c != "help")
        .map(str::to_owned)
        .collect()
}

/// The long options a `--help` lists (but `--help` and `--version`).
fn long_options(help: &str) -> Vec<String> {
    (help.lines())
        .filter(|l| l.trim_start().starts_with('-'))
        .filter_map(|l| l.split_whitespace().find(|w| w.starts_with("--")))
        .map(|w| w.trim_end_matches(',').to_owned())
        .filter(|o| o != "--help" && o != "--version")
        .collect()
}

fn help_of(program: &Path, args: &[&str]) -> String {
    let output = Command::new(program)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("{}: {e}", program.display()));
    ok(&output);
    String::from_utf8(output.stdout).unwrap()
}

/// Every long option of `program`'s subcommands `subs` (the program itself
/// if empty) is named in the section of `doc` headed by `` `<title> <sub>` ``.
fn options_in_sections(
    program: &Path,
    title: &str,
    subs: &[String],
    doc: &str,
    missing: &mut Vec<String>,
) {
    let commands: Vec<(String, Vec<&str>)> = if subs.is_empty() {
        vec![(title.to_owned(), vec!["--help"])]
    } else {
        (subs.iter())
            .map(|s| (format!("{title} {s}"), vec![s.as_str(), "--help"]))
            .collect()
    };
    for (command, args) in commands {
        let heading = format!("`{command}`");
        let Some(text) = section(doc, &heading) else {
            missing.push(format!("  a section headed {heading}, with its options"));
            continue;
        };
        let named = names_in(&text);
        for option in long_options(&help_of(program, &args)) {
            if !named.contains(&option) {
                missing.push(format!("  option `{option}` in the section {heading}"));
            }
        }
    }
}

/// Every object key of `value`, with its path, arrays' items included.
fn keys_of(value: &Value, at: &str, into: &mut BTreeMap<String, String>) {
    match value {
        Value::Object(map) => {
            for (key, v) in map {
                let path = if at.is_empty() {
                    key.clone()
                } else {
                    format!("{at}.{key}")
                };
                into.entry(key.clone()).or_insert(path.clone());
                keys_of(v, &path, into);
            }
        }
        Value::Array(items) => {
            for item in items {
                keys_of(item, &format!("{at}[]"), into);
            }
        }
        _ => {}
    }
}

/// Every key of a team file's `[[agent]]` table, as the code writes them:
/// every algorithm's flat table, the optional keys (network conditions,
/// the reachable sets, `load`, `keep_counters`, `learner`) given.
fn team_file_keys() -> BTreeMap<String, String> {
    let mut configs: Vec<AgentConfig> = Algorithm::all()
        .map(|algorithm| {
            let mut config = AgentConfig {
                network: Some(NetworkConditions::default()),
                ..AgentConfig::of(algorithm, Profile::Paper)
            };
            // The keys written only when set, set (a number: a fraction or
            // a count).
            for (key, value) in config.algorithm.settings() {
                match value {
                    Value::Null => (config.algorithm.set(&key, Value::from(0.1)))
                        .or_else(|_| config.algorithm.set(&key, Value::from(1)))
                        .unwrap(),
                    Value::Bool(false) => config.algorithm.set(&key, Value::Bool(true)).unwrap(),
                    _ => continue,
                }
            }
            config
        })
        .collect();
    for reachable in [Reachable::Agents(vec![1]), Reachable::WithinDistance(9.0)] {
        let mut config = AgentConfig::of("adhoc-visit".parse().unwrap(), Profile::Paper);
        config.algorithm.get_mut::<AdHoc>().unwrap().reachable = reachable;
        configs.push(config);
    }
    for learner in ["ensemble", "dqn"] {
        configs.push(AgentConfig {
            learner: LearnerSettings::named(learner).unwrap(),
            ..AgentConfig::default()
        });
    }
    let child = ChildSpec {
        command: vec!["python3".into(), "child.py".into()],
        dir: Some("children".into()),
        source: Some("child.py".into()),
        source_fnv64: Some("0123456789abcdef".into()),
    };
    let mut keys = BTreeMap::new();
    for config in configs {
        let spec = AgentSpec {
            config,
            load: Some("expert.snapshot".into()),
            keep_counters: true,
            learner: Some(child.clone()),
            strategy_process: Some(child.clone()),
            plugin: Some(PluginSpec {
                learner: Some("numpy-linear-sarsa 1".into()),
                strategy: Some("nearest-teammate 1".into()),
            }),
        };
        keys_of(&serde_json::to_value(spec).unwrap(), "", &mut keys);
    }
    keys
}

/// Every key of a study file, as the code writes them: every preset's, and
/// the zenoh transport's table; an entry's team-file keys are the Team
/// files section's.
fn study_file_keys() -> BTreeMap<String, String> {
    let mut keys = BTreeMap::new();
    for (name, _) in PRESETS {
        let mut study = StudyConfig::preset(name).unwrap();
        for entry in &mut study.entries {
            entry.settings.clear();
        }
        keys_of(&serde_json::to_value(&study).unwrap(), "", &mut keys);
        study.transport = Transport::Zenoh(ZenohSettings::default());
        keys_of(&serde_json::to_value(&study).unwrap(), "", &mut keys);
    }
    keys
}

#[test]
fn every_setting_is_in_settings_md() {
    let doc = doc("settings.md");
    let mut missing = Vec::new();

    let bin = Path::new(env!("CARGO_BIN_EXE_coordinator"));
    let subs = subcommands(&help_of(bin, &["--help"]));
    assert!(subs.contains(&"run".to_owned()), "{subs:?}");
    options_in_sections(bin, "coordinator", &subs, &doc, &mut missing);
    // The other binaries, when built beside it (`cargo test --workspace`
    // builds them; `cargo test -p coordinator` may not).
    let agent = bin.with_file_name("agent");
    if agent.is_file() {
        options_in_sections(&agent, "agent", &[], &doc, &mut missing);
    } else {
        eprintln!("{} not built: its options are not checked", agent.display());
    }
    let env_server = bin.with_file_name("env-server");
    if env_server.is_file() {
        let subs = subcommands(&help_of(&env_server, &["--help"]));
        options_in_sections(&env_server, "env-server", &subs, &doc, &mut missing);
    } else {
        eprintln!(
            "{} not built: its options are not checked",
            env_server.display()
        );
    }

    let mut in_section = |title: &str, what: &str, keys: BTreeMap<String, String>| {
        let Some(text) = section(&doc, title) else {
            missing.push(format!("  a section headed {title}, with every {what}"));
            return;
        };
        let named = names_in(&text);
        for (key, path) in keys {
            if !named.contains(&key) {
                missing.push(format!(
                    "  {what} `{key}` (at `{path}`) in the section {title}"
                ));
            }
        }
    };
    in_section("Team files", "team-file key", team_file_keys());
    in_section("Study files", "study-file key", study_file_keys());
    let mut env = BTreeMap::new();
    let env_config = env_server::EnvConfig::default();
    keys_of(&serde_json::to_value(env_config).unwrap(), "", &mut env);
    in_section("Env settings", "env setting", env);
    let mut values = BTreeMap::new();
    for algorithm in Algorithm::all() {
        values.insert(algorithm.name().to_owned(), "algorithm".to_owned());
        for alias in algorithm.aliases() {
            values.insert((*alias).to_owned(), "algorithm (old spelling)".to_owned());
        }
    }
    for profile in Profile::ALL {
        values.insert(profile.name().to_owned(), "profile".to_owned());
    }
    in_section("Team files", "value", values);
    let preset_row = (doc.lines())
        .find(|line| line.starts_with("| `--preset` |"))
        .unwrap_or_default();
    for (name, _) in PRESETS {
        if !preset_row.contains(&format!("`{name}`")) {
            missing.push(format!("  preset `{name}` in the row of `--preset`"));
        }
    }

    assert!(
        missing.is_empty(),
        "docs/settings.md lacks these; add each as `name`, with its type, default, meaning \
         and where it is recorded:\n{}",
        missing.join("\n")
    );
}

#[test]
fn patterns_and_sections_read_as_meant() {
    assert_eq!(pattern("give_spent_12"), "give_spent_<i>");
    assert_eq!(
        pattern("run-3-agent-2.snapshot"),
        "run-<k>-agent-<i>.snapshot"
    );
    assert_eq!(pattern("run-10.csv"), "run-<k>.csv");
    assert_eq!(pattern("p99"), "p99");
    assert_eq!(pattern("7"), "<i>");
    let md =
        "# A\n`a`\n## `B c`\n`b.c_d[]` `[t.z]` `[[h]]`\n### sub\n`e`\n## D\n`f`\n```\n`g`\n```\n";
    let b = section(md, "`B c`").unwrap();
    let named = names_in(&b);
    for name in ["b.c_d[]", "b", "c_d", "e", "t", "z", "h"] {
        assert!(named.contains(name), "{name} in {named:?}");
    }
    assert!(!named.contains("f") && !named.contains("a"));
    assert!(!names_in(md).contains("g"), "fenced code is not a name");
    let help = "Commands:\n  run  Run\n  help  Help\n\nOptions:\n      --out <DIR>  Out\n  -h, --help  Help\n";
    assert_eq!(subcommands(help), ["run"]);
    assert_eq!(long_options(help), ["--out"]);
}
