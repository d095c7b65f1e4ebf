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

use std::path::{Path, PathBuf};

use serde::Deserialize;
use sha2::{Digest, Sha256};

use vbi::modal::ModeKind;
use vbi::model::{paper_bridge, BridgeModel};
use vbi::road::{RoadSpec, Roughness};
use vbi::units::KMH;
use vbi::vehicle::{preset, VehicleSpec, PRESET_NAMES};

use crate::input::{require_in_range, require_positive, InputError, SourceFile};
use crate::inputs::{bridge, road, vehicle};

/// The vehicle of the built-in scenario: the paper's five-axle tractor–semitrailer (15 DOF).
pub const DEFAULT_VEHICLE: &str = "tractor-semitrailer-5axle";
/// Speed of the built-in scenario [km/h].
pub const DEFAULT_SPEED_KMH: f64 = 80.0;

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

/// A validated scenario, SI units.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// Name for reports.
    pub name: String,
    /// The bridge.
    pub bridge: BridgeModel,
    /// How the bridge was named (preset, file or inline).
    pub bridge_label: String,
    /// The vehicle description.
    pub vehicle: VehicleSpec,
    /// The road; its seed is the scenario's seed.
    pub road: RoadSpec,
    /// Speed v [m/s].
    pub speed: f64,
    /// Lateral position of the vehicle centreline from the deck centreline [m], left positive.
    pub lateral_position: f64,
    /// Longitudinal element length of the mesh [m] (default 1).
    pub element_length: f64,
    /// Number of modes (default 50).
    pub mode_count: usize,
    /// Mode kinds kept (default: vertical bending and torsion, the modes trucks excite).
    pub mode_kinds: Vec<ModeKind>,
    /// Time step [s]; None for the solver's default.
    pub time_step: Option<f64>,
    /// Newmark β (default 0.25).
    pub newmark_beta: f64,
    /// Newmark γ (default 0.5).
    pub newmark_gamma: f64,
    /// Free vibration after the vehicle leaves [s]; None for the solver's default.
    pub free_vibration: Option<f64>,
    /// Tolerance of the convergence mode (default 0.01).
    pub convergence_tolerance: f64,
    /// Mode counts K for which the crossing is solved again with only the first K modes, to
    /// compare with the partial modal sums of the full run (default: none).
    pub rerun_mode_counts: Vec<usize>,
    /// Whether a tyre may leave the road (default true); false keeps tyres bonded.
    pub tyre_separation: bool,
    /// SHA-256 of the scenario text and every file it names, hex.
    pub input_hash: String,
}

/// The built-in default scenario: the paper's 3 × 30 m bridge, its five-axle truck on a
/// 'medium' road at 80 km/h, seed 1.
pub fn built_in_default() -> Scenario {
    let vehicle = preset(DEFAULT_VEHICLE).expect("the default vehicle is a preset");
    let mut hasher = Sha256::new();
    hasher.update(b"built-in default scenario");
    Scenario {
        name: "paper-3x30-medium-80kmh".into(),
        bridge: paper_bridge(3, 30.0),
        bridge_label: "paper-3x30 (preset)".into(),
        vehicle,
        road: RoadSpec::default(),
        speed: DEFAULT_SPEED_KMH * KMH,
        lateral_position: 0.0,
        element_length: 1.0,
        mode_count: 50,
        mode_kinds: default_mode_kinds(),
        time_step: None,
        newmark_beta: 0.25,
        newmark_gamma: 0.5,
        free_vibration: None,
        convergence_tolerance: 0.01,
        rerun_mode_counts: Vec::new(),
        tyre_separation: true,
        input_hash: hex(&hasher.finalize()),
    }
}

