//! What every process of an experiment needs, written once: joining the
//! zenoh network ([`net`]), the common command line, one-line errors and
//! logging ([`cli`]), following the coordinator's liveliness ([`alive`]),
//! atomic file output ([`files`]; SVG to PNG with the `png` feature) and
//! one policy for poisoned locks ([`sync`]).
//!
//! The wire protocol itself stays in `proto`, which knows nothing of zenoh.

#![warn(missing_docs)]

pub mod alive;
pub mod cli;
pub mod files;
pub mod net;
pub mod secret;
pub mod sync;
