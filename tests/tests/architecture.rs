//! The rules of docs/ARCHITECTURE.md that the sources themselves can show:
//! no module imports forming a circle in any crate, pure libraries that
//! touch neither the network nor files, and packages, Rust or Python, that
//! stay in their layers.

use std::path::{Path, PathBuf};
use std::process::Command;

use integration_tests::modules::ModuleGraph;

/// The workspace's root directory.
fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The workspace's packages as `cargo metadata` describes them.
fn metadata() -> serde_json::Value {
    let output = Command::new(env!("CARGO"))
        .args([
            "metadata",
            "--no-deps",
            "--offline",
            "--format-version",
            "1",
        ])
        .current_dir(workspace())
        .output()
        .expect("cargo metadata runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).expect("JSON")
}

/// Every target's root file of every workspace package (libraries,
/// binaries, tests, benches, examples), read from `cargo metadata`.
fn target_roots() -> Vec<PathBuf> {
    let metadata = metadata();
    let packages = metadata["packages"].as_array().expect("packages");
    let roots: Vec<PathBuf> = packages
        .iter()
        .flat_map(|p| p["targets"].as_array().expect("targets"))
        .map(|t| PathBuf::from(t["src_path"].as_str().expect("src_path")))
        .collect();
    assert!(roots.len() > 10, "{roots:?}");
    roots
}

#[test]
fn no_crate_has_an_import_circle() {
    let mut circles = Vec::new();
    for root in target_roots() {
        let graph = ModuleGraph::read(&root).unwrap_or_else(|e| panic!("{e}"));
        circles.extend(graph.circles());
    }
    let workspace = workspace().canonicalize().unwrap().display().to_string() + "/";
    let circles: Vec<String> = circles.iter().map(|c| c.replace(&workspace, "")).collect();
    assert!(
        circles.is_empty(),
        "import circles:\n{}",
        circles.join("\n")
    );
}

/// What `crate` depends on through normal dependencies, one package a line.
fn normal_dependencies(krate: &str) -> String {
    dependencies_to(krate, &[])
}

/// `krate` and the packages it names itself (`cargo tree --depth 1`).
fn direct_dependencies(krate: &str) -> String {
    dependencies_to(krate, &["--depth", "1"])
}

fn dependencies_to(krate: &str, depth: &[&str]) -> String {
    let output = Command::new(env!("CARGO"))
        .args([
            "tree",
            "--offline",
            "-e",
            "normal",
            "--prefix",
            "none",
            "-p",
            krate,
        ])
        .args(depth)
        .current_dir(workspace())
        .output()
        .expect("cargo tree runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).expect("UTF-8")
}

/// Every workspace package, by name, with the directory of its manifest
/// relative to the workspace.
fn packages() -> Vec<(String, PathBuf)> {
    let metadata = metadata();
    let root = workspace().canonicalize().unwrap();
    let packages = metadata["packages"].as_array().expect("packages");
    packages
        .iter()
        .map(|p| {
            let manifest = Path::new(p["manifest_path"].as_str().expect("manifest_path"));
            let dir = manifest.parent().unwrap().strip_prefix(&root).unwrap();
            (
                p["name"].as_str().expect("name").to_owned(),
                dir.to_path_buf(),
            )
        })
        .collect()
}

/// The layers, lowest first: a package under a layer's directory (the
/// longest that holds it) depends on no package of a layer above it, and a
/// Python file there imports none (a package's layer: the top directory
/// that holds it). The simulator and its binding stand below the agent; the
/// coordinator above both; the Python package `adhoc_advising`, the
/// framework from Python, on top of them all.
const LAYERS: [(&str, &[&str]); 4] = [
    ("proto", &["env-server", "agent", "coordinator"]),
    ("env-server", &["agent", "coordinator"]),
    ("agent", &["env-server", "coordinator"]),
    ("coordinator/python", &[]),
];

/// What the layer holding `path` (relative to the workspace) must not
/// depend on: the list of the longest of LAYERS that holds it.
fn layer_above(path: &Path) -> Option<&'static [&'static str]> {
    (LAYERS.iter())
        .filter(|(layer, _)| path.starts_with(layer))
        .max_by_key(|(layer, _)| layer.len())
        .map(|(_, above)| *above)
}

/// The top directory of `path` (relative to the workspace), as LAYERS's
/// lists name them.
fn home(path: &Path) -> String {
    let top = path.components().next();
    top.map(|c| c.as_os_str().to_string_lossy().into_owned())
        .unwrap_or_default()
}

#[test]
fn every_package_stays_in_its_layer() {
    let packages = packages();
    let home_of = |name: &str| {
        let (_, dir) = packages.iter().find(|(n, _)| n == name).expect("a package");
        home(dir)
    };
    let mut violations = Vec::new();
    for (name, dir) in &packages {
        if let Some(above) = layer_above(dir) {
            for line in normal_dependencies(name).lines().skip(1) {
                let dependency = line.split(' ').next().unwrap_or_default();
                if packages.iter().any(|(n, _)| n == dependency)
                    && above.contains(&home_of(dependency).as_str())
                {
                    violations.push(format!(
                        "{name} ({}) depends on {dependency}",
                        dir.display()
                    ));
                }
            }
        }
    }
    violations.sort();
    violations.dedup();
    assert!(
        violations.is_empty(),
        "layers crossed:\n{}",
        violations.join("\n")
    );
}

/// Every `.py` file of the workspace and every Python package (the
/// outermost directory with an `__init__.py`) by name, relative to the
/// workspace; build outputs, hidden directories and virtual environments
/// left out. A package under a `tests` directory is a test's stand-in
/// (`fake_hfo/hfo` for HFO's `hfo`) or helper: its files are among the
/// files, but it is no package of its layer, so that a stand-in for a
/// package of ours can neither hide nor move that package's layer.
fn python_sources() -> (Vec<PathBuf>, Vec<(String, PathBuf)>) {
    let root = workspace().canonicalize().unwrap();
    let (mut files, mut packages) = (Vec::new(), Vec::new());
    let mut dirs = vec![PathBuf::new()];
    while let Some(dir) = dirs.pop() {
        if root.join(&dir).join("pyvenv.cfg").exists() {
            continue;
        }
        let is_package = |d: &Path| root.join(d).join("__init__.py").is_file();
        let in_tests = dir.components().any(|c| c.as_os_str() == "tests");
        if is_package(&dir) && !dir.parent().is_some_and(is_package) && !in_tests {
            let name = dir.file_name().unwrap().to_string_lossy().into_owned();
            packages.push((name, dir.clone()));
        }
        for entry in std::fs::read_dir(root.join(&dir)).unwrap() {
            let entry = entry.unwrap();
            let name = entry.file_name().to_string_lossy().into_owned();
            let kind = entry.file_type().unwrap();
            let skipped =
                name.starts_with('.') || ["target", "__pycache__"].contains(&name.as_str());
            if kind.is_dir() && !skipped {
                dirs.push(dir.join(&name));
            } else if kind.is_file() && name.ends_with(".py") {
                files.push(dir.join(&name));
            }
        }
    }
    files.sort();
    (files, packages)
}

/// The top-level modules a line of Python imports, at any indentation:
/// `import a.b, c as d` gives `a` and `c`; `from a.b import c` gives `a`;
/// a relative import, none.
fn imported_modules(line: &str) -> Vec<&str> {
    let code = line.split('#').next().unwrap_or_default().trim();
    fn top(module: &str) -> &str {
        module.trim().split(['.', ' ']).next().unwrap_or_default()
    }
    if let Some(rest) = code.strip_prefix("from ") {
        match rest.split_whitespace().collect::<Vec<_>>()[..] {
            [module, "import", ..] if !module.starts_with('.') => vec![top(module)],
            _ => Vec::new(),
        }
    } else if let Some(rest) = code.strip_prefix("import ") {
        rest.split(',').map(top).filter(|m| !m.is_empty()).collect()
    } else {
        Vec::new()
    }
}

#[test]
fn python_modules_stay_in_their_layers() {
    let (files, packages) = python_sources();
    assert!(
        ["adhoc_advising", "halffield", "hfo_oracle"]
            .iter()
            .all(|p| packages.iter().any(|(name, _)| name == p)),
        "{packages:?}"
    );
    let mut violations = Vec::new();
    for file in &files {
        let Some(above) = layer_above(file) else {
            continue;
        };
        let text = std::fs::read_to_string(workspace().join(file)).expect("UTF-8");
        for (number, line) in text.lines().enumerate() {
            for module in imported_modules(line) {
                for (name, dir) in &packages {
                    if name == module && above.contains(&home(dir).as_str()) {
                        violations.push(format!(
                            "{}:{}: imports {module}, a package of {} ({})",
                            file.display(),
                            number + 1,
                            home(dir),
                            dir.display()
                        ));
                    }
                }
            }
        }
    }
    assert!(
        violations.is_empty(),
        "Python imports of a layer above or beside the file's:\n{}",
        violations.join("\n")
    );
}

#[test]
fn the_pure_libraries_use_neither_network_nor_files() {
    for krate in ["proto", "agent", "env-server"] {
        let tree = normal_dependencies(krate);
        for forbidden in ["zenoh", "tokio", "clap"] {
            let found = tree
                .lines()
                .find(|l| l.starts_with(&format!("{forbidden} ")));
            assert!(found.is_none(), "{krate} depends on {found:?}");
        }
        let root = workspace().join(krate).join("src/lib.rs");
        let graph = ModuleGraph::read(&root).unwrap_or_else(|e| panic!("{e}"));
        for (file, path) in graph.external_paths() {
            let io = ["fs", "net", "process"]
                .iter()
                .any(|m| path.starts_with(&format!("std::{m}")));
            assert!(!io, "{} uses {path}", file.display());
        }
    }
}

#[test]
fn the_analysis_needs_no_transport_and_no_runner() {
    let tree = normal_dependencies("analysis");
    for forbidden in ["zenoh", "tokio", "coordinator", "env-server"] {
        let found = tree
            .lines()
            .find(|l| l.starts_with(&format!("{forbidden} ")));
        assert!(found.is_none(), "analysis depends on {found:?}");
    }
    // The runner's pool is no dependency of its own. (candle, the DQN's
    // tensors in `agent`, brings rayon for its CPU kernels: no runner.)
    let direct = direct_dependencies("analysis");
    let found = direct.lines().find(|l| l.starts_with("rayon "));
    assert!(found.is_none(), "analysis depends on {found:?} itself");
    // Its files are read and written in one module.
    let root = workspace().join("coordinator/analysis/src/lib.rs");
    let graph = ModuleGraph::read(&root).unwrap_or_else(|e| panic!("{e}"));
    for (file, path) in graph.external_paths() {
        let io = ["fs", "net", "process"]
            .iter()
            .any(|m| path.starts_with(&format!("std::{m}")));
        let files = file.ends_with("coordinator/analysis/src/files.rs");
        assert!(!io || files, "{} uses {path}", file.display());
    }
}

#[test]
fn files_are_written_in_one_place() {
    // What creates or writes files and directories, outside test code.
    let writes = [
        "std::fs::write",
        "std::fs::File::create",
        "std::fs::OpenOptions",
        "std::fs::create_dir",
        "std::fs::rename",
        "std::fs::copy",
        "tempfile::Builder",
        "tempfile::tempdir",
        "tempfile::NamedTempFile",
        "fs::write",
        "fs::File::create",
        "fs::OpenOptions",
        "fs::create_dir",
    ];
    // node's atomic write and secret file, the coordinator's results and
    // the analysis's report.
    let allowed = [
        "proto/node/src/files.rs",
        "proto/node/src/secret.rs",
        "coordinator/src/store.rs",
        "coordinator/analysis/src/files.rs",
    ];
    let workspace = workspace().canonicalize().unwrap();
    for root in target_roots() {
        let graph = ModuleGraph::read(&root).unwrap_or_else(|e| panic!("{e}"));
        for (file, path) in graph.external_paths() {
            let file = file.strip_prefix(&workspace).unwrap_or(file);
            let writes_files = writes.iter().any(|w| path.starts_with(w));
            let allowed = allowed.iter().any(|a| file == Path::new(a));
            let is_test = file.components().any(|c| {
                c.as_os_str() == "tests"
                    || c.as_os_str() == "benches"
                    || c.as_os_str() == "examples"
            });
            assert!(
                !writes_files || allowed || is_test,
                "{} writes files: {path}",
                file.display()
            );
        }
    }
}

#[test]
fn advising_is_decided_only_by_the_agent_library() {
    // The formulas and budgets of the strategies: a transport never names them.
    let advising = [
        "p_ask",
        "p_give",
        "psi_td",
        "psi_visit",
        "ask_budget",
        "give_budget",
    ];
    for krate in [
        "agent/process/src/main.rs",
        "env-server/process/src/main.rs",
        "coordinator/src/lib.rs",
    ] {
        let graph = ModuleGraph::read(&workspace().join(krate)).unwrap_or_else(|e| panic!("{e}"));
        for (file, path) in graph.external_paths() {
            let decides = advising
                .iter()
                .any(|name| path.split("::").any(|s| s == *name));
            assert!(!decides, "{} decides advice: {path}", file.display());
        }
    }
}
