//! The `[measurement]` input file. Placeholder until its issue lands.

use crate::input::{InputError, SourceFile};

/// Validates a `[measurement]` file.
pub fn validate(file: &SourceFile) -> Result<(), InputError> {
    Err(file.error_at("measurement", "this kind of input is not supported yet"))
}
