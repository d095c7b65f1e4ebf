//! TOML values read as the values of the library's key table ([`vbi::crossing::keys`]), with
//! located refusals, and the ranges that table gives, for the loaders that check a key of their
//! own against the same range (a speed-profile knot's `speed_kmh`, a bridge's `damping_ratio`).

use vbi::crossing::keys::{self, Allowed};
use vbi::crossing::{KeyError, KeyValue};

use crate::source::{InputError, SourceFile};

/// A TOML value as a key's value.
pub fn key_value(
    file: &SourceFile,
    path: &str,
    value: &toml::Value,
) -> Result<KeyValue, InputError> {
    Ok(match value {
        toml::Value::Integer(i) => KeyValue::Integer(*i),
        toml::Value::Float(x) => KeyValue::Number(*x),
        toml::Value::String(s) => KeyValue::Text(s.clone()),
        toml::Value::Boolean(b) => KeyValue::Bool(*b),
        toml::Value::Array(items) => KeyValue::List(
            items
                .iter()
                .enumerate()
                .map(|(i, item)| key_value(file, &format!("{path}[{i}]"), item))
                .collect::<Result<_, _>>()?,
        ),
        other => {
            return Err(file.error_at(
                path,
                format!(
                    "{other} is not allowed here; expected a number, a text, true/false or a list"
                ),
            ))
        }
    })
}

/// A key's refusal, located at the key (or the list element at fault) under `table`.
pub fn key_error(file: &SourceFile, table: &str, error: KeyError) -> InputError {
    let index = error.index.map(|i| format!("[{i}]")).unwrap_or_default();
    file.error_at(&format!("{table}.{}{index}", error.key), error.message)
}

/// The range `[low, high]` that the key table ([`vbi::crossing::keys::SCENARIO_KEYS`]) allows
/// for the number key `name`, in the key's unit: the one definition of that range, read by a
/// loader that checks the same quantity under a key of its own.
///
/// # Panics
/// When the table has no number key of that name: a mistake in this crate, caught by its tests.
pub fn key_range(name: &str) -> (f64, f64) {
    match keys::key(name).map(|key| key.allowed) {
        Some(Allowed::Number { low, high }) => (low, high),
        _ => panic!("the key table has no number key `{name}`"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn key_range_reads_the_speed_and_damping_ranges_of_the_key_table() {
        assert_eq!(key_range("speed_kmh"), (0.1, 500.0));
        assert_eq!(key_range("damping_ratio"), (0.0, 0.99));
    }
}
