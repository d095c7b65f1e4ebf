//! The `[bridge]` keys of a damping law other than one ratio (`damping_ratios`,
//! `rayleigh_damping`) and of a damage scenario (`[[bridge.stiffness_loss]]`,
//! `[[bridge.support_change]]`); docs/input-format.md.
//!
//! Girders and supports are numbered from 1 here, as the station names number them (`g1` the
//! rightmost girder, `support1` the support at x = 0); the library numbers them from 0.

use serde::Deserialize;
use vbi::model::{Damage, ModeDamping, RayleighDamping, StiffnessLoss, SupportChange};

use crate::source::{require_in_range, shown, InputError, SourceFile};
use crate::values::key_range;

/// `rayleigh_damping = { ratio_1, frequency_1_hz, ratio_2, frequency_2_hz }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawRayleigh {
    ratio_1: f64,
    frequency_1_hz: f64,
    ratio_2: f64,
    frequency_2_hz: f64,
}

/// One `[[bridge.stiffness_loss]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawStiffnessLoss {
    start_m: f64,
    end_m: f64,
    girder: Option<i64>,
    modulus_factor: f64,
}

/// One `[[bridge.support_change]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSupportChange {
    support: i64,
    vertical_stiffness_n_per_m: f64,
}

/// The damping keys of a `[bridge]` as given.
pub(crate) struct RawDampingKeys<'a> {
    pub damping_ratio_given: bool,
    pub damping_ratios: Option<&'a [f64]>,
    pub rayleigh_damping: Option<&'a RawRayleigh>,
}

/// The damping law of `damping_ratios` or `rayleigh_damping` (None: `damping_ratio` alone);
/// the three keys exclude each other.
pub(crate) fn mode_damping(
    file: &SourceFile,
    keys: RawDampingKeys<'_>,
) -> Result<Option<ModeDamping>, InputError> {
    let given = [
        ("damping_ratio", keys.damping_ratio_given),
        ("damping_ratios", keys.damping_ratios.is_some()),
        ("rayleigh_damping", keys.rayleigh_damping.is_some()),
    ];
    let named: Vec<&str> = given.iter().filter(|g| g.1).map(|g| g.0).collect();
    if named.len() > 1 {
        return Err(file.error_at(
            &format!("bridge.{}", named[1]),
            format!(
                "`{}` and `{}` both give the damping; expected one of damping_ratio (every \
                 mode), damping_ratios (one per mode) or rayleigh_damping",
                named[0], named[1]
            ),
        ));
    }
    if let Some(ratios) = keys.damping_ratios {
        if ratios.is_empty() {
            return Err(file.error_at(
                "bridge.damping_ratios",
                "an empty list gives no mode a ratio; expected at least one ratio",
            ));
        }
        for (i, &ratio) in ratios.iter().enumerate() {
            ratio_in_range(file, &format!("bridge.damping_ratios[{i}]"), ratio)?;
        }
        return Ok(Some(ModeDamping::PerMode {
            ratios: ratios.to_vec(),
        }));
    }
    let Some(raw) = keys.rayleigh_damping else {
        return Ok(None);
    };
    let p = "bridge.rayleigh_damping";
    let frequency = |key: &str, value: f64| {
        require_in_range(file, &format!("{p}.{key}"), value, 0.01, 1000.0, "Hz")
    };
    let rayleigh = RayleighDamping {
        first_ratio: ratio_in_range(file, &format!("{p}.ratio_1"), raw.ratio_1)?,
        first_frequency: frequency("frequency_1_hz", raw.frequency_1_hz)?,
        second_ratio: ratio_in_range(file, &format!("{p}.ratio_2"), raw.ratio_2)?,
        second_frequency: frequency("frequency_2_hz", raw.frequency_2_hz)?,
    };
    rayleigh
        .coefficients()
        .map_err(|error| file.error_at(p, error.to_string()))?;
    Ok(Some(ModeDamping::Rayleigh(rayleigh)))
}

