//! Arrays across the boundary. A `Vec<f64>` that Rust gives away becomes the numpy array's
//! buffer without a copy ([`IntoPyArray`]); a table stored row-major in one `Vec` is reshaped in
//! place into a 2-D array (a view of that buffer).

use nalgebra::DMatrix;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;

/// A row-major table of `columns` values per row as a 2-D array, without a copy.
pub fn table<'py>(
    py: Python<'py>,
    values: Vec<f64>,
    columns: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let rows = values.len().checked_div(columns).unwrap_or(0);
    values.into_pyarray(py).reshape([rows, columns])
}

/// A matrix as a 2-D array (a copy: nalgebra stores columns, numpy rows).
pub fn matrix<'py>(py: Python<'py>, values: &DMatrix<f64>) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let row_major: Vec<f64> = values.transpose().as_slice().to_vec();
    table(py, row_major, values.ncols())
}

/// Optional numbers as an array with NaN where a value is undefined.
pub fn with_nan<'py>(py: Python<'py>, values: &[Option<f64>]) -> Bound<'py, PyArray1<f64>> {
    values
        .iter()
        .map(|v| v.unwrap_or(f64::NAN))
        .collect::<Vec<_>>()
        .into_pyarray(py)
}

/// A slice as a new array (for the small arrays that stay with a Rust value).
pub fn copied<'py>(py: Python<'py>, values: &[f64]) -> Bound<'py, PyArray1<f64>> {
    values.to_vec().into_pyarray(py)
}
