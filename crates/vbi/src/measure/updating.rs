//! The bridge model's modes, and model updating to the identified frequencies (the paper's §6):
//! the stiffness (E of a grillage, EI of a continuous beam) and optionally the added pavement
//! mass are scaled until the model's frequencies match the identified ones.

use super::{error_chain, BridgeUpdate, IdentifiedMode, MeasureError};
use crate::crossing::PipelineError;
use crate::fe::{discretise, MeshOptions};
use crate::measure::measurement::{MeasuredBridge, Measurement, UpdatingSpec};
use crate::modal::{solve_modes_with, CheckModes, ModalOptions, ModeKind};
use crate::model::BridgeModel;
use crate::signal::{
    update_model, IdentifiedFrequency, SignalError, UpdatedModel, UpdatingOptions,
};

/// The bridge with its stiffness (E of a grillage, EI of a continuous beam) multiplied by
/// `stiffness` and its added (pavement) mass by `mass`. Grillage: E scales G = E/(2(1+ν)) with
/// it, so every member stiffness scales alike; the pavement mass scales through the concrete
/// pavement and asphalt thicknesses (they carry no stiffness). Continuous beam: elastic
/// support springs are not scaled.
pub fn scaled_bridge(base: &BridgeModel, stiffness: f64, mass: f64) -> BridgeModel {
    let mut model = base.clone();
    match &mut model {
        BridgeModel::ContinuousBeam(b) => {
            b.section.flexural_rigidity *= stiffness;
            b.added_mass_per_length *= mass;
        }
        BridgeModel::Grillage(g) => {
            g.material.elastic_modulus *= stiffness;
            g.deck.pavement_concrete_thickness *= mass;
            g.deck.asphalt_thickness *= mass;
        }
        // Imported matrices have no added mass apart from the structure's: K (and the deck
        // lines' EI, which read the moments) scale.
        BridgeModel::ImportedMatrices(m) => {
            let mut k = (*m.stiffness).clone();
            k.values.iter_mut().for_each(|v| *v *= stiffness);
            m.stiffness = std::sync::Arc::new(k);
            m.deck_lines
                .iter_mut()
                .for_each(|line| line.flexural_rigidity *= stiffness);
        }
        // A uniform stiffness factor scales ω by its square root and the modal moments (per
        // unit modal coordinate, M = EI φ'') by itself; the mass-normalised shapes stay.
        BridgeModel::ImportedModes(m) => {
            let data = std::sync::Arc::make_mut(&mut m.data);
            data.frequencies_hz
                .iter_mut()
                .for_each(|f| *f *= stiffness.sqrt());
            for station in &mut data.stations {
                station.moments.iter_mut().for_each(|v| *v *= stiffness);
            }
        }
    }
    model
}

/// Total added (non-structural) mass of a bridge model per unit length [kg/m]: what a mass
/// scale multiplies.
pub fn added_mass_per_length(model: &BridgeModel) -> f64 {
    match model {
        BridgeModel::ContinuousBeam(b) => b.added_mass_per_length,
        BridgeModel::Grillage(g) => (0..g.girder_count)
            .map(|i| g.added_mass_per_length(i))
            .sum(),
        BridgeModel::ImportedMatrices(_) | BridgeModel::ImportedModes(_) => 0.0,
    }
}

/// The name and value of the stiffness parameter that updating scales [Pa or N·m²].
fn stiffness_of(model: &BridgeModel) -> (&'static str, f64) {
    match model {
        BridgeModel::ContinuousBeam(b) => ("flexural_rigidity_n_m2", b.section.flexural_rigidity),
        BridgeModel::Grillage(g) => ("elastic_modulus_pa", g.material.elastic_modulus),
        BridgeModel::ImportedMatrices(m) => (
            "deck_lines_flexural_rigidity_n_m2",
            m.deck_lines.iter().map(|line| line.flexural_rigidity).sum(),
        ),
        // The first frequency squared stands for the stiffness (ω² ∝ k).
        BridgeModel::ImportedModes(m) => (
            "first_frequency_squared_hz2",
            m.data.frequencies_hz.first().map_or(0.0, |f| f * f),
        ),
    }
}

