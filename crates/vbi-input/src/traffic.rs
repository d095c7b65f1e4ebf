//! The further vehicles of a crossing event, `[[traffic]]` beside `[scenario]`, and the speed
//! profiles of `[scenario]` and of each `[[traffic]]` entry (docs/input-format.md, section
//! "Several vehicles and variable speed").
//!
//! ```toml
//! [[traffic]]
//! vehicle = "three-axle-truck-36t"  # a preset or a [vehicle] file, relative to this file
//! direction = "backward"         # the opposite lane
//! lateral_position_m = -1.8
//! speed_kmh = 60
//! entry_time_s = 2.5             # its front axle reaches its deck entry at t = 2.5 s
//!
//! [[traffic]]
//! vehicle = "quarter-car"
//! gap_m = 15                     # 15 m behind the last tyre of the vehicle before it
//! speed_profile = [ { travel_m = 0, speed_kmh = 60 }, { travel_m = 40, speed_kmh = 30 } ]
//! ```
//!
//! The motion keys (`speed_kmh`, `lateral_position_m`, `direction`, `acceleration_ms2`) are the
//! scenario's keys of the one key table, read by [`Scenario::set`], so they accept and refuse
//! exactly what `[scenario]` does.

use vbi::crossing::keys::{seed_from_value, SEED_ALLOWED};
use vbi::crossing::{
    error_chain, input_entry, vehicle_runs, Entry, Motion, PipelineError, Scenario, TrafficVehicle,
};
use vbi::solver::SolverError;
use vbi::solver::SpeedKnot;
use vbi::traffic::stream::{MixEntry, TrafficStream};
use vbi::units::KMH;

use crate::resolve::Resolver;
use crate::source::{require_in_range, InputError, SourceFile};
use crate::values::{key_error, key_range, key_value};

/// The keys of the one key table that a `[[traffic]]` entry may give.
const MOTION_KEYS: [&str; 4] = [
    "speed_kmh",
    "lateral_position_m",
    "direction",
    "acceleration_ms2",
];

/// The keys of a `[[traffic]]` entry besides [`MOTION_KEYS`].
const TRAFFIC_KEYS: [&str; 5] = ["vehicle", "label", "entry_time_s", "gap_m", "speed_profile"];

/// Reads `[[traffic]]` (if any) into `scenario.traffic`, after `[scenario]` has been read (an
/// entry's speed defaults to the scenario's).
pub fn load(
    file: &SourceFile,
    table: &toml::Table,
    resolver: &mut Resolver,
    scenario: &mut Scenario,
) -> Result<(), InputError> {
    let Some(value) = table.get("traffic") else {
        return Ok(());
    };
    let toml::Value::Array(entries) = value else {
        return Err(file.error_at(
            "traffic",
            "expected [[traffic]] tables, one per further vehicle",
        ));
    };
    for (i, entry) in entries.iter().enumerate() {
        let at = format!("traffic[{i}]");
        let toml::Value::Table(entry) = entry else {
            return Err(file.error_at(&at, "expected a [[traffic]] table"));
        };
        let vehicle = load_entry(file, &at, entry, resolver, scenario)?;
        scenario.traffic.push(vehicle);
    }
    Ok(())
}

fn load_entry(
    file: &SourceFile,
    at: &str,
    entry: &toml::Table,
    resolver: &mut Resolver,
    scenario: &Scenario,
) -> Result<TrafficVehicle, InputError> {
    let known = |k: &str| TRAFFIC_KEYS.contains(&k) || MOTION_KEYS.contains(&k);
    if let Some(unknown) = entry.keys().find(|k| !known(k)) {
        return Err(file.error_at(
            &format!("{at}.{unknown}"),
            format!(
                "unknown key `{unknown}` in [[traffic]]; expected one of {}, {}",
                TRAFFIC_KEYS.join(", "),
                MOTION_KEYS.join(", ")
            ),
        ));
    }
    let name = match entry.get("vehicle") {
        Some(toml::Value::String(name)) => name,
        _ => {
            return Err(file.error_at(
                &format!("{at}.vehicle"),
                "each [[traffic]] entry needs `vehicle`: a preset of `vbi vehicle list`, or a \
                 [vehicle] file",
            ))
        }
    };
    let vehicle = resolver.vehicle(file, &format!("{at}.vehicle"), name)?;
    let motion = motion(file, at, entry, &scenario.motion)?;
    let label = match entry.get("label") {
        Some(toml::Value::String(label)) => label.clone(),
        Some(_) => return Err(file.error_at(&format!("{at}.label"), "expected a text")),
        None => name.clone(),
    };
    Ok(TrafficVehicle {
        label,
        vehicle,
        motion,
        entry: entry_of(file, at, entry)?,
    })
}

