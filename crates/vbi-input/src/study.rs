//! The `[study]` input file: a base scenario and the axes to vary (docs/study.md).
//!
//! ```toml
//! [study]
//! name = "paper"        # default: the file stem
//! seed = 1              # study seed; each case's road seed derives from it and the case
//! samples = 10          # roughness samples per parameter combination
//!
//! [study.axes]          # Cartesian product, the first axis varying slowest
//! span_count = [2, 3, 4]
//! span_length_m = [20, 30, 40]
//! road = ["smooth", "good", "medium", "poor"]
//! speed_kmh = [40, 80, 120]
//!
//! [scenario]            # the base scenario (optional; inline [bridge], [vehicle], [road] too)
//! modes = 50
//! ```

use std::collections::BTreeMap;
use std::path::PathBuf;

use serde::Deserialize;
use sha2::{Digest, Sha256};

use vbi::analysis::StationScope;
use vbi::crossing::keys::{self, Place};
use vbi::crossing::{KeyValue, Scenario};
use vbi::modal::Quantity;
use vbi::study::{expand, Axis, Case, RecordRequest, StudyDesign, Value};

use crate::resolve::Resolver;
use crate::scenario;
use crate::source::{InputError, SourceFile};

/// Fields that identify a bridge type in figures (panels, Fig. 25 bars, Table 2 groups).
pub const STRUCTURE_FIELDS: [&str; 3] = ["bridge", "span_count", "span_length_m"];

#[derive(Debug, Deserialize)]
struct Document {
    study: RawStudy,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStudy {
    name: Option<String>,
    seed: Option<crate::seed::Seed>,
    samples: Option<i64>,
    axes: Option<toml::Table>,
    cases: Option<Vec<toml::Table>>,
    reference: Option<toml::Table>,
    record: Option<toml::Value>,
}

/// A validated study: its cases and the scenario of each.
#[derive(Debug, Clone)]
pub struct Study {
    /// Name for reports.
    pub name: String,
    /// The study file.
    pub path: PathBuf,
    /// Its text.
    pub source: String,
    /// The design (rows, axes, samples, seed).
    pub design: StudyDesign,
    /// The base scenario.
    pub base: Scenario,
    /// Every case, in order.
    pub cases: Vec<Case>,
    /// The scenario of each case (same order).
    pub scenarios: Vec<Scenario>,
    /// Key of each case's bridge analysis (cases with equal keys share one).
    pub bridge_keys: Vec<String>,
    /// The varied fields, rows' first, then the axes: the parameter columns.
    pub fields: Vec<String>,
    /// Value of each varied field held fixed in figures ([study.reference], default the middle
    /// value of each axis).
    pub reference: BTreeMap<String, String>,
    /// The stations and quantities recorded besides the RDM station (`record`; default none).
    pub record: Vec<RecordRequest>,
    /// Normalised specification: everything that determines the results, flat.
    pub spec: BTreeMap<String, String>,
    /// SHA-256 of the normalised specification, hex.
    pub hash: String,
}

impl Study {
    /// The cells of case `case`'s parameter columns ([`Study::fields`]): each field's value as
    /// the study file wrote it, empty where the case does not set the field.
    pub fn parameter_cells(&self, case: usize) -> Vec<String> {
        let case = &self.cases[case];
        self.fields
            .iter()
            .map(|f| case.value(f).map(|v| v.to_string()).unwrap_or_default())
            .collect()
    }

