//! Model calibration with several parameters (the paper's §6 model updating, extended): the
//! bridge model's girder stiffness (one factor, or one per span), its added (pavement) mass and
//! the vertical stiffness of its elastic bearings are fitted to the identified frequencies and,
//! where several sensors give mode shapes, to the shapes at the sensors; modes are paired by
//! MAC; the fit reports its residuals, the standard uncertainty of every parameter and the
//! calibrated model.
//!
//! With θ = ln(factors), the residuals
//!
//! ```text
//! r_f,i = f_j(i)(θ)/f̂_i − 1                                   (every pair i ↔ j(i))
//! r_φ,i = w_φ·(φ_j(i)(θ)/‖φ_j(i)‖·sign − φ̂_i/‖φ̂_i‖)            (pairs with shapes)
//! ```
//!
//! are minimised by Levenberg–Marquardt (forward-difference Jacobian, damping λ·diag(JᵀJ)).
//! w_φ = [`SHAPE_WEIGHT`]: a shape component is typically identified to a few per cent and a
//! frequency to a few tenths of a per cent. The parameters' covariance is
//! s²·(JᵀJ)⁻¹ with s² = Σr²/(n − p) (n residuals, p parameters), reported as the factors'
//! standard uncertainties; a JᵀJ whose condition number exceeds [`MAXIMUM_CONDITION`] is refused:
//! its parameters are not identifiable from these modes.
//!
//! A factor per span multiplies E of the girder elements in that span. It is built from the
//! model's stiffness-loss regions (`model::damage`, factors ≤ 1) below a global factor equal to
//! the largest one, so the transverse members (slab strips, diaphragms) scale with the largest
//! span factor.
//!
//! The bearing factor multiplies the vertical stiffness of every elastic support: a beam's
//! `SupportKind::Elastic` supports, a grillage's bearings with a vertical stiffness, and the
//! springs of changed supports (`damage.support_changes`, which replace the support's own
//! restraint). Rigid supports stay rigid and removed ones removed; rotational springs are kept.
//! A model without any elastic support is refused: it has no bearing stiffness to fit.

use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use super::{error_chain, IdentifiedMode, MeasureError};
use crate::fe::{discretise, MeshOptions};
use crate::measure::measurement::{CalibrationParameter, MeasuredBridge, SensorLocation};
use crate::modal::{solve_modes_with, CheckModes, ModalBasis, ModalOptions, ModeKind};
use crate::model::{support_positions_of, BridgeModel, StiffnessLoss, SupportKind};
use crate::signal::mac;

use super::updating::{scaled_bridge, ModelFrequencies};

/// Weight of a mode-shape component against a relative frequency error.
pub const SHAPE_WEIGHT: f64 = 0.1;

/// Condition number of JᵀJ above which the parameters are not identifiable.
pub const MAXIMUM_CONDITION: f64 = 1e10;

/// Smallest MAC for a pair found by shapes.
pub const MINIMUM_PAIRING_MAC: f64 = 0.5;

/// Relative frequency window in which a model mode may pair with an identified one.
const PAIRING_WINDOW: f64 = 0.3;

/// Levenberg–Marquardt iterations at most.
const MAX_ITERATIONS: usize = 40;

/// Forward-difference step in ln(factor).
const STEP: f64 = 1e-5;

/// Largest change of ln(factor) in one Levenberg–Marquardt step.
const MAX_STEP: f64 = 0.5;

/// One fitted factor.
#[derive(Debug, Clone, Serialize)]
pub struct CalibratedParameter {
    /// "stiffness", "stiffness_span_<k>" (1-based), "added_mass" or "bearing_stiffness".
    pub name: String,
    /// The factor on the model's value after calibration [-] (1 before).
    pub factor: f64,
    /// Its standard uncertainty [-], when the fit has more residuals than parameters.
    pub standard_uncertainty: Option<f64>,
}

/// One identified mode and its model partner.
#[derive(Debug, Clone, Serialize)]
pub struct CalibratedMode {
    /// Index of the identified mode (0-based, in frequency order).
    pub identified_index: usize,
    /// The model's mode (1-based, as `vbi modes` lists them).
    pub model_mode: usize,
    /// Its kind.
    pub kind: ModeKind,
    /// Identified frequency [Hz].
    pub identified_hz: f64,
    /// The model's before calibration [Hz].
    pub initial_hz: f64,
    /// After [Hz].
    pub updated_hz: f64,
    /// MAC of the shapes at the sensors before calibration [-], where shapes were identified.
    pub mac_initial: Option<f64>,
    /// After [-].
    pub mac_updated: Option<f64>,
}

/// The calibration's result.
#[derive(Debug, Clone, Serialize)]
pub struct Calibration {
    /// The fitted factors.
    pub parameters: Vec<CalibratedParameter>,
    /// How the pairs were found: "mac" (shapes at two or more sensors) or "order_in_kind".
    pub pairing: &'static str,
    /// The pairs.
    pub modes: Vec<CalibratedMode>,
    /// RMS of the relative frequency errors before and after [-].
    pub initial_rms_frequency_error: f64,
    /// After [-].
    pub updated_rms_frequency_error: f64,
    /// Residuals (frequencies and shape components) [-].
    pub residual_count: usize,
    /// Condition number of JᵀJ at the solution [-].
    pub condition_number: f64,
    /// Iterations of Levenberg–Marquardt.
    pub iterations: usize,
    /// Frequencies of every model mode after calibration [Hz], in the model's order.
    pub updated_frequencies_hz: Vec<f64>,
    /// The bridge model with the fitted factors applied: the model behind
    /// `updated_frequencies_hz`, for the model's influence lines.
    #[serde(skip)]
    pub model: BridgeModel,
}