/// The motion of an entry: its keys set on a scenario whose motion is the base's speed on the
/// centreline, forward, at constant speed.
fn motion(
    file: &SourceFile,
    at: &str,
    entry: &toml::Table,
    base: &Motion,
) -> Result<Motion, InputError> {
    let mut probe = Scenario {
        motion: Motion::constant(base.speed, 0.0),
        ..Scenario::default()
    };
    for name in MOTION_KEYS {
        if let Some(value) = entry.get(name) {
            let value = key_value(file, &format!("{at}.{name}"), value)?;
            probe
                .set(name, &value)
                .map_err(|e| key_error(file, at, e))?;
        }
    }
    probe.motion.speed_profile = speed_profile(file, at, entry)?;
    Ok(probe.motion)
}

/// Exactly one of `entry_time_s` (≥ 0) and `gap_m` (≥ 0).
fn entry_of(file: &SourceFile, at: &str, entry: &toml::Table) -> Result<Entry, InputError> {
    let number = |key: &str| -> Result<Option<f64>, InputError> {
        let path = format!("{at}.{key}");
        match entry.get(key) {
            None => Ok(None),
            Some(toml::Value::Integer(i)) => Ok(Some(*i as f64)),
            Some(toml::Value::Float(x)) => Ok(Some(*x)),
            Some(other) => Err(file.error_at(&path, format!("{other} is not a number"))),
        }
        .and_then(|value| match value {
            Some(x) => {
                let unit = if key == "gap_m" { "m" } else { "s" };
                require_in_range(file, &path, x, 0.0, 1.0e4, unit).map(Some)
            }
            None => Ok(None),
        })
    };
    match (number("entry_time_s")?, number("gap_m")?) {
        (Some(time), None) => Ok(Entry::Time(time)),
        (None, Some(gap)) => Ok(Entry::Gap(gap)),
        (Some(_), Some(_)) => Err(file.error_at(
            &format!("{at}.gap_m"),
            "give `entry_time_s` or `gap_m`, not both",
        )),
        (None, None) => Err(file.error_at(
            at,
            "each [[traffic]] entry needs `entry_time_s` (when its front axle reaches the deck \
             [s]) or `gap_m` (its clear distance behind the vehicle before it [m])",
        )),
    }
}