    /// The given cases (indices into [`Study::cases`]) grouped by bridge analysis, in case
    /// order: (analysis key, case indices). Each group's bridge is prepared once.
    pub fn bridge_groups(&self, cases: &[usize]) -> Vec<(String, Vec<usize>)> {
        let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
        for &i in cases {
            let key = &self.bridge_keys[i];
            match groups.iter_mut().find(|(k, _)| k == key) {
                Some((_, list)) => list.push(i),
                None => groups.push((key.clone(), vec![i])),
            }
        }
        groups
    }
}

/// Validates a `[study]` file: every case is built before any work.
pub fn validate(file: &SourceFile) -> Result<(), InputError> {
    load(file).map(|_| ())
}

fn field_help() -> String {
    keys::names_for(false).join(", ")
}

fn to_value(file: &SourceFile, path: &str, value: &toml::Value) -> Result<Value, InputError> {
    match value {
        toml::Value::Integer(i) => Ok(Value::Number(*i as f64)),
        toml::Value::Float(x) if x.is_finite() => Ok(Value::Number(*x)),
        toml::Value::String(s) if !s.trim().is_empty() => Ok(Value::Text(s.clone())),
        other => Err(file.error_at(
            path,
            format!("{other} is not allowed; expected a finite number or a non-empty text"),
        )),
    }
}

fn check_field(file: &SourceFile, path: &str, field: &str) -> Result<(), InputError> {
    if keys::names_for(false).contains(&field) {
        Ok(())
    } else {
        Err(file.error_at(
            path,
            format!(
                "unknown field `{field}` to vary; expected one of {}",
                field_help()
            ),
        ))
    }
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Applies one field to a scenario through the one key table; `at` is where the value stands,
/// for errors.
fn apply(
    file: &SourceFile,
    files: &mut Resolver,
    scenario: &mut Scenario,
    field: &str,
    value: &Value,
    at: &str,
) -> Result<(), InputError> {
    let key = keys::key(field)
        .filter(|k| k.place != Place::Scenario)
        .ok_or_else(|| {
            file.error_at(
                at,
                format!(
                    "unknown field `{field}` to vary; expected one of {}",
                    field_help()
                ),
            )
        })?;
    let text = || {
        value.as_text().ok_or_else(|| {
            file.error_at(
                at,
                format!("`{value}` is not allowed; expected {}", key.expected()),
            )
        })
    };
    match field {
        "bridge" => {
            let named = files.bridge(file, at, text()?)?;
            scenario.bridge.model = named.model;
            scenario.bridge_label = named.label;
        }
        "vehicle" => scenario.vehicle = files.vehicle(file, at, text()?)?,
        "road" => scenario.road = files.road(file, at, text()?, &scenario.road)?,
        _ => {
            let value = match value {
                Value::Number(x) => KeyValue::Number(*x),
                Value::Text(t) => KeyValue::Text(t.clone()),
            };
            scenario
                .set(field, &value)
                .map_err(|e| file.error_at(at, e.message))?;
        }
    }
    Ok(())
}

/// The base scenario of a study file: its `[scenario]` (with inline tables), or the defaults.
fn base_scenario(file: &SourceFile) -> Result<Scenario, InputError> {
    let table: toml::Table = file.parse()?;
    let loaded = if table.contains_key("scenario") {
        scenario::load(file)?
    } else {
        // An empty [scenario] appended after the last line: line numbers are unchanged.
        let text = format!("{}\n[scenario]\n", file.text);
        scenario::load(&SourceFile::from_text(file.path.clone(), text))?
    };
    Ok(loaded.scenario)
}

/// Reads and validates a study file; builds and checks every case's scenario.
pub fn load(file: &SourceFile) -> Result<Study, InputError> {
    let document: Document = file.parse()?;
    let raw = document.study;
    let base = base_scenario(file)?;
    let design = StudyDesign {
        rows: rows(file, &raw)?,
        axes: axes(file, &raw)?,
        samples: samples(file, &raw)?,
        seed: raw.seed.map_or(1, |seed| seed.0),
    };
    let cases = expand(&design).map_err(|e| file.error_at("study", e.to_string()))?;

    // Varied fields: rows' fields in order of appearance, then the axes.
    let mut fields: Vec<String> = Vec::new();
    for row in &design.rows {
        for (f, _) in row {
            if !fields.contains(f) {
                fields.push(f.clone());
            }
        }
    }
    fields.extend(design.axes.iter().map(|a| a.field.clone()));

    let record = record(file, &raw)?;
    let mut files = Resolver::default();
    let study_name = raw.name.as_deref().unwrap_or("study");
    let (scenarios, bridge_keys) = case_scenarios(
        file, &design, &cases, &base, &mut files, study_name, &record,
    )?;
    let reference = reference_values(file, &design, &raw)?;
    let mut spec = normalised_spec(&design, &base, &files);
    if !record.is_empty() {
        spec.insert("study.record".into(), record_text(&record));
    }
    let mut hasher = Sha256::new();
    for (k, v) in &spec {
        hasher.update(k.as_bytes());
        hasher.update(b"\x00");
        hasher.update(v.as_bytes());
        hasher.update(b"\x00");
    }
    let name = raw.name.clone().unwrap_or_else(|| {
        file.path
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_else(|| "study".into())
    });
    Ok(Study {
        name,
        path: file.path.clone(),
        source: file.text.clone(),
        design,
        base,
        cases,
        scenarios,
        bridge_keys,
        fields,
        reference,
        record,
        spec,
        hash: hex(&hasher.finalize()),
    })
}

/// `study.samples`: roughness samples per combination.
fn samples(file: &SourceFile, raw: &RawStudy) -> Result<usize, InputError> {
    match raw.samples {
        None => Ok(1),
        Some(n) if (1..=100_000).contains(&n) => Ok(n as usize),
        Some(n) => Err(file.error_at(
            "study.samples",
            format!("{n} is not allowed; expected a whole number from 1 to 100000"),
        )),
    }
}

/// `[study.axes]`, in the order they stand in the file.
fn axes(file: &SourceFile, raw: &RawStudy) -> Result<Vec<Axis>, InputError> {
    let mut axes = Vec::new();
    let Some(table) = &raw.axes else {
        return Ok(axes);
    };
    for (field, values) in table {
        let path = format!("study.axes.{field}");
        check_field(file, &path, field)?;
        let list = match values {
            toml::Value::Array(list) => list,
            _ => {
                return Err(file.error_at(
                    &path,
                    "expected a list of values, for example [40, 80, 120]",
                ))
            }
        };
        if list.is_empty() {
            return Err(file.error_at(
                &path,
                "an empty axis gives no case; list at least one value",
            ));
        }
        let values = list
            .iter()
            .enumerate()
            .map(|(i, v)| to_value(file, &format!("{path}[{i}]"), v))
            .collect::<Result<Vec<_>, _>>()?;
        refuse_repeated_values(file, &path, &values)?;
        axes.push(Axis {
            field: field.clone(),
            values,
        });
    }
    axes.sort_by_key(|a| {
        file.error_at(&format!("study.axes.{}", a.field), "")
            .location
            .unwrap_or((usize::MAX, 0))
    });
    Ok(axes)
}

/// Refuses an axis that lists a value twice (a number, or a name ignoring case: `"B"` and `"b"`
/// are one road class), which would run the same cases twice under two names.
fn refuse_repeated_values(
    file: &SourceFile,
    path: &str,
    values: &[Value],
) -> Result<(), InputError> {
    for (i, value) in values.iter().enumerate() {
        let same = |earlier: &Value| match (earlier, value) {
            (Value::Number(a), Value::Number(b)) => a == b,
            (Value::Text(a), Value::Text(b)) => a.eq_ignore_ascii_case(b),
            _ => false,
        };
        if let Some(earlier) = values[..i].iter().find(|earlier| same(earlier)) {
            return Err(file.error_at(
                &format!("{path}[{i}]"),
                format!("`{value}` repeats `{earlier}` of this axis; give each value once"),
            ));
        }
    }
    Ok(())
}

/// `study.record`: the stations (by name) and quantities recorded besides the RDM station, each
/// entry a station name (every quantity) or `{ station = "…", quantities = ["…", …] }`. The
/// names are checked against each case's bridge in [`case_scenarios`].
fn record(file: &SourceFile, raw: &RawStudy) -> Result<Vec<RecordRequest>, InputError> {
    let Some(value) = &raw.record else {
        return Ok(Vec::new());
    };
    let form = "expected a list of stations, each a station name or \
                { station = \"span1_mid_section\", quantities = [\"deflection\"] }";
    let toml::Value::Array(entries) = value else {
        return Err(file.error_at("study.record", form));
    };
    let quantities_allowed = || {
        let names: Vec<String> = Quantity::names().iter().map(|n| format!("`{n}`")).collect();
        names.join(", ")
    };
    let mut record: Vec<RecordRequest> = Vec::new();
    for (i, entry) in entries.iter().enumerate() {
        let at = format!("study.record[{i}]");
        let (station, quantities) = match entry {
            toml::Value::String(name) => (name.clone(), Quantity::all()),
            toml::Value::Table(table) => {
                if let Some(unknown) = table
                    .keys()
                    .find(|k| !["station", "quantities"].contains(&k.as_str()))
                {
                    return Err(file.error_at(
                        &format!("{at}.{unknown}"),
                        format!("unknown key `{unknown}`; expected `station`, `quantities`"),
                    ));
                }
                let station = match table.get("station") {
                    Some(toml::Value::String(name)) => name.clone(),
                    _ => {
                        return Err(file.error_at(
                            &format!("{at}.station"),
                            "expected `station = \"<name>\"`, a station of the bridge",
                        ))
                    }
                };
                let quantities = match table.get("quantities") {
                    None => Quantity::all(),
                    Some(toml::Value::Array(list)) if !list.is_empty() => {
                        let mut quantities = Vec::new();
                        for (q, item) in list.iter().enumerate() {
                            let path = format!("{at}.quantities[{q}]");
                            let quantity =
                                item.as_str().and_then(Quantity::from_name).ok_or_else(|| {
                                    file.error_at(
                                        &path,
                                        format!(
                                            "unknown quantity `{}`; expected one of {}",
                                            item.as_str().map_or(item.to_string(), str::to_string),
                                            quantities_allowed()
                                        ),
                                    )
                                })?;
                            if quantities.contains(&quantity) {
                                return Err(file.error_at(
                                    &path,
                                    format!("`{}` is listed twice; give it once", quantity.name()),
                                ));
                            }
                            quantities.push(quantity);
                        }
                        quantities
                    }
                    Some(_) => {
                        return Err(file.error_at(
                            &format!("{at}.quantities"),
                            format!(
                                "expected a non-empty list of quantities, each one of {}",
                                quantities_allowed()
                            ),
                        ))
                    }
                };
                (station, quantities)
            }
            _ => return Err(file.error_at(&at, form)),
        };
        if record.iter().any(|r| r.station == station) {
            return Err(file.error_at(
                &at,
                format!("station `{station}` is recorded twice; give it once"),
            ));
        }
        record.push(RecordRequest {
            station,
            quantities,
        });
    }
    Ok(record)
}

/// Refuses the bridge of a case that its mesh or the memory of its modal analysis would make
/// the run refuse ([`vbi::crossing::check_bridge`]), at the axis that sets the element length or
/// the mode count for this case, else where the study's scenario sets it.
fn check_case_bridge(
    file: &SourceFile,
    design: &StudyDesign,
    case: &Case,
    scenario: &Scenario,
    bridge: &str,
) -> Result<(), InputError> {
    use vbi::crossing::PipelineError;
    let Err(error) = vbi::crossing::check_bridge(&scenario.bridge) else {
        return Ok(());
    };
    let axis = match &error {
        PipelineError::Discretise(_) => "element_length_m",
        _ => "modes",
    };
    let located = scenario::locate_failure(file, scenario, &error);
    if case.value(axis).is_none() || bridge.is_empty() {
        return Err(located);
    }
    Err(file.error_at(
        &locate(design, case, axis),
        format!("the bridge of the cases with {bridge}: {}", located.message),
    ))
}

/// The record as one line of the normalised specification.
fn record_text(record: &[RecordRequest]) -> String {
    let entries: Vec<String> = record
        .iter()
        .map(|r| {
            let names: Vec<&str> = r.quantities.iter().map(|q| q.name()).collect();
            format!("{}: {}", r.station, names.join(", "))
        })
        .collect();
    entries.join("; ")
}

/// Refuses a recorded station that the bridge of some cases does not have, naming the stations
/// it has; `bridge` says which cases (empty: every case, the base bridge).
fn check_record_stations(
    file: &SourceFile,
    record: &[RecordRequest],
    scenario: &Scenario,
    bridge: &str,
) -> Result<(), InputError> {
    // A mesh that cannot be made is the mesh's fault (`scenario.element_length_m`, the
    // bridge), not the record's.
    let fe = vbi::fe::discretise(&scenario.bridge.model, &scenario.bridge.mesh).map_err(|e| {
        scenario::locate_failure(file, scenario, &vbi::crossing::PipelineError::Discretise(e))
    })?;
    let names: Vec<&str> = fe.stations.iter().map(|s| s.name.as_str()).collect();
    for (i, request) in record.iter().enumerate() {
        if !names.contains(&request.station.as_str()) {
            let which = if bridge.is_empty() {
                "the study's bridge".to_string()
            } else {
                format!("the bridge of the cases with {bridge}")
            };
            // At the `station` key of a table entry, at the entry itself for a bare name.
            let (entry, key) = (
                format!("study.record[{i}]"),
                format!("study.record[{i}].station"),
            );
            let path = if file.error_at(&key, "").location != file.error_at(&entry, "").location {
                key
            } else {
                entry
            };
            return Err(file.error_at(
                &path,
                format!(
                    "unknown station `{}` on {which}; expected one of {}",
                    request.station,
                    names.join(", ")
                ),
            ));
        }
        // A station reads the shear force, or at a support the support reaction; a list that
        // names the other is refused (every quantity, the default, means those it has).
        let station = &fe.stations[names
            .iter()
            .position(|n| *n == request.station)
            .unwrap_or(0)];
        if request.quantities == Quantity::all() {
            continue;
        }
        for (q, quantity) in request.quantities.iter().enumerate() {
            if !station.quantities().contains(quantity) {
                let has: Vec<&str> = station.quantities().iter().map(|q| q.name()).collect();
                return Err(file.error_at(
                    &format!("study.record[{i}].quantities[{q}]"),
                    format!(
                        "station `{}` has no {}; it records {}",
                        request.station,
                        quantity.name(),
                        has.join(", ")
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `[[study.cases]]`: explicit rows of field values.
fn rows(file: &SourceFile, raw: &RawStudy) -> Result<Vec<Vec<(String, Value)>>, InputError> {
    let mut rows = Vec::new();
    for (r, row) in raw.cases.iter().flatten().enumerate() {
        let mut pairs = Vec::new();
        for (field, value) in row {
            let path = format!("study.cases[{r}].{field}");
            check_field(file, &path, field)?;
            pairs.push((field.clone(), to_value(file, &path, value)?));
        }
        rows.push(pairs);
    }
    Ok(rows)
}

/// Where a case's value of a field stands in the file, for errors.
fn locate(design: &StudyDesign, case: &Case, field: &str) -> String {
    if let Some(a) = design.axes.iter().find(|a| a.field == field) {
        let value = case.value(field);
        let i = a.values.iter().position(|v| Some(v) == value).unwrap_or(0);
        format!("study.axes.{field}[{i}]")
    } else {
        let r = design
            .rows
            .iter()
            .position(|row| row.iter().all(|(f, v)| case.value(f) == Some(v)))
            .unwrap_or(0);
        format!("study.cases[{r}].{field}")
    }
}

/// The scenario of every case, and the key of its bridge analysis (cases with equal keys share
/// one); each bridge, vehicle and road is checked once, before any work.
fn case_scenarios(
    file: &SourceFile,
    design: &StudyDesign,
    cases: &[Case],
    base: &Scenario,
    files: &mut Resolver,
    study_name: &str,
    record: &[RecordRequest],
) -> Result<(Vec<Scenario>, Vec<String>), InputError> {
    let mut scenarios = Vec::with_capacity(cases.len());
    let mut bridge_keys = Vec::with_capacity(cases.len());
    let mut checked_bridges = std::collections::HashSet::new();
    let mut checked_vehicles = std::collections::HashSet::new();
    for case in cases {
        let mut s = base.clone();
        for field in keys::names_for(false) {
            if let Some(value) = case.value(field) {
                apply(
                    file,
                    files,
                    &mut s,
                    field,
                    value,
                    &locate(design, case, field),
                )?;
            }
        }
        s.road.seed = case.seed;
        // A study records the RDM station (and the stations of its `record`) only: the full
        // analysis of every station would cost O(steps × modes) each, for columns that no table
        // holds.
        s.analysis.stations = if record.is_empty() {
            StationScope::RdmStation
        } else {
            StationScope::RdmStationAnd(record.iter().map(|r| r.station.clone()).collect())
        };
        check_new_axes(file, design, case, &s)?;
        s.name = format!("{study_name} {}", case.key());
        let bridge_params: Vec<String> = keys::BRIDGE_KEYS
            .iter()
            .filter_map(|f| case.value(f).map(|v| format!("{f}={v}")))
            .collect();
        let key = bridge_params.join(";");
        if checked_bridges.insert(key.clone()) {
            s.bridge.model.validate().map_err(|e| {
                // A bridge made invalid by a damage or support axis: at that axis's value.
                let at = [
                    "support_stiffness_n_per_m",
                    "damage_end_m",
                    "damage_start_m",
                ]
                .into_iter()
                .find(|f| case.value(f).is_some())
                .map_or("study".to_string(), |f| locate(design, case, f));
                file.error_at(&at, format!("the bridge of the cases with {key}: {e}"))
            })?;
            if !record.is_empty() {
                check_record_stations(file, record, &s, &key)?;
            }
            check_case_bridge(file, design, case, &s, &key)?;
        }
        let vehicle_key = case
            .value("vehicle")
            .map(|v| v.to_string())
            .unwrap_or_default();
        if checked_vehicles.insert(vehicle_key) {
            vbi::vehicle::assemble(&s.vehicle).map_err(|e| {
                file.error_at("study", format!("the vehicle `{}`: {e}", s.vehicle.name))
            })?;
        }
        s.road
            .validate()
            .map_err(|e| file.error_at("study", format!("the road of case {}: {e}", case.key())))?;
        scenarios.push(s);
        bridge_keys.push(key);
    }
    Ok((scenarios, bridge_keys))
}

/// The checks of the axes that need the whole case: the damage region's start below its end
/// (`damage_start_m`, `damage_end_m`), and a lane pattern's vehicles placed on the deck
/// (`lane_pattern`; the pipeline's own placement, which `vbi run` runs too).
fn check_new_axes(
    file: &SourceFile,
    design: &StudyDesign,
    case: &Case,
    scenario: &Scenario,
) -> Result<(), InputError> {
    if let Some(field) = ["damage_end_m", "damage_start_m"]
        .into_iter()
        .find(|f| case.value(f).is_some())
    {
        keys::check_damage_region(&scenario.bridge.model)
            .map_err(|e| file.error_at(&locate(design, case, field), e.message))?;
    }
    if !scenario.lane_pattern.is_single() {
        if let Err(e) = vbi::crossing::vehicle_runs(scenario) {
            let at = if case.value("lane_pattern").is_some() {
                locate(design, case, "lane_pattern")
            } else {
                "scenario.lane_pattern".to_string()
            };
            return Err(file.error_at(&at, vbi::crossing::error_chain(&e)));
        }
    }
    Ok(())
}

/// Values held fixed in figures: `[study.reference]`, default the middle value of each axis.
fn reference_values(
    file: &SourceFile,
    design: &StudyDesign,
    raw: &RawStudy,
) -> Result<BTreeMap<String, String>, InputError> {
    let mut reference = BTreeMap::new();
    for a in &design.axes {
        reference.insert(a.field.clone(), a.values[a.values.len() / 2].to_string());
    }
    for (field, value) in raw.reference.iter().flatten() {
        let path = format!("study.reference.{field}");
        let v = to_value(file, &path, value)?;
        let axis = design
            .axes
            .iter()
            .find(|a| &a.field == field)
            .ok_or_else(|| {
                file.error_at(
                    &path,
                    "a reference value is only for a field that is an axis",
                )
            })?;
        if !axis.values.contains(&v) {
            return Err(file.error_at(&path, format!("`{v}` is not one of the axis values")));
        }
        reference.insert(field.clone(), v.to_string());
    }
    Ok(reference)
}

/// The normalised specification: everything that determines the results, flat, for the
/// manifest and the change detection of `--resume`.
fn normalised_spec(
    design: &StudyDesign,
    base: &Scenario,
    files: &Resolver,
) -> BTreeMap<String, String> {
    let mut spec = BTreeMap::new();
    spec.insert("vbi.version".into(), env!("CARGO_PKG_VERSION").to_string());
    spec.insert("study.seed".into(), design.seed.to_string());
    spec.insert("study.samples".into(), design.samples.to_string());
    for a in &design.axes {
        let values: Vec<String> = a.values.iter().map(|v| v.to_string()).collect();
        spec.insert(
            format!("study.axes.{}", a.field),
            format!("[{}]", values.join(", ")),
        );
    }
    for (r, row) in design.rows.iter().enumerate() {
        let pairs: Vec<String> = row.iter().map(|(f, v)| format!("{f} = {v}")).collect();
        spec.insert(format!("study.cases[{r}]"), pairs.join(", "));
    }
    // The base scenario whole, as the library serialises it: no field can be left out of the
    // change detection of `--resume`. Its name and seed are the study's (each case has its own).
    let mut normalised = base.clone();
    normalised.name.clear();
    normalised.road.seed = 0;
    let value = serde_json::to_value(&normalised).expect("a scenario serialises");
    flatten("scenario", &value, &mut spec);
    for (name, text) in &files.files {
        spec.insert(
            format!("file:{name}"),
            hex(&Sha256::digest(text.as_bytes())),
        );
    }
    spec
}

/// Every leaf of a JSON value as `path = value` (`scenario.solver.tyre_separation = true`), so
/// that a changed field is named by its path.
fn flatten(path: &str, value: &serde_json::Value, out: &mut BTreeMap<String, String>) {
    match value {
        serde_json::Value::Object(map) => {
            for (key, item) in map {
                flatten(&format!("{path}.{key}"), item, out);
            }
        }
        serde_json::Value::Array(list) => {
            if list.is_empty() {
                out.insert(path.to_string(), "[]".into());
            }
            for (i, item) in list.iter().enumerate() {
                flatten(&format!("{path}[{i}]"), item, out);
            }
        }
        leaf => {
            out.insert(path.to_string(), leaf.to_string());
        }
    }
}