/// The model's modes at one set of factors: frequencies, kinds and shapes at the sensors.
struct ModelModes {
    frequencies: Vec<f64>,
    kinds: Vec<ModeKind>,
    /// `shapes[j]`: mode j at the sensors.
    shapes: Vec<Vec<f64>>,
}

/// The fitted parameters: each with its role.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Role {
    Stiffness,
    Span(usize),
    AddedMass,
    BearingStiffness,
}

impl Role {
    fn name(self) -> String {
        match self {
            Role::Stiffness => "stiffness".into(),
            Role::Span(k) => format!("stiffness_span_{}", k + 1),
            Role::AddedMass => "added_mass".into(),
            Role::BearingStiffness => "bearing_stiffness".into(),
        }
    }
}

/// Calibrates `bridge` to the identified modes (with shapes at `sensors` where identified).
pub(super) fn calibrate(
    bridge: &MeasuredBridge,
    parameters: &[CalibrationParameter],
    identified: &[IdentifiedMode],
    sensors: &[SensorLocation],
) -> Result<Calibration, MeasureError> {
    let roles = roles_of(&bridge.model, parameters)?;
    check_sensors(&bridge.model, sensors)?;
    let initial = model_modes(bridge, &roles, &vec![0.0; roles.len()], sensors, None)?;
    // Every evaluation's modes in the unmodified model's order: the r-th mode of each kind
    // keeps its index, so a factor that lets a torsion mode overtake a bending one neither
    // swaps the pairs nor the K1 mode numbers.
    let reference = initial.kinds.clone();
    let evaluate =
        |theta: &[f64]| model_modes(bridge, &roles, theta, sensors, Some(reference.as_slice()));
    let (pairs, pairing) = pair(identified, &initial, sensors.len())?;
    let residuals = |modes: &ModelModes| residuals_of(identified, &pairs, modes);
    if residuals(&initial).len() <= roles.len() {
        return Err(MeasureError::input(
            "updating.parameters",
            format!(
                "{} parameters cannot be fitted to {} residuals ({} paired modes{}); identify more modes (spectrum.modes, more sensors with position_m) or fit fewer parameters",
                roles.len(),
                residuals(&initial).len(),
                pairs.len(),
                if sensors.len() >= 2 { " with their shapes" } else { "" }
            ),
        ));
    }
    let fit = levenberg_marquardt(&evaluate, &residuals, roles.len())?;
    let updated = evaluate(&fit.theta)?;
    let covariance = fit.covariance();
    let parameters = roles
        .iter()
        .enumerate()
        .map(|(k, role)| {
            let factor = fit.theta[k].exp();
            CalibratedParameter {
                name: role.name(),
                factor,
                standard_uncertainty: covariance.as_ref().map(|c| factor * c[(k, k)].sqrt()),
            }
        })
        .collect();
    let frequency_error = |modes: &ModelModes| {
        let sum: f64 = pairs
            .iter()
            .map(|&(i, j)| (modes.frequencies[j] / identified[i].frequency_hz - 1.0).powi(2))
            .sum();
        (sum / pairs.len() as f64).sqrt()
    };
    let shape_mac = |modes: &ModelModes, i: usize, j: usize| {
        identified[i]
            .shape
            .as_ref()
            .filter(|_| sensors.len() >= 2)
            .map(|s| mac(s, &modes.shapes[j]))
    };
    let modes = pairs
        .iter()
        .map(|&(i, j)| CalibratedMode {
            identified_index: i,
            model_mode: j + 1,
            kind: initial.kinds[j],
            identified_hz: identified[i].frequency_hz,
            initial_hz: initial.frequencies[j],
            updated_hz: updated.frequencies[j],
            mac_initial: shape_mac(&initial, i, j),
            mac_updated: shape_mac(&updated, i, j),
        })
        .collect();
    Ok(Calibration {
        parameters,
        pairing,
        modes,
        initial_rms_frequency_error: frequency_error(&initial),
        updated_rms_frequency_error: frequency_error(&updated),
        residual_count: residuals(&updated).len(),
        condition_number: fit.condition,
        iterations: fit.iterations,
        updated_frequencies_hz: updated.frequencies,
        model: calibrated_bridge(&bridge.model, &roles, &fit.theta),
    })
}