fn default_mode_kinds() -> Vec<ModeKind> {
    vec![ModeKind::VerticalBending, ModeKind::Torsion]
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Validates a `[scenario]` file, including every file it names.
pub fn validate(file: &SourceFile) -> Result<(), InputError> {
    load(file).map(|_| ())
}

/// A bridge preset name `paper-NxL` (N spans of L metres).
fn bridge_preset(name: &str) -> Option<BridgeModel> {
    let rest = name.strip_prefix("paper-")?;
    let (spans, length) = rest.split_once('x')?;
    let spans: usize = spans.parse().ok()?;
    let length: f64 = length.parse().ok()?;
    ([2, 3, 4].contains(&spans) && [20.0, 30.0, 40.0].contains(&length))
        .then(|| paper_bridge(spans, length))
}

fn relative(file: &SourceFile, reference: &str) -> PathBuf {
    let base = file.path.parent().unwrap_or(Path::new("."));
    base.join(reference)
}

/// Reads and validates a scenario file.
pub fn load(file: &SourceFile) -> Result<Scenario, InputError> {
    let document: Document = file.parse()?;
    let raw = document.scenario;
    let table: toml::Table = file.parse()?;
    let mut hasher = Sha256::new();
    hasher.update(file.text.as_bytes());

    // Bridge: inline [bridge], or a preset, or a file.
    let (bridge, bridge_label) = match (&raw.bridge, table.contains_key("bridge")) {
        (Some(_), true) => {
            return Err(file.error_at(
                "scenario.bridge",
                "the bridge is both named here and inlined as [bridge]; keep one",
            ))
        }
        (None, true) => (bridge::load(file)?, "inline [bridge]".to_string()),
        (None, false) => (paper_bridge(3, 30.0), "paper-3x30 (preset)".to_string()),
        (Some(name), false) => match bridge_preset(name) {
            Some(model) => (model, format!("{name} (preset)")),
            None if name.ends_with(".toml") => {
                let path = relative(file, name);
                let source = SourceFile::read(&path)
                    .map_err(|e| file.error_at("scenario.bridge", e.to_string()))?;
                hasher.update(source.text.as_bytes());
                (bridge::load(&source)?, path.display().to_string())
            }
            None => {
                return Err(file.error_at(
                    "scenario.bridge",
                    format!(
                        "`{name}` is neither a preset nor a .toml file; expected paper-NxL with \
                         N in 2, 3, 4 and L in 20, 30, 40, or a [bridge] file"
                    ),
                ))
            }
        },
    };

    // Vehicle: inline [vehicle], or a preset, or a file.
    let vehicle = match (&raw.vehicle, table.contains_key("vehicle")) {
        (Some(_), true) => {
            return Err(file.error_at(
                "scenario.vehicle",
                "the vehicle is both named here and inlined as [vehicle]; keep one",
            ))
        }
        (None, true) => vehicle::load(file)?,
        (None, false) => preset(DEFAULT_VEHICLE).expect("the default vehicle is a preset"),
        (Some(name), false) => match preset(name) {
            Some(spec) => spec,
            None if name.ends_with(".toml") => {
                let path = relative(file, name);
                let source = SourceFile::read(&path)
                    .map_err(|e| file.error_at("scenario.vehicle", e.to_string()))?;
                hasher.update(source.text.as_bytes());
                vehicle::load(&source)?
            }
            None => {
                return Err(file.error_at(
                    "scenario.vehicle",
                    format!(
                        "`{name}` is neither a preset nor a .toml file; expected a [vehicle] file \
                         or one of: {}",
                        PRESET_NAMES.join(", ")
                    ),
                ))
            }
        },
    };

    // Road: inline [road], or a class name, or a file.
    let mut road_spec = match (&raw.road, table.contains_key("road")) {
        (Some(_), true) => {
            return Err(file.error_at(
                "scenario.road",
                "the road is both named here and inlined as [road]; keep one",
            ))
        }
        (None, true) => road::load(file)?,
        (None, false) => RoadSpec::default(),
        (Some(name), false) if name.ends_with(".toml") => {
            let path = relative(file, name);
            let source = SourceFile::read(&path)
                .map_err(|e| file.error_at("scenario.road", e.to_string()))?;
            hasher.update(source.text.as_bytes());
            road::load(&source)?
        }
        (Some(name), false) => {
            let class = road::parse_class(name).map_err(|m| file.error_at("scenario.road", m))?;
            RoadSpec {
                roughness: Roughness::Class(class),
                ..RoadSpec::default()
            }
        }
    };
    if let Some(seed) = raw.seed {
        road_spec.seed = seed;
    }

    let speed_kmh = match raw.speed_kmh {
        Some(v) => require_in_range(file, "scenario.speed_kmh", v, 0.1, 500.0, "km/h")?,
        None => DEFAULT_SPEED_KMH,
    };
    let lateral_position = match raw.lateral_position_m {
        Some(y) => require_in_range(file, "scenario.lateral_position_m", y, -50.0, 50.0, "m")?,
        None => 0.0,
    };
    let element_length = match raw.element_length_m {
        Some(h) => require_in_range(file, "scenario.element_length_m", h, 0.01, 10.0, "m")?,
        None => 1.0,
    };
    let mode_count = match raw.modes {
        Some(n) if (1..=1000).contains(&n) => n as usize,
        Some(n) => {
            return Err(file.error_at(
                "scenario.modes",
                format!("{n} is not allowed; expected a whole number from 1 to 1000"),
            ))
        }
        None => 50,
    };
    let mode_kinds = match &raw.mode_kinds {
        None => default_mode_kinds(),
        Some(names) if names.is_empty() => {
            return Err(file.error_at("scenario.mode_kinds", "an empty list keeps no mode; expected at least one of vertical_bending, torsion, lateral, longitudinal"))
        }
        Some(names) => names
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
            .collect::<Result<_, _>>()?,
    };
    let time_step = raw
        .time_step_s
        .map(|dt| require_in_range(file, "scenario.time_step_s", dt, 1e-6, 0.1, "s"))
        .transpose()?;
    let newmark_beta = match raw.newmark_beta {
        Some(b) => require_in_range(file, "scenario.newmark_beta", b, 0.0, 0.5, "")?,
        None => 0.25,
    };
    let newmark_gamma = match raw.newmark_gamma {
        Some(g) => require_in_range(file, "scenario.newmark_gamma", g, 0.5, 1.0, "")?,
        None => 0.5,
    };
    let free_vibration = raw
        .free_vibration_s
        .map(|t| require_in_range(file, "scenario.free_vibration_s", t, 0.0, 600.0, "s"))
        .transpose()?;
    let convergence_tolerance = match raw.convergence_tolerance {
        Some(t) => require_positive(file, "scenario.convergence_tolerance", t, "(fraction)")?,
        None => 0.01,
    };
    let rerun_mode_counts = match &raw.rerun_modes {
        None => Vec::new(),
        Some(counts) => counts
            .iter()
            .enumerate()
            .map(|(i, &k)| {
                if (1..=mode_count as i64).contains(&k) {
                    Ok(k as usize)
                } else {
                    Err(file.error_at(
                        &format!("scenario.rerun_modes[{i}]"),
                        format!("{k} is not allowed; expected a mode count from 1 to {mode_count} (`modes`)"),
                    ))
                }
            })
            .collect::<Result<_, _>>()?,
    };
    let name = raw.name.clone().unwrap_or_else(|| {
        file.path
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_else(|| "scenario".into())
    });
    Ok(Scenario {
        name,
        bridge,
        bridge_label,
        vehicle,
        road: road_spec,
        speed: speed_kmh * KMH,
        lateral_position,
        element_length,
        mode_count,
        mode_kinds,
        time_step,
        newmark_beta,
        newmark_gamma,
        free_vibration,
        convergence_tolerance,
        rerun_mode_counts,
        tyre_separation: raw.tyre_separation.unwrap_or(true),
        input_hash: hex(&hasher.finalize()),
    })
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
