//! The seam between the advising framework and an advising method: the
//! [`AdvisingStrategy`] trait, with the decisions the literature varies
//! (whether to ask, whom, whether to give, what the asker does with the
//! advice), and the paper's methods as its implementations. The framework
//! ([`Agent`](crate::Agent)) keeps what every method shares: budgets'
//! counters, visit counts n(s), network conditions, Mistake Correcting's
//! exchange and the transports.
//!
//! [`Strategy`] is a method's settings as team and study files write them;
//! [`Strategy::build`] makes its decisions.

mod ad_hoc;
mod baselines;
mod budgeted;
mod build;
mod episode_sharing;
mod peers;
mod psaf;
mod rcmp;
mod reuse;
mod seam;
mod settings;
mod torrey;
mod trust;

pub use seam::{AdvisingStrategy, AskContext, GiveContext, Outcome, Replies};
pub use settings::{
    AdHoc, Budgeted, Confidence, PeerLearning, Psaf, Rcmp, Reuse, ReuseRule, Strategy, Torrey,
};
