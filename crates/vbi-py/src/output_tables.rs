//! The Python attributes of a class whose attributes are the rows of one of the library's tables
//! of outputs (`vbi::outputs`): `StationDaf`, `DetailFatigue`.

use pyo3::prelude::*;
use pyo3::IntoPyObjectExt;

use vbi::outputs::OutputValue;

use crate::arrays::copied;

/// The attribute `name` of a Python class whose attributes are the rows of a table of
/// outputs: the row's value read from `entry`, or AttributeError where the table has no such
/// row.
pub(crate) fn table_attribute<E>(
    py: Python<'_>,
    class: &str,
    name: &str,
    value: Option<fn(&E) -> OutputValue<'_>>,
    entry: &E,
) -> PyResult<Py<PyAny>> {
    match value {
        Some(value) => output_to_python(py, value(entry)),
        None => Err(pyo3::exceptions::PyAttributeError::new_err(format!(
            "'{class}' object has no attribute '{name}'"
        ))),
    }
}

/// An output value as Python holds it: str, float, None, int, bool, or a float64 array.
pub(crate) fn output_to_python(py: Python<'_>, value: OutputValue<'_>) -> PyResult<Py<PyAny>> {
    Ok(match value {
        OutputValue::Text(text) => text.into_py_any(py)?,
        OutputValue::Number(number) => number.into_py_any(py)?,
        OutputValue::OptionalNumber(number) => number.into_py_any(py)?,
        OutputValue::Count(count) => count.into_py_any(py)?,
        OutputValue::Flag(flag) => flag.into_py_any(py)?,
        OutputValue::OptionalFlag(flag) => flag.into_py_any(py)?,
        OutputValue::Series(values) => copied(py, values).into_any().unbind(),
    })
}
