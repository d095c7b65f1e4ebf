//! A lifetime file (`vbi lifetime`, docs/lifetime.md): the `[lifetime]` table naming the
//! traffic and the bridge, the lanes, and `[[station]]`s as a scenario has them.
//!
//! ```toml
//! [lifetime]
//! bridge = "paper-2x20"                 # a preset or a bridge file; or an inline [bridge]
//! traffic_file = "traffic/week.castor.txt"
//! traffic_format = "castor"             # castor | bedit | ditis | mon | csv
//! block_days = 1                        # the block of the block maxima [days]; default 1
//! dynamics = false                      # true: full VBI on the events that can govern
//! screening_ratio = 0.7                 # events integrated: static ≥ r × the block's maximum
//! points_per_element = 4                # influence lines tabulated per element; default 4
//! quantities = ["bending_moment"]       # default every quantity a station has
//! return_periods_years = [1000]         # return levels of the fits; default [1000]
//! days_per_year = 250                   # days of traffic in a year; default 250 (BTLS's)
//! bootstrap_resamples = 400             # resamples of the levels' intervals; 0: none
//! seed = 0                              # seed of the resamples; default 0
//! peaks_over_threshold = 1000           # exceedances of the GP fit; 0: none; default 1000
//!
//! [[lifetime.lane]]                     # default on a beam: direction 1 and 2, lane 1, y = 0
//! direction = 1                         # 1 enters at x = 0, 2 at x = L
//! lane = 1                              # from 1 within its direction, as the file numbers it
//! lateral_position_m = 1.75             # lane centreline from the deck centreline, left +
//!
//! [lifetime.crossing]                   # with dynamics: the crossing's keys, as a scenario's
//! road = "good"                         # road class or [road] file; seed, modes, time_step_s …
//! ```

use std::cell::{Cell, RefCell};

use sha2::{Digest, Sha256};
use vbi::crossing::{BridgeSpec, Scenario};
use vbi::fe::Quantity;
use vbi::lifetime::event::EventExtreme;
use vbi::lifetime::{
    fit_peaks, static_and_total_block_maxima, static_maxima_and_peaks, BlockMaximaTally,
    BlockMaximum, DynamicSettings, EffectFits, EventPeaks, EventTotals, LifetimeCounts,
    LifetimeLane, PeaksOverThresholdFit, ReturnLevelSettings, StaticLifetime, TotalBlockMaxima,
    DEFAULT_POINTS_PER_ELEMENT, DEFAULT_SCREENING_RATIO, SECONDS_PER_DAY,
};
use vbi::model::BridgeModel;
use vbi::road::RoadSpec;
use vbi::traffic::TravelDirection;

use crate::resolve::{relative, Resolver};
use crate::source::{require_in_range, InputError, SourceFile};
use crate::traffic_file::{TrafficFileReader, TrafficFormat};
use crate::traffic_source::{TrafficInput, TrafficSource};
use crate::{bridge, stations};

/// Every key of `[lifetime]`.
const LIFETIME_KEYS: [&str; 18] = [
    "name",
    "bridge",
    "traffic_file",
    "traffic_format",
    "block_days",
    "dynamics",
    "points_per_element",
    "quantities",
    "return_periods_years",
    "days_per_year",
    "bootstrap_resamples",
    "seed",
    "peaks_over_threshold",
    "lane",
    "screening_ratio",
    "crossing",
    "generator",
    "road_change",
];

/// The scenario keys a `[lifetime.crossing]` table may set: the road, the modes and the time
/// integration of every event's crossing (the bridge is the lifetime's, the vehicles and their
/// motion the traffic's).
pub const CROSSING_KEYS: [&str; 11] = [
    "road",
    "seed",
    "modes",
    "mode_kinds",
    "time_step_s",
    "time_step_check",
    "newmark_beta",
    "newmark_gamma",
    "free_vibration_s",
    "convergence_tolerance",
    "tyre_separation",
];

/// The most exceedances of the peaks-over-threshold fit (memory: 8 bytes each per effect).
const MAX_EXCEEDANCES: i64 = 10_000_000;

/// The shortest and longest block [days]: an hour, a century.
pub const BLOCK_DAYS_RANGE: (f64, f64) = (1.0 / 24.0, 36_500.0);

/// The fewest and most days of traffic in a year.
pub const DAYS_PER_YEAR_RANGE: (f64, f64) = (1.0, 366.0);

/// The longest return period [years] (a level a million years out is no longer an
/// extrapolation a block-maxima fit supports; the limit keeps (1 − 1/T) representable).
pub const MAX_RETURN_PERIOD_YEARS: f64 = 1.0e6;

/// The most bootstrap resamples.
const MAX_BOOTSTRAP_RESAMPLES: i64 = 100_000;

/// Every key of a `[[lifetime.lane]]`.
const LANE_KEYS: [&str; 3] = ["direction", "lane", "lateral_position_m"];

/// The most points per element (a finer tabulation only slows the analysis).
const MAX_POINTS_PER_ELEMENT: i64 = 64;

/// A lifetime file, read and validated.
#[derive(Debug, Clone)]
pub struct LifetimeFile {
    /// The analysis's name (the file's stem by default).
    pub name: String,
    /// The bridge, with its mesh and stations.
    pub bridge: BridgeSpec,
    /// How the bridge was named, for reports.
    pub bridge_label: String,
    /// The traffic: a file, or the generator.
    pub traffic: TrafficInput,
    /// The lanes.
    pub lanes: Vec<LifetimeLane>,
    /// Block length [s].
    pub block_seconds: f64,
    /// Influence-line tabulation points per element.
    pub points_per_element: usize,
    /// The quantities tracked at every station (default all).
    pub quantities: Vec<Quantity>,
    /// How the block maxima's return levels are computed.
    pub return_levels: ReturnLevelSettings,
    /// With `dynamics = true`: how the events that can govern are integrated.
    pub dynamics: Option<DynamicSettings>,
    /// What a governing event's `vbi run` scenario copies from this file.
    pub replay: crate::lifetime_replay::ReplayInputs,
    /// The fatigue details (`[[fatigue_detail]]`), each on one of the tracked effects.
    pub fatigue_details: Vec<vbi::fatigue::FatigueDetail>,
    /// SHA-256 of the file and the files it names (not the traffic file).
    pub input_hash: String,
}

