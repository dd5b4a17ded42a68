//! Python exceptions of the binding's errors.

use crate::checked_env::StepError;
use pyo3::PyErr;
use pyo3::exceptions::{PyRuntimeError, PyValueError};

/// A bad value, as `ValueError` with its message.
pub(crate) fn value_error(e: impl ToString) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// Refused actions: `RuntimeError` for a finished episode (call `reset`),
/// `ValueError` for bad actions.
pub(crate) fn step_error(e: StepError) -> PyErr {
    raise(&e, e.to_string())
}

/// Refused actions of environment `env` of a batch.
pub(crate) fn batch_step_error(env: usize, e: StepError) -> PyErr {
    raise(&e, format!("environment {env}: {e}"))
}

fn raise(e: &StepError, message: String) -> PyErr {
    match e {
        StepError::Finished { .. } => PyRuntimeError::new_err(message),
        _ => PyValueError::new_err(message),
    }
}

/// A call before the first `reset`.
pub(crate) fn not_started() -> PyErr {
    PyRuntimeError::new_err("no episode has started: call reset() first")
}
