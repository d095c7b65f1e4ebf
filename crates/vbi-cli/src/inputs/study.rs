//! The `[study]` input file. Placeholder until its issue lands.

use crate::input::{InputError, SourceFile};

/// Validates a `[study]` file.
pub fn validate(file: &SourceFile) -> Result<(), InputError> {
    Err(file.error_at("study", "this kind of input is not supported yet"))
}