/// `speed_profile = [{ travel_m, speed_kmh }, ...]` under `table_path` (`scenario` or
/// `traffic[i]`): knots at strictly increasing travel coordinates [m] past the deck entry with
/// speeds in the range of the key table's `speed_kmh` (0.1 to 500 km/h); empty when absent.
pub fn speed_profile(
    file: &SourceFile,
    table_path: &str,
    table: &toml::Table,
) -> Result<Vec<SpeedKnot>, InputError> {
    let at = format!("{table_path}.speed_profile");
    let Some(value) = table.get("speed_profile") else {
        return Ok(Vec::new());
    };
    let expected = "a list of at least two { travel_m = …, speed_kmh = … } tables, travel_m \
                    increasing";
    let toml::Value::Array(items) = value else {
        return Err(file.error_at(&at, format!("expected {expected}")));
    };
    if items.len() < 2 {
        return Err(file.error_at(&at, format!("expected {expected}")));
    }
    // A knot's speed is allowed what the scenario's `speed_kmh` is, by the one key table.
    let (lowest_speed, highest_speed) = key_range("speed_kmh");
    let mut knots: Vec<SpeedKnot> = Vec::with_capacity(items.len());
    for (i, item) in items.iter().enumerate() {
        let path = format!("{at}[{i}]");
        // A misspelt key (`speed_kph`) is refused, not dropped.
        if let Some(unknown) = item.as_table().and_then(|knot| {
            knot.keys()
                .find(|k| !matches!(k.as_str(), "travel_m" | "speed_kmh"))
        }) {
            return Err(file.error_at(
                &format!("{path}.{unknown}"),
                format!("unknown key `{unknown}` in a speed-profile knot; expected {expected}"),
            ));
        }
        let field = |key: &str, low: f64, high: f64, unit: &str| -> Result<f64, InputError> {
            let value = match item.get(key) {
                Some(toml::Value::Integer(v)) => *v as f64,
                Some(toml::Value::Float(v)) => *v,
                _ => return Err(file.error_at(&path, format!("expected {expected}"))),
            };
            require_in_range(file, &format!("{path}.{key}"), value, low, high, unit)
        };
        let knot = SpeedKnot {
            travel: field("travel_m", -1.0e5, 1.0e5, "m")?,
            speed: field("speed_kmh", lowest_speed, highest_speed, "km/h")? * KMH,
        };
        if knots.last().is_some_and(|last| knot.travel <= last.travel) {
            return Err(file.error_at(
                &format!("{path}.travel_m"),
                format!("travel_m must increase from knot to knot; expected {expected}"),
            ));
        }
        knots.push(knot);
    }
    Ok(knots)
}

/// The vehicles of the scenario's event placed as the run will place them
/// ([`vbi::crossing::vehicle_runs`]: speeds that stay positive, gaps with a vehicle
/// ahead, wheels on the deck, no overlap at t = 0, no catching up), before any modal analysis;
/// a refusal is located at the `[[traffic]]` entry (or `[scenario]`) of the vehicle at fault.
pub fn check(file: &SourceFile, scenario: &Scenario) -> Result<(), InputError> {
    let Err(error) = vehicle_runs(scenario) else {
        return Ok(());
    };
    let vehicle = match &error {
        PipelineError::Traffic { vehicle, .. } => *vehicle,
        PipelineError::Crossing(SolverError::VehiclesOverlap(overlap)) => overlap.second,
        _ => 1,
    };
    let at = input_entry(scenario, vehicle.saturating_sub(1));
    Err(file.error_at(&at, error_chain(&error)))
}

/// Every key of `[traffic_stream]`.
const STREAM_KEYS: [&str; 12] = [
    "vehicle_count",
    "vehicles",
    "weights",
    "mean_headway_s",
    "minimum_headway_s",
    "first_entry_s",
    "speed_kmh",
    "speed_sd_kmh",
    "load_scale_sd",
    "lateral_position_m",
    "direction",
    "seed",
];

