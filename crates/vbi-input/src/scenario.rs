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

use sha2::{Digest, Sha256};

use vbi::crossing::keys::{self, Allowed, Place};
use vbi::crossing::{PipelineError, Scenario, SCENARIO_KEYS};
use vbi::road::RoadSpec;

use crate::resolve::Resolver;
use crate::source::{InputError, SourceFile};
pub use crate::values::{key_error, key_value};
use crate::{bridge, fatigue_details, road, stations, traffic, vehicle};

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

/// Lower-case hexadecimal of a digest (the input hashes).
pub(crate) fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Validates a `[scenario]` file, including every file it names.
pub fn validate(file: &SourceFile) -> Result<(), InputError> {
    let loaded = load(file)?;
    // What the run would refuse before any numeric work: the mesh and the modal memory, and
    // the fatigue details' stations.
    let failure = |e: vbi::crossing::PipelineError| locate_failure(file, &loaded.scenario, &e);
    vbi::crossing::check_bridge(&loaded.scenario.bridge).map_err(failure)?;
    if !loaded.scenario.fatigue_details.is_empty() {
        let stations = vbi::crossing::bridge_stations(&loaded.scenario.bridge).map_err(failure)?;
        fatigue_details::check(file, &loaded.scenario, &stations)?;
    }
    Ok(())
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

/// Reads and validates a scenario file: every key of `[scenario]` through the one key table
/// ([`vbi::crossing::keys`]), the parts it names through the one resolver.
pub fn load(file: &SourceFile) -> Result<ScenarioFile, InputError> {
    let table: toml::Table = file.parse()?;
    let raw = match table.get("scenario") {
        Some(toml::Value::Table(raw)) => raw,
        _ => {
            return Err(file.error_at(
                "scenario",
                "expected a [scenario] table of keys, for example speed_kmh = 80",
            ))
        }
    };
    refuse_unknown_keys(file, raw)?;
    let mut resolver = Resolver::default();
    let mut scenario = Scenario::default();
    set_parts(file, &table, raw, &mut resolver, &mut scenario)?;
    for key in SCENARIO_KEYS {
        let Some(value) = raw.get(key.name) else {
            continue;
        };
        if key.place == Place::Study || matches!(key.allowed, Allowed::Name(_)) {
            continue;
        }
        let path = format!("scenario.{}", key.name);
        let value = key_value(file, &path, value)?;
        scenario
            .set(key.name, &value)
            .map_err(|e| key_error(file, "scenario", e))?;
    }
    scenario.motion.speed_profile = traffic::speed_profile(file, "scenario", raw)?;
    traffic::load(file, &table, &mut resolver, &mut scenario)?;
    traffic::load_stream(file, &table, &mut resolver, &mut scenario)?;
    stations::load(file, &table, &mut scenario)?;
    fatigue_details::load(file, &table, &mut scenario)?;
    traffic::check(file, &scenario)?;
    check_profile_extent(file, &table, &scenario)?;
    if !raw.contains_key("name") {
        scenario.name = file
            .path
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_else(|| "scenario".into());
    }
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

/// Refuses, before any work, a user road profile that does not cover the crossing's extent
/// (the one the pipeline generates for every vehicle of the event,
/// [`vbi::crossing::road_extent`]). Traffic that cannot be placed is reported by
/// `traffic::check` before, a vehicle that does not assemble by the run.
fn check_profile_extent(
    file: &SourceFile,
    table: &toml::Table,
    scenario: &Scenario,
) -> Result<(), InputError> {
    let (Some(profile), Ok(vehicles)) = (
        &scenario.road.profile,
        vbi::crossing::vehicle_runs(scenario),
    ) else {
        return Ok(());
    };
    let (start, end) = vbi::crossing::road_extent(scenario, &vehicles);
    let at = if table.contains_key("road") {
        "road.profile_csv"
    } else {
        "scenario.road"
    };
    profile
        .covers(start, end, scenario.road.sample_spacing)
        .map_err(|e| file.error_at(at, e.to_string()))
}

/// Refuses a key of `[scenario]` that the key table does not define for a scenario file.
fn refuse_unknown_keys(file: &SourceFile, raw: &toml::Table) -> Result<(), InputError> {
    let mut known = keys::names_for(true);
    known.push("speed_profile");
    match raw.keys().find(|k| !known.contains(&k.as_str())) {
        Some(unknown) => Err(file.error_at(
            &format!("scenario.{unknown}"),
            format!(
                "unknown key `{unknown}` in [scenario]; expected one of {}{}",
                known.join(", "),
                if keys::key(unknown).is_some() {
                    " (this one is only for a study's axes)"
                } else {
                    ""
                }
            ),
        )),
        None => Ok(()),
    }
}

/// The bridge, the vehicle and the road: each an inline table, or a name (a preset or class, or
/// a file) in `[scenario]`, or the default.
fn set_parts(
    file: &SourceFile,
    table: &toml::Table,
    raw: &toml::Table,
    resolver: &mut Resolver,
    scenario: &mut Scenario,
) -> Result<(), InputError> {
    let name = |part: &str| -> Result<Option<&str>, InputError> {
        match raw.get(part) {
            None => Ok(None),
            Some(toml::Value::String(name)) => Ok(Some(name)),
            Some(other) => Err(file.error_at(
                &format!("scenario.{part}"),
                format!(
                    "{other} is not allowed; expected {}",
                    keys::key(part).map(|k| k.expected()).unwrap_or_default()
                ),
            )),
        }
    };
    if one_source(file, table, "bridge", raw.contains_key("bridge"))? {
        scenario.bridge.model = bridge::load(file)?;
        scenario.bridge_label = "inline [bridge]".to_string();
    } else if let Some(name) = name("bridge")? {
        let named = resolver.bridge(file, "scenario.bridge", name)?;
        scenario.bridge.model = named.model;
        scenario.bridge_label = named.label;
    }
    if one_source(file, table, "vehicle", raw.contains_key("vehicle"))? {
        scenario.vehicle = vehicle::load(file)?;
    } else if let Some(name) = name("vehicle")? {
        scenario.vehicle = resolver.vehicle(file, "scenario.vehicle", name)?;
    }
    if one_source(file, table, "road", raw.contains_key("road"))? {
        let (spec, sources) = road::load_with_sources(file)?;
        scenario.road = spec;
        resolver.files.extend(sources);
    } else if let Some(name) = name("road")? {
        scenario.road = resolver.road(file, "scenario.road", name, &RoadSpec::default())?;
    }
    Ok(())
}

/// A failure of the pipeline on a scenario that `file` validated, located at the key that
/// governs what failed, so that every refusal of `vbi run` names a place in its file: the mesh
/// (`element_length_m`) for the discretisation, `modes` for an analysis that would not fit in
/// memory, the supports for a mechanism, the bridge for the other modal and static failures,
/// the vehicle, the road, the time step (or the Newmark parameters) for the crossing, the
/// traffic entry of a vehicle at fault, and `rerun_modes` for a re-run. The first key of each
/// list that the file holds is named; failing all, `[scenario]`.
pub fn locate_failure(file: &SourceFile, scenario: &Scenario, error: &PipelineError) -> InputError {
    use vbi::modal::ModalError;
    use vbi::solver::SolverError;
    let keys: Vec<String> = match error {
        PipelineError::Discretise(_) => vec!["scenario.element_length_m".into(), "bridge".into()],
        PipelineError::Modes(ModalError::MemoryLimit { .. } | ModalError::WorkLimit { .. }) => {
            vec!["scenario.modes".into(), "scenario.element_length_m".into()]
        }
        PipelineError::Modes(ModalError::Mechanism { .. } | ModalError::Unstable { .. }) => {
            vec![
                "bridge.stiffness_mtx".into(),
                "bridge.supports".into(),
                "bridge".into(),
                "scenario.bridge".into(),
            ]
        }
        PipelineError::ImportedModes(_) => vec![
            "scenario.mode_kinds".into(),
            "scenario.modes".into(),
            "bridge".into(),
            "scenario.bridge".into(),
        ],
        PipelineError::Modes(_) | PipelineError::Influence(_) | PipelineError::BridgeMismatch => {
            vec![
                "bridge".into(),
                "scenario.bridge".into(),
                "scenario.modes".into(),
            ]
        }
        PipelineError::Vehicle(_) => vec!["vehicle".into(), "scenario.vehicle".into()],
        PipelineError::Road(e) => vec![
            road::generation_key(e).into(),
            "road".into(),
            "scenario.road".into(),
        ],
        PipelineError::Crossing(SolverError::InvalidNewmark { .. }) => {
            vec![
                "scenario.newmark_beta".into(),
                "scenario.newmark_gamma".into(),
            ]
        }
        PipelineError::Crossing(
            SolverError::InvalidTimeStep { .. }
            | SolverError::UnstableTimeStep { .. }
            | SolverError::TooLong { .. },
        ) => vec![
            "scenario.time_step_s".into(),
            "scenario.free_vibration_s".into(),
            "scenario.speed_kmh".into(),
        ],
        PipelineError::Traffic { vehicle, .. } => vec![vbi::crossing::input_entry(
            scenario,
            vehicle.saturating_sub(1),
        )],
        PipelineError::Stream(_) => vec!["traffic_stream".into()],
        PipelineError::FatigueDetail { index, .. } => vec![
            format!("fatigue_detail[{index}].station"),
            "fatigue_detail".into(),
        ],
        PipelineError::Rerun(_) | PipelineError::RerunModeCount { .. } => {
            vec!["scenario.rerun_modes".into(), "scenario.modes".into()]
        }
        _ => vec![],
    };
    let key = keys
        .iter()
        .find(|k| file.has_key(k))
        .map_or("scenario", String::as_str);
    file.error_at(key, vbi::crossing::error_chain(error))
}