/// Reads and validates a lifetime file (the traffic file is read by the analysis, line by
/// line, or by `vbi check`).
pub fn load(file: &SourceFile) -> Result<LifetimeFile, InputError> {
    let table: toml::Table = file.parse()?;
    let Some(toml::Value::Table(raw)) = table.get("lifetime") else {
        return Err(file.error_at("lifetime", "expected a [lifetime] table"));
    };
    if let Some(unknown) = raw.keys().find(|k| !LIFETIME_KEYS.contains(&k.as_str())) {
        return Err(file.error_at(
            &format!("lifetime.{unknown}"),
            format!(
                "unknown key `{unknown}` in [lifetime]; expected one of {}",
                LIFETIME_KEYS.join(", ")
            ),
        ));
    }
    let string = |key: &str| -> Result<Option<&str>, InputError> {
        match raw.get(key) {
            None => Ok(None),
            Some(toml::Value::String(s)) => Ok(Some(s.as_str())),
            Some(other) => Err(file.error_at(
                &format!("lifetime.{key}"),
                format!("{other} is not allowed; expected a string"),
            )),
        }
    };
    let mut resolver = Resolver::default();
    let mut scenario = Scenario::default();
    match (table.contains_key("bridge"), string("bridge")?) {
        (true, Some(_)) => {
            return Err(file.error_at("lifetime.bridge", "the bridge is both named here and inlined as [bridge]; keep one"))
        }
        (true, None) => {
            scenario.bridge.model = bridge::load(file)?;
            scenario.bridge_label = "inline [bridge]".into();
        }
        (false, Some(name)) => {
            let named = resolver.bridge(file, "lifetime.bridge", name)?;
            scenario.bridge.model = named.model;
            scenario.bridge_label = named.label;
        }
        (false, None) => {
            return Err(file.error_at("lifetime.bridge", "expected the bridge: a preset or a bridge file (bridge = \"paper-2x20\"), or an inline [bridge]"))
        }
    }
    if matches!(scenario.bridge.model, BridgeModel::ImportedModes(_)) {
        return Err(file.error_at("lifetime.bridge", "an imported modal basis has no static model to take influence lines from; expected a beam, a grillage or imported matrices"));
    }
    stations::load(file, &table, &mut scenario)?;
    let traffic = match raw.get("generator") {
        Some(generator) => {
            for key in ["traffic_file", "traffic_format"] {
                if raw.contains_key(key) {
                    return Err(file.error_at(
                        &format!("lifetime.{key}"),
                        "the traffic is both a file and generated ([lifetime.generator]); keep one",
                    ));
                }
            }
            let length = scenario.bridge.model.deck_length();
            TrafficInput::Generator(Box::new(crate::lifetime_generator::load(
                file, generator, length,
            )?))
        }
        None => traffic_file(file, &string)?,
    };
    let number = |key: &str, default: f64| -> Result<f64, InputError> {
        raw.get(key).map_or(Ok(default), |value| {
            number_of(file, &format!("lifetime.{key}"), value)
        })
    };
    let block_days = require_in_range(
        file,
        "lifetime.block_days",
        number("block_days", 1.0)?,
        BLOCK_DAYS_RANGE.0,
        BLOCK_DAYS_RANGE.1,
        "days",
    )?;
    let points = number("points_per_element", DEFAULT_POINTS_PER_ELEMENT as f64)?;
    if points.fract() != 0.0 || !(1.0..=MAX_POINTS_PER_ELEMENT as f64).contains(&points) {
        return Err(file.error_at("lifetime.points_per_element", format!("{points} is not allowed; expected a whole number from 1 to {MAX_POINTS_PER_ELEMENT}")));
    }
    let dynamics = match raw.get("dynamics") {
        None | Some(toml::Value::Boolean(false)) => false,
        Some(toml::Value::Boolean(true)) => true,
        Some(other) => {
            return Err(file.error_at(
                "lifetime.dynamics",
                format!("{other} is not allowed; expected true or false"),
            ))
        }
    };
    let screening_ratio = require_in_range(
        file,
        "lifetime.screening_ratio",
        number("screening_ratio", DEFAULT_SCREENING_RATIO)?,
        0.0,
        1.0,
        "× the block's static maximum",
    )?;
    for key in ["screening_ratio", "crossing", "road_change"] {
        if raw.contains_key(key) && !dynamics {
            return Err(file.error_at(
                &format!("lifetime.{key}"),
                format!("`{key}` sets the dynamics of the events; it needs dynamics = true"),
            ));
        }
    }
    let return_levels = return_levels(file, raw)?;
    let dynamics = match dynamics {
        true => {
            let template = crossing(file, raw, &mut resolver, scenario.clone())?;
            let road_changes = road_changes(file, raw, return_levels.days_per_year)?;
            if !road_changes.is_empty() && template.road.profile.is_some() {
                return Err(file.error_at(
                    "lifetime.road_change",
                    "the crossings' road is a measured profile, whose roughness does not change with a class; road_change needs a generated road (road = a class)",
                ));
            }
            Some(DynamicSettings {
                template,
                screening_ratio,
                road_changes,
            })
        }
        false => None,
    };
    let lanes = lanes(file, raw, &scenario.bridge.model)?;
    let quantities = quantities(file, raw)?;
    let name = match string("name")? {
        Some(name) => name.to_string(),
        None => file
            .path
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_else(|| "lifetime".into()),
    };
    let mut hasher = Sha256::new();
    hasher.update(file.text.as_bytes());
    for (_, text) in &resolver.files {
        hasher.update(text.as_bytes());
    }
    Ok(LifetimeFile {
        name,
        bridge: scenario.bridge,
        bridge_label: scenario.bridge_label,
        traffic,
        lanes,
        block_seconds: block_days * SECONDS_PER_DAY,
        points_per_element: points as usize,
        quantities,
        return_levels,
        dynamics,
        replay: crate::lifetime_replay::replay_inputs(file, &table),
        fatigue_details: crate::fatigue_details::read(file, &table)?,
        input_hash: crate::scenario::hex(&hasher.finalize()),
    })
}

