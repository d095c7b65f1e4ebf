//! The cells of a study's tables and journal: a number as its shortest exact text, an optional
//! number or count as a cell, and the serde of an `f64` as that text.

/// A number as the tables write it: the shortest text that reads back as the same `f64`.
pub fn number(value: f64) -> String {
    format!("{value}")
}

/// A table cell of an optional float: [`number`], or empty.
pub(super) fn float_cell(value: Option<f64>) -> String {
    value.map(number).unwrap_or_default()
}

/// A table cell of an optional count or mode number, or empty.
pub(super) fn count_cell(value: Option<usize>) -> String {
    value.map(|v| v.to_string()).unwrap_or_default()
}

/// serde of an `f64` as the JSON string of its shortest round-trip text, read back exactly
/// ([`super::record`]'s documentation says why); `exact::option` for an `Option<f64>` (None is `null`).
pub(super) mod exact {
    use serde::{Deserialize, Deserializer, Serializer};

    use super::number;

    pub(in crate::study) fn parse<E: serde::de::Error>(text: &str) -> Result<f64, E> {
        text.parse()
            .map_err(|_| E::custom(format!("{text:?} is not a number")))
    }

    pub fn serialize<S: Serializer>(value: &f64, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(&number(*value))
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f64, D::Error> {
        parse(&String::deserialize(deserializer)?)
    }

    pub mod option {
        use serde::{Deserialize, Deserializer, Serializer};

        pub fn serialize<S: Serializer>(
            value: &Option<f64>,
            serializer: S,
        ) -> Result<S::Ok, S::Error> {
            match value {
                Some(v) => super::serialize(v, serializer),
                None => serializer.serialize_none(),
            }
        }

        pub fn deserialize<'de, D: Deserializer<'de>>(
            deserializer: D,
        ) -> Result<Option<f64>, D::Error> {
            Option::<String>::deserialize(deserializer)?
                .map(|text| super::parse(&text))
                .transpose()
        }
    }
}
