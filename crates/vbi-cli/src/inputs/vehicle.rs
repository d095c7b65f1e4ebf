//! The `[vehicle]` input file. Placeholder until its issue lands.

use crate::input::{InputError, SourceFile};

/// Validates a `[vehicle]` file.
pub fn validate(file: &SourceFile) -> Result<(), InputError> {
    Err(file.error_at("vehicle", "this kind of input is not supported yet"))
}
