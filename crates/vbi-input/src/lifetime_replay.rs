//! The governing events of a lifetime with dynamics written as `vbi run` scenarios: for each
//! effect, the event with the largest total over the record becomes a directory with a
//! `scenario.toml` (the lifetime's bridge and stations, the event's road seed and the crossing
//! keys of `[lifetime.crossing]`, the first truck as the scenario's vehicle and the others as
//! `[[traffic]]` with their entry times) and one `[vehicle]` file per truck
//! ([`crate::vehicle_toml`]). `vbi run` on it integrates the same crossing: the same vehicles bit
//! for bit, speeds written so that they read back to the same f64, the same road.

use std::fmt::Write;
use std::path::Path;

use vbi::lifetime::{event_scenario_at, GoverningEvent, LifetimeEffect, LifetimeLane};
use vbi::traffic::TravelDirection;
use vbi::units::KMH;

use crate::source::{relative, SourceFile};
use crate::vehicle_toml::{quoted, vehicle_toml};

/// What a governing event's scenario copies from the lifetime file.
#[derive(Debug, Clone, Default)]
pub struct ReplayInputs {
    /// `bridge = "…"`: a preset's name, or a bridge file's absolute path; None for an inline
    /// `[bridge]`, which `tables` then holds.
    pub bridge: Option<String>,
    /// The inline `[bridge]` and the `[[station]]`s, as TOML.
    pub tables: String,
    /// The `[lifetime.crossing]` keys but `seed` (the event has its own), a road file's path
    /// made absolute.
    pub crossing: Vec<(String, toml::Value)>,
}

/// The parts of `file` (its parsed `table`) that a governing event's scenario copies.
pub fn replay_inputs(file: &SourceFile, table: &toml::Table) -> ReplayInputs {
    let lifetime = table.get("lifetime").and_then(toml::Value::as_table);
    let absolute = |name: &str| match name.ends_with(".toml") {
        true => relative(file, name).display().to_string(),
        false => name.to_string(),
    };
    let bridge = lifetime
        .and_then(|l| l.get("bridge"))
        .and_then(toml::Value::as_str)
        .map(absolute);
    let mut tables = toml::Table::new();
    for key in ["bridge", "station"] {
        if let Some(value) = table.get(key) {
            tables.insert(key.into(), value.clone());
        }
    }
    let crossing = lifetime
        .and_then(|l| l.get("crossing"))
        .and_then(toml::Value::as_table)
        .map(|crossing| {
            (crossing.iter())
                .filter(|(key, _)| key.as_str() != "seed")
                .map(|(key, value)| match (key.as_str(), value) {
                    ("road", toml::Value::String(name)) => {
                        (key.clone(), toml::Value::String(absolute(name)))
                    }
                    _ => (key.clone(), value.clone()),
                })
                .collect()
        })
        .unwrap_or_default();
    ReplayInputs {
        bridge,
        tables: toml::to_string(&tables).unwrap_or_default(),
        crossing,
    }
}

/// A speed [m/s] as the `speed_kmh` that reads back to it exactly (`speed_kmh × KMH`): v / KMH,
/// or the nearest f64 to it that does.
fn speed_kmh(speed: f64) -> f64 {
    let first = speed / KMH;
    let mut candidate = first;
    for step in 0..8 {
        if candidate * KMH == speed {
            return candidate;
        }
        let ulps = (step / 2 + 1) as i64 * if step % 2 == 0 { 1 } else { -1 };
        candidate = f64::from_bits((first.to_bits() as i64 + ulps) as u64);
    }
    first
}

fn direction_name(direction: TravelDirection) -> &'static str {
    match direction {
        TravelDirection::Forward => "forward",
        TravelDirection::Backward => "backward",
    }
}

