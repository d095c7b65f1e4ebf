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

/// `[measurement.weighing]` as the library takes it ([`WeighingRequest`]); `None` without the
/// table. What it needs of the record (a vehicle, channels with influence lines) is the
/// library's to check (`vbi::measure::check_preparation`), for `vbi check` and `vbi measure`
/// alike.
pub(crate) fn weighing_request(m: &RawMeasurement) -> Option<WeighingRequest> {
    let w = m.weighing.as_ref()?;
    Some(WeighingRequest {
        channels: w.channels.clone().unwrap_or_default(),
        fit_entry: w.fit_entry,
        split_groups: w.split_groups.unwrap_or(false),
        low_pass: w.low_pass.unwrap_or(false),
        axle_loads_given: m
            .vehicle
            .as_ref()
            .is_some_and(|v| !v.axle_loads_kn.is_empty()),
    })
}
