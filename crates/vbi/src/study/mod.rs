//! Parametric studies: expansion of a study into cases, per-case seeds, shards and the
//! statistics over roughness samples (the paper's §4.2 and §5: nine bridges × four road classes
//! × three speeds × ten samples).
//!
//! The library knows nothing of scenario fields: an axis is a field name and a list of values
//! ([`Value`]); the caller (the `vbi study` command) decides what the names mean.
//!
//! - Cases: the explicit rows (or one empty row) × the Cartesian product of the axes × the
//!   samples. Order: rows outermost, then the axes in the order given (the first varies
//!   slowest), the sample index innermost. This order numbers the cases ([`Case::order`]).
//! - Seeds: [`case_seed`] hashes the study seed with the case's parameters *sorted by field
//!   name* and its sample index, never its position, so adding an axis value or reordering the
//!   axes leaves every other case's seed (and road profile) unchanged.
//! - Identifiers: [`Case::id`] is a hash of the same canonical key: stable across edits too.
//! - Shards: [`Shard`] `I/N` takes the I-th of N contiguous, nearly equal blocks of the case
//!   order (blocks keep the cases of one bridge together when the bridge axes come first, so
//!   each shard computes few modal analyses).
//! - Statistics: [`statistics`] gives count, mean, sample standard deviation (n − 1), min, max
//!   and the 95th percentile (linear interpolation between order statistics, Hyndman–Fan
//!   type 7, the default of R and NumPy).

use crate::road::splitmix64_of as splitmix64;
use std::fmt;
use std::ops::Range;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// Errors of study expansion, shards and statistics.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StudyError {
    /// An axis without values.
    #[error("axis `{field}` has no values; give at least one")]
    EmptyAxis {
        /// Field of the axis.
        field: String,
    },
    /// A field given twice (two axes, or an axis and an explicit row).
    #[error("field `{field}` is varied twice; give it once")]
    DuplicateField {
        /// The field.
        field: String,
    },
    /// The same value twice in one axis.
    #[error("axis `{field}` lists the value {value} twice")]
    DuplicateValue {
        /// Field of the axis.
        field: String,
        /// The repeated value.
        value: String,
    },
    /// Two explicit rows (or rows × axes) give the same case.
    #[error("two cases have the same parameters: {key}")]
    DuplicateCase {
        /// Canonical key of the case.
        key: String,
    },
    /// A number that is not finite.
    #[error("field `{field}`: {value} is not a finite number")]
    NonFinite {
        /// The field.
        field: String,
        /// The value.
        value: f64,
    },
    /// No roughness samples.
    #[error("the number of samples is {samples}; expected at least 1")]
    NoSamples {
        /// Samples asked for.
        samples: usize,
    },
    /// A shard specification that is not `I/N` with 1 ≤ I ≤ N.
    #[error("shard `{text}` is invalid: {reason}")]
    InvalidShard {
        /// What was given.
        text: String,
        /// What is allowed.
        reason: String,
    },
    /// Statistics of no values.
    #[error("statistics of an empty set of values")]
    NoValues,
}

/// One value of an axis: a number (compared and printed by its shortest round-trip form) or a
/// text (a preset or class name, a file).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Value {
    /// A number.
    Number(f64),
    /// A text.
    Text(String),
}

impl Value {
    /// The number, if this is one.
    pub fn as_number(&self) -> Option<f64> {
        match self {
            Value::Number(x) => Some(*x),
            Value::Text(_) => None,
        }
    }

    /// The text, if this is one.
    pub fn as_text(&self) -> Option<&str> {
        match self {
            Value::Number(_) => None,
            Value::Text(t) => Some(t),
        }
    }
}

impl fmt::Display for Value {
    /// Numbers with `{}` (shortest representation that round-trips: 80.0 prints `80`), texts
    /// as they are.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::Number(x) => write!(f, "{x}"),
            Value::Text(t) => write!(f, "{t}"),
        }
    }
}

/// One varied field and its values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Axis {
    /// Field name (its meaning is the caller's).
    pub field: String,
    /// Values, in the order given.
    pub values: Vec<Value>,
}

/// A study: explicit rows × axes × samples, and the study seed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudyDesign {
    /// Explicit cases: each row sets some fields. Empty: one empty row.
    pub rows: Vec<Vec<(String, Value)>>,
    /// Axes of the Cartesian product, the first varying slowest.
    pub axes: Vec<Axis>,
    /// Roughness samples per parameter combination (≥ 1).
    pub samples: usize,
    /// Study seed; every case seed derives from it ([`case_seed`]).
    pub seed: u64,
}