/// The roles of the parameters asked for, checked against the model.
fn roles_of(
    model: &BridgeModel,
    parameters: &[CalibrationParameter],
) -> Result<Vec<Role>, MeasureError> {
    let has = |p| parameters.contains(&p);
    if has(CalibrationParameter::Stiffness) && has(CalibrationParameter::SpanStiffness) {
        return Err(MeasureError::input(
            "updating.parameters",
            "\"stiffness\" and \"span_stiffness\" together fit the same stiffness twice; choose one",
        ));
    }
    let native = matches!(
        model,
        BridgeModel::ContinuousBeam(_) | BridgeModel::Grillage(_)
    );
    if !native
        && parameters
            .iter()
            .any(|p| *p != CalibrationParameter::Stiffness)
    {
        return Err(MeasureError::input(
            "updating.parameters",
            "span_stiffness, added_mass and bearing_stiffness need a bridge built by vbi (a continuous beam or a grillage); an imported model allows \"stiffness\" only",
        ));
    }
    if has(CalibrationParameter::BearingStiffness) && !has_elastic_bearing(model) {
        let how = match model {
            BridgeModel::Grillage(_) => {
                "give the bearings a vertical stiffness in the bridge file (vertical_stiffness_n_per_m in [bridge.bearings] or in a supports table { kind = \"roller\", vertical_stiffness_n_per_m = … })"
            }
            _ => {
                "give supports a vertical spring in the bridge file (a supports item { kind = \"elastic\", vertical_stiffness_n_per_m = … })"
            }
        };
        return Err(MeasureError::input(
            "updating.parameters",
            format!(
                "\"bearing_stiffness\" scales the vertical stiffness of the elastic bearings, and every support of this bridge model is rigid (or removed): a rigid bearing has no stiffness to calibrate; {how}, or a [[bridge.support_change]] with a positive vertical_stiffness_n_per_m; or remove bearing_stiffness from the parameters"
            ),
        ));
    }
    if let Some(twice) = parameters
        .iter()
        .enumerate()
        .find(|(i, p)| parameters[..*i].contains(p))
    {
        return Err(MeasureError::input(
            "updating.parameters",
            format!(
                "\"{}\" is listed twice; list each parameter once",
                twice.1.input_name()
            ),
        ));
    }
    let mut roles = Vec::new();
    for p in parameters {
        match p {
            CalibrationParameter::Stiffness => roles.push(Role::Stiffness),
            CalibrationParameter::SpanStiffness => {
                roles.extend((0..model.span_lengths().len()).map(Role::Span))
            }
            CalibrationParameter::AddedMass => roles.push(Role::AddedMass),
            CalibrationParameter::BearingStiffness => roles.push(Role::BearingStiffness),
        }
    }
    Ok(roles)
}

/// The bridge with the factors e^θ applied.
fn calibrated_bridge(base: &BridgeModel, roles: &[Role], theta: &[f64]) -> BridgeModel {
    let (mut stiffness, mut mass, mut bearing, mut spans) = (1.0, 1.0, 1.0, Vec::new());
    for (role, t) in roles.iter().zip(theta) {
        match role {
            Role::Stiffness => stiffness = t.exp(),
            Role::AddedMass => mass = t.exp(),
            Role::BearingStiffness => bearing = t.exp(),
            Role::Span(k) => spans.push((*k, t.exp())),
        }
    }
    let largest = spans.iter().map(|s| s.1).fold(f64::MIN, f64::max);
    let global = if spans.is_empty() { stiffness } else { largest };
    let mut model = scaled_bridge(base, global, mass);
    if bearing != 1.0 {
        scale_bearings(&mut model, bearing);
    }
    let supports = support_positions_of(base.span_lengths());
    let damage = match &mut model {
        BridgeModel::ContinuousBeam(b) => Some(&mut b.damage),
        BridgeModel::Grillage(g) => Some(&mut g.damage),
        _ => None,
    };
    if let Some(damage) = damage {
        for (k, factor) in spans {
            let relative = factor / largest;
            if relative < 1.0 {
                damage.stiffness_losses.push(StiffnessLoss {
                    start: supports[k],
                    end: supports[k + 1],
                    girder: None,
                    elastic_modulus_factor: relative,
                });
            }
        }
    }
    model
}

/// Whether some support of the model holds it by a vertical spring of positive stiffness: an
/// elastic support (a beam) or bearing (a grillage), or a changed support, which replaces the
/// support's own restraint.
fn has_elastic_bearing(model: &BridgeModel) -> bool {
    let damage = model.damage();
    let elastic =
        |j: usize, own: Option<f64>| damage.support_stiffness(j).or(own).is_some_and(|k| k > 0.0);
    match model {
        BridgeModel::ContinuousBeam(b) => b.supports.iter().enumerate().any(|(j, s)| {
            let own = match *s {
                SupportKind::Elastic {
                    vertical_stiffness, ..
                } => Some(vertical_stiffness),
                _ => None,
            };
            elastic(j, own)
        }),
        BridgeModel::Grillage(g) => {
            (0..g.supports.len()).any(|j| elastic(j, g.bearing(j).vertical_stiffness))
        }
        _ => false,
    }
}

/// Multiplies the vertical stiffness of every elastic support of `model` by `factor`: a beam's
/// elastic supports, a grillage's bearings with a stiffness, and the changed supports' springs
/// (a removed support, stiffness 0, stays removed). Rigid supports and rotational springs stay.
fn scale_bearings(model: &mut BridgeModel, factor: f64) {
    let damage = match model {
        BridgeModel::ContinuousBeam(b) => {
            for support in &mut b.supports {
                if let SupportKind::Elastic {
                    vertical_stiffness, ..
                } = support
                {
                    *vertical_stiffness *= factor;
                }
            }
            &mut b.damage
        }
        BridgeModel::Grillage(g) => {
            for k in g
                .bearings
                .iter_mut()
                .filter_map(|b| b.vertical_stiffness.as_mut())
            {
                *k *= factor;
            }
            &mut g.damage
        }
        _ => return,
    };
    for change in &mut damage.support_changes {
        change.vertical_stiffness *= factor;
    }
}

/// Sensors on the model's deck: x from 0 to the bridge's length (a stencil beyond it reads 0).
fn check_sensors(model: &BridgeModel, sensors: &[SensorLocation]) -> Result<(), MeasureError> {
    let length = model.length();
    match sensors
        .iter()
        .find(|s| !(0.0..=length).contains(&s.position))
    {
        Some(s) => Err(MeasureError::input(
            "channels",
            format!(
                "a sensor's position_m {} m lies off the bridge model's deck (0 to {length} m)",
                s.position
            ),
        )),
        None => Ok(()),
    }
}