/// The crossing every event's scenario is made from: the lifetime's bridge (`scenario`), with
/// the keys of `[lifetime.crossing]` ([`CROSSING_KEYS`]) set through the one key table as a
/// scenario file sets them; its name is the lifetime's.
fn crossing(
    file: &SourceFile,
    raw: &toml::Table,
    resolver: &mut Resolver,
    mut scenario: Scenario,
) -> Result<Scenario, InputError> {
    let Some(value) = raw.get("crossing") else {
        return Ok(scenario);
    };
    let toml::Value::Table(crossing) = value else {
        return Err(file.error_at("lifetime.crossing", "expected a [lifetime.crossing] table of scenario keys (road, seed, modes, time_step_s …)"));
    };
    if let Some(unknown) = crossing
        .keys()
        .find(|k| !CROSSING_KEYS.contains(&k.as_str()))
    {
        return Err(file.error_at(
            &format!("lifetime.crossing.{unknown}"),
            format!(
                "`{unknown}` is not a key of [lifetime.crossing] (the bridge is the lifetime's, the vehicles and their motion the traffic's); expected one of {}",
                CROSSING_KEYS.join(", ")
            ),
        ));
    }
    for (key, value) in crossing {
        let path = format!("lifetime.crossing.{key}");
        if key == "road" {
            let toml::Value::String(name) = value else {
                return Err(file.error_at(&path, format!("{value} is not allowed; expected a road class (`vbi road list`) or a [road] file")));
            };
            let seed = scenario.road.seed;
            scenario.road = resolver.road(file, &path, name, &RoadSpec::default())?;
            scenario.road.seed = seed;
            continue;
        }
        let value = crate::values::key_value(file, &path, value)?;
        scenario
            .set(key, &value)
            .map_err(|e| crate::values::key_error(file, "lifetime.crossing", e))?;
    }
    Ok(scenario)
}

/// The return-level keys: `return_periods_years`, `days_per_year`, `bootstrap_resamples`,
/// `seed`, `peaks_over_threshold`.
fn return_levels(file: &SourceFile, raw: &toml::Table) -> Result<ReturnLevelSettings, InputError> {
    let mut settings = ReturnLevelSettings::default();
    let number = |key: &str, value: &toml::Value| number_of(file, key, value);
    if let Some(value) = raw.get("return_periods_years") {
        let key = "lifetime.return_periods_years";
        let toml::Value::Array(periods) = value else {
            return Err(file.error_at(key, format!("{value} is not allowed; expected a list of return periods in years, as [100, 1000]")));
        };
        if periods.is_empty() {
            return Err(file.error_at(key, "expected at least one return period"));
        }
        settings.periods_years = periods
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let at = format!("{key}[{i}]");
                let years = number(&at, p)?;
                if years.is_finite() && years > 1.0 && years <= MAX_RETURN_PERIOD_YEARS {
                    Ok(years)
                } else {
                    Err(file.error_at(&at, format!("{p} is not allowed; expected a return period above 1 and at most {MAX_RETURN_PERIOD_YEARS:e} years")))
                }
            })
            .collect::<Result<_, _>>()?;
    }
    if let Some(value) = raw.get("days_per_year") {
        let key = "lifetime.days_per_year";
        settings.days_per_year = require_in_range(
            file,
            key,
            number(key, value)?,
            DAYS_PER_YEAR_RANGE.0,
            DAYS_PER_YEAR_RANGE.1,
            "days",
        )?;
    }
    if let Some(value) = raw.get("bootstrap_resamples") {
        let allowed = format!("a whole number from 0 to {MAX_BOOTSTRAP_RESAMPLES}");
        let key = "lifetime.bootstrap_resamples";
        settings.resamples = whole_number(file, key, value, MAX_BOOTSTRAP_RESAMPLES, &allowed)?;
    }
    if let Some(value) = raw.get("peaks_over_threshold") {
        let allowed = format!("the number of exceedances, a whole number from 0 (no peaks-over-threshold fit) to {MAX_EXCEEDANCES}");
        let key = "lifetime.peaks_over_threshold";
        settings.exceedances = whole_number(file, key, value, MAX_EXCEEDANCES, &allowed)?;
    }
    if let Some(value) = raw.get("seed") {
        settings.seed = value
            .clone()
            .try_into::<crate::seed::Seed>()
            .map_err(|e| file.error_at("lifetime.seed", e.message().to_string()))?
            .0;
    }
    Ok(settings)
}

/// A TOML number (an integer or a float) at `key`, or the error naming it.
fn number_of(file: &SourceFile, key: &str, value: &toml::Value) -> Result<f64, InputError> {
    match value {
        toml::Value::Integer(i) => Ok(*i as f64),
        toml::Value::Float(f) => Ok(*f),
        other => Err(file.error_at(key, format!("{other} is not allowed; expected a number"))),
    }
}

/// A TOML integer from 0 to `most` at `key`, or the error saying what is `allowed`.
fn whole_number(
    file: &SourceFile,
    key: &str,
    value: &toml::Value,
    most: i64,
    allowed: &str,
) -> Result<usize, InputError> {
    match value {
        toml::Value::Integer(i) if (0..=most).contains(i) => Ok(*i as usize),
        other => Err(file.error_at(key, format!("{other} is not allowed; expected {allowed}"))),
    }
}

/// The `quantities` list: names of [`Quantity`] (default all four; a station tracks those it
/// has).
fn quantities(file: &SourceFile, raw: &toml::Table) -> Result<Vec<Quantity>, InputError> {
    let Some(value) = raw.get("quantities") else {
        return Ok(Quantity::ALL.to_vec());
    };
    let allowed = Quantity::ALL.map(Quantity::name).join(", ");
    let toml::Value::Array(names) = value else {
        return Err(file.error_at(
            "lifetime.quantities",
            format!("expected a list of quantity names from {allowed}"),
        ));
    };
    let mut quantities = Vec::new();
    for (i, name) in names.iter().enumerate() {
        let quantity = name.as_str().and_then(Quantity::from_name).ok_or_else(|| {
            file.error_at(
                &format!("lifetime.quantities[{i}]"),
                format!("{name} is not a quantity; expected one of {allowed}"),
            )
        })?;
        quantities.push(quantity);
    }
    if quantities.is_empty() {
        return Err(file.error_at(
            "lifetime.quantities",
            format!("expected at least one of {allowed}"),
        ));
    }
    Ok(quantities)
}