/// One case of a study: a parameter combination and a sample index.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Case {
    /// Stable identifier: 16 hex digits of the hash of [`Case::key`].
    pub id: String,
    /// Position in the expansion order (0-based).
    pub order: usize,
    /// Field values, rows' fields first, then the axes in order.
    pub parameters: Vec<(String, Value)>,
    /// Roughness sample index (0-based).
    pub sample: usize,
    /// Seed of the case's road profile.
    pub seed: u64,
}

impl Case {
    /// Canonical key of the parameters only (the group over samples): `field=value` pairs
    /// sorted by field, joined by `;`.
    pub fn group_key(&self) -> String {
        canonical_parameters(&self.parameters)
    }

    /// Canonical key of the case: the group key and `sample=i`.
    pub fn key(&self) -> String {
        case_key(&self.parameters, self.sample)
    }

    /// The value of a field, if the case sets it.
    pub fn value(&self, field: &str) -> Option<&Value> {
        self.parameters
            .iter()
            .find(|(f, _)| f == field)
            .map(|(_, v)| v)
    }
}

fn canonical_parameters(parameters: &[(String, Value)]) -> String {
    let mut pairs: Vec<String> = parameters.iter().map(|(f, v)| format!("{f}={v}")).collect();
    pairs.sort();
    pairs.join(";")
}

fn case_key(parameters: &[(String, Value)], sample: usize) -> String {
    let group = canonical_parameters(parameters);
    if group.is_empty() {
        format!("sample={sample}")
    } else {
        format!("{group};sample={sample}")
    }
}

/// 64-bit FNV-1a of bytes, finished by the SplitMix64 mixer. Hand-written (a few lines; the
/// standard hasher is not stable across Rust versions): the same bytes give the same number on
/// every platform and release.
pub fn stable_hash(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    splitmix64(h)
}

/// Seed of a case: a hash of the study seed and the canonical key (parameters sorted by field,
/// then the sample index). Independent of the case's position, so adding values to an axis or
/// reordering axes does not change the other cases.
pub fn case_seed(study_seed: u64, parameters: &[(String, Value)], sample: usize) -> u64 {
    let key = case_key(parameters, sample);
    splitmix64(stable_hash(key.as_bytes()) ^ splitmix64(study_seed))
}

/// Expands a study into its cases, in order (see the module doc).
pub fn expand(design: &StudyDesign) -> Result<Vec<Case>, StudyError> {
    if design.samples == 0 {
        return Err(StudyError::NoSamples { samples: 0 });
    }
    let mut axis_fields: Vec<&str> = Vec::new();
    for axis in &design.axes {
        if axis.values.is_empty() {
            return Err(StudyError::EmptyAxis {
                field: axis.field.clone(),
            });
        }
        if axis_fields.contains(&axis.field.as_str()) {
            return Err(StudyError::DuplicateField {
                field: axis.field.clone(),
            });
        }
        axis_fields.push(&axis.field);
        for (i, v) in axis.values.iter().enumerate() {
            check_finite(&axis.field, v)?;
            if axis.values[..i].contains(v) {
                return Err(StudyError::DuplicateValue {
                    field: axis.field.clone(),
                    value: v.to_string(),
                });
            }
        }
    }
    let empty_row = vec![Vec::new()];
    let rows = if design.rows.is_empty() {
        &empty_row
    } else {
        &design.rows
    };
    for row in rows {
        for (i, (field, value)) in row.iter().enumerate() {
            check_finite(field, value)?;
            if axis_fields.contains(&field.as_str()) || row[..i].iter().any(|(f, _)| f == field) {
                return Err(StudyError::DuplicateField {
                    field: field.clone(),
                });
            }
        }
    }
    let combinations: usize = design.axes.iter().map(|a| a.values.len()).product();
    let mut cases = Vec::with_capacity(rows.len() * combinations * design.samples);
    let mut keys = std::collections::HashSet::new();
    for row in rows {
        for c in 0..combinations {
            // Mixed-radix digits of c, the last axis fastest.
            let mut parameters = row.clone();
            let mut rest = c;
            let mut digits = vec![0; design.axes.len()];
            for (a, axis) in design.axes.iter().enumerate().rev() {
                digits[a] = rest % axis.values.len();
                rest /= axis.values.len();
            }
            for (a, axis) in design.axes.iter().enumerate() {
                parameters.push((axis.field.clone(), axis.values[digits[a]].clone()));
            }
            let group = canonical_parameters(&parameters);
            if !keys.insert(group.clone()) {
                return Err(StudyError::DuplicateCase { key: group });
            }
            for sample in 0..design.samples {
                let key = case_key(&parameters, sample);
                cases.push(Case {
                    id: format!("{:016x}", stable_hash(key.as_bytes())),
                    order: cases.len(),
                    parameters: parameters.clone(),
                    sample,
                    seed: case_seed(design.seed, &parameters, sample),
                });
            }
        }
    }
    Ok(cases)
}

