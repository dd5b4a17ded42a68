//! Records the commit the coordinator is built from (`ADV_COMMIT`), which
//! every run it plays records (`played_with` in `run-<k>.json`):
//! `<hash>`, `<hash>-modified` when tracked files differ from it, or
//! `unknown` outside a git checkout.

use std::path::{Path, PathBuf};
use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git")
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_owned())
}

fn main() {
    let commit = match git(&["rev-parse", "--short=12", "HEAD"]) {
        Some(hash) => {
            let modified = git(&["status", "--porcelain", "--untracked-files=no"])
                .is_some_and(|s| !s.is_empty());
            if modified {
                format!("{hash}-modified")
            } else {
                hash
            }
        }
        None => "unknown".to_owned(),
    };
    println!("cargo:rustc-env=ADV_COMMIT={commit}");
    // Built again when the commit, the index or a source the results
    // depend on changes.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    if let Some(git_dir) = git(&["rev-parse", "--absolute-git-dir"]) {
        let git_dir = PathBuf::from(git_dir);
        for file in ["HEAD", "index"] {
            println!("cargo:rerun-if-changed={}", git_dir.join(file).display());
        }
        if let Some(common) = git(&["rev-parse", "--git-common-dir"]) {
            let common = root.join("coordinator").join(common);
            println!("cargo:rerun-if-changed={}", common.join("refs").display());
        }
    }
    for dir in [
        "proto/src",
        "env-server/src",
        "agent/src",
        "coordinator/src",
    ] {
        println!("cargo:rerun-if-changed={}", root.join(dir).display());
    }
}
