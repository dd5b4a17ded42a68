//! `halffield._halffield`: the env-server simulator for Python. The
//! simulation stays in `env_server`; this crate converts and checks what
//! crosses the boundary. The Python package `halffield` builds PettingZoo's
//! and Gymnasium's environments on it.

mod actions;
mod arrays;
mod batch;
mod checked_env;
mod errors;
mod observation;
mod scripted;
mod settings;
mod single;
mod status;

use pyo3::prelude::*;

/// The native part of `halffield`.
#[pymodule]
fn _halffield(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<settings::TaskSettings>()?;
    m.add_class::<single::Env>()?;
    m.add_class::<batch::BatchEnv>()?;
    m.add_class::<scripted::ScriptedPolicy>()?;
    m.add("STATUS_NAMES", status::NAMES.to_vec())?;
    m.add("MAX_BATCH_ENVS", batch::MAX_ENVS)?;
    Ok(())
}