/// Frequencies, kinds and sensor shapes of the model at e^θ; with `reference` (the kinds of
/// the unmodified model's modes) reordered so that index j holds the r-th mode of the kind of
/// `reference[j]`, r its rank within that kind (an error when the model lacks one).
fn model_modes(
    bridge: &MeasuredBridge,
    roles: &[Role],
    theta: &[f64],
    sensors: &[SensorLocation],
    reference: Option<&[ModeKind]>,
) -> Result<ModelModes, MeasureError> {
    let model = calibrated_bridge(&bridge.model, roles, theta);
    let failed = |message: String| MeasureError::Input {
        field: "updating.parameters".into(),
        message: format!(
            "the bridge model with factors {:?} failed: {message}",
            theta.iter().map(|t| t.exp()).collect::<Vec<_>>()
        ),
    };
    let fe = discretise(&model, &MeshOptions::default()).map_err(|e| failed(e.to_string()))?;
    let options = ModalOptions {
        mode_count: bridge.mode_count,
        ..ModalOptions::default()
    };
    // The frequencies and shapes alone: no check modes.
    let basis =
        solve_modes_with(&fe, &options, CheckModes::Skip).map_err(|e| failed(error_chain(&e)))?;
    let modes = ModelModes {
        frequencies: basis.modes.iter().map(|m| m.frequency_hz()).collect(),
        kinds: basis.modes.iter().map(|m| m.kind).collect(),
        shapes: sensor_shapes(&basis, sensors),
    };
    let Some(reference) = reference else {
        return Ok(modes);
    };
    let mut order = Vec::with_capacity(reference.len());
    for (j, kind) in reference.iter().enumerate() {
        let rank = reference[..j].iter().filter(|k| *k == kind).count();
        let index = (0..modes.kinds.len())
            .filter(|&i| modes.kinds[i] == *kind)
            .nth(rank)
            .ok_or_else(|| {
                failed(format!(
                    "it has fewer {kind:?} modes than the unmodified one"
                ))
            })?;
        order.push(index);
    }
    Ok(ModelModes {
        frequencies: order.iter().map(|&i| modes.frequencies[i]).collect(),
        kinds: order.iter().map(|&i| modes.kinds[i]).collect(),
        shapes: order.iter().map(|&i| modes.shapes[i].clone()).collect(),
    })
}

/// Each mode's vertical value at each sensor.
fn sensor_shapes(basis: &ModalBasis, sensors: &[SensorLocation]) -> Vec<Vec<f64>> {
    let count = basis.mode_count();
    let mut shapes = vec![vec![0.0; sensors.len()]; count];
    let mut values = vec![0.0; count];
    for (s, sensor) in sensors.iter().enumerate() {
        basis
            .deck
            .stencil(sensor.position, sensor.lateral_position)
            .values_many(
                &basis.deck_deflection,
                &basis.deck_slope,
                count,
                &mut values,
            );
        for (shape, v) in shapes.iter_mut().zip(&values) {
            shape[s] = *v;
        }
    }
    shapes
}

/// The pairs (identified index, model index) and how they were found.
type Pairing = (Vec<(usize, usize)>, &'static str);

/// Pairs (identified, model) by the best MAC within ±30 % in frequency when shapes were
/// identified at two or more sensors, else the n-th identified with the n-th vertical-bending
/// mode.
fn pair(
    identified: &[IdentifiedMode],
    model: &ModelModes,
    sensor_count: usize,
) -> Result<Pairing, MeasureError> {
    let by_shape = sensor_count >= 2 && identified.iter().all(|p| p.shape.is_some());
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    let bending: Vec<usize> = (0..model.kinds.len())
        .filter(|&j| model.kinds[j] == ModeKind::VerticalBending)
        .collect();
    for (i, p) in identified.iter().enumerate() {
        let partner = if by_shape {
            let shape = p.shape.as_deref().unwrap_or_default();
            (0..model.frequencies.len())
                .filter(|&j| (model.frequencies[j] / p.frequency_hz - 1.0).abs() < PAIRING_WINDOW)
                .map(|j| (j, mac(shape, &model.shapes[j])))
                .filter(|(_, m)| *m >= MINIMUM_PAIRING_MAC)
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(j, _)| j)
        } else {
            bending.get(i).copied()
        };
        let Some(j) = partner else {
            return Err(MeasureError::input(
                "updating",
                format!(
                    "the identified mode at {:.3} Hz has no model mode to pair with ({}); check the sensors' position_m and lateral_position_m, or the band of the spectrum",
                    p.frequency_hz,
                    if by_shape {
                        format!("no MAC of at least {MINIMUM_PAIRING_MAC} within ±30 % in frequency")
                    } else {
                        "the model has fewer vertical bending modes".to_string()
                    }
                ),
            ));
        };
        if let Some(&(other, _)) = pairs.iter().find(|&&(_, k)| k == j) {
            return Err(MeasureError::input(
                "updating",
                format!(
                    "the identified modes at {:.3} and {:.3} Hz both pair with model mode {}: one of them is not the bridge's, or the sensors cannot tell them apart",
                    identified[other].frequency_hz,
                    p.frequency_hz,
                    j + 1
                ),
            ));
        }
        pairs.push((i, j));
    }
    Ok((pairs, if by_shape { "mac" } else { "order_in_kind" }))
}

