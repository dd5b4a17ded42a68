//! The advising strategies (docs/algorithms.md 2-3) as one sum type: each
//! variant carries its own constants, with the paper's defaults.
//!
//! Every constant is named as its key in a team file (see [`AgentConfig`]);
//! the confidence function comes with the name (`adhoc-visit`, `adhoc-td`).
//!
//! [`AgentConfig`]: crate::AgentConfig

mod decisions;
mod settings;

pub(crate) use decisions::AskContext;
pub use settings::{AdHoc, Confidence, Strategy, Torrey};