/// The `[[lifetime.lane]]`s, or on a single-line beam the default: lane 1 of each direction on
/// the beam's line.
/// The `[[lifetime.road_change]]` tables: `from_year` (years of traffic from the record's
/// start, `days_per_year` days each; after the previous change) and `road` (an ISO 8608 or
/// Dodds–Robson class name, as the crossing's `road` takes it), converted to instants [s].
fn road_changes(
    file: &SourceFile,
    raw: &toml::Table,
    days_per_year: f64,
) -> Result<Vec<vbi::lifetime::RoadChange>, InputError> {
    let Some(value) = raw.get("road_change") else {
        return Ok(Vec::new());
    };
    let toml::Value::Array(entries) = value else {
        return Err(file.error_at(
            "lifetime.road_change",
            "expected [[lifetime.road_change]] tables with from_year and road",
        ));
    };
    let mut changes: Vec<vbi::lifetime::RoadChange> = Vec::new();
    for (i, entry) in entries.iter().enumerate() {
        let at = format!("lifetime.road_change[{i}]");
        let toml::Value::Table(entry) = entry else {
            return Err(file.error_at(&at, "expected a [[lifetime.road_change]] table"));
        };
        if let Some(unknown) = entry
            .keys()
            .find(|k| !["from_year", "road"].contains(&k.as_str()))
        {
            return Err(file.error_at(
                &format!("{at}.{unknown}"),
                format!("unknown key `{unknown}`; expected from_year and road"),
            ));
        }
        let year = match entry.get("from_year") {
            Some(value) => number_of(file, &format!("{at}.from_year"), value)?,
            None => return Err(file.error_at(&at, "expected from_year: the years of traffic from the record's start at which the road changes")),
        };
        let from_time = year * days_per_year * SECONDS_PER_DAY;
        let previous = changes.last().map_or(0.0, |c| c.from_time);
        if !(year.is_finite() && year > 0.0 && from_time > previous) {
            return Err(file.error_at(
                &format!("{at}.from_year"),
                format!("{year} is not allowed; expected a number of years > 0, after the previous change's"),
            ));
        }
        let roughness = match entry.get("road") {
            Some(toml::Value::String(name)) => vbi::road::RoughnessClass::from_name(name)
                .map(vbi::road::Roughness::Class)
                .ok_or_else(|| {
                    file.error_at(
                        &format!("{at}.road"),
                        format!(
                            "`{name}` is not a road class; expected one of {}",
                            (vbi::road::RoughnessClass::ALL.iter())
                                .map(|c| c.name())
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    )
                })?,
            _ => {
                return Err(file.error_at(
                    &format!("{at}.road"),
                    "expected the road's class from then on, as road = \"poor\"",
                ))
            }
        };
        changes.push(vbi::lifetime::RoadChange {
            from_time,
            roughness,
        });
    }
    Ok(changes)
}

fn lanes(
    file: &SourceFile,
    raw: &toml::Table,
    model: &BridgeModel,
) -> Result<Vec<LifetimeLane>, InputError> {
    let Some(value) = raw.get("lane") else {
        if matches!(model, BridgeModel::ContinuousBeam(_)) {
            return Ok([TravelDirection::Forward, TravelDirection::Backward]
                .map(|direction| LifetimeLane {
                    direction,
                    number: 1,
                    lateral_position: 0.0,
                })
                .to_vec());
        }
        return Err(file.error_at("lifetime.lane", "a deck of several girders needs its lanes: [[lifetime.lane]] tables with direction, lane and lateral_position_m"));
    };
    let toml::Value::Array(entries) = value else {
        return Err(file.error_at(
            "lifetime.lane",
            "expected [[lifetime.lane]] tables, one per lane",
        ));
    };
    let mut lanes: Vec<LifetimeLane> = Vec::new();
    for (i, entry) in entries.iter().enumerate() {
        let at = format!("lifetime.lane[{i}]");
        let toml::Value::Table(entry) = entry else {
            return Err(file.error_at(&at, "expected a [[lifetime.lane]] table"));
        };
        if let Some(unknown) = entry.keys().find(|k| !LANE_KEYS.contains(&k.as_str())) {
            return Err(file.error_at(
                &format!("{at}.{unknown}"),
                format!(
                    "unknown key `{unknown}`; expected one of {}",
                    LANE_KEYS.join(", ")
                ),
            ));
        }
        let integer = |key: &str, allowed: &str| -> Result<i64, InputError> {
            match entry.get(key) {
                Some(toml::Value::Integer(v)) => Ok(*v),
                _ => Err(file.error_at(&format!("{at}.{key}"), format!("expected {allowed}"))),
            }
        };
        let direction = match integer("direction", "1 or 2")? {
            1 => TravelDirection::Forward,
            2 => TravelDirection::Backward,
            other => {
                return Err(file.error_at(
                    &format!("{at}.direction"),
                    format!("{other} is not allowed; expected 1 or 2"),
                ))
            }
        };
        let number = integer("lane", "a whole number from 1")?;
        if !(1..=99).contains(&number) {
            return Err(file.error_at(
                &format!("{at}.lane"),
                format!("{number} is not allowed; expected a whole number from 1 to 99"),
            ));
        }
        let y = match entry.get("lateral_position_m") {
            Some(toml::Value::Float(f)) => *f,
            Some(toml::Value::Integer(v)) => *v as f64,
            None if matches!(model, BridgeModel::ContinuousBeam(_)) => 0.0,
            _ => return Err(file.error_at(&format!("{at}.lateral_position_m"), "expected the lane centreline's lateral position [m] from the deck centreline, left positive")),
        };
        let y = require_in_range(
            file,
            &format!("{at}.lateral_position_m"),
            y,
            -100.0,
            100.0,
            "m",
        )?;
        let lane = LifetimeLane {
            direction,
            number: number as usize,
            lateral_position: y,
        };
        if lanes
            .iter()
            .any(|l| l.direction == lane.direction && l.number == lane.number)
        {
            return Err(file.error_at(
                &at,
                format!(
                    "lane {number} of direction {} is given twice",
                    vbi::lifetime::direction_number(direction)
                ),
            ));
        }
        lanes.push(lane);
    }
    if lanes.is_empty() {
        return Err(file.error_at("lifetime.lane", "expected at least one [[lifetime.lane]]"));
    }
    Ok(lanes)
}

/// One effect's line of [`LifetimeSummary`].
#[derive(Debug, Clone, serde::Serialize)]
pub struct EffectSummary {
    /// The station.
    pub station: String,
    /// The quantity's name.
    pub quantity: &'static str,
    /// Its SI unit.
    pub unit: &'static str,
    /// The largest block maximum in the effect's sense (signed) [unit].
    pub largest_block_maximum: f64,
    /// The block that holds it (from 0).
    pub largest_block: u64,
    /// The mean of the block maxima [unit].
    pub mean_block_maximum: f64,
    /// The Gumbel and GEV fits of the block maxima with their return levels, or None with
    /// [`EffectSummary::fit_error`] saying why not.
    pub fits: Option<EffectFits>,
    /// Why the block maxima could not be fitted (too few blocks, no spread).
    pub fit_error: Option<String>,
    /// The generalised Pareto fit of the largest events with its return levels, or None with
    /// [`EffectSummary::peaks_error`] saying why not.
    pub peaks_over_threshold: Option<PeaksOverThresholdFit>,
    /// Why the largest events could not be fitted (too few events, or none asked).
    pub peaks_error: Option<String>,
    /// With dynamics: the total (dynamic) block maxima, their fits, and the assessment DAF.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub total: Option<TotalSummary>,
}

/// One effect's total (dynamic) effect over the lifetime ([`EffectSummary::total`]).
#[derive(Debug, Clone, serde::Serialize)]
pub struct TotalSummary {
    /// The largest total block maximum in the effect's sense (signed) [unit].
    pub largest_block_maximum: f64,
    /// The block that holds it (from 0).
    pub largest_block: u64,
    /// The mean of the total block maxima [unit].
    pub mean_block_maximum: f64,
    /// The Gumbel and GEV fits of the total block maxima with their return levels.
    pub fits: Option<EffectFits>,
    /// Why the total block maxima could not be fitted.
    pub fit_error: Option<String>,
    /// The assessment DAF of each return period: the characteristic total effect over the
    /// characteristic static effect, each the return level of its own block maxima's fit.
    pub assessment_daf: Vec<AssessmentDaf>,
    /// The design codes' DAFs 1 + IM at the effect's station and quantity, beside it (the
    /// fatigue factors left out: they are no peak DAF).
    pub design_codes: Vec<CodeDaf>,
    /// Whether the screening may have missed a block's total ([`ScreeningCheck`]); None with
    /// r = 0 (no event left out).
    pub screening_check: Option<ScreeningCheck>,
}

/// The screening check said in a sentence, for the command's table and the report.
pub fn screening_sentence(check: &ScreeningCheck) -> String {
    let band = format!(
        "{} to {} of the block's static maximum",
        vbi::units::shown(check.band[0]),
        vbi::units::shown((check.band[1] * 1e12).round() / 1e12)
    );
    match check.edge_daf {
        None => format!("no integrated event lies just above the threshold ({band}) to check it by"),
        Some(daf) if check.blocks_at_risk == 0 => format!(
            "none of the {} blocks at risk (the largest DAF just above the threshold, {band}, is {daf:.3}: an event just below it with that DAF would not exceed any block's total)",
            check.blocks
        ),
        Some(daf) => format!(
            "{} of {} blocks at risk: an event just below the threshold with the largest DAF just above it ({daf:.3}, {band}) would exceed their total; a lower screening_ratio integrates more events",
            check.blocks_at_risk, check.blocks
        ),
    }
}

/// The screening's check of one effect ([`vbi::lifetime::screening_risk`]): the largest DAF
/// of the integrated events just above the threshold, and the blocks where an event just below
/// it with that DAF would exceed the block's total maximum.
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct ScreeningCheck {
    /// The band of static levels, as shares of the block's static maximum: [low, high).
    pub band: [f64; 2],
    /// The largest DAF of the integrated events in the band (None without one).
    pub edge_daf: Option<f64>,
    /// Blocks at risk: where r × the static maximum × that DAF exceeds the total maximum.
    pub blocks_at_risk: u64,
    /// Blocks with a static maximum, checked.
    pub blocks: u64,
}

/// One design code's DAF beside the assessment DAF.
#[derive(Debug, Clone, serde::Serialize)]
pub struct CodeDaf {
    /// The code's name.
    pub code: &'static str,
    /// Which case of the code.
    pub provision: String,
    /// The clause.
    pub clause: String,
    /// The input the factor follows from.
    pub basis: String,
    /// The code's design DAF, 1 + IM [-].
    pub daf: f64,
}

/// The assessment DAF of one return period (Caprani et al.; OBrien et al. 2010): the T-year
/// total effect over the T-year static effect, by each law fitted to both.
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct AssessmentDaf {
    /// The return period [years].
    pub period_years: f64,
    /// By the GEV levels, where both fits have one.
    pub gev: Option<f64>,
    /// By the Gumbel levels, where both fits have one.
    pub gumbel: Option<f64>,
}

/// What a lifetime analysis ran and found: `lifetime.json` of `vbi lifetime`, and the attrs of
/// Python's `vbi.lifetime` frame (one summary for both).
#[derive(Debug, Clone, serde::Serialize)]
pub struct LifetimeSummary {
    /// The crate's version.
    pub vbi_version: &'static str,
    /// The analysis's name.
    pub name: String,
    /// How the bridge was named.
    pub bridge: String,
    /// The traffic file's path.
    pub traffic_file: String,
    /// Its format's name.
    pub traffic_format: &'static str,
    /// SHA-256 of the lifetime file and the files it names.
    pub input_hash: String,
    /// Whether dynamics were run on the events that can govern.
    pub dynamics: bool,
    /// With dynamics: the screening ratio, and the events integrated and refused.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dynamic_events: Option<DynamicEvents>,
    /// Block length [s].
    pub block_seconds: f64,
    /// Influence-line tabulation points per element.
    pub points_per_element: usize,
    /// Trucks read.
    pub trucks: usize,
    /// Events.
    pub events: usize,
    /// Events of two trucks or more.
    pub multiple_presence_events: usize,
    /// Blocks.
    pub blocks: u64,
    /// The record's length, from the first truck's arrival to the last one's departure [days]:
    /// the observation period of the peaks over threshold.
    pub record_days: f64,
    /// Return periods of the fits' levels [years].
    pub return_periods_years: Vec<f64>,
    /// Days of traffic in a year.
    pub days_per_year: f64,
    /// Bootstrap resamples of the levels' intervals.
    pub bootstrap_resamples: usize,
    /// Their seed.
    pub seed: u64,
    /// Exceedances of the peaks-over-threshold fits.
    pub peaks_over_threshold: usize,
    /// Per station and quantity.
    pub effects: Vec<EffectSummary>,
}

/// How many events a lifetime with dynamics integrated ([`LifetimeSummary::dynamic_events`]).
#[derive(Debug, Clone, serde::Serialize)]
pub struct DynamicEvents {
    /// The screening ratio r.
    pub screening_ratio: f64,
    /// The road of the crossings (its class or file).
    pub road: String,
    /// Events integrated.
    pub integrated: u64,
    /// Events screened in whose crossing was refused.
    pub refused: u64,
    /// The first refusal.
    pub first_refusal: Option<String>,
}

/// The summary of a finished run of `lifetime`'s `analysis`: its counts, and each effect's block
/// maxima, their fits, and the fit of its largest events (`peaks`).
pub fn summary(
    lifetime: &LifetimeFile,
    analysis: &vbi::lifetime::StaticLifetime,
    counts: vbi::lifetime::LifetimeCounts,
    tally: &vbi::lifetime::BlockMaximaTally,
    peaks: &EventPeaks,
    totals: Option<&TotalBlockMaxima>,
) -> LifetimeSummary {
    let record_days = counts.record_days();
    let first_block = counts.first_block(lifetime.block_seconds);
    LifetimeSummary {
        vbi_version: env!("CARGO_PKG_VERSION"),
        name: lifetime.name.clone(),
        bridge: lifetime.bridge_label.clone(),
        traffic_file: lifetime.traffic.label(),
        traffic_format: lifetime.traffic.format_name(),
        input_hash: lifetime.input_hash.clone(),
        dynamics: totals.is_some(),
        dynamic_events: lifetime
            .dynamics
            .as_ref()
            .zip(totals)
            .map(|(settings, totals)| DynamicEvents {
                screening_ratio: settings.screening_ratio,
                road: road_with_changes(settings, lifetime.return_levels.days_per_year),
                integrated: totals.integrated,
                refused: totals.refused,
                first_refusal: totals.first_refusal.clone(),
            }),
        block_seconds: lifetime.block_seconds,
        points_per_element: lifetime.points_per_element,
        trucks: counts.trucks,
        events: counts.events,
        multiple_presence_events: counts.multiple_presence_events,
        blocks: counts.blocks,
        record_days,
        return_periods_years: lifetime.return_levels.periods_years.clone(),
        days_per_year: lifetime.return_levels.days_per_year,
        bootstrap_resamples: lifetime.return_levels.resamples,
        seed: lifetime.return_levels.seed,
        peaks_over_threshold: lifetime.return_levels.exceedances,
        effects: analysis
            .effects
            .iter()
            .enumerate()
            .map(|(e, effect)| {
                let fitted = tally.fit(analysis, e, first_block, &lifetime.return_levels);
                let (fits, fit_error) = match fitted {
                    Ok(fits) => (Some(fits), None),
                    Err(error) => (None, Some(error.to_string())),
                };
                let fitted = fit_peaks(
                    &peaks.values(e),
                    effect.sense,
                    record_days,
                    &lifetime.return_levels,
                );
                let (peaks_over_threshold, peaks_error) = match fitted {
                    Ok(fit) => (Some(fit), None),
                    Err(error) => (None, Some(error.to_string())),
                };
                EffectSummary {
                    station: effect.station.clone(),
                    quantity: effect.quantity.name(),
                    unit: effect.quantity.unit(),
                    largest_block_maximum: tally.largest[e].0,
                    largest_block: tally.largest[e].1,
                    mean_block_maximum: tally.mean(e, counts.blocks),
                    fit_error,
                    total: totals.map(|totals| {
                        let fixed = tally.values[e].as_slice();
                        total_summary(
                            lifetime,
                            (analysis, e, fixed),
                            first_block,
                            totals,
                            fits.as_ref(),
                        )
                    }),
                    fits,
                    peaks_over_threshold,
                    peaks_error,
                }
            })
            .collect(),
    }
}

/// The crossings' road for the summary, with its changes: `good; from year 30 medium`.
fn road_with_changes(settings: &DynamicSettings, days_per_year: f64) -> String {
    let mut name = road_name(&settings.template.road);
    for change in &settings.road_changes {
        let year = change.from_time / (days_per_year * SECONDS_PER_DAY);
        let mut road = settings.template.road.clone();
        road.roughness = change.roughness;
        name.push_str(&format!(
            "; from year {} {}",
            vbi::units::shown((year * 1e9).round() / 1e9),
            road_name(&road)
        ));
    }
    name
}

/// A road's name for the summary: its class, a custom roughness, or a measured profile.
fn road_name(road: &RoadSpec) -> String {
    match (&road.profile, road.roughness) {
        (Some(_), _) => "a measured profile".into(),
        (None, vbi::road::Roughness::Class(class)) => class.name().into(),
        (None, vbi::road::Roughness::Custom { psd_at_reference }) => {
            format!("G_d(n0) = {psd_at_reference:e} m^3")
        }
    }
}

/// Effect e's total block maxima summarised and fitted, with the assessment DAF against the
/// static fits `static_fits`.
fn total_summary(
    lifetime: &LifetimeFile,
    (analysis, e, static_values): (&StaticLifetime, usize, &[f64]),
    first_block: u64,
    totals: &TotalBlockMaxima,
    static_fits: Option<&EffectFits>,
) -> TotalSummary {
    let sense = analysis.effects[e].sense;
    let values = &totals.values[e];
    let (mut largest, mut largest_block) = (0.0, 0);
    for (block, &value) in values.iter().enumerate() {
        if sense * value > sense * largest {
            (largest, largest_block) = (value, block as u64);
        }
    }
    let fitted = vbi::lifetime::fit_block_maxima(
        &values[(first_block as usize).min(values.len())..],
        sense,
        lifetime.block_seconds / SECONDS_PER_DAY,
        &lifetime.return_levels,
    );
    let (fits, fit_error) = match fitted {
        Ok(fits) => (Some(fits), None),
        Err(error) => (None, Some(error.to_string())),
    };
    let level = |fits: Option<&EffectFits>, model, period: f64| {
        fits?
            .fits
            .iter()
            .find(|f| f.model == model)?
            .return_levels
            .iter()
            .find(|l| l.period_years == period)
            .map(|l| l.value)
    };
    let ratio = |model, period| {
        let (total, fixed) = (
            level(fits.as_ref(), model, period)?,
            level(static_fits, model, period)?,
        );
        (fixed != 0.0).then(|| total / fixed)
    };
    use vbi::statistics::extreme_value::ExtremeValueModel;
    let assessment_daf = (lifetime.return_levels.periods_years.iter())
        .map(|&period| AssessmentDaf {
            period_years: period,
            gev: ratio(ExtremeValueModel::Gev, period),
            gumbel: ratio(ExtremeValueModel::Gumbel, period),
        })
        .collect();
    let design_codes = (totals.design_codes[e].iter())
        .filter(|factor| !factor.is_fatigue_factor())
        .map(|factor| CodeDaf {
            code: factor.code.name(),
            provision: factor.provision.clone(),
            clause: factor.clause.clone(),
            basis: factor.basis.clone(),
            daf: factor.daf(),
        })
        .collect();
    let ratio = lifetime
        .dynamics
        .as_ref()
        .map_or(0.0, |d| d.screening_ratio);
    let screening_check = (ratio > 0.0).then(|| {
        let edge_daf = totals.edge_daf[e];
        let (blocks_at_risk, blocks) = vbi::lifetime::screening_risk(
            ratio,
            edge_daf,
            (static_values, values),
            first_block as usize,
        );
        ScreeningCheck {
            band: [ratio, ratio + vbi::lifetime::SCREENING_BAND],
            edge_daf,
            blocks_at_risk,
            blocks,
        }
    });
    TotalSummary {
        screening_check,
        largest_block_maximum: largest,
        largest_block,
        mean_block_maximum: values.iter().sum::<f64>() / values.len().max(1) as f64,
        fits,
        fit_error,
        assessment_daf,
        design_codes,
    }
}

/// The static analysis of a loaded file, or the bridge's failure located at `lifetime.bridge`.
pub fn prepare(
    file: &SourceFile,
    lifetime: &LifetimeFile,
) -> Result<vbi::lifetime::StaticLifetime, InputError> {
    let mut analysis = vbi::lifetime::prepare_static(
        &lifetime.bridge,
        lifetime.lanes.clone(),
        lifetime.block_seconds,
        lifetime.points_per_element,
        &lifetime.quantities,
    )
    .map_err(|e| file.error_at("lifetime.bridge", format!("{e}")))?;
    // Simulated traffic has a known end: its days, the blocks they make, and no block of the
    // last trucks' tail past midnight.
    if let TrafficInput::Generator(generator) = &lifetime.traffic {
        analysis.record_end = Some(generator.days as f64 * SECONDS_PER_DAY);
    }
    Ok(analysis)
}

/// Streams the trucks of `reader` through `analysis`, `on_block` receiving each block's rows
/// ([`static_maxima_and_peaks`]), and tallies them, keeping each effect's `exceedances` + 1
/// largest events: the one run of `vbi lifetime`, Python's `vbi.lifetime` and `vbi check`. A
/// bad line of the traffic file, or a truck the analysis refuses (a lane it does not have, out
/// of order in time), is an error located at its line (the library refuses the truck it has
/// just been handed, the last one read). `on_progress` receives, as each block ends, the
/// progress so far ([`TrafficSource::progress`]: kB of the file read, or hours generated).
pub fn run(
    analysis: &StaticLifetime,
    mut reader: TrafficSource,
    exceedances: usize,
    mut on_block: impl FnMut(&[BlockMaximum]),
    mut on_progress: impl FnMut(u64),
) -> Result<(LifetimeCounts, BlockMaximaTally, EventPeaks), InputError> {
    let path = reader.path().to_string();
    let (line, bytes, bad_line) = (Cell::new(0), Cell::new(0), RefCell::new(None));
    let trucks = trucks_of(&mut reader, (&line, &bytes, &bad_line));
    let mut tally = BlockMaximaTally::new(analysis);
    let mut peaks = EventPeaks::new(analysis, exceedances);
    let result =
        static_maxima_and_peaks(analysis, trucks, &mut peaks, |rows: &[BlockMaximum]| {
            tally.add(analysis, rows);
            on_block(rows);
            on_progress(bytes.get());
        });
    if let Some(error) = bad_line.into_inner() {
        return Err(error);
    }
    let counts = result.map_err(|error| truck_error(&path, line.get(), error))?;
    Ok((counts, tally, peaks))
}

/// The trucks of `reader` as an iterator that stops at the first bad line (kept in `bad`),
/// with the line number and the bytes read so far in `line` and `bytes`.
fn trucks_of<'a>(
    reader: &'a mut TrafficSource,
    (line, bytes, bad): (
        &'a Cell<usize>,
        &'a Cell<u64>,
        &'a RefCell<Option<InputError>>,
    ),
) -> impl Iterator<Item = vbi::traffic::RecordedTruck> + 'a {
    std::iter::from_fn(move || {
        let next = reader.next_truck()?;
        line.set(reader.line_number());
        bytes.set(reader.progress().0);
        next.map_err(|error| *bad.borrow_mut() = Some(error)).ok()
    })
}