/// The residual vector of the pairs.
fn residuals_of(
    identified: &[IdentifiedMode],
    pairs: &[(usize, usize)],
    model: &ModelModes,
) -> Vec<f64> {
    let mut r: Vec<f64> = pairs
        .iter()
        .map(|&(i, j)| model.frequencies[j] / identified[i].frequency_hz - 1.0)
        .collect();
    for &(i, j) in pairs {
        let Some(measured) = identified[i].shape.as_deref() else {
            continue;
        };
        if measured.len() < 2 {
            continue;
        }
        let unit = |v: &[f64]| -> Vec<f64> {
            let norm = v
                .iter()
                .map(|x| x * x)
                .sum::<f64>()
                .sqrt()
                .max(f64::MIN_POSITIVE);
            v.iter().map(|x| x / norm).collect()
        };
        let (a, b) = (unit(measured), unit(&model.shapes[j]));
        let sign = if a.iter().zip(&b).map(|(x, y)| x * y).sum::<f64>() < 0.0 {
            -1.0
        } else {
            1.0
        };
        r.extend(a.iter().zip(&b).map(|(x, y)| SHAPE_WEIGHT * (sign * y - x)));
    }
    r
}

/// The minimum found.
struct Fit {
    theta: Vec<f64>,
    jacobian: DMatrix<f64>,
    residuals: DVector<f64>,
    condition: f64,
    iterations: usize,
}

impl Fit {
    /// s²·(JᵀJ)⁻¹ on θ, when there are more residuals than parameters.
    fn covariance(&self) -> Option<DMatrix<f64>> {
        let (n, p) = self.jacobian.shape();
        if n <= p {
            return None;
        }
        let s2 = self.residuals.norm_squared() / (n - p) as f64;
        let normal = self.jacobian.transpose() * &self.jacobian;
        normal.try_inverse().map(|inverse| inverse * s2)
    }
}

/// Levenberg–Marquardt on θ from 0 (the unmodified model).
fn levenberg_marquardt(
    evaluate: &dyn Fn(&[f64]) -> Result<ModelModes, MeasureError>,
    residuals: &dyn Fn(&ModelModes) -> Vec<f64>,
    count: usize,
) -> Result<Fit, MeasureError> {
    let mut theta = vec![0.0; count];
    let mut r = DVector::from_vec(residuals(&evaluate(&theta)?));
    let mut lambda = 1e-3;
    let mut iterations = 0;
    let mut jacobian = jacobian_at(evaluate, residuals, &theta, &r)?;
    while iterations < MAX_ITERATIONS {
        iterations += 1;
        let normal = jacobian.transpose() * &jacobian;
        let gradient = jacobian.transpose() * &r;
        let mut damped = normal.clone();
        for k in 0..count {
            damped[(k, k)] += lambda * normal[(k, k)].max(1e-12);
        }
        let Some(mut step) = damped.lu().solve(&(-gradient)) else {
            break;
        };
        // At most a factor e^MAX_STEP per iteration: a weakly determined parameter must not
        // jump to a model that cannot be built.
        let largest = step.amax();
        if largest > MAX_STEP {
            step *= MAX_STEP / largest;
        }
        let trial: Vec<f64> = theta.iter().zip(step.iter()).map(|(t, s)| t + s).collect();
        // A trial model that fails (or lacks a paired mode) is a rejected step.
        let trial_r = match evaluate(&trial) {
            Ok(modes) => DVector::from_vec(residuals(&modes)),
            Err(_) => DVector::from_element(r.len(), f64::INFINITY),
        };
        if trial_r.norm_squared() < r.norm_squared() {
            theta = trial;
            r = trial_r;
            lambda = (lambda / 10.0).max(1e-12);
            if step.amax() < 1e-8 {
                break;
            }
            jacobian = jacobian_at(evaluate, residuals, &theta, &r)?;
        } else {
            lambda *= 10.0;
            if lambda > 1e8 {
                break;
            }
        }
    }
    let condition = condition_number(&(jacobian.transpose() * &jacobian));
    if condition.is_nan() || condition > MAXIMUM_CONDITION {
        return Err(MeasureError::input(
            "updating.parameters",
            format!(
                "the parameters are not identifiable from these modes (the normal matrix's condition number is {condition:.3e}, above {MAXIMUM_CONDITION:e}): two of them change the frequencies and shapes alike; fit fewer parameters or identify more modes and sensors"
            ),
        ));
    }
    Ok(Fit {
        theta,
        jacobian,
        residuals: r,
        condition,
        iterations,
    })
}

/// Forward-difference Jacobian of the residuals at θ.
fn jacobian_at(
    evaluate: &dyn Fn(&[f64]) -> Result<ModelModes, MeasureError>,
    residuals: &dyn Fn(&ModelModes) -> Vec<f64>,
    theta: &[f64],
    r: &DVector<f64>,
) -> Result<DMatrix<f64>, MeasureError> {
    let mut jacobian = DMatrix::zeros(r.len(), theta.len());
    for k in 0..theta.len() {
        let mut shifted = theta.to_vec();
        shifted[k] += STEP;
        let rk = residuals(&evaluate(&shifted)?);
        for (i, v) in rk.iter().enumerate() {
            jacobian[(i, k)] = (v - r[i]) / STEP;
        }
    }
    Ok(jacobian)
}

