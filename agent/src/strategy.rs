//! The seam between the advising framework and an advising method: the
//! [`AdvisingStrategy`] trait, with the decisions the literature varies
//! (whether to ask, whom, whether to give, what the asker does with the
//! advice, what it sends unasked), and the methods as its implementations,
//! one file each with its settings and its [`Method`](crate::method::Method).
//! The framework ([`Agent`](crate::Agent)) keeps what every method shares:
//! budgets' counters, visit counts n(s), network conditions, Mistake
//! Correcting's exchange and the transports.
//!
//! [`ALGORITHMS`] is the one place a method is registered: a new method is
//! its file here plus one line there (docs/strategies.md).

mod ad_hoc;
mod alone;
mod budgeted;
mod ef_ontl;
mod episode_sharing;
mod imitation;
mod peers;
mod psaf;
mod rcmp;
mod reuse;
mod seam;
mod torrey;
mod trust;

use crate::method::Registration;

pub use ad_hoc::{AdHoc, Confidence};
pub use alone::NoSettings;
pub use budgeted::{EarlyAdvising, RandomAdvising};
pub use ef_ontl::{EfOntl, TeacherRule};
pub use episode_sharing::EpisodeSharing;
pub use imitation::{AdviceImitation, Collection};
pub use peers::PeerLearning;
pub use psaf::{Psaf, PsafShares};
pub use rcmp::Rcmp;
pub use reuse::{AdviceReuse, ReuseRule};
pub use seam::{
    Adopted, AdvisingStrategy, AskContext, EndContext, GiveContext, Outcome, OwnChoice, Replies,
    ReuseContext, Sends,
};
pub use torrey::Torrey;

/// Every algorithm, registered once: the paper's, in the order it
/// presents them, then the field's since, then `external`. The first is
/// the default.
pub(crate) static ALGORITHMS: &[Registration] = &[
    Registration::of::<alone::NoAdvice>(),
    Registration::of::<ad_hoc::AdHocVisit>(),
    Registration::of::<ad_hoc::AdHocTd>(),
    Registration::of::<torrey::TorreyMethod>(),
    Registration::of::<episode_sharing::EpisodeSharingMethod>(),
    Registration::of::<alone::RandomPolicy>(),
    Registration::of::<budgeted::EarlyAdvisingMethod>(),
    Registration::of::<budgeted::RandomAdvisingMethod>(),
    Registration::of::<reuse::AdviceReuseMethod>(),
    Registration::of::<peers::PeerLearningMethod>(),
    Registration::of::<rcmp::RcmpMethod>(),
    Registration::of::<psaf::PsafMethod>(),
    Registration::of::<imitation::AdviceImitationMethod>(),
    Registration::of::<ef_ontl::EfOntlMethod>(),
    Registration::of::<alone::External>(),
];