/// A truck the library refused, located at the line just read.
fn truck_error(path: &str, line: usize, error: vbi::lifetime::LifetimeError) -> InputError {
    InputError {
        file: path.to_string(),
        location: Some((line, 1)),
        field: Some("truck".into()),
        message: error.to_string(),
    }
}

/// What a run with dynamics gives: the static pass's counts, block maxima and largest events,
/// and the totals.
pub type DynamicRun = (
    LifetimeCounts,
    BlockMaximaTally,
    EventPeaks,
    TotalBlockMaxima,
);

/// [`run`] with dynamics, in one pass over the traffic
/// ([`vbi::lifetime::static_and_total_block_maxima`]): the events that can govern integrated on
/// the bridge prepared for crossings (its modes; a failure is located at `lifetime.bridge`).
/// `on_block` receives each block's static rows, `on_event` each integrated event's totals with
/// its static extremes, `on_progress` the progress so far after each of either.
pub fn run_with_dynamics(
    file: &SourceFile,
    (analysis, settings): (&StaticLifetime, &DynamicSettings),
    (mut reader, exceedances): (TrafficSource, usize),
    (mut on_block, mut on_event): (
        impl FnMut(&[BlockMaximum]),
        impl FnMut(&EventTotals, &[EventExtreme]),
    ),
    on_progress: impl FnMut(u64),
) -> Result<DynamicRun, InputError> {
    let bridge = vbi::crossing::prepare_scenario_bridge(&settings.template)
        .map_err(|e| file.error_at("lifetime.bridge", vbi::crossing::error_chain(&e)))?;
    let path = reader.path().to_string();
    let (line, bytes, bad_line) = (Cell::new(0), Cell::new(0), RefCell::new(None));
    let trucks = trucks_of(&mut reader, (&line, &bytes, &bad_line));
    let mut tally = BlockMaximaTally::new(analysis);
    let mut peaks = EventPeaks::new(analysis, exceedances);
    let on_progress = RefCell::new(on_progress);
    let result = static_and_total_block_maxima(
        analysis,
        (&bridge, settings),
        trucks,
        &mut peaks,
        (
            |rows: &[BlockMaximum]| {
                tally.add(analysis, rows);
                on_block(rows);
                (on_progress.borrow_mut())(bytes.get());
            },
            |totals: &EventTotals, extremes: &[EventExtreme]| {
                on_event(totals, extremes);
                (on_progress.borrow_mut())(bytes.get());
            },
        ),
    );
    if let Some(error) = bad_line.into_inner() {
        return Err(error);
    }
    let (counts, totals) = result.map_err(|error| truck_error(&path, line.get(), error))?;
    Ok((counts, tally, peaks, totals))
}

