//! The `[bridge]` input file. Placeholder until its issue lands.

use crate::input::{InputError, SourceFile};

/// Validates a `[bridge]` file.
pub fn validate(file: &SourceFile) -> Result<(), InputError> {
    Err(file.error_at("bridge", "this kind of input is not supported yet"))
}
