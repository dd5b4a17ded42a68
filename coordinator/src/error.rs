//! Why an experiment could not start or finish.

use std::path::PathBuf;

use agent::PersistError;

/// A configuration value out of its allowed range, or a file that cannot be
/// read as a configuration.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("invalid config `{key}`: {reason}")]
pub struct ConfigError {
    /// The offending key, as spelled in the configuration (`team[2].alpha`).
    pub key: String,
    /// What is wrong with its value, and what is accepted.
    pub reason: String,
}

impl ConfigError {
    /// An error about `key`.
    pub fn new(key: impl Into<String>, reason: impl Into<String>) -> Self {
        Self {
            key: key.into(),
            reason: reason.into(),
        }
    }
}

/// Every failure of the coordinator library; each displays as one line.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A configuration value or file was rejected.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// An agent's snapshot could not be loaded or does not fit the agent.
    #[error("cannot load agent {agent} from {}: {source}", path.display())]
    Snapshot {
        /// The agent's id.
        agent: usize,
        /// The snapshot file.
        path: PathBuf,
        /// What went wrong.
        source: PersistError,
    },
    /// The output directory holds the results of another configuration.
    #[error(
        "output directory {} holds the results of another configuration ({reason}); \
         choose another --out or remove it",
        dir.display()
    )]
    OtherResults {
        /// The output directory.
        dir: PathBuf,
        /// What differs.
        reason: String,
    },
    /// The output path exists and is not a directory.
    #[error("output path {} is a file, not a directory; choose another --out", .0.display())]
    NotADirectory(PathBuf),
    /// Reading or writing a file failed.
    #[error("cannot {action} {}: {source}", path.display())]
    Io {
        /// What was being done ("write", "create", ...).
        action: &'static str,
        /// The file or directory.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The analysis of a study could not be made.
    #[error(transparent)]
    Analysis(#[from] analysis::Error),
    /// A run failed while playing (a lost peer, a process that did not answer).
    #[error("run {run}: {message}")]
    Run {
        /// The run.
        run: u64,
        /// What happened.
        message: String,
    },
    /// The processes of an experiment could not be started, joined or reached.
    #[error("{0}")]
    Transport(String),
    /// Stopped on request (Ctrl-C in Python) after the episodes in flight.
    #[error("interrupted: the runs finished so far are kept, and the same call resumes")]
    Interrupted,
}

impl Error {
    /// A failure of run `run`.
    pub fn run(run: u64, message: impl std::fmt::Display) -> Self {
        Self::Run {
            run,
            message: message.to_string(),
        }
    }

    /// An I/O error on `path`.
    pub fn io(action: &'static str, path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Self::Io {
            action,
            path: path.into(),
            source,
        }
    }
}
