//! The `[road]` input file. Placeholder until its issue lands.

use crate::input::{InputError, SourceFile};

/// Validates a `[road]` file.
pub fn validate(file: &SourceFile) -> Result<(), InputError> {
    Err(file.error_at("road", "this kind of input is not supported yet"))
}
