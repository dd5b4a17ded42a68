//! What played a run: the commit of this build and the simulator with its
//! fingerprint, recorded with every run (`played_with` in `run-<k>.json`)
//! and stated by every report.

use std::sync::OnceLock;

use analysis::PlayedWith;
use env_server::tools::fingerprint::{RECORDED_EPISODES, fingerprint};
use proto::Simulator;

/// The commit this coordinator was built from (`<hash>`, `<hash>-modified`
/// when built with uncommitted changes, or `unknown`).
pub const COMMIT: &str = env!("ADV_COMMIT");

/// This build of the code, playing `simulator`: ours with the fingerprint
/// of its trajectories over [`RECORDED_EPISODES`] episodes of each baseline
/// policy from seed 1, computed once.
pub fn played_with(simulator: Simulator) -> PlayedWith {
    static OURS: OnceLock<String> = OnceLock::new();
    let fingerprint = (simulator == Simulator::Ours).then(|| {
        OURS.get_or_init(|| format!("{:016x}", fingerprint(RECORDED_EPISODES, 1).1))
            .clone()
    });
    PlayedWith {
        commit: COMMIT.to_owned(),
        simulator,
        fingerprint,
    }
}
