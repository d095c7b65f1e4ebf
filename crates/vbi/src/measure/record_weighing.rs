//! Weighing the vehicle of a record (issue 52, item 6): the influence line of each weighing
//! channel and the passage, handed to Moses' least squares ([`super::weigh`]).
//!
//! Each deflection, strain or moment channel (or those `[measurement.weighing] channels`
//! names) weighs with its static reference's line when it has one, else the line calibrated
//! from the crawl run (which needs the crawl truck's axle loads, so the given ones), else the
//! bridge model's at the sensor: updated or calibrated to the identified modes when the
//! measurement fits it, else flagged (its stiffness error enters the weights one to one). The
//! passage: the vehicle's axle offsets, the stated speed, and the entry time, fitted when it
//! was found in the record and taken as exact when given (axle detectors), unless
//! `fit_entry` says otherwise.

use super::influence_lines::{crawl_influence_line, model_influence_line};
use super::measurement::{Channel, Measurement, StaticReference};
use super::weighing::WEIGHING_CUTOFF_FRACTION;
use super::{weigh, MeasureError, VehicleWeighing, WeighingChannel, WeighingStart};
use crate::model::BridgeModel;
use crate::signal::SampledInfluenceLine;

/// The weighed vehicle of `m`, when `[measurement.weighing]` asks for it. `model` is the
/// bridge model (fitted to the identified modes when `model_fitted`); `entry_found`: the entry
/// time was found in the record.
pub(super) fn weigh_record(
    m: &Measurement,
    model: Option<&BridgeModel>,
    model_fitted: bool,
    entry_found: bool,
    first_frequency_hz: Option<f64>,
) -> Result<Option<VehicleWeighing>, MeasureError> {
    let Some(request) = &m.weighing else {
        return Ok(None);
    };
    check_request(m)?;
    let vehicle = m.vehicle.as_ref().expect("check_request: a vehicle");
    let mut lines: Vec<(&Channel, &'static str, SampledInfluenceLine)> = Vec::new();
    for c in weighing_channels(m).filter(|c| can_weigh(m, c, request)) {
        match line_for_weighing(m, c, model, model_fitted, request.axle_loads_given)? {
            Some((source, line)) => lines.push((c, source, line)),
            // The crawl run lacks the channel and no model gives it a line.
            None if request.channels.contains(&c.name) => {
                return Err(MeasureError::input(
                    "weighing.channels",
                    format!(
                    "the crawl run gives channel `{}` no influence line, and no bridge model does",
                    c.name
                ),
                ))
            }
            None => {}
        }
    }
    if lines.is_empty() {
        return Err(MeasureError::input(
            "weighing",
            "no channel of the record has an influence line to weigh with (the crawl run lacks them, and no bridge model gives one)",
        ));
    }
    let channels: Vec<WeighingChannel> = lines
        .iter()
        .map(|(c, source, line)| WeighingChannel {
            name: &c.name,
            line_source: source,
            samples: &c.samples,
            line,
        })
        .collect();
    let start = WeighingStart {
        axle_offsets: vehicle.axle_offsets.clone(),
        speed: vehicle.speed,
        entry_time: vehicle.entry_time,
        fit_entry: request.fit_entry.unwrap_or(entry_found),
        split_groups: request.split_groups,
        low_pass_hz: first_frequency_hz
            .filter(|_| request.low_pass)
            .map(|f| WEIGHING_CUTOFF_FRACTION * f)
            .filter(|&cutoff| cutoff < 0.8 * m.sampling_rate_hz / 2.0),
    };
    let given = request
        .axle_loads_given
        .then_some(vehicle.axle_loads.as_slice());
    weigh(&m.time, &channels, &start, given).map(Some)
}

/// The bridge's first frequency f₁ [Hz] for the weighing's low-pass
/// ([`WEIGHING_CUTOFF_FRACTION`] · f₁): given (`first_frequency_hz`), else the bridge model's
/// first vertical bending mode (fitted to the identified modes when the measurement fits it),
/// else the first identified mode whose damping ratio is plausible (at most
/// [`super::IMPLAUSIBLE_DAMPING_RATIO`]). A truck's bounce read as the bridge's first mode
/// (low, heavily damped; battery case c75: 2.3 Hz at 18 % on a bridge of 5.6 Hz) would put the
/// cut-off below the passage's own content, and the axles' split with it.
pub(super) fn weighing_first_frequency(
    m: &Measurement,
    identified: &[super::IdentifiedMode],
    model_first_bending_hz: Option<f64>,
) -> Option<f64> {
    let plausible = identified.iter().find(|p| {
        p.damping_ratio
            .is_none_or(|z| z <= super::IMPLAUSIBLE_DAMPING_RATIO)
    });
    m.first_frequency_hz
        .or(model_first_bending_hz)
        .or(plausible.map(|p| p.frequency_hz))
}

/// What `[measurement.weighing]` needs of the record before anything is computed, so that
/// `vbi check` ([`super::check_preparation`]) refuses what `vbi measure` would: the vehicle's
/// axle offsets, each named channel a deflection, strain or moment channel with an influence
/// line to weigh with (and one such channel at least), a crawl-run line only with the crawl
/// truck's loads given.
pub(super) fn check_request(m: &Measurement) -> Result<(), MeasureError> {
    let Some(request) = &m.weighing else {
        return Ok(());
    };
    let vehicle = m.vehicle.as_ref().ok_or_else(|| {
        MeasureError::input(
            "weighing",
            "weighing needs the vehicle's axle layout and speed: give [measurement.vehicle] axle_offsets_m (axle_loads_kn optional: the weighed ones are compared with them)",
        )
    })?;
    super::weighing::check_axle_offsets(&vehicle.axle_offsets)?;
    let crawl_without_loads = m
        .channels
        .iter()
        .find(|c| matches!(c.static_reference, Some(StaticReference::CrawlRun)));
    if let Some(c) = crawl_without_loads.filter(|_| !request.axle_loads_given) {
        return Err(MeasureError::input(
            "vehicle.axle_loads_kn",
            format!(
                "channel `{}` calibrates its influence line from the crawl run, which needs the crawl truck's axle loads: give axle_loads_kn",
                c.name
            ),
        ));
    }
    for name in &request.channels {
        let Some(c) = m.channels.iter().find(|c| c.has_daf() && &c.name == name) else {
            return Err(MeasureError::input(
                "weighing.channels",
                format!("`{name}` is not a deflection, strain or moment channel of the record"),
            ));
        };
        if !has_line(m, c, request.axle_loads_given) {
            return Err(MeasureError::input(
                "weighing.channels",
                format!(
                    "channel `{name}` has no influence line to weigh with: give its static_reference, a crawl run (with axle_loads_kn) or a bridge model and its position_m"
                ),
            ));
        }
    }
    if !weighing_channels(m).any(|c| can_weigh(m, c, request)) {
        return Err(MeasureError::input(
            "weighing",
            "weighing needs a deflection, strain or moment channel with an influence line: its static_reference, a crawl run (with the truck's axle_loads_kn) or a bridge model (bridge = \"file.toml\") and the channel's position_m",
        ));
    }
    Ok(())
}

/// The record's deflection, strain and moment channels.
fn weighing_channels(m: &Measurement) -> impl Iterator<Item = &Channel> {
    m.channels.iter().filter(|c| c.has_daf())
}

/// Whether channel `c` weighs: named (or none named), with a line.
fn can_weigh(m: &Measurement, c: &Channel, request: &super::WeighingRequest) -> bool {
    (request.channels.is_empty() || request.channels.contains(&c.name))
        && has_line(m, c, request.axle_loads_given)
}

/// Whether the record gives channel `c` an influence line ([`line_for_weighing`]'s sources).
fn has_line(m: &Measurement, c: &Channel, loads_given: bool) -> bool {
    let model = m
        .bridge
        .as_ref()
        .is_some_and(|b| !matches!(b.model, BridgeModel::ImportedModes(_)));
    c.static_reference.is_some()
        || (m.crawl.is_some() && loads_given)
        || (model && c.location.is_some())
}

/// The influence line channel `c` weighs with, and where it comes from; `None` when the record
/// gives none.
fn line_for_weighing(
    m: &Measurement,
    c: &Channel,
    model: Option<&BridgeModel>,
    model_fitted: bool,
    loads_given: bool,
) -> Result<Option<(&'static str, SampledInfluenceLine)>, MeasureError> {
    let crawl = || -> Result<SampledInfluenceLine, MeasureError> {
        let crawl = m.crawl.as_deref().ok_or_else(|| {
            MeasureError::input("crawl", "the crawl run's influence line needs a crawl run")
        })?;
        let loads = m.vehicle.as_ref().filter(|_| loads_given).ok_or_else(|| {
            MeasureError::input(
                "vehicle.axle_loads_kn",
                "an influence line calibrated from the crawl run needs the crawl truck's axle loads: give axle_loads_kn, or weigh with the bridge model's line",
            )
        })?;
        let length = m
            .bridge_length
            .or(model.map(BridgeModel::length))
            .ok_or_else(|| {
                MeasureError::input(
                    "bridge_length_m",
                    "the crawl run's influence line needs the bridge's length",
                )
            })?;
        Ok(crawl_influence_line(crawl, &c.name, loads, length)?.line)
    };
    let model_line =
        |model: &BridgeModel| -> Result<(&'static str, SampledInfluenceLine), MeasureError> {
            let source = if model_fitted {
                "influence_line_model"
            } else {
                "influence_line_model_unfitted"
            };
            Ok((source, model_influence_line(model, c, m.vehicle_track)?))
        };
    Ok(match &c.static_reference {
        Some(StaticReference::Given(line)) => Some(("influence_line", line.clone())),
        Some(StaticReference::CrawlRun) => Some(("influence_line_crawl", crawl()?)),
        Some(StaticReference::BridgeModel) => {
            let model = model.ok_or_else(|| {
                MeasureError::input(
                    "bridge",
                    "the bridge model's influence line needs the bridge model",
                )
            })?;
            Some(model_line(model)?)
        }
        // Without a static reference of its own, the crawl run's line, else the model's; a
        // line that cannot be made for this channel (the crawl run lacks it) leaves the next.
        None => {
            let from_crawl = (m.crawl.is_some() && loads_given)
                .then(crawl)
                .and_then(Result::ok)
                .map(|line| ("influence_line_crawl", line));
            match (from_crawl, model, c.location) {
                (Some(line), _, _) => Some(line),
                (None, Some(model), Some(_)) if !matches!(model, BridgeModel::ImportedModes(_)) => {
                    Some(model_line(model)?)
                }
                _ => None,
            }
        }
    })
}
