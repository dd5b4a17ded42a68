//! `halffield._halffield`: the env-server simulator for Python. The
//! simulation stays in `env_server`; this crate converts and checks what
//! crosses the boundary. The Python package `halffield` builds PettingZoo's
//! and Gymnasium's environments on it.

mod actions;
mod arrays;
mod batch;
mod errors;
mod game;
mod learned;
mod observation;
mod policy;
mod settings;
mod single;
mod status;

use pyo3::prelude::*;

/// The native part of `halffield`.
#[pymodule]
fn _halffield(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<settings::TaskSettings>()?;
    m.add_class::<single::Simulator>()?;
    m.add_class::<batch::BatchSimulator>()?;
    m.add_class::<policy::SeededPolicy>()?;
    m.add_class::<learned::GreedyAgent>()?;
    m.add("PAPER_ACTIONS", learned::paper_action_names())?;
    m.add("STATUS_NAMES", status::NAMES.to_vec())?;
    Ok(())
}
