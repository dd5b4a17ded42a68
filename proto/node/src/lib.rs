//! What every process of an experiment needs, written once: joining the
//! zenoh network ([`net`]), the common command line, one-line errors and
//! logging ([`cli`]), following the coordinator's liveliness ([`alive`]),
//! atomic file output ([`files`]) and one policy for poisoned locks
//! ([`sync`]). Feature `zenoh` (default): [`net`] and [`cli`].
//!
//! The wire protocol itself stays in `proto`, which knows nothing of zenoh.

#![warn(missing_docs)]

// Secret files are checked by their Unix permissions and synced through
// their directory, and the processes stop on Unix signals.
#[cfg(not(unix))]
compile_error!("the experiment's processes run on Unix only (Linux, macOS)");

pub mod alive;
#[cfg(feature = "zenoh")]
pub mod cli;
pub mod files;
#[cfg(feature = "zenoh")]
pub mod net;
pub mod secret;
pub mod sync;