/// Opens `lifetime`'s traffic: its file, or the generator (an error located at the key that
/// names it).
pub fn open_traffic(
    file: &SourceFile,
    lifetime: &LifetimeFile,
) -> Result<TrafficSource, InputError> {
    match &lifetime.traffic {
        TrafficInput::File { path, format } => TrafficFileReader::open(path, *format)
            .map(TrafficSource::File)
            .map_err(|e| e.at_naming_key(file, "lifetime.traffic_file")),
        TrafficInput::Generator(generator) => crate::lifetime_generator::open(file, generator),
    }
}

/// The `traffic_file` and `traffic_format` keys.
fn traffic_file<'a>(
    file: &SourceFile,
    string: &impl Fn(&str) -> Result<Option<&'a str>, InputError>,
) -> Result<TrafficInput, InputError> {
    let traffic_file = string("traffic_file")?.ok_or_else(|| {
        file.error_at(
            "lifetime.traffic_file",
            "expected the traffic file (traffic_file = \"traffic.txt\"), or a [lifetime.generator]",
        )
    })?;
    let format_name = string("traffic_format")?.unwrap_or("castor");
    let format = TrafficFormat::from_name(format_name).ok_or_else(|| {
        file.error_at(
            "lifetime.traffic_format",
            format!(
                "`{format_name}` is not a traffic format; expected one of {}",
                TrafficFormat::NAMES.join(", ")
            ),
        )
    })?;
    Ok(TrafficInput::File {
        path: relative(file, traffic_file),
        format,
    })
}

