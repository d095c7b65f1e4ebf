//! `[measurement.updating]`: model updating (stiffness, mass or named parameters) against the
//! bridge model's frequencies or frequencies given as numbers.

use vbi::measure::added_mass_per_length;
use vbi::measure::measurement::{Channel, MeasuredBridge, UpdatingSpec};
use vbi::signal::MeasuredQuantity;

use crate::measurement::raw::RawUpdating;
use crate::source::{require_positive, InputError, SourceFile};

/// The updating keys, checked against the bridge model (if named) and the channels (an
/// acceleration channel gives the identified frequencies).
pub(crate) fn updating(
    file: &SourceFile,
    updating: Option<RawUpdating>,
    bridge: Option<&MeasuredBridge>,
    channels: &[Channel],
) -> Result<Option<UpdatingSpec>, InputError> {
    let at = |key: &str| format!("measurement.{key}");
    Ok(match updating {
        None => None,
        Some(u) => {
            match (&u.model_frequencies_hz, &bridge) {
                (Some(_), Some(_)) => {
                    return Err(file.error_at(
                        &at("updating.model_frequencies_hz"),
                        "the model frequencies come from the bridge model; remove model_frequencies_hz or the bridge",
                    ))
                }
                (None, None) => {
                    return Err(file.error_at(
                        &at("updating"),
                        "model updating needs a model: give bridge = \"file.toml\" or [measurement.updating] model_frequencies_hz",
                    ))
                }
                _ => {}
            }
            if u.fit_mass {
                match &bridge {
                    None => {
                        return Err(file.error_at(
                            &at("updating.fit_mass"),
                            "a mass scale cannot be identified from model frequencies given as numbers: uniform stiffness and mass scales change every frequency alike (ω² ∝ k/m); name the bridge model (bridge = \"file.toml\"), whose added (pavement) mass is then scaled, or fit the stiffness alone (fit_mass = false)",
                        ));
                    }
                    Some(b) if added_mass_per_length(&b.model) <= 0.0 => {
                        return Err(file.error_at(
                            &at("updating.fit_mass"),
                            format!("the bridge {} has no added (pavement) mass to scale; fit the stiffness alone (fit_mass = false)", b.label),
                        ));
                    }
                    Some(_) => {}
                }
            }
            model_frequencies(file, &u)?;
            if !channels
                .iter()
                .any(|c| c.kind == MeasuredQuantity::Acceleration)
            {
                return Err(file.error_at(
                    &at("updating"),
                    "model updating needs identified frequencies: add an acceleration channel",
                ));
            }
            let parameters = u.parameters.unwrap_or_default();
            if !parameters.is_empty() {
                if bridge.is_none() {
                    return Err(file.error_at(
                        &at("updating.parameters"),
                        "calibration re-solves the bridge model: give bridge = \"file.toml\"",
                    ));
                }
                if u.fit_mass {
                    return Err(file.error_at(
                        &at("updating.fit_mass"),
                        "with parameters, the added mass is fitted by \"added_mass\" in the list; remove fit_mass",
                    ));
                }
                if u.identified_kinds.is_some() {
                    return Err(file.error_at(
                        &at("updating.identified_kinds"),
                        "calibration pairs modes by MAC at the sensors (position_m), or by order within the vertical bending modes; remove identified_kinds",
                    ));
                }
            }
            Some(UpdatingSpec {
                model_frequencies_hz: u.model_frequencies_hz,
                fit_mass: u.fit_mass,
                model_kinds: u.model_kinds,
                identified_kinds: u.identified_kinds,
                parameters,
            })
        }
    })
}

/// `model_frequencies_hz` [Hz] (positive, ascending, at least one) with `model_kinds` (one per
/// frequency) and `identified_kinds` (both or neither); without them, no `model_kinds`.
fn model_frequencies(file: &SourceFile, u: &RawUpdating) -> Result<(), InputError> {
    let at = |key: &str| format!("measurement.{key}");
    if let Some(freqs) = &u.model_frequencies_hz {
        if freqs.is_empty() {
            return Err(file.error_at(
                &at("updating.model_frequencies_hz"),
                "at least one model frequency is required",
            ));
        }
        for (i, f) in freqs.iter().enumerate() {
            require_positive(
                file,
                &at(&format!("updating.model_frequencies_hz[{i}]")),
                *f,
                "Hz",
            )?;
            if i > 0 && *f < freqs[i - 1] {
                return Err(file.error_at(
                    &at(&format!("updating.model_frequencies_hz[{i}]")),
                    "model frequencies must be in ascending order",
                ));
            }
        }
        if let Some(k) = &u.model_kinds {
            if k.len() != freqs.len() {
                return Err(file.error_at(
                    &at("updating.model_kinds"),
                    format!(
                        "{} kinds for {} model frequencies; expected one per frequency",
                        k.len(),
                        freqs.len()
                    ),
                ));
            }
        }
        if u.identified_kinds.is_some() != u.model_kinds.is_some() {
            return Err(file.error_at(
                &at("updating.identified_kinds"),
                "give both model_kinds and identified_kinds, or neither",
            ));
        }
    } else if u.model_kinds.is_some() {
        return Err(file.error_at(
            &at("updating.model_kinds"),
            "the kinds of the model modes come from the bridge model; remove model_kinds",
        ));
    }
    Ok(())
}
