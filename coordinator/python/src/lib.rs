//! `adhoc_advising._adhoc_advising`: the agent library for Python. The
//! learning and advising stay in `agent`; this crate converts and checks what
//! crosses the boundary: frozen agents ([`greedy`]), experiments and
//! studies in process ([`experiments`]) with Python learners as objects
//! ([`objects`]). The Python package `adhoc_advising` adds the learner and
//! strategy channels and the results' DataFrames in pure Python.

mod experiments;
mod greedy;
mod objects;

use pyo3::prelude::*;

/// The native part of `adhoc_advising`.
#[pymodule]
fn _adhoc_advising(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<greedy::GreedyAgent>()?;
    m.add("PAPER_ACTIONS", greedy::paper_action_names())?;
    m.add("STATE_FEATURES", proto::STATE_FEATURES)?;
    m.add_function(wrap_pyfunction!(experiments::run, m)?)?;
    m.add_function(wrap_pyfunction!(experiments::study, m)?)?;
    m.add_function(wrap_pyfunction!(experiments::replay, m)?)?;
    Ok(())
}
