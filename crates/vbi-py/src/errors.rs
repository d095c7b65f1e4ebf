//! The exceptions of the package: `vbi.VbiError` for anything the library refuses, and its
//! subclass `vbi.InputError` for a bad input, with the CLI's located message
//! (`file:line:column: field `…`: message`) and the parts as attributes.

use std::error::Error;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    _vbi,
    VbiError,
    PyException,
    "A failure of the vbi library (a bridge without modes, a crossing that diverged, ...)."
);
create_exception!(
    _vbi,
    InputError,
    VbiError,
    "A bad input, located as the vbi command locates it: `file`, `line`, `column`, `field`, \
     `message` (each None when unknown); str() is `file:line:column: field `…`: message`."
);

/// A located input error as a `vbi.InputError` carrying its parts.
pub fn input_error(error: vbi_input::InputError) -> PyErr {
    let exception = InputError::new_err(error.to_string());
    Python::attach(|py| {
        let value = exception.value(py);
        let (line, column) = error.location.unzip();
        // Setting attributes on a fresh exception instance cannot fail.
        let _ = value.setattr("file", error.file);
        let _ = value.setattr("line", line);
        let _ = value.setattr("column", column);
        let _ = value.setattr("field", error.field);
        let _ = value.setattr(
            "message",
            vbi::units::with_short_numbers(&error.message).into_owned(),
        );
    });
    exception
}

/// A library error as a `vbi.VbiError` with its causes in the message.
pub fn library_error(error: &dyn Error) -> PyErr {
    VbiError::new_err(vbi::study::error_chain(error))
}

/// Registers the exceptions in the module.
pub fn register(module: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = module.py();
    module.add("VbiError", py.get_type::<VbiError>())?;
    module.add("InputError", py.get_type::<InputError>())?;
    Ok(())
}
