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
) -> Result<Option<VehicleWeighing>, MeasureError> {
    let Some(request) = &m.weighing else {
        return Ok(None);
    };
    let vehicle = m.vehicle.as_ref().ok_or_else(|| {
        MeasureError::input(
            "weighing",
            "weighing needs the vehicle's axle offsets and speed: give [measurement.vehicle] axle_offsets_m",
        )
    })?;
    for name in &request.channels {
        if !m.channels.iter().any(|c| c.has_daf() && &c.name == name) {
            return Err(MeasureError::input(
                "weighing.channels",
                format!("`{name}` is not a deflection, strain or moment channel of the record"),
            ));
        }
    }
    let mut lines: Vec<(&Channel, &'static str, SampledInfluenceLine)> = Vec::new();
    for c in m.channels.iter().filter(|c| c.has_daf()) {
        let named = request.channels.contains(&c.name);
        if !request.channels.is_empty() && !named {
            continue;
        }
        match line_for_weighing(m, c, model, model_fitted, request.axle_loads_given)? {
            Some((source, line)) => lines.push((c, source, line)),
            None if named => {
                return Err(MeasureError::input(
                    "weighing.channels",
                    format!(
                        "channel `{}` has no influence line to weigh with: give its static_reference, a crawl run or a bridge model with its position_m",
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
            "weighing needs a deflection, strain or moment channel with an influence line: its static_reference, a crawl run (with the truck's axle loads) or a bridge model (bridge = \"file.toml\") and the channel's position_m",
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
    };
    let given = request
        .axle_loads_given
        .then_some(vehicle.axle_loads.as_slice());
    weigh(&m.time, &channels, &start, given).map(Some)
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