/// Frequencies [Hz] and kinds of the lowest `mode_count` modes of a bridge model (default
/// mesh, every kind).
fn bridge_modes(
    model: &BridgeModel,
    mode_count: usize,
) -> Result<(Vec<f64>, Vec<ModeKind>), PipelineError> {
    let fe = discretise(model, &MeshOptions::default()).map_err(PipelineError::Discretise)?;
    let options = ModalOptions {
        mode_count,
        ..ModalOptions::default()
    };
    // The frequencies alone: no check modes.
    let basis = solve_modes_with(&fe, &options, CheckModes::Skip).map_err(PipelineError::Modes)?;
    Ok((
        basis.modes.iter().map(|m| m.frequency_hz()).collect(),
        basis.modes.iter().map(|m| m.kind).collect(),
    ))
}

/// Reorders `frequencies` (of modes of `kinds`) so that position j holds the r-th mode of the
/// kind of `reference[j]`, r being its rank within that kind in `reference`: a scaled model
/// whose modes of different kinds swap order is still compared mode by mode. Stops at the
/// first reference mode without a counterpart.
fn align_by_kind(frequencies: &[f64], kinds: &[ModeKind], reference: &[ModeKind]) -> Vec<f64> {
    let mut out = Vec::with_capacity(reference.len());
    for (j, kind) in reference.iter().enumerate() {
        let rank = reference[..j].iter().filter(|k| *k == kind).count();
        match kinds
            .iter()
            .enumerate()
            .filter(|(_, k)| *k == kind)
            .nth(rank)
        {
            Some((i, _)) => out.push(frequencies[i]),
            None => break,
        }
    }
    out
}

/// The bridge model's frequencies for the cut-off modes, with the updating that produced them.
pub(super) struct ModelFrequencies {
    /// Frequencies of the model's modes [Hz], updated when updating was asked; `None` without
    /// a bridge model.
    pub frequencies: Option<Vec<f64>>,
    /// Kinds of the model's modes.
    kinds: Vec<ModeKind>,
    /// The updating, when asked.
    pub updating: Option<UpdatedModel>,
    /// The bridge before and after updating, when there is a model.
    pub bridge: Option<BridgeUpdate>,
    /// The bridge model behind `frequencies`: updated or calibrated when `fitted`.
    pub model: Option<BridgeModel>,
    /// The model was fitted to the identified modes (updating or calibration).
    pub fitted: bool,
}

impl ModelFrequencies {
    /// The (updated) frequency of the model's first vertical bending mode [Hz].
    pub fn first_bending_hz(&self) -> Option<f64> {
        let i = self
            .kinds
            .iter()
            .position(|k| *k == ModeKind::VerticalBending)?;
        self.frequencies.as_ref().map(|f| f[i])
    }
}

/// Solves the bridge model's modes and, when asked, updates the model to the identified
/// frequencies.
/// With `calibrating`, the classic updating is left to the calibration
/// ([`ModelFrequencies::calibrated`]).
pub(super) fn model_frequencies(
    m: &Measurement,
    identified: &[IdentifiedMode],
    calibrating: bool,
) -> Result<ModelFrequencies, MeasureError> {
    let base = match &m.bridge {
        Some(b) => Some(bridge_modes(&b.model, b.mode_count).map_err(|source| {
            MeasureError::BridgeModel {
                label: b.label.clone(),
                source,
            }
        })?),
        None => None,
    };
    let updating = match &m.updating {
        Some(u) if !calibrating => Some(update(u, m.bridge.as_ref(), base.as_ref(), identified)?),
        _ => None,
    };
    let (Some(b), Some((f, kinds))) = (&m.bridge, base) else {
        return Ok(ModelFrequencies {
            frequencies: None,
            kinds: Vec::new(),
            updating,
            bridge: None,
            model: None,
            fitted: false,
        });
    };
    let frequencies = match &updating {
        Some(u) if u.updated_frequencies_hz.len() == f.len() => u.updated_frequencies_hz.clone(),
        _ => f.clone(),
    };
    let (parameter, stiffness) = stiffness_of(&b.model);
    let updated = updating
        .as_ref()
        .map(|u| scaled_bridge(&b.model, u.stiffness_scale, u.mass_scale.unwrap_or(1.0)));
    let bridge = BridgeUpdate {
        file: b.label.clone(),
        frequencies_hz: f,
        kinds: kinds.clone(),
        updated_frequencies_hz: updating.as_ref().map(|_| frequencies.clone()),
        stiffness_parameter: parameter,
        stiffness_initial: stiffness,
        stiffness_updated: updated.as_ref().map(|u| stiffness_of(u).1),
        added_mass_initial_kg_per_m: added_mass_per_length(&b.model),
        added_mass_updated_kg_per_m: updated.as_ref().map(added_mass_per_length),
    };
    let fitted = updated.is_some();
    Ok(ModelFrequencies {
        frequencies: Some(frequencies),
        kinds,
        updating,
        bridge: Some(bridge),
        model: Some(updated.unwrap_or_else(|| b.model.clone())),
        fitted,
    })
}

