//! vbi's input files, read into the library's typed values: one module per kind of file. Each
//! file names its kind by its top-level table (`[bridge]`, `[vehicle]`, `[road]`, ...). Units
//! other than SI are named in the key (`speed_kmh`) and converted here, once. Every error is an
//! [`InputError`] that names the file, the line and column, the field and what is allowed.
//!
//! The `vbi` command and the Python package both read their files through this crate, so that
//! a file is accepted or refused, with the same message, whichever of them reads it.

pub mod bridge;
mod bridge_damage;
mod csv_table;
pub mod fatigue_details;
pub mod grave_parameters;
pub mod influence_csv;
pub mod kind;
pub mod lifetime;
pub mod lifetime_generator;
pub mod lifetime_replay;
pub mod logger_csv;
pub mod matrix_market;
pub mod measurement;
pub mod modal_import;
pub mod resolve;
pub mod road;
pub mod scenario;
pub mod seed;
pub mod source;
pub mod stations;
pub mod study;
pub mod traffic;
pub mod traffic_file;
pub mod traffic_source;
pub mod values;
pub mod vehicle;
pub mod vehicle_toml;

pub use crate::bridge::imported_matrices;
pub use crate::kind::{expect_kind, kind_of};
pub use crate::source::{InputError, SourceFile};

/// Validates a file of any kind and returns the kind's name: what `vbi check` runs, and the same
/// loaders that the commands run.
pub fn validate(file: &SourceFile) -> Result<&'static str, InputError> {
    let kind = kind_of(file)?;
    match kind {
        "study" => study::validate(file)?,
        "scenario" => scenario::validate(file)?,
        "bridge" => bridge::validate(file)?,
        "vehicle" => vehicle::validate(file)?,
        "road" => road::validate(file)?,
        "measurement" => measurement::validate(file)?,
        "lifetime" => lifetime::validate(file)?,
        _ => unreachable!("every kind is dispatched"),
    }
    Ok(kind)
}