fn check_finite(field: &str, value: &Value) -> Result<(), StudyError> {
    match value {
        Value::Number(x) if !x.is_finite() => Err(StudyError::NonFinite {
            field: field.to_string(),
            value: *x,
        }),
        _ => Ok(()),
    }
}

/// One of N shards of a study (`I/N`, 1 ≤ I ≤ N).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// 1-based shard index I.
    pub index: usize,
    /// Number of shards N.
    pub count: usize,
}

impl Shard {
    /// The whole study as one shard.
    pub const WHOLE: Shard = Shard { index: 1, count: 1 };

    /// The case positions of this shard among `total` cases: block I of N contiguous blocks,
    /// positions `⌊(I−1)·total/N⌋ .. ⌊I·total/N⌋` (sizes differ by at most one).
    pub fn range(&self, total: usize) -> Range<usize> {
        let start = (self.index - 1) * total / self.count;
        let end = self.index * total / self.count;
        start..end
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl FromStr for Shard {
    type Err = StudyError;

    /// Parses `I/N`, refusing I = 0, I > N and N = 0.
    fn from_str(text: &str) -> Result<Shard, StudyError> {
        let bad = |reason: &str| StudyError::InvalidShard {
            text: text.to_string(),
            reason: reason.to_string(),
        };
        let (i, n) = text
            .split_once('/')
            .ok_or_else(|| bad("expected I/N, for example 2/8"))?;
        let index: usize = i
            .trim()
            .parse()
            .map_err(|_| bad("I is not a whole number"))?;
        let count: usize = n
            .trim()
            .parse()
            .map_err(|_| bad("N is not a whole number"))?;
        if count == 0 {
            return Err(bad("N must be at least 1"));
        }
        if index == 0 || index > count {
            return Err(bad(&format!(
                "I must be from 1 to N = {count} (shards are numbered from 1)"
            )));
        }
        Ok(Shard { index, count })
    }
}

/// Count, mean, standard deviation, extremes and 95th percentile of a set of values.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Statistics {
    /// Number of values.
    pub count: usize,
    /// Arithmetic mean.
    pub mean: f64,
    /// Sample standard deviation √(Σ(x − x̄)²/(n − 1)); 0 for one value.
    pub std: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// 95th percentile ([`percentile`]).
    pub p95: f64,
}

/// Statistics of finite values (non-finite values are an error, never silently dropped).
pub fn statistics(values: &[f64]) -> Result<Statistics, StudyError> {
    if values.is_empty() {
        return Err(StudyError::NoValues);
    }
    if let Some(&bad) = values.iter().find(|v| !v.is_finite()) {
        return Err(StudyError::NonFinite {
            field: "statistics".into(),
            value: bad,
        });
    }
    let n = values.len() as f64;
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let (min, max) = (sorted[0], sorted[sorted.len() - 1]);
    // The mean of the differences from the first value, added to it: equal values give that
    // value and a zero deviation exactly (a plain Σv/n of ten equal values can miss it by an
    // ulp, below their minimum); held within [min, max], which rounding can leave. Values more
    // than f64::MAX apart overflow the differences: then the plain Σv/n.
    let shift = values[0];
    let shifted = shift + values.iter().map(|v| v - shift).sum::<f64>() / n;
    let mean = if shifted.is_finite() {
        shifted
    } else {
        values.iter().sum::<f64>() / n
    };
    let mean = mean.clamp(min, max);
    let std = if values.len() > 1 {
        (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()
    } else {
        0.0
    };
    Ok(Statistics {
        count: values.len(),
        mean,
        std,
        min,
        max,
        p95: percentile_sorted(&sorted, 0.95),
    })
}

/// Mean participation of several cases, mode by mode (the paper's Fig. 25 averages the twelve
/// cases of each bridge). Cases with fewer modes contribute zeros beyond their last mode.
pub fn mean_participation(cases: &[&[f64]]) -> Vec<f64> {
    let modes = cases.iter().map(|c| c.len()).max().unwrap_or(0);
    let mut mean = vec![0.0; modes];
    for c in cases {
        for (m, v) in mean.iter_mut().zip(c.iter()) {
            *m += v;
        }
    }
    for m in &mut mean {
        *m /= cases.len().max(1) as f64;
    }
    mean
}

pub use crate::analysis::{cutoff_mode, cutoff_mode_among};
/// The cut-off modes K1/K2 of a (mean) participation: one implementation, in the DAF analysis.
pub use crate::statistics::percentile_sorted;

pub mod assessment;
mod cells;
pub mod record;
mod station_record;
pub use record::{
    case_record, case_record_with, case_records_with, error_chain, number, CaseRecord, CodeRecord,
    RecordRequest, StationRecord, STUDY_BATCH_SIZE,
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cutoff_among_selected_modes_counts_only_those_modes() {
        // Modes 2 and 4 are left out; over the others the shares are 0.8, 0.15, 0.05.
        let participation = [0.4, 0.5, 0.075, 0.0, 0.025];
        let selected = [true, false, true, false, true];
        assert_eq!(cutoff_mode_among(&participation, &selected, 0.95), Some(2));
        assert_eq!(cutoff_mode_among(&participation, &selected, 0.99), Some(3));
        assert_eq!(cutoff_mode_among(&participation, &[false; 5], 0.95), None);
    }

    fn axis(field: &str, values: &[f64]) -> Axis {
        Axis {
            field: field.into(),
            values: values.iter().map(|&v| Value::Number(v)).collect(),
        }
    }

    fn design(axes: Vec<Axis>, samples: usize) -> StudyDesign {
        StudyDesign {
            rows: Vec::new(),
            axes,
            samples,
            seed: 7,
        }
    }

    #[test]
    fn the_product_has_the_first_axis_slowest_and_the_sample_innermost() {
        let cases = expand(&design(
            vec![
                axis("span_count", &[2.0, 3.0]),
                axis("speed_kmh", &[40.0, 80.0]),
            ],
            2,
        ))
        .unwrap();
        assert_eq!(cases.len(), 8);
        let keys: Vec<String> = cases.iter().map(|c| c.key()).collect();
        assert_eq!(keys[0], "span_count=2;speed_kmh=40;sample=0");
        assert_eq!(keys[1], "span_count=2;speed_kmh=40;sample=1");
        assert_eq!(keys[2], "span_count=2;speed_kmh=80;sample=0");
        assert_eq!(keys[7], "span_count=3;speed_kmh=80;sample=1");
        assert!(cases.iter().enumerate().all(|(i, c)| c.order == i));
    }

    #[test]
    fn adding_an_axis_value_or_reordering_axes_keeps_every_other_seed_and_id() {
        let small = expand(&design(
            vec![axis("span_count", &[2.0, 3.0]), axis("speed_kmh", &[80.0])],
            3,
        ))
        .unwrap();
        let large = expand(&design(
            vec![
                axis("speed_kmh", &[40.0, 80.0, 120.0]),
                axis("span_count", &[4.0, 3.0, 2.0]),
            ],
            4,
        ))
        .unwrap();
        for c in &small {
            let twin = large.iter().find(|d| d.key() == c.key()).unwrap();
            assert_eq!((twin.seed, &twin.id), (c.seed, &c.id));
        }
        // Different cases get different seeds.
        let mut seeds: Vec<u64> = large.iter().map(|c| c.seed).collect();
        seeds.sort_unstable();
        seeds.dedup();
        assert_eq!(seeds.len(), large.len());
    }

    #[test]
    fn the_study_seed_changes_every_case_seed() {
        let a = expand(&design(vec![axis("speed_kmh", &[80.0])], 2)).unwrap();
        let mut d = design(vec![axis("speed_kmh", &[80.0])], 2);
        d.seed = 8;
        let b = expand(&d).unwrap();
        assert!(a
            .iter()
            .zip(&b)
            .all(|(x, y)| x.seed != y.seed && x.id == y.id));
    }

    #[test]
    fn rows_times_axes_and_bad_designs() {
        let mut d = design(vec![axis("speed_kmh", &[40.0, 80.0])], 1);
        d.rows = vec![
            vec![("bridge".into(), Value::Text("paper-2x20".into()))],
            vec![("bridge".into(), Value::Text("paper-3x30".into()))],
        ];
        let cases = expand(&d).unwrap();
        assert_eq!(cases.len(), 4);
        assert_eq!(cases[1].key(), "bridge=paper-2x20;speed_kmh=80;sample=0");
        assert!(matches!(
            expand(&design(vec![axis("speed_kmh", &[])], 1)),
            Err(StudyError::EmptyAxis { .. })
        ));
        assert!(matches!(
            expand(&design(vec![axis("speed_kmh", &[40.0, 40.0])], 1)),
            Err(StudyError::DuplicateValue { .. })
        ));
        assert!(matches!(
            expand(&design(
                vec![axis("speed_kmh", &[40.0]), axis("speed_kmh", &[80.0])],
                1
            )),
            Err(StudyError::DuplicateField { .. })
        ));
        assert!(matches!(
            expand(&design(vec![axis("speed_kmh", &[f64::NAN])], 1)),
            Err(StudyError::NonFinite { .. })
        ));
        assert!(matches!(
            expand(&design(vec![], 0)),
            Err(StudyError::NoSamples { .. })
        ));
        let mut d = design(vec![], 1);
        d.rows = vec![
            vec![("speed_kmh".into(), Value::Number(80.0))],
            vec![("speed_kmh".into(), Value::Number(80.0))],
        ];
        assert!(matches!(expand(&d), Err(StudyError::DuplicateCase { .. })));
    }

    #[test]
    fn shards_partition_the_cases_in_nearly_equal_blocks() {
        for total in [0, 1, 7, 10, 1080] {
            for count in 1..=7 {
                let mut covered = Vec::new();
                for index in 1..=count {
                    let r = Shard { index, count }.range(total);
                    assert!(r.len() <= total / count + 1 && r.len() >= total / count);
                    covered.extend(r);
                }
                assert_eq!(covered, (0..total).collect::<Vec<_>>());
            }
        }
    }

    #[test]
    fn shard_specs_are_parsed_and_bad_ones_refused() {
        assert_eq!("2/3".parse::<Shard>(), Ok(Shard { index: 2, count: 3 }));
        for bad in ["0/3", "4/3", "1/0", "3", "a/3", "1/b", ""] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }

    #[test]
    fn statistics_match_hand_computed_values() {
        // Reference: hand computation; NumPy's percentile(…, 95) (type 7) of 1..=5 is 4.8.
        let s = statistics(&[3.0, 1.0, 5.0, 2.0, 4.0]).unwrap();
        assert_eq!((s.count, s.mean, s.min, s.max), (5, 3.0, 1.0, 5.0));
        // Sample variance 10/4 = 2.5; 1e-15 is a few ulps of √2.5.
        assert!((s.std - 2.5_f64.sqrt()).abs() < 1e-15);
        assert!((s.p95 - 4.8).abs() < 1e-12, "{}", s.p95);
        let one = statistics(&[1.25]).unwrap();
        assert_eq!((one.std, one.p95), (0.0, 1.25));
        assert_eq!(statistics(&[]), Err(StudyError::NoValues));
        assert!(statistics(&[1.0, f64::NAN]).is_err());
    }

    #[test]
    fn equal_values_have_that_mean_and_no_deviation_and_a_mean_lies_within_the_extremes() {
        // Invariant: ten equal DAFs (a smooth road's samples; the value of the paper study's
        // 2 × 20 m smooth-road case), whose plain Σv/n misses them by an ulp.
        let v = 1.023860945941815;
        let s = statistics(&[v; 10]).unwrap();
        assert_eq!((s.mean, s.std, s.min, s.max, s.p95), (v, 0.0, v, v, v));
        // Values one ulp apart: the mean within [min, max].
        let next = f64::from_bits(v.to_bits() + 1);
        for count in 2..40 {
            let values: Vec<f64> = (0..count)
                .map(|i| if i % 3 == 0 { next } else { v })
                .collect();
            let s = statistics(&values).unwrap();
            assert!(s.min <= s.mean && s.mean <= s.max, "{count}: {}", s.mean);
        }
        // Values more than f64::MAX apart: their mean, not an overflow.
        assert_eq!(statistics(&[f64::MAX, -f64::MAX]).unwrap().mean, 0.0);
    }

    #[test]
    fn cutoff_of_mean_participation() {
        let a = [0.9, 0.06, 0.03, 0.01];
        let b = [0.8, 0.1, 0.05, 0.05];
        let mean = mean_participation(&[&a, &b]);
        // Mean 0.85, 0.08, 0.04, 0.03: cumulative 0.85, 0.93, 0.97, 1.0.
        assert_eq!(cutoff_mode(&mean, 0.95), Some(3));
        assert_eq!(cutoff_mode(&mean, 0.99), Some(4));
        assert_eq!(cutoff_mode(&[0.0, 0.0], 0.95), None);
    }
}