/// A damping ratio [-] checked against the key table's range of `damping_ratio` (0 to 0.99):
/// a bridge's `damping_ratio`, each of its `damping_ratios` and the two of its Rayleigh law.
pub(crate) fn ratio_in_range(file: &SourceFile, path: &str, ratio: f64) -> Result<f64, InputError> {
    let (lowest, largest) = key_range("damping_ratio");
    require_in_range(file, path, ratio, lowest, largest, "(fraction of critical)")
}

/// What the damage keys are checked against.
pub(crate) struct BridgeExtent {
    /// Bridge length [m].
    pub length: f64,
    /// Girders (1 for a beam).
    pub girder_count: usize,
    /// Supports (spans + 1).
    pub support_count: usize,
}

/// The damage of `[[bridge.stiffness_loss]]` and `[[bridge.support_change]]`, each key checked
/// against the bridge before any analysis.
pub(crate) fn damage(
    file: &SourceFile,
    losses: &[RawStiffnessLoss],
    changes: &[RawSupportChange],
    extent: &BridgeExtent,
) -> Result<Damage, InputError> {
    let stiffness_losses = losses
        .iter()
        .enumerate()
        .map(|(i, raw)| stiffness_loss(file, i, raw, extent))
        .collect::<Result<_, _>>()?;
    let mut support_changes: Vec<SupportChange> = Vec::with_capacity(changes.len());
    for (i, raw) in changes.iter().enumerate() {
        let p = format!("bridge.support_change[{i}]");
        let count = extent.support_count;
        if !(1..=count as i64).contains(&raw.support) {
            return Err(file.error_at(
                &format!("{p}.support"),
                format!(
                    "{} is not allowed; expected a support from 1 (at x = 0) to {count}",
                    raw.support
                ),
            ));
        }
        let support = raw.support as usize - 1;
        if support_changes.iter().any(|c| c.support == support) {
            return Err(file.error_at(
                &format!("{p}.support"),
                format!(
                    "support {} is changed twice; expected one change per support",
                    raw.support
                ),
            ));
        }
        let vertical_stiffness = require_in_range(
            file,
            &format!("{p}.vertical_stiffness_n_per_m"),
            raw.vertical_stiffness_n_per_m,
            0.0,
            f64::INFINITY,
            "N/m (0 removes the support)",
        )?;
        support_changes.push(SupportChange {
            support,
            vertical_stiffness,
        });
    }
    Ok(Damage {
        stiffness_losses,
        support_changes,
    })
}

fn stiffness_loss(
    file: &SourceFile,
    i: usize,
    raw: &RawStiffnessLoss,
    extent: &BridgeExtent,
) -> Result<StiffnessLoss, InputError> {
    let p = format!("bridge.stiffness_loss[{i}]");
    let length = extent.length;
    let start = require_in_range(
        file,
        &format!("{p}.start_m"),
        raw.start_m,
        0.0,
        length,
        "m (on the bridge)",
    )?;
    let end = require_in_range(
        file,
        &format!("{p}.end_m"),
        raw.end_m,
        0.0,
        length,
        "m (on the bridge)",
    )?;
    if end <= start {
        return Err(file.error_at(
            &format!("{p}.end_m"),
            format!(
                "{} is not allowed; expected an end after the start, {} m",
                shown(end),
                shown(start)
            ),
        ));
    }
    if !(raw.modulus_factor.is_finite() && raw.modulus_factor > 0.0 && raw.modulus_factor <= 1.0) {
        return Err(file.error_at(
            &format!("{p}.modulus_factor"),
            format!(
                "{} is not allowed; expected a factor on E above 0 and at most 1 (1 = intact)",
                shown(raw.modulus_factor)
            ),
        ));
    }
    let girder = match raw.girder {
        None => None,
        Some(g) if (1..=extent.girder_count as i64).contains(&g) => Some(g as usize - 1),
        Some(g) => {
            return Err(file.error_at(
                &format!("{p}.girder"),
                format!(
                    "{g} is not allowed; expected a girder from 1 (the rightmost) to {}, or no \
                     `girder` for every girder",
                    extent.girder_count
                ),
            ))
        }
    };
    Ok(StiffnessLoss {
        start,
        end,
        girder,
        elastic_modulus_factor: raw.modulus_factor,
    })
}