/// What `vbi check` decides of a lifetime file, as `vbi lifetime` decides it: the file, the
/// bridge's static model (and with dynamics its modal analysis's plan,
/// [`vbi::crossing::check_bridge`]), and every line of the traffic file through [`run`] (its
/// fields, its lane among the analysis's lanes, its order in time), with no effect tracked.
pub fn validate(file: &SourceFile) -> Result<(), InputError> {
    let lifetime = load(file)?;
    if let Some(settings) = &lifetime.dynamics {
        vbi::crossing::check_bridge(&settings.template.bridge)
            .map_err(|e| file.error_at("lifetime.bridge", vbi::crossing::error_chain(&e)))?;
    }
    let mut analysis = prepare(file, &lifetime)?;
    crate::fatigue_details::lifetime_details(file, &lifetime.fatigue_details, &analysis)?;
    analysis.effects.clear();
    run(&analysis, open_traffic(file, &lifetime)?, 0, |_| {}, |_| {})?;
    Ok(())
}

/// The static fatigue of the lifetime's details: a second pass over the traffic
/// ([`vbi::lifetime::fatigue::static_lifetime_fatigue`]), the record counted as one history;
/// a bad line or a refused truck is located as in [`run`].
pub fn run_fatigue(
    analysis: &StaticLifetime,
    details: &[vbi::lifetime::fatigue::LifetimeDetail],
    mut reader: TrafficSource,
) -> Result<vbi::lifetime::fatigue::LifetimeFatigue, InputError> {
    let path = reader.path().to_string();
    let (line, bytes, bad_line) = (Cell::new(0), Cell::new(0), RefCell::new(None));
    let trucks = trucks_of(&mut reader, (&line, &bytes, &bad_line));
    let result = vbi::lifetime::fatigue::static_lifetime_fatigue(analysis, details, trucks);
    if let Some(error) = bad_line.into_inner() {
        return Err(error);
    }
    result.map_err(|error| truck_error(&path, line.get(), error))
}

