//! numpy arrays that take over the binding's buffers without a copy.

use numpy::ndarray::{Array, Dimension, ShapeBuilder};
use numpy::{Element, IntoPyArray, PyArray};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// `data` as an array of `shape` (row-major).
pub(crate) fn array<'py, T: Element, D: Dimension>(
    py: Python<'py>,
    shape: impl ShapeBuilder<Dim = D>,
    data: Vec<T>,
) -> PyResult<Bound<'py, PyArray<T, D>>> {
    Array::from_shape_vec(shape, data)
        .map(|a| a.into_pyarray(py))
        .map_err(|e| PyRuntimeError::new_err(format!("internal shape error: {e}")))
}