/// Reads `[traffic_stream]` (if any) into `scenario.traffic_stream`: a seeded random stream of
/// vehicles in one lane ([`vbi::crossing::stream`]).
///
/// ```toml
/// [traffic_stream]
/// vehicle_count = 10
/// vehicles = ["tractor-semitrailer-5axle", "three-axle-truck-36t"]
/// weights = [0.7, 0.3]          # default: equal
/// mean_headway_s = 3.0
/// minimum_headway_s = 1.0       # default 1
/// speed_kmh = 80                # default: the scenario's
/// speed_sd_kmh = 5              # default 0
/// load_scale_sd = 0.1           # default 0
/// ```
pub fn load_stream(
    file: &SourceFile,
    table: &toml::Table,
    resolver: &mut Resolver,
    scenario: &mut Scenario,
) -> Result<(), InputError> {
    let Some(value) = table.get("traffic_stream") else {
        return Ok(());
    };
    let at = "traffic_stream";
    let toml::Value::Table(raw) = value else {
        return Err(file.error_at(at, "expected a [traffic_stream] table"));
    };
    if let Some(unknown) = raw.keys().find(|k| !STREAM_KEYS.contains(&k.as_str())) {
        return Err(file.error_at(
            &format!("{at}.{unknown}"),
            format!(
                "unknown key `{unknown}` in [traffic_stream]; expected one of {}",
                STREAM_KEYS.join(", ")
            ),
        ));
    }
    let number = |key: &str, low: f64, high: f64, unit: &str, default: Option<f64>| {
        let path = format!("{at}.{key}");
        match (raw.get(key), default) {
            (Some(toml::Value::Integer(i)), _) => {
                require_in_range(file, &path, *i as f64, low, high, unit)
            }
            (Some(toml::Value::Float(x)), _) => require_in_range(file, &path, *x, low, high, unit),
            (Some(other), _) => Err(file.error_at(&path, format!("{other} is not a number"))),
            (None, Some(default)) => Ok(default),
            (None, None) => Err(file.error_at(at, format!("[traffic_stream] needs `{key}`"))),
        }
    };
    let count = number("vehicle_count", 1.0, 200.0, "vehicles", None)?;
    if count.fract() != 0.0 {
        return Err(file.error_at(
            &format!("{at}.vehicle_count"),
            "expected a whole number of vehicles from 1 to 200",
        ));
    }
    let names = match raw.get("vehicles") {
        Some(toml::Value::Array(items)) if !items.is_empty() => items,
        _ => {
            return Err(file.error_at(
                &format!("{at}.vehicles"),
                "expected a non-empty list of vehicle names (presets or [vehicle] files)",
            ))
        }
    };
    let weights = stream_weights(file, at, raw, names.len())?;
    let mut mix = Vec::with_capacity(names.len());
    for (i, (name, weight)) in names.iter().zip(weights).enumerate() {
        let path = format!("{at}.vehicles[{i}]");
        let toml::Value::String(name) = name else {
            return Err(file.error_at(&path, "expected a vehicle name"));
        };
        mix.push(MixEntry {
            label: name.clone(),
            vehicle: resolver.vehicle(file, &path, name)?,
            weight,
        });
    }
    let lane = motion(file, at, raw, &scenario.motion)?;
    let seed = match raw.get("seed") {
        None => None,
        Some(value) => {
            let value = key_value(file, &format!("{at}.seed"), value)?;
            Some(seed_from_value(&value).ok_or_else(|| {
                file.error_at(&format!("{at}.seed"), format!("expected {SEED_ALLOWED}"))
            })?)
        }
    };
    let stream = TrafficStream {
        vehicle_count: count as usize,
        mix,
        mean_headway: number("mean_headway_s", 0.01, 3600.0, "s", None)?,
        minimum_headway: number("minimum_headway_s", 0.0, 3600.0, "s", Some(1.0))?,
        first_entry: number("first_entry_s", 0.0, 3600.0, "s", Some(0.0))?,
        mean_speed: lane.speed,
        speed_deviation: number("speed_sd_kmh", 0.0, 100.0, "km/h", Some(0.0))? * KMH,
        load_scale_deviation: number("load_scale_sd", 0.0, 0.33, "", Some(0.0))?,
        lateral_position: lane.lateral_position,
        direction: lane.direction,
        seed,
    };
    stream
        .validate()
        .map_err(|e| file.error_at(at, e.to_string()))?;
    scenario.traffic_stream = Some(stream);
    Ok(())
}

/// The weights of the mix: positive numbers, one per vehicle; equal when absent.
fn stream_weights(
    file: &SourceFile,
    at: &str,
    raw: &toml::Table,
    count: usize,
) -> Result<Vec<f64>, InputError> {
    let path = format!("{at}.weights");
    let Some(value) = raw.get("weights") else {
        return Ok(vec![1.0; count]);
    };
    let expected = format!("expected a list of {count} positive weights, one per vehicle");
    let toml::Value::Array(items) = value else {
        return Err(file.error_at(&path, expected));
    };
    if items.len() != count {
        return Err(file.error_at(&path, expected));
    }
    items
        .iter()
        .enumerate()
        .map(|(i, item)| match item {
            toml::Value::Integer(w) if *w > 0 => Ok(*w as f64),
            toml::Value::Float(w) if *w > 0.0 && w.is_finite() => Ok(*w),
            _ => Err(file.error_at(&format!("{path}[{i}]"), expected.clone())),
        })
        .collect()
}