/// A shard's `shard.json` (`vbi lifetime --shard I/N`, Python's `vbi.lifetime(..., shard=)`):
/// what the merge needs of it, with the lifetime file it ran (its name and input hash, which
/// the merge checks).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ShardFile {
    /// The crate's version that ran it.
    pub vbi_version: String,
    /// The analysis's name.
    pub name: String,
    /// SHA-256 of the lifetime file and the files it names.
    pub input_hash: String,
    /// The shard's blocks, counts, largest events and totals.
    pub part: vbi::lifetime::LifetimeShard,
}

impl ShardFile {
    /// The shard's file after its run.
    pub fn new(lifetime: &LifetimeFile, part: vbi::lifetime::LifetimeShard) -> ShardFile {
        ShardFile {
            vbi_version: env!("CARGO_PKG_VERSION").to_string(),
            name: lifetime.name.clone(),
            input_hash: lifetime.input_hash.clone(),
            part,
        }
    }
}

/// Makes `analysis` shard I of N of its record: the blocks of [`BlockRange::of_shard`] of the
/// record's block count, known for simulated traffic (its days), estimated for a traffic
/// file from its last truck's arrival (the file is read once to find it). The estimate only
/// balances the shards: the merge is exact whatever it is (shards past the record's end hand
/// on no block).
///
/// [`BlockRange::of_shard`]: vbi::lifetime::BlockRange::of_shard
pub fn make_shard(
    file: &SourceFile,
    lifetime: &LifetimeFile,
    analysis: &mut StaticLifetime,
    shard: vbi::study::Shard,
) -> Result<(), InputError> {
    let blocks = match analysis.last_block() {
        Some(last) => last + 1,
        None => {
            let mut reader = open_traffic(file, lifetime)?;
            let mut last_arrival = None;
            while let Some(truck) = reader.next_truck() {
                last_arrival = Some(truck?.arrival_time);
            }
            last_arrival.map_or(0, |time| analysis.block_of(time) + 1)
        }
    };
    analysis.blocks = vbi::lifetime::BlockRange::of_shard(shard, blocks);
    Ok(())
}

/// The shards of `lifetime`'s run merged ([`vbi::lifetime::merge_shards`]), after checking
/// that each ran this lifetime file (its input hash): `analysis` is the whole run's.
pub fn merge_shards(
    lifetime: &LifetimeFile,
    analysis: &StaticLifetime,
    shards: &[ShardFile],
) -> Result<vbi::lifetime::MergedShards, String> {
    for shard in shards {
        if shard.input_hash != lifetime.input_hash {
            return Err(format!(
                "shard {} ran another lifetime file, or the file or its traffic changed since (its input hash {} is not {})",
                shard.part.shard, shard.input_hash, lifetime.input_hash
            ));
        }
    }
    let parts: Vec<vbi::lifetime::LifetimeShard> = shards.iter().map(|s| s.part.clone()).collect();
    vbi::lifetime::merge_shards(analysis, lifetime.return_levels.exceedances, &parts)
        .map_err(|e| e.to_string())
}
