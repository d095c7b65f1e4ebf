//! Inputs as the vbi command reads them: a TOML file by its path, or a Python dict holding the
//! same document (top-level tables `[bridge]`, `[scenario]`, ...), written as TOML text named
//! `<dict>` so that the very same validation and messages apply.

use std::path::{Path, PathBuf};

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

use vbi_input::SourceFile;

use crate::errors::input_error;

/// The name that messages give a document that came from a dict.
pub const DICT_NAME: &str = "<dict>";

/// A file read by its path.
pub fn read(path: &Path) -> PyResult<SourceFile> {
    SourceFile::read(path).map_err(input_error)
}

/// A dict written as the TOML document it stands for.
pub fn from_dict(document: &Bound<'_, PyDict>) -> PyResult<SourceFile> {
    let table = table_of(document, "")?;
    let text = toml::to_string(&table)
        .map_err(|e| PyTypeError::new_err(format!("the dict is not a TOML document: {e}")))?;
    Ok(SourceFile::from_text(PathBuf::from(DICT_NAME), text))
}

/// A path (str or os.PathLike) or a dict: the two ways to give a document.
pub fn from_path_or_dict(source: &Bound<'_, PyAny>) -> PyResult<SourceFile> {
    if let Ok(document) = source.cast::<PyDict>() {
        return from_dict(document);
    }
    let path: PathBuf = source.extract().map_err(|_| {
        PyTypeError::new_err("expected a path to a TOML file (str or os.PathLike) or a dict")
    })?;
    read(&path)
}

/// The file of `source` checked to be of `kind` (a `[bridge]` file to `vbi.Bridge`, ...).
pub fn of_kind(source: &Bound<'_, PyAny>, kind: &str, caller: &str) -> PyResult<SourceFile> {
    let file = from_path_or_dict(source)?;
    vbi_input::expect_kind(&file, kind, caller).map_err(input_error)?;
    Ok(file)
}

fn table_of(dict: &Bound<'_, PyDict>, path: &str) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (key, value) in dict.iter() {
        let key: String = key
            .extract()
            .map_err(|_| PyTypeError::new_err(format!("`{path}`: every key must be a str")))?;
        let at = if path.is_empty() {
            key.clone()
        } else {
            format!("{path}.{key}")
        };
        table.insert(key, toml_value(&value, &at)?);
    }
    Ok(table)
}

/// A Python value as the TOML value a file would hold (`path` names it in messages).
pub fn toml_value(value: &Bound<'_, PyAny>, path: &str) -> PyResult<toml::Value> {
    // bool before int: a Python bool is an int.
    if value.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(value.extract()?));
    }
    if value.is_instance_of::<PyInt>() {
        return Ok(toml::Value::Integer(value.extract()?));
    }
    if value.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(value.extract()?));
    }
    if value.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(value.extract()?));
    }
    if let Ok(dict) = value.cast::<PyDict>() {
        return Ok(toml::Value::Table(table_of(dict, path)?));
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let items = value
            .try_iter()?
            .enumerate()
            .map(|(i, item)| toml_value(&item?, &format!("{path}[{i}]")))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    // numpy scalars: an integer type has __index__, a float type converts to float.
    if let Ok(integer) = value.extract::<i64>() {
        return Ok(toml::Value::Integer(integer));
    }
    if let Ok(number) = value.extract::<f64>() {
        return Ok(toml::Value::Float(number));
    }
    Err(PyTypeError::new_err(format!(
        "`{path}`: {} is not a TOML value; expected a bool, int, float, str, list or dict",
        value.get_type().name()?
    )))
}
