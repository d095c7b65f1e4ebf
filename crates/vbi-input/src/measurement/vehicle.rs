//! `[measurement.vehicle]`: the axle loads of the crossing vehicle (for influence-line
//! references), where it runs on the deck, and its own frequencies.

use vbi::measure::measurement::{VehicleTrack, WeighingRequest};
use vbi::signal::MovingLoads;
use vbi::units;

use crate::measurement::raw::{RawMeasurement, RawVehicle};
use crate::source::{require_in_range, require_positive, InputError, SourceFile};

/// The vehicle's moving loads: axle loads [kN → N] with their offsets [m], the speed [m/s] and
/// the time its first axle enters the bridge [s] (its own, the record's, or 0 when searched
/// for); `None` without `[measurement.vehicle]`. With `[measurement.weighing]` the axle loads
/// may be left out: 1 kN each stands in until the weighing replaces them.
pub(crate) fn moving_loads(
    file: &SourceFile,
    m: &RawMeasurement,
    speed: Option<f64>,
) -> Result<Option<MovingLoads>, InputError> {
    let at = |key: &str| format!("measurement.{key}");
    let vehicle = match &m.vehicle {
        None => None,
        Some(v) => {
            // Weighing finds the axle loads: without them, equal placeholders stand in (only
            // the entry search's template uses them; the weighed loads replace them).
            let weighed = m.weighing.is_some() && v.axle_loads_kn.is_empty();
            if weighed && v.axle_offsets_m.is_empty() {
                return Err(file.error_at(
                    &at("vehicle.axle_offsets_m"),
                    "weighing needs the vehicle's axle offsets behind the first axle (the first 0), in m",
                ));
            }
            if !weighed && v.axle_loads_kn.is_empty() {
                return Err(file.error_at(
                    &at("vehicle.axle_loads_kn"),
                    "give the vehicle's axle loads in kN, one per axle offset, or weigh them from the record ([measurement.weighing])",
                ));
            }
            if m.weighing.is_some() {
                // Moses' least squares need the axles in order, each at its own place.
                let d = &v.axle_offsets_m;
                if d.first() != Some(&0.0) || d.windows(2).any(|w| w[1] <= w[0]) {
                    return Err(file.error_at(
                        &at("vehicle.axle_offsets_m"),
                        "weighing needs the axle offsets behind the first axle: the first 0, then increasing, in m",
                    ));
                }
            }
            if !weighed && v.axle_loads_kn.len() != v.axle_offsets_m.len() {
                return Err(file.error_at(
                    &at("vehicle.axle_offsets_m"),
                    format!(
                        "{} axle loads and {} axle offsets; expected one offset per load (the first 0)",
                        v.axle_loads_kn.len(),
                        v.axle_offsets_m.len()
                    ),
                ));
            }
            for (i, p) in v.axle_loads_kn.iter().enumerate() {
                require_positive(file, &at(&format!("vehicle.axle_loads_kn[{i}]")), *p, "kN")?;
            }
            for (i, d) in v.axle_offsets_m.iter().enumerate() {
                require_in_range(
                    file,
                    &at(&format!("vehicle.axle_offsets_m[{i}]")),
                    *d,
                    0.0,
                    f64::INFINITY,
                    "m",
                )?;
            }
            // Without a time of its own the vehicle enters at the record's entry time, given or
            // found in the record (the measurement stage sets it then).
            if v.entry_time_s.is_some() && m.detect_entry == Some(true) {
                return Err(file.error_at(
                    &at("detect_entry"),
                    "[measurement.vehicle] gives entry_time_s: the entry is not searched for; remove one of the two",
                ));
            }
            let entry = match (v.entry_time_s, m.entry_time_s, m.detect_entry) {
                (Some(t), _, _) | (None, Some(t), _) => t,
                // Looked for in the record (by default, or asked for).
                (None, None, None | Some(true)) => 0.0,
                (None, None, Some(false)) => {
                    return Err(file.error_at(
                        &at("vehicle.entry_time_s"),
                        "the vehicle needs the time its first axle enters the bridge: give entry_time_s here or in [measurement], or detect_entry = true",
                    ))
                }
            };
            if !entry.is_finite() {
                return Err(
                    file.error_at(&at("vehicle.entry_time_s"), "expected a finite time in s")
                );
            }
            let speed = speed.ok_or_else(|| {
                file.error_at(
                    &at("speed_kmh"),
                    "[measurement.vehicle] needs the vehicle speed: give speed_kmh or speed_m_s",
                )
            })?;
            let axle_loads = if weighed {
                vec![units::KN; v.axle_offsets_m.len()]
            } else {
                v.axle_loads_kn.iter().map(|p| p * units::KN).collect()
            };
            Some(MovingLoads {
                axle_loads,
                axle_offsets: v.axle_offsets_m.clone(),
                speed,
                entry_time: entry,
            })
        }
    };
    Ok(vehicle)
}

