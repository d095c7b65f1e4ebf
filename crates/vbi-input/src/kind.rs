//! The kind of an input file, told by its top-level table (`[scenario]`, `[bridge]`, ...), and
//! the top-level tables each kind may hold: the first check of `vbi check` and of every command
//! that reads a file.

use crate::source::{InputError, SourceFile};

/// The kinds of input file, by top-level table. A scenario and a lifetime come before the
/// parts: they may inline the `[bridge]` (a scenario also `[vehicle]` and `[road]`) beside
/// their own table.
const KINDS: [&str; 7] = [
    "study",
    "scenario",
    "lifetime",
    "bridge",
    "vehicle",
    "road",
    "measurement",
];

/// The top-level tables of a scenario: `[scenario]`, its inline parts, its traffic, its
/// stations and its fatigue details (a scenario's only: a study's crossings keep no histories).
const SCENARIO_TABLES: [&str; 8] = [
    "scenario",
    "bridge",
    "vehicle",
    "road",
    "traffic",
    "traffic_stream",
    "station",
    "fatigue_detail",
];

/// The top-level tables each kind of file may hold.
fn allowed_tables(kind: &str) -> &'static [&'static str] {
    const STUDY_TABLES: [&str; 8] = [
        "study",
        SCENARIO_TABLES[0],
        SCENARIO_TABLES[1],
        SCENARIO_TABLES[2],
        SCENARIO_TABLES[3],
        SCENARIO_TABLES[4],
        SCENARIO_TABLES[5],
        SCENARIO_TABLES[6],
    ];
    match kind {
        "study" => &STUDY_TABLES,
        "scenario" => &SCENARIO_TABLES,
        "bridge" => &["bridge"],
        "vehicle" => &["vehicle"],
        "road" => &["road"],
        "lifetime" => &["lifetime", "bridge", "station", "fatigue_detail"],
        _ => &["measurement"],
    }
}

/// The kind of a file (its top-level table), with its top-level tables checked against what
/// that kind may hold: the first check of `vbi check` and of every command that reads a file.
pub fn kind_of(file: &SourceFile) -> Result<&'static str, InputError> {
    let table: toml::Table = file.parse()?;
    let kind = KINDS
        .iter()
        .find(|k| table.contains_key(**k))
        .ok_or_else(|| InputError {
            file: file.name(),
            location: Some((1, 1)),
            field: None,
            message: format!(
                "cannot tell what kind of input this is: expected a top-level table named one of {}",
                KINDS.map(|k| format!("[{k}]")).join(", ")
            ),
        })?;
    let allowed = allowed_tables(kind);
    if let Some(extra) = table.keys().find(|k| !allowed.contains(&k.as_str())) {
        return Err(file.error_at(
            extra,
            format!(
                "unknown top-level key in a {kind} file; expected {}",
                allowed
                    .iter()
                    .map(|k| format!("[{k}]"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ));
    }
    Ok(kind)
}

/// Checks that a file given to `command` is of the kind it takes, exactly as `vbi check` checks
/// its kind and tables: a misspelt table (`[raod]`) or a file of another kind (a study given to
/// `vbi run`) is refused instead of silently defaulted.
pub fn expect_kind(file: &SourceFile, expected: &str, command: &str) -> Result<(), InputError> {
    let kind = kind_of(file)?;
    if kind == expected {
        return Ok(());
    }
    Err(file.error_at(
        kind,
        format!(
            "this is a {kind} file; `{command}` takes a [{expected}] file{}",
            match kind {
                "study" => " (run a study with `vbi study FILE`)",
                "scenario" => " (run a scenario with `vbi run FILE`)",
                "measurement" => " (process it with `vbi measure FILE`)",
                _ => "",
            }
        ),
    ))
}