/// Largest over smallest eigenvalue of a symmetric positive semi-definite matrix (infinite when
/// singular).
pub(super) fn condition_number(normal: &DMatrix<f64>) -> f64 {
    let eigen = nalgebra::SymmetricEigen::new(normal.clone());
    let largest = eigen.eigenvalues.iter().cloned().fold(0.0, f64::max);
    let smallest = eigen
        .eigenvalues
        .iter()
        .cloned()
        .fold(f64::INFINITY, f64::min);
    if smallest > 0.0 {
        largest / smallest
    } else {
        f64::INFINITY
    }
}

/// The model's frequencies after a calibration (here, with the calibration, so that updating
/// does not refer back to it).
impl ModelFrequencies {
    /// Takes the calibrated model's frequencies (in its own mode order) as the model's.
    pub fn calibrated(&mut self, calibration: &Calibration) {
        let updated = calibration.updated_frequencies_hz.clone();
        if let Some(bridge) = self.bridge.as_mut() {
            bridge.updated_frequencies_hz = Some(updated.clone());
        }
        self.frequencies = Some(updated);
        self.model = Some(calibration.model.clone());
        self.fitted = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{BeamSection, Bearing, ContinuousBeam, SupportChange};

    /// A three-span beam (20 + 25 + 20 m, EI 1e10 N·m², 10 t/m, 2 t/m of pavement).
    fn beam() -> MeasuredBridge {
        let mut beam = ContinuousBeam::pinned(
            vec![20.0, 25.0, 20.0],
            BeamSection {
                flexural_rigidity: 1e10,
                mass_per_length: 10e3,
            },
        );
        beam.added_mass_per_length = 2e3;
        MeasuredBridge {
            label: "three-span beam".into(),
            model: BridgeModel::ContinuousBeam(beam),
            mode_count: 8,
        }
    }

    /// Accelerometers at the quarter and three-quarter points of every span.
    fn sensors() -> Vec<SensorLocation> {
        [5.0, 15.0, 26.25, 38.75, 50.0, 60.0]
            .into_iter()
            .map(|position| SensorLocation {
                position,
                lateral_position: 0.0,
            })
            .collect()
    }

    /// The first `count` modes of `bridge` with factors e^θ, as an identification gives them.
    fn identified_from(
        bridge: &MeasuredBridge,
        roles: &[Role],
        theta: &[f64],
        count: usize,
    ) -> Vec<IdentifiedMode> {
        let modes = model_modes(bridge, roles, theta, &sensors(), None).unwrap();
        (0..count)
            .map(|j| IdentifiedMode {
                frequency_hz: modes.frequencies[j],
                damping_ratio: None,
                damping_resolution_limited: false,
                frequency_std_hz: None,
                damping_std: None,
                shape: Some(modes.shapes[j].clone()),
                modal_phase_collinearity: None,
            })
            .collect()
    }

    #[test]
    fn a_softer_middle_span_is_found_from_frequencies_and_shapes_by_mac() {
        // Reference: modes of the same beam with E × 0.8 over span 2 (the model's own
        // stiffness-loss regions), three frequencies and shapes at six sensors, noise-free:
        // the fit gives back 1, 0.8, 1 to 1e-6 (the Jacobian's forward differences with a
        // step of 1e-5 in ln(factor) and the eigen solve's 1e-12 leave far less).
        let bridge = beam();
        let roles = [Role::Span(0), Role::Span(1), Role::Span(2)];
        let truth = [0.0, 0.8f64.ln(), 0.0];
        let identified = identified_from(&bridge, &roles, &truth, 3);
        let c = calibrate(
            &bridge,
            &[CalibrationParameter::SpanStiffness],
            &identified,
            &sensors(),
        )
        .unwrap();
        assert_eq!(c.pairing, "mac");
        let factors: Vec<f64> = c.parameters.iter().map(|p| p.factor).collect();
        for (got, exact) in factors.iter().zip([1.0, 0.8, 1.0]) {
            assert!((got - exact).abs() < 1e-6, "{factors:?}");
        }
        assert!(c.updated_rms_frequency_error < 1e-8, "{c:?}");
        assert!(c.initial_rms_frequency_error > 1e-2, "{c:?}");
        for mode in &c.modes {
            assert!(mode.mac_updated.unwrap() > 1.0 - 1e-10, "{mode:?}");
        }
        // A noise-free fit has (numerically) no scatter.
        for p in &c.parameters {
            assert!(p.standard_uncertainty.unwrap() < 1e-6, "{p:?}");
        }
    }

    #[test]
    fn a_uniform_stiffness_and_the_pavement_of_a_uniform_beam_are_refused_as_not_identifiable() {
        // Reference: ω² ∝ α·EI/(m̄ + β·m̄_a) for every mode of a uniform beam on rigid supports,
        // with the same shapes: α and β move every residual alike, JᵀJ is singular.
        let bridge = beam();
        let identified = identified_from(&bridge, &[Role::Stiffness], &[0.1], 3);
        let e = calibrate(
            &bridge,
            &[
                CalibrationParameter::Stiffness,
                CalibrationParameter::AddedMass,
            ],
            &identified,
            &sensors(),
        )
        .unwrap_err();
        match e {
            MeasureError::Input { field, message } => {
                assert_eq!(field, "updating.parameters");
                assert!(message.contains("not identifiable"), "{message}");
            }
            other => panic!("{other:?}"),
        }
    }

    /// The calibration of `bridge`'s one parameter `role` to three frequencies (no shapes) of
    /// the same model with the factor `factor`; pairs by order.
    fn fit_without_shapes(bridge: MeasuredBridge, role: Role, factor: f64) -> Calibration {
        let mut identified = identified_from(&bridge, &[role], &[factor.ln()], 3);
        identified.iter_mut().for_each(|p| p.shape = None);
        let parameter = match role {
            Role::Stiffness => CalibrationParameter::Stiffness,
            Role::BearingStiffness => CalibrationParameter::BearingStiffness,
            Role::AddedMass => CalibrationParameter::AddedMass,
            Role::Span(_) => CalibrationParameter::SpanStiffness,
        };
        let c = calibrate(&bridge, &[parameter], &identified, &[]).unwrap();
        assert_eq!(c.pairing, "order_in_kind");
        c
    }

    #[test]
    fn without_shapes_modes_pair_by_order_and_a_stiffness_factor_is_fitted() {
        // Reference: frequencies scale as √α with a uniform stiffness factor α = 1.21: the fit
        // gives back 1.21 from the frequencies alone, pairs by order within the bending kind.
        let c = fit_without_shapes(beam(), Role::Stiffness, 1.21);
        assert!((c.parameters[0].factor - 1.21).abs() < 1e-6, "{c:?}");
    }

    /// The three-span beam of [`beam`] on elastic interior supports of k = 5e7 N/m each, about
    /// 48EI/L³ of its spans (3.1e7 N/m for the 25 m one, 6.0e7 N/m for the 20 m ones): the
    /// supports' deflection is comparable to the spans' own, so the springs move every frequency.
    fn beam_on_springs() -> MeasuredBridge {
        let mut bridge = beam();
        let BridgeModel::ContinuousBeam(b) = &mut bridge.model else {
            unreachable!()
        };
        for support in &mut b.supports[1..3] {
            *support = SupportKind::Elastic {
                vertical_stiffness: 5e7,
                rotational_stiffness: 0.0,
            };
        }
        bridge.label = "three-span beam on springs".into();
        bridge
    }

    /// Relative difference of each of two frequency lists (of equal length), the largest.
    fn largest_relative_difference(a: &[f64], b: &[f64]) -> f64 {
        assert_eq!(a.len(), b.len());
        a.iter()
            .zip(b)
            .map(|(x, y)| (x / y - 1.0).abs())
            .fold(0.0, f64::max)
    }

    /// Frequencies of every mode of `model` [Hz], `mode_count` of them, as calibration solves
    /// them.
    fn frequencies_of(model: &BridgeModel, mode_count: usize) -> Vec<f64> {
        let fe = discretise(model, &MeshOptions::default()).unwrap();
        let options = ModalOptions {
            mode_count,
            ..ModalOptions::default()
        };
        solve_modes_with(&fe, &options, CheckModes::Skip)
            .unwrap()
            .modes
            .iter()
            .map(|m| m.frequency_hz())
            .collect()
    }

    #[test]
    fn softened_elastic_supports_and_the_girder_stiffness_are_found_from_frequencies_and_shapes() {
        // Reference: modes of the same beam with its elastic supports' vertical stiffness × 0.6
        // and EI × 1.1, four frequencies and shapes at six sensors, noise-free. The supports'
        // springs move the modes unlike EI does (a spring softens the modes that deflect the
        // interior supports most, EI scales a rigidly supported beam's ω² uniformly), so both
        // are identifiable. The data are exactly reproducible by the model (the same mesh and
        // eigen solver), so the minimum has zero residual and LM converges to it whatever the
        // forward-difference Jacobian's O(1e-5) error: the factors come back to the eigen
        // solve's precision, far below 1e-6.
        let bridge = beam_on_springs();
        let roles = [Role::Stiffness, Role::BearingStiffness];
        let truth = [1.1f64.ln(), 0.6f64.ln()];
        let identified = identified_from(&bridge, &roles, &truth, 4);
        // The springs matter: softening them by 0.6 alone moves the first frequency by more
        // than a per cent.
        let softer = identified_from(&bridge, &[Role::BearingStiffness], &[0.6f64.ln()], 1);
        let intact = identified_from(&bridge, &[], &[], 1);
        assert!(softer[0].frequency_hz / intact[0].frequency_hz < 0.99);
        let c = calibrate(
            &bridge,
            &[
                CalibrationParameter::Stiffness,
                CalibrationParameter::BearingStiffness,
            ],
            &identified,
            &sensors(),
        )
        .unwrap();
        assert_eq!(c.pairing, "mac");
        let names: Vec<&str> = c.parameters.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["stiffness", "bearing_stiffness"]);
        assert!((c.parameters[0].factor - 1.1).abs() < 1e-6, "{c:?}");
        assert!((c.parameters[1].factor - 0.6).abs() < 1e-6, "{c:?}");
        assert!(c.updated_rms_frequency_error < 1e-8, "{c:?}");
        assert!(c.initial_rms_frequency_error > 1e-2, "{c:?}");
        // The returned model carries the fitted springs, rigid ends kept.
        let BridgeModel::ContinuousBeam(b) = &c.model else {
            panic!("{:?}", c.model)
        };
        assert_eq!(b.supports[0], SupportKind::Pinned);
        for support in &b.supports[1..3] {
            let SupportKind::Elastic {
                vertical_stiffness, ..
            } = *support
            else {
                panic!("{support:?}")
            };
            assert!((vertical_stiffness / (5e7 * c.parameters[1].factor) - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn a_bearing_factor_alone_is_fitted_to_frequencies_without_shapes() {
        // Reference: the beam's elastic supports × 0.6, three frequencies only (paired by order):
        // one parameter from three exact residuals comes back as exactly as above.
        let c = fit_without_shapes(beam_on_springs(), Role::BearingStiffness, 0.6);
        assert_eq!(c.parameters[0].name, "bearing_stiffness");
        assert!((c.parameters[0].factor - 0.6).abs() < 1e-6, "{c:?}");
    }

    #[test]
    fn a_bearing_factor_on_rigid_supports_is_refused_at_updating_parameters() {
        // Reference: pinned supports have no vertical stiffness; the refusal says how to give one.
        let bridge = beam();
        let identified = identified_from(&bridge, &[], &[], 3);
        let e = calibrate(
            &bridge,
            &[CalibrationParameter::BearingStiffness],
            &identified,
            &sensors(),
        )
        .unwrap_err();
        match e {
            MeasureError::Input { field, message } => {
                assert_eq!(field, "updating.parameters");
                assert!(message.contains("rigid"), "{message}");
                assert!(message.contains("vertical_stiffness_n_per_m"), "{message}");
            }
            other => panic!("{other:?}"),
        }
        // A removed support (a changed support of stiffness 0) is no spring either.
        let mut model = bridge.model.clone();
        model.damage_mut().support_changes.push(SupportChange {
            support: 1,
            vertical_stiffness: 0.0,
        });
        assert!(!has_elastic_bearing(&model));
        model.damage_mut().support_changes[0].vertical_stiffness = 1e8;
        assert!(has_elastic_bearing(&model));
    }

    #[test]
    fn the_bearing_factor_scales_grillage_bearings_and_changed_supports_and_keeps_rigid_ones() {
        // Reference: the factor multiplies every finite vertical stiffness (a grillage's
        // bearings, the changed supports' springs); rigid bearings (None) stay rigid, rotational
        // springs are kept, and a model of rigid bearings only has no elastic one.
        let mut model = crate::model::paper_bridge(2, 20.0);
        assert!(!has_elastic_bearing(&model));
        let BridgeModel::Grillage(g) = &mut model else {
            unreachable!()
        };
        g.bearings = vec![
            Bearing::default(),
            Bearing {
                vertical_stiffness: Some(4e8),
                rotational_stiffness: 1e6,
                torsion_free: false,
            },
            Bearing::default(),
        ];
        g.damage.support_changes.push(SupportChange {
            support: 2,
            vertical_stiffness: 2e8,
        });
        assert!(has_elastic_bearing(&model));
        let scaled = calibrated_bridge(&model, &[Role::BearingStiffness], &[0.5f64.ln()]);
        let BridgeModel::Grillage(s) = &scaled else {
            unreachable!()
        };
        assert_eq!(s.bearings[0].vertical_stiffness, None);
        assert_eq!(s.bearings[2].vertical_stiffness, None);
        assert!((s.bearings[1].vertical_stiffness.unwrap() / 2e8 - 1.0).abs() < 1e-12);
        assert_eq!(s.bearings[1].rotational_stiffness, 1e6);
        assert!((s.damage.support_changes[0].vertical_stiffness / 1e8 - 1.0).abs() < 1e-12);
        // Nothing else changes.
        let mut back = scaled.clone();
        let BridgeModel::Grillage(b) = &mut back else {
            unreachable!()
        };
        b.bearings[1].vertical_stiffness = Some(4e8);
        b.damage.support_changes[0].vertical_stiffness = 2e8;
        assert_eq!(back, model);
    }

    /// The calibration's model, solved again, gives its `updated_frequencies_hz` within 1e-9
    /// relative (the same model through the same mesh and solver).
    fn assert_reproduces_its_frequencies(c: &Calibration, mode_count: usize) {
        let solved = frequencies_of(&c.model, mode_count);
        assert!(
            largest_relative_difference(&solved, &c.updated_frequencies_hz) < 1e-9,
            "{solved:?} {:?}",
            c.updated_frequencies_hz
        );
    }

    #[test]
    fn the_returned_model_carries_the_fitted_stiffness_and_reproduces_the_updated_frequencies() {
        // Reference: the stiffness fit of the uniform beam (α = 1.21): the returned model's EI is
        // the base EI × the fitted factor, and solving its modes gives `updated_frequencies_hz`
        // (the same model through the same mesh and solver: equal to round-off, 1e-9 relative;
        // every mode of a beam is vertical bending, so the reordering by kind keeps the order).
        let bridge = beam();
        let identified = identified_from(&bridge, &[Role::Stiffness], &[1.21f64.ln()], 3);
        let c = calibrate(
            &bridge,
            &[CalibrationParameter::Stiffness],
            &identified,
            &sensors(),
        )
        .unwrap();
        let BridgeModel::ContinuousBeam(b) = &c.model else {
            panic!("{:?}", c.model)
        };
        assert!(
            (b.section.flexural_rigidity / (1e10 * c.parameters[0].factor) - 1.0).abs() < 1e-12
        );
        assert_eq!(b.added_mass_per_length, 2e3);
        assert_reproduces_its_frequencies(&c, bridge.mode_count);
        // The same for the bearing fit's model, with springs.
        let springs = beam_on_springs();
        let identified = identified_from(&springs, &[Role::BearingStiffness], &[0.6f64.ln()], 3);
        let c = calibrate(
            &springs,
            &[CalibrationParameter::BearingStiffness],
            &identified,
            &sensors(),
        )
        .unwrap();
        assert_reproduces_its_frequencies(&c, springs.mode_count);
    }
}
