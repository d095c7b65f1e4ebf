//! Road and study seeds in input files: a TOML integer from 0 to 2⁶³ − 1, or a decimal string
//! from "0" to "18446744073709551615" (2⁶⁴ − 1), read by the library's one seed parser
//! ([`vbi::crossing::keys::seed_from_text`]). Study seeds are 64-bit hashes; half of them lie
//! above the largest TOML integer, so a case is replayed with `seed = "<its seed>"`.

use serde::de::{self, Deserializer, Visitor};
use serde::Deserialize;
use vbi::crossing::keys::{seed_from_text, SEED_ALLOWED};

/// A seed as read from a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Seed(pub u64);

impl<'de> Deserialize<'de> for Seed {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(SeedVisitor)
    }
}

struct SeedVisitor;

impl Visitor<'_> for SeedVisitor {
    type Value = Seed;

    fn expecting(&self, formatter: &mut std::fmt::Formatter) -> std::fmt::Result {
        formatter.write_str(SEED_ALLOWED)
    }

    fn visit_i64<E: de::Error>(self, value: i64) -> Result<Seed, E> {
        u64::try_from(value)
            .map(Seed)
            .map_err(|_| E::custom(format!("`{value}` is not allowed; expected {SEED_ALLOWED}")))
    }

    fn visit_u64<E: de::Error>(self, value: u64) -> Result<Seed, E> {
        Ok(Seed(value))
    }

    fn visit_str<E: de::Error>(self, text: &str) -> Result<Seed, E> {
        seed_from_text(text)
            .map(Seed)
            .ok_or_else(|| E::custom(format!("`{text}` is not allowed; expected {SEED_ALLOWED}")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Deserialize)]
    struct File {
        seed: Seed,
    }

    /// Every 64-bit seed can be written (issue 14: study seeds up to 1.8e19 could not be
    /// replayed), and what is not a seed is refused naming what is allowed.
    #[test]
    fn a_seed_is_an_integer_or_a_decimal_string_of_any_64_bit_value() {
        let read = |text: &str| toml::from_str::<File>(text).map(|f| f.seed.0);
        assert_eq!(read("seed = 9223372036854775807").unwrap(), i64::MAX as u64);
        assert_eq!(read("seed = \"18446744073709551615\"").unwrap(), u64::MAX);
        assert_eq!(read("seed = \"9223372036854775808\"").unwrap(), 1 << 63);
        for bad in [
            "seed = -1",
            "seed = \"18446744073709551616\"",
            "seed = \"x\"",
            "seed = 1.5",
        ] {
            let error = read(bad).unwrap_err().to_string();
            assert!(error.contains("18446744073709551615"), "{bad}: {error}");
        }
    }
}
