//! What played a run: the commit of the code and the simulator with its
//! fingerprint, recorded with every run (`played_with` in `run-<k>.json`)
//! and stated by every report.

use std::sync::OnceLock;

use env_server::tools::fingerprint::{RECORDED_EPISODES, fingerprint};
use proto::Simulator;
use serde::{Deserialize, Serialize};

/// The commit this coordinator was built from (`<hash>`, `<hash>-modified`
/// when built with uncommitted changes, or `unknown`).
pub const COMMIT: &str = env!("ADV_COMMIT");

/// The code and simulator that played a run.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct PlayedWith {
    /// The commit of the code (see [`COMMIT`]).
    pub commit: String,
    /// The simulator: `ours` or `real-hfo`.
    pub simulator: Simulator,
    /// Ours: the fingerprint of its trajectories over
    /// [`RECORDED_EPISODES`] episodes of each baseline policy from seed 1
    /// (`cargo run --release -p env-server --example fingerprint --
    /// 10`'s `all`); none for the real HFO.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fingerprint: Option<String>,
}

impl PlayedWith {
    /// This build of the code, playing `simulator`.
    pub fn this_build(simulator: Simulator) -> Self {
        static OURS: OnceLock<String> = OnceLock::new();
        let fingerprint = (simulator == Simulator::Ours).then(|| {
            OURS.get_or_init(|| format!("{:016x}", fingerprint(RECORDED_EPISODES, 1).1))
                .clone()
        });
        Self {
            commit: COMMIT.to_owned(),
            simulator,
            fingerprint,
        }
    }
}
