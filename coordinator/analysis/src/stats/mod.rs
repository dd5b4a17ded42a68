//! Every statistic the coordinator computes, in one place.
//!
//! - [`estimate`]: mean and Student's t interval over runs; Welch's interval
//!   of a difference of means.
//! - [`summary`]: an experiment's `summary.json`: those estimates at every
//!   evaluation point, the communication and the cost.
//! - [`wilcoxon`]: the signed-rank test between two algorithms paired by run,
//!   and the episode intervals where one is better.
//! - [`bootstrap`]: mean, IQM and probability of improvement with
//!   stratified bootstrap intervals (Agarwal et al. 2021, `rliable`).
//! - A study's analyses: [`analysis`] (Wilcoxon at every evaluation point
//!   between entries), [`holm`] (against the baseline, Holm-corrected across
//!   entries), [`gains`] (last ten and area, paired by run),
//!   [`aggregates`] (the bootstrap statistics of each entry's scores) and
//!   [`frontier`] (each entry's gain against its advising traffic, the
//!   Pareto front, gains at equal cost) and [`sweeps`] (whether a swept
//!   group's result depends on its value).

pub mod aggregates;
pub mod analysis;
pub mod bootstrap;
pub mod estimate;
pub mod frontier;
pub mod gains;
pub mod holm;
pub mod summary;
pub mod sweeps;
pub mod wilcoxon;

pub use estimate::{Estimate, difference_of_means, estimate, t_quantile};
