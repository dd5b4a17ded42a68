//! `adhoc_advising._adhoc_advising`: the agent library for Python. The
//! learning and advising stay in `agent`; this crate converts and checks what
//! crosses the boundary. The Python package `adhoc_advising` adds the learner
//! channel (`adhoc_advising.learner`) in pure Python.

mod greedy;

use pyo3::prelude::*;

/// The native part of `adhoc_advising`.
#[pymodule]
fn _adhoc_advising(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<greedy::GreedyAgent>()?;
    m.add("PAPER_ACTIONS", greedy::paper_action_names())?;
    Ok(())
}
