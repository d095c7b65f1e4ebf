//! The `[scenario]` input file: one crossing of one vehicle over one bridge on one road
//! (docs/input-format.md, section `[scenario]`).
//!
//! ```toml
//! [scenario]
//! bridge = "paper-3x30"                  # preset `paper-NxL`, or a [bridge] file; or inline [bridge]
//! vehicle = "tractor-semitrailer-5axle"  # preset, or a [vehicle] file; or inline [vehicle]
//! road = "medium"                        # class name, or a [road] file; or inline [road]
//! speed_kmh = 80.0
//! ```
//!
//! Paths are relative to the scenario file. Every other key has a default.

use serde::Deserialize;
use sha2::{Digest, Sha256};

use vbi::modal::ModeKind;
use vbi::pipeline::Scenario;
use vbi::road::RoadSpec;
use vbi::units::KMH;

use crate::input::{require_in_range, require_positive, InputError, SourceFile};
use crate::inputs::resolve::Resolver;
use crate::inputs::{bridge, road, vehicle};

/// Other top-level tables ([bridge], [vehicle], [road]) may stand beside `[scenario]`.
#[derive(Debug, Deserialize)]
struct Document {
    scenario: RawScenario,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScenario {
    name: Option<String>,
    bridge: Option<String>,
    vehicle: Option<String>,
    road: Option<String>,
    seed: Option<u64>,
    speed_kmh: Option<f64>,
    lateral_position_m: Option<f64>,
    element_length_m: Option<f64>,
    modes: Option<i64>,
    mode_kinds: Option<Vec<String>>,
    time_step_s: Option<f64>,
    newmark_beta: Option<f64>,
    newmark_gamma: Option<f64>,
    free_vibration_s: Option<f64>,
    convergence_tolerance: Option<f64>,
    rerun_modes: Option<Vec<i64>>,
    tyre_separation: Option<bool>,
}

/// A scenario read from a file: the library's typed [`Scenario`] and the hash of its inputs.
#[derive(Debug, Clone)]
pub struct ScenarioFile {
    /// The validated scenario, SI units.
    pub scenario: Scenario,
    /// SHA-256 of the scenario text and every file it names, hex.
    pub input_hash: String,
}

/// The built-in default scenario ([`Scenario::default`]): the paper's 3 × 30 m bridge, its
/// five-axle truck on a 'medium' road at 80 km/h, seed 1.
pub fn built_in_default() -> ScenarioFile {
    let mut hasher = Sha256::new();
    hasher.update(b"built-in default scenario");
    ScenarioFile {
        scenario: Scenario::default(),
        input_hash: hex(&hasher.finalize()),
    }
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Validates a `[scenario]` file, including every file it names.
pub fn validate(file: &SourceFile) -> Result<(), InputError> {
    load(file).map(|_| ())
}

/// Refuses a part both named in `[scenario]` and inlined as its own table.
fn one_source(
    file: &SourceFile,
    table: &toml::Table,
    part: &str,
    named: bool,
) -> Result<bool, InputError> {
    let inline = table.contains_key(part);
    if named && inline {
        return Err(file.error_at(
            &format!("scenario.{part}"),
            format!("the {part} is both named here and inlined as [{part}]; keep one"),
        ));
    }
    Ok(inline)
}

/// Reads and validates a scenario file.
pub fn load(file: &SourceFile) -> Result<ScenarioFile, InputError> {
    let document: Document = file.parse()?;
    let raw = document.scenario;
    let table: toml::Table = file.parse()?;
    let mut resolver = Resolver::default();
    let mut scenario = Scenario::default();

    // Bridge, vehicle, road: inline tables, or names (a preset or class, or a file).
    if one_source(file, &table, "bridge", raw.bridge.is_some())? {
        scenario.bridge.model = bridge::load(file)?;
        scenario.bridge_label = "inline [bridge]".to_string();
    } else if let Some(name) = &raw.bridge {
        let named = resolver.bridge(file, "scenario.bridge", name)?;
        scenario.bridge.model = named.model;
        scenario.bridge_label = named.label;
    }
    if one_source(file, &table, "vehicle", raw.vehicle.is_some())? {
        scenario.vehicle = vehicle::load(file)?;
    } else if let Some(name) = &raw.vehicle {
        scenario.vehicle = resolver.vehicle(file, "scenario.vehicle", name)?;
    }
    if one_source(file, &table, "road", raw.road.is_some())? {
        scenario.road = road::load(file)?;
    } else if let Some(name) = &raw.road {
        scenario.road = resolver.road(file, "scenario.road", name, &RoadSpec::default())?;
    }
    if let Some(seed) = raw.seed {
        scenario.road.seed = seed;
    }
    apply_settings(file, &raw, &mut scenario)?;
    scenario.name = raw.name.clone().unwrap_or_else(|| {
        file.path
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_else(|| "scenario".into())
    });
    let mut hasher = Sha256::new();
    hasher.update(file.text.as_bytes());
    for (_, text) in &resolver.files {
        hasher.update(text.as_bytes());
    }
    Ok(ScenarioFile {
        scenario,
        input_hash: hex(&hasher.finalize()),
    })
}

/// The numeric settings of `[scenario]`, each checked against its range.
fn apply_settings(
    file: &SourceFile,
    raw: &RawScenario,
    scenario: &mut Scenario,
) -> Result<(), InputError> {
    if let Some(v) = raw.speed_kmh {
        scenario.motion.speed =
            require_in_range(file, "scenario.speed_kmh", v, 0.1, 500.0, "km/h")? * KMH;
    }
    if let Some(y) = raw.lateral_position_m {
        scenario.motion.lateral_position =
            require_in_range(file, "scenario.lateral_position_m", y, -50.0, 50.0, "m")?;
    }
    if let Some(h) = raw.element_length_m {
        scenario.bridge.mesh.element_length =
            require_in_range(file, "scenario.element_length_m", h, 0.01, 10.0, "m")?;
    }
    let modal = &mut scenario.bridge.modal;
    match raw.modes {
        Some(n) if (1..=1000).contains(&n) => modal.mode_count = n as usize,
        Some(n) => {
            return Err(file.error_at(
                "scenario.modes",
                format!("{n} is not allowed; expected a whole number from 1 to 1000"),
            ))
        }
        None => {}
    }
    if let Some(names) = &raw.mode_kinds {
        modal.keep_kinds = mode_kinds(file, names)?;
    }
    let solver = &mut scenario.solver;
    solver.time_step = raw
        .time_step_s
        .map(|dt| require_in_range(file, "scenario.time_step_s", dt, 1e-6, 0.1, "s"))
        .transpose()?;
    if let Some(b) = raw.newmark_beta {
        solver.newmark_beta = require_in_range(file, "scenario.newmark_beta", b, 0.0, 0.5, "")?;
    }
    if let Some(g) = raw.newmark_gamma {
        solver.newmark_gamma = require_in_range(file, "scenario.newmark_gamma", g, 0.5, 1.0, "")?;
    }
    if let Some(separation) = raw.tyre_separation {
        solver.tyre_separation = separation;
    }
    scenario.free_vibration_duration = raw
        .free_vibration_s
        .map(|t| require_in_range(file, "scenario.free_vibration_s", t, 0.0, 600.0, "s"))
        .transpose()?;
    if let Some(t) = raw.convergence_tolerance {
        scenario.analysis.convergence_tolerance =
            require_positive(file, "scenario.convergence_tolerance", t, "(fraction)")?;
    }
    let mode_count = scenario.bridge.modal.mode_count;
    if let Some(counts) = &raw.rerun_modes {
        scenario.rerun_mode_counts = counts
            .iter()
            .enumerate()
            .map(|(i, &k)| {
                if (1..=mode_count as i64).contains(&k) {
                    Ok(k as usize)
                } else {
                    Err(file.error_at(
                        &format!("scenario.rerun_modes[{i}]"),
                        format!(
                            "{k} is not allowed; expected a mode count from 1 to {mode_count} \
                             (`modes`)"
                        ),
                    ))
                }
            })
            .collect::<Result<_, _>>()?;
    }
    Ok(())
}

fn mode_kinds(file: &SourceFile, names: &[String]) -> Result<Vec<ModeKind>, InputError> {
    if names.is_empty() {
        return Err(file.error_at(
            "scenario.mode_kinds",
            "an empty list keeps no mode; expected at least one of vertical_bending, torsion, \
             lateral, longitudinal",
        ));
    }
    names
        .iter()
        .enumerate()
        .map(|(i, name)| {
            parse_mode_kind(name).ok_or_else(|| {
                file.error_at(
                    &format!("scenario.mode_kinds[{i}]"),
                    format!(
                        "unknown mode kind `{name}`; expected vertical_bending, torsion, \
                         lateral or longitudinal"
                    ),
                )
            })
        })
        .collect()
}

/// A mode kind by its snake_case name.
pub fn parse_mode_kind(name: &str) -> Option<ModeKind> {
    match name {
        "vertical_bending" => Some(ModeKind::VerticalBending),
        "torsion" => Some(ModeKind::Torsion),
        "lateral" => Some(ModeKind::Lateral),
        "longitudinal" => Some(ModeKind::Longitudinal),
        _ => None,
    }
}