/// Where the vehicle runs: `[measurement.vehicle]`'s `lateral_position_m` (default 0, the deck
/// centreline) and `track_width_m` (default 0, one wheel line).
pub(crate) fn vehicle_track_of(
    file: &SourceFile,
    m: &RawMeasurement,
) -> Result<VehicleTrack, InputError> {
    let Some(v) = &m.vehicle else {
        return Ok(VehicleTrack::default());
    };
    let at = |k: &str| format!("measurement.vehicle.{k}");
    let lateral_position =
        match v.lateral_position_m {
            Some(y) if !y.is_finite() => return Err(file.error_at(
                &at("lateral_position_m"),
                "expected a finite position in m from the deck centreline (positive to the left)",
            )),
            y => y.unwrap_or(0.0),
        };
    let track_width = v
        .track_width_m
        .map(|w| require_in_range(file, &at("track_width_m"), w, 0.0, 5.0, "m"))
        .transpose()?
        .unwrap_or(0.0);
    Ok(VehicleTrack {
        lateral_position,
        track_width,
    })
}

/// `[measurement.vehicle] frequencies_hz`, each positive and finite.
pub(crate) fn vehicle_frequencies(
    file: &SourceFile,
    vehicle: Option<&RawVehicle>,
) -> Result<Vec<f64>, InputError> {
    let given = vehicle
        .and_then(|v| v.frequencies_hz.clone())
        .unwrap_or_default();
    for (i, f) in given.iter().enumerate() {
        require_positive(
            file,
            &format!("measurement.vehicle.frequencies_hz[{i}]"),
            *f,
            "Hz",
        )?;
    }
    Ok(given)
}

/// `[measurement.weighing]`: the channels to weigh with (each a deflection, strain or moment
/// channel of the record) and whether the entry time is fitted; `None` without the table.
pub(crate) fn weighing_request(
    file: &SourceFile,
    m: &RawMeasurement,
) -> Result<Option<WeighingRequest>, InputError> {
    let Some(w) = &m.weighing else {
        return Ok(None);
    };
    let Some(v) = &m.vehicle else {
        return Err(file.error_at(
            "measurement.weighing",
            "weighing needs the vehicle's axle layout and speed: give [measurement.vehicle] axle_offsets_m (axle_loads_kn optional: the weighed ones are compared with them)",
        ));
    };
    let channels = w.channels.clone().unwrap_or_default();
    for (i, name) in channels.iter().enumerate() {
        let known = m
            .channels
            .iter()
            .any(|c| &c.name == name && c.kind != vbi::signal::MeasuredQuantity::Acceleration);
        if !known {
            return Err(file.error_at(
                &format!("measurement.weighing.channels[{i}]"),
                format!("`{name}` is not a deflection, strain or moment channel of this record"),
            ));
        }
    }
    // `vbi check` refuses what the weighing would: a channel to weigh with needs a line, and a
    // line calibrated from the crawl run needs the crawl truck's loads.
    let loads_given = !v.axle_loads_kn.is_empty();
    let crawl_reference = |c: &crate::measurement::raw::RawChannel| {
        c.static_reference
            .as_ref()
            .is_some_and(|r| r.as_str() == Some("crawl"))
    };
    if !loads_given {
        if let Some(c) = m.channels.iter().find(|c| crawl_reference(c)) {
            return Err(file.error_at(
                "measurement.vehicle.axle_loads_kn",
                format!(
                    "channel `{}` calibrates its influence line from the crawl run, which needs the crawl truck's axle loads: give axle_loads_kn",
                    c.name
                ),
            ));
        }
    }
    let has_line = |c: &crate::measurement::raw::RawChannel| {
        c.kind != vbi::signal::MeasuredQuantity::Acceleration
            && (c.static_reference.is_some()
                || (m.crawl.is_some() && loads_given)
                || (m.bridge.is_some() && c.position_m.is_some()))
    };
    for (i, name) in channels.iter().enumerate() {
        if let Some(c) = m.channels.iter().find(|c| &c.name == name && !has_line(c)) {
            return Err(file.error_at(
                &format!("measurement.weighing.channels[{i}]"),
                format!(
                    "channel `{}` has no influence line to weigh with: give its static_reference, a crawl run (with axle_loads_kn) or a bridge model and its position_m",
                    c.name
                ),
            ));
        }
    }
    let weighed_with = |c: &&crate::measurement::raw::RawChannel| {
        channels.is_empty() || channels.contains(&c.name)
    };
    if !m.channels.iter().filter(weighed_with).any(has_line) {
        return Err(file.error_at(
            "measurement.weighing",
            "weighing needs a deflection, strain or moment channel with an influence line: its static_reference, a crawl run (with the truck's axle_loads_kn) or a bridge model (bridge = \"file.toml\") and the channel's position_m",
        ));
    }
    Ok(Some(WeighingRequest {
        channels,
        fit_entry: w.fit_entry,
        split_groups: w.split_groups.unwrap_or(false),
        axle_loads_given: loads_given,
    }))
}
