//! A transport opened for one experiment: a [`Driver`] hands out the
//! backend of each run.

use crate::backend::Backend;
use crate::config::AgentSpec;
use crate::error::Error;
use crate::experiment::Experiment;
use crate::in_process::InProcess;
#[cfg(feature = "zenoh")]
use crate::remote::{RemoteBackend, ZenohTeam};
use crate::transport::Transport;

/// Hands out one backend per run of an experiment.
pub trait Driver: Sync {
    /// The backend of run `run`, its agents at their start.
    fn backend(&self, experiment: &Experiment, run: u64) -> Result<Box<dyn Backend + '_>, Error>;

    /// How many runs may play at the same time.
    fn max_parallel_runs(&self) -> usize;
}

/// Opens `transport` for an experiment with `team`: over zenoh, joins the
/// network and starts (or finds) the processes.
pub fn open(transport: &Transport, team: &[AgentSpec]) -> Result<Box<dyn Driver>, Error> {
    Ok(match transport {
        Transport::InProcess => Box::new(InProcessDriver),
        #[cfg(feature = "zenoh")]
        Transport::Zenoh(settings) => Box::new(ZenohTeam::start(settings, team)?),
        #[cfg(not(feature = "zenoh"))]
        Transport::Zenoh(_) => {
            let _ = team;
            return Err(crate::error::ConfigError::new(
                "transport",
                "this build has no zenoh transport (built without the `zenoh` feature, as the \
                 Python package is): use transport in-process, or the `coordinator` command",
            )
            .into());
        }
    })
}

/// Every run in its own thread, as library calls.
struct InProcessDriver;

impl Driver for InProcessDriver {
    fn backend(&self, experiment: &Experiment, run: u64) -> Result<Box<dyn Backend + '_>, Error> {
        Ok(Box::new(InProcess::new(experiment, run)?))
    }

    fn max_parallel_runs(&self) -> usize {
        usize::MAX
    }
}

/// Over zenoh the runs play one after another on the same processes.
#[cfg(feature = "zenoh")]
impl Driver for ZenohTeam {
    fn backend(&self, experiment: &Experiment, run: u64) -> Result<Box<dyn Backend + '_>, Error> {
        Ok(Box::new(RemoteBackend::new(self, experiment, run)?))
    }

    fn max_parallel_runs(&self) -> usize {
        1
    }
}
