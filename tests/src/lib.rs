//! Helpers shared by the end-to-end tests in `tests/`: where the workspace's
//! executables are, one run of a team file, unique experiment names (free
//! loopback ports come from `node::net::free_port`), and the module graph of
//! a crate ([`modules`]).

use std::path::{Path, PathBuf};
use std::process::Command;

pub mod modules;

/// The directory holding the workspace's executables (`target/<profile>`).
///
/// # Panics
/// If the `env-server`, `agent` and `coordinator` executables are not there:
/// run the tests with `cargo test --workspace`, which builds them.
pub fn bin_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable path");
    let dir = exe
        .parent()
        .and_then(|deps| deps.parent())
        .expect("target/<profile>/deps")
        .to_path_buf();
    for name in ["env-server", "agent", "coordinator"] {
        let path = dir.join(format!("{name}{}", std::env::consts::EXE_SUFFIX));
        assert!(
            path.is_file(),
            "{} is missing: run `cargo test --workspace` (it builds every executable)",
            path.display()
        );
    }
    dir
}

/// The path of one of the workspace's executables.
pub fn bin(name: &str) -> PathBuf {
    bin_dir().join(format!("{name}{}", std::env::consts::EXE_SUFFIX))
}

/// One run of the team file `team` over `transport` into `out`, played by
/// `coordinator run` with `schedule` (`--episodes`, `--eval-every`, ...):
/// its `run-0.json`, without the measured `timing`.
///
/// # Panics
/// If the run fails (with its standard error) or its file does not parse.
pub fn team_run(team: &Path, transport: &str, schedule: &[&str], out: &Path) -> serde_json::Value {
    let output = Command::new(bin("coordinator"))
        .args(["run", "--team"])
        .arg(team)
        .args(["--runs", "1"])
        .args(schedule)
        .args(["--transport", transport, "--quiet", "--out"])
        .arg(out)
        .output()
        .expect("start the coordinator");
    assert!(
        output.status.success(),
        "{transport}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = std::fs::read_to_string(out.join("run-0.json")).expect("run-0.json");
    let mut run: serde_json::Value = serde_json::from_str(&text).expect("run-0.json parses");
    if let Some(run) = run.as_object_mut() {
        run.remove("timing");
    }
    run
}

/// An experiment name unique to this test process and `tag`.
pub fn experiment_name(tag: &str) -> String {
    format!("test-{tag}-{}", std::process::id())
}

/// The command line of process `pid`, arguments separated by NUL (Linux
/// /proc; empty once it is gone).
pub fn cmdline(pid: u32) -> String {
    std::fs::read_to_string(format!("/proc/{pid}/cmdline")).unwrap_or_default()
}

/// Whether process `pid` runs (exists and is not a zombie).
pub fn is_running(pid: u32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/stat"))
        .map(|s| !s.contains(") Z "))
        .unwrap_or(false)
}

/// Running processes whose command line contains `needle`, e.g. an
/// experiment name passed with `--experiment`.
pub fn processes_with(needle: &str) -> Vec<u32> {
    let Ok(entries) = std::fs::read_dir("/proc") else {
        return Vec::new();
    };
    entries
        .filter_map(|e| e.ok()?.file_name().to_str()?.parse::<u32>().ok())
        .filter(|&pid| pid != std::process::id())
        .filter(|&pid| cmdline(pid).contains(needle) && is_running(pid))
        .collect()
}
