//! Model calibration with several parameters (the paper's §6 model updating, extended): the
//! bridge model's girder stiffness (one factor, or one per span) and its added (pavement) mass
//! are fitted to the identified frequencies and, where several sensors give mode shapes, to the
//! shapes at the sensors; modes are paired by MAC; the fit reports its residuals and the
//! standard uncertainty of every parameter.
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

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use super::{error_chain, IdentifiedMode, MeasureError};
use crate::fe::{discretise, MeshOptions};
use crate::modal::{solve_modes, ModalBasis, ModalOptions, ModeKind};
use crate::model::{support_positions_of, BridgeModel, StiffnessLoss};
use crate::pipeline::measurement::{MeasuredBridge, SensorLocation};
use crate::signal::mac;

use super::updating::scaled_bridge;

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

/// What calibration fits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CalibrationParameter {
    /// One factor on the girders' stiffness (E of a grillage, EI of a beam).
    Stiffness,
    /// One factor per span on the girders' stiffness.
    SpanStiffness,
    /// One factor on the added (pavement) mass.
    AddedMass,
}

/// One fitted factor.
#[derive(Debug, Clone, Serialize)]
pub struct CalibratedParameter {
    /// "stiffness", "stiffness_span_<k>" (1-based) or "added_mass".
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
}

impl Role {
    fn name(self) -> String {
        match self {
            Role::Stiffness => "stiffness".into(),
            Role::Span(k) => format!("stiffness_span_{}", k + 1),
            Role::AddedMass => "added_mass".into(),
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
            "span_stiffness and added_mass need a bridge built by vbi (a continuous beam or a grillage); an imported model allows \"stiffness\" only",
        ));
    }
    if let Some(twice) = parameters
        .iter()
        .enumerate()
        .find(|(i, p)| parameters[..*i].contains(p))
    {
        return Err(MeasureError::input(
            "updating.parameters",
            format!("{:?} is listed twice; list each parameter once", twice.1),
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
        }
    }
    Ok(roles)
}

/// The bridge with the factors e^θ applied.
fn calibrated_bridge(base: &BridgeModel, roles: &[Role], theta: &[f64]) -> BridgeModel {
    let (mut stiffness, mut mass, mut spans) = (1.0, 1.0, Vec::new());
    for (role, t) in roles.iter().zip(theta) {
        match role {
            Role::Stiffness => stiffness = t.exp(),
            Role::AddedMass => mass = t.exp(),
            Role::Span(k) => spans.push((*k, t.exp())),
        }
    }
    let largest = spans.iter().map(|s| s.1).fold(f64::MIN, f64::max);
    let global = if spans.is_empty() { stiffness } else { largest };
    let mut model = scaled_bridge(base, global, mass);
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
    let basis = solve_modes(&fe, &options).map_err(|e| failed(error_chain(&e)))?;
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
fn condition_number(normal: &DMatrix<f64>) -> f64 {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{BeamSection, ContinuousBeam};

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

    #[test]
    fn without_shapes_modes_pair_by_order_and_a_stiffness_factor_is_fitted() {
        // Reference: frequencies scale as √α with a uniform stiffness factor α = 1.21: the fit
        // gives back 1.21 from the frequencies alone, pairs by order within the bending kind.
        let bridge = beam();
        let mut identified = identified_from(&bridge, &[Role::Stiffness], &[1.21f64.ln()], 3);
        identified.iter_mut().for_each(|p| p.shape = None);
        let c = calibrate(
            &bridge,
            &[CalibrationParameter::Stiffness],
            &identified,
            &[],
        )
        .unwrap();
        assert_eq!(c.pairing, "order_in_kind");
        assert!((c.parameters[0].factor - 1.21).abs() < 1e-6, "{c:?}");
    }
}