/// The files of effect `effect`'s governing event, as (file name, text): `scenario.toml` and
/// `truck-<k>.toml` per truck. `template` is the crossing every event's scenario is made from.
pub fn governing_files(
    inputs: &ReplayInputs,
    (settings, lanes): (&vbi::lifetime::DynamicSettings, &[LifetimeLane]),
    effect: &LifetimeEffect,
    governing: &GoverningEvent,
) -> Vec<(String, String)> {
    let (template, changes) = (&settings.template, settings.road_changes.as_slice());
    let made = event_scenario_at(changes, template, lanes, &governing.trucks, governing.event);
    let Ok(scenario) = made else {
        return Vec::new();
    };
    // The road of the event's year, where it has changed since the record's start.
    let changed =
        (scenario.road.roughness != template.road.roughness).then_some(scenario.road.roughness);
    let mut files = Vec::new();
    let mut text = String::new();
    let _ = writeln!(
        text,
        "# The event that gives the largest total {} at {} of the record: event {}, {},\n\
         # total {:e} and static {:e} ({}), at t = {:.3} s of the record. Written by\n\
         # `vbi lifetime`; `vbi run scenario.toml` integrates the same crossing (its DAF is read\n\
         # in the sense of the static extreme of largest magnitude, the lifetime's in the\n\
         # effect's own sense: they differ only where the event loads the effect more the other way).\n",
        effect.quantity.name(),
        effect.station,
        governing.event,
        match governing.trucks.len() {
            1 => "1 truck".to_string(),
            n => format!("{n} trucks"),
        },
        governing.total.total,
        governing.total.static_value,
        effect.quantity.unit(),
        governing.total.time,
    );
    let _ = writeln!(text, "[scenario]");
    let _ = writeln!(text, "name = {}", quoted(&scenario.name));
    if let Some(bridge) = &inputs.bridge {
        let _ = writeln!(text, "bridge = {}", quoted(bridge));
    }
    let _ = writeln!(text, "vehicle = \"truck-1.toml\"");
    let _ = writeln!(text, "speed_kmh = {:?}", speed_kmh(scenario.motion.speed));
    let _ = writeln!(
        text,
        "lateral_position_m = {:?}",
        scenario.motion.lateral_position
    );
    let _ = writeln!(
        text,
        "direction = \"{}\"",
        direction_name(scenario.motion.direction)
    );
    let _ = writeln!(text, "seed = \"{}\"", scenario.road.seed);
    for (key, value) in &inputs.crossing {
        if key != "road" || changed.is_none() {
            let _ = writeln!(text, "{key} = {value}");
        }
    }
    if let Some(vbi::road::Roughness::Class(class)) = changed {
        let _ = writeln!(text, "road = {}", quoted(class.name()));
    }
    files.push(("truck-1.toml".to_string(), vehicle_toml(&scenario.vehicle)));
    for (k, further) in scenario.traffic.iter().enumerate() {
        let name = format!("truck-{}.toml", k + 2);
        let entry = match further.entry {
            vbi::traffic::Entry::Time(time) => time,
            vbi::traffic::Entry::Gap(_) => unreachable!("an event's trucks enter by time"),
        };
        let _ = writeln!(text, "\n[[traffic]]");
        let _ = writeln!(text, "vehicle = {}", quoted(&name));
        let _ = writeln!(text, "label = {}", quoted(&further.label));
        let _ = writeln!(text, "speed_kmh = {:?}", speed_kmh(further.motion.speed));
        let _ = writeln!(
            text,
            "lateral_position_m = {:?}",
            further.motion.lateral_position
        );
        let _ = writeln!(
            text,
            "direction = \"{}\"",
            direction_name(further.motion.direction)
        );
        let _ = writeln!(text, "entry_time_s = {entry:?}");
        if !further.motion.speed_profile.is_empty() {
            // A follower that fell back from its leader before the deck (its approach speed,
            // braking, its recorded speed: vbi::lifetime::dynamics::follower_profile).
            let knots: Vec<String> = (further.motion.speed_profile.iter())
                .map(|k| {
                    format!(
                        "{{ travel_m = {:?}, speed_kmh = {:?} }}",
                        k.travel,
                        speed_kmh(k.speed)
                    )
                })
                .collect();
            let _ = writeln!(text, "speed_profile = [{}]", knots.join(", "));
        }
        files.push((name, vehicle_toml(&further.vehicle)));
    }
    if !inputs.tables.is_empty() {
        let _ = writeln!(text, "\n{}", inputs.tables);
    }
    files.insert(0, ("scenario.toml".to_string(), text));
    files
}

/// The directory name of an effect's governing event: `<station>-<quantity>`.
pub fn governing_directory(effect: &LifetimeEffect) -> String {
    governing_directory_of(&effect.station, effect.quantity.name())
}

/// The directory name of the governing event of a station's quantity (by its name, as
/// lifetime.json writes it): `<station>-<quantity>`.
pub fn governing_directory_of(station: &str, quantity: &str) -> String {
    format!("{station}-{quantity}")
}

/// Whether `path` is a directory name that stays inside its parent (station names are the
/// input's: a name with a separator or `..` is not written).
pub fn safe_directory_name(name: &str) -> bool {
    !name.is_empty()
        && name != "."
        && name != ".."
        && Path::new(name).components().count() == 1
        && !name.contains(['/', '\\'])
}