/// Model updating: the given model frequencies (scaled as √α by a stiffness scale α) or the
/// bridge model (rebuilt and re-solved for every trial of the scales), fitted to the
/// identified frequencies.
fn update(
    u: &UpdatingSpec,
    bridge: Option<&MeasuredBridge>,
    base: Option<&(Vec<f64>, Vec<ModeKind>)>,
    identified: &[IdentifiedMode],
) -> Result<UpdatedModel, MeasureError> {
    if identified.is_empty() {
        return Err(MeasureError::input(
            "updating",
            "no frequency was identified in the acceleration spectrum; lower spectrum.min_prominence_db or check the band",
        ));
    }
    if let Some(kinds) = &u.identified_kinds {
        if kinds.len() != identified.len() {
            return Err(MeasureError::input(
                "updating.identified_kinds",
                format!("{} kinds given but {} frequencies were identified; give one kind per identified frequency", kinds.len(), identified.len()),
            ));
        }
    }
    let options = UpdatingOptions {
        fit_mass: u.fit_mass,
        ..UpdatingOptions::default()
    };
    let identified_kind = |i: usize| u.identified_kinds.as_ref().map(|k| k[i]);
    let result = match (&u.model_frequencies_hz, bridge, base) {
        (Some(base), _, _) => {
            let targets = targets(identified, identified_kind);
            // Frequencies given as numbers scale as √α with a uniform stiffness scale α.
            let model = |s: &[f64]| -> Result<Vec<f64>, String> {
                Ok(base.iter().map(|f| f * s[0].sqrt()).collect())
            };
            update_model(model, u.model_kinds.as_deref(), &targets, &options)
        }
        (None, Some(b), Some((_, kinds))) => {
            // Without identified kinds, every identified mode is taken as vertical bending
            // (what a vertical accelerometer on the deck sees first).
            let targets = targets(identified, |i| {
                Some(identified_kind(i).unwrap_or(ModeKind::VerticalBending))
            });
            let model = |s: &[f64]| -> Result<Vec<f64>, String> {
                let scaled = scaled_bridge(&b.model, s[0], s.get(1).copied().unwrap_or(1.0));
                let (f, k) = bridge_modes(&scaled, b.mode_count).map_err(|e| error_chain(&e))?;
                Ok(align_by_kind(&f, &k, kinds))
            };
            update_model(model, Some(kinds), &targets, &options)
        }
        _ => return Err(MeasureError::input(
            "updating",
            "model updating needs a model: give updating.model_frequencies_hz or a bridge model",
        )),
    };
    result.map_err(|e| {
        let field = if u.model_frequencies_hz.is_some() {
            "updating.model_frequencies_hz"
        } else {
            "bridge"
        };
        let message = match e {
            SignalError::NotIdentifiable { cosine } if bridge.is_some() => format!(
                "the stiffness and the added (pavement) mass of this bridge change the paired frequencies alike (sensitivity cosine {cosine}): these modes cannot separate them; set fit_mass = false, or identify modes that feel the pavement differently (give identified_kinds, for example a torsion mode)"
            ),
            other => other.to_string(),
        };
        MeasureError::input(field, message)
    })
}

/// The identified frequencies as targets of the updating, with their kinds.
fn targets(
    identified: &[IdentifiedMode],
    kind: impl Fn(usize) -> Option<ModeKind>,
) -> Vec<IdentifiedFrequency> {
    identified
        .iter()
        .enumerate()
        .map(|(i, p)| IdentifiedFrequency {
            frequency_hz: p.frequency_hz,
            kind: kind(i),
        })
        .collect()
}
