//! Model updating from identified natural frequencies: scale the stiffness (E) and, optionally,
//! a mass of a bridge model so that its first frequencies match the measured ones in the
//! least-squares sense.
//!
//! Identifiability: natural frequencies depend on stiffness and mass only through their ratio
//! (ω² = k/m for every mode when K and M are scaled uniformly), so a uniform stiffness scale and
//! a uniform mass scale cannot both be identified from frequencies alone. The model closure must
//! therefore scale only part of the mass (for example the added mass of pavement and barriers)
//! when a mass scale is fitted; [`update_model`] checks it and returns
//! [`SignalError::NotIdentifiable`] when the two scale factors act alike on every frequency.

use serde::{Deserialize, Serialize};

use super::SignalError;
use crate::modal::ModeKind;

/// A natural frequency identified from measurements.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IdentifiedFrequency {
    /// Frequency [Hz].
    pub frequency_hz: f64,
    /// Kind of mode, when known (pairs it with model modes of the same kind).
    pub kind: Option<ModeKind>,
}

/// Options of [`update_model`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UpdatingOptions {
    /// Also fit a mass scale (second parameter of the model closure) (default false).
    pub fit_mass: bool,
    /// Maximum Levenberg–Marquardt iterations (default 100).
    pub max_iterations: usize,
    /// Stop when the relative change of every scale factor is below this (default 1e-10).
    pub tolerance: f64,
    /// Forward-difference step in ln(scale) for the Jacobian (default 1e-6).
    pub finite_difference_step: f64,
}

impl Default for UpdatingOptions {
    fn default() -> Self {
        UpdatingOptions {
            fit_mass: false,
            max_iterations: 100,
            tolerance: 1e-10,
            finite_difference_step: 1e-6,
        }
    }
}

/// How the scale factors were found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum UpdatingMethod {
    /// √α = Σ f_i f̂_i / Σ f_i² (stiffness only, frequencies ∝ √α).
    ClosedForm,
    /// Levenberg–Marquardt with a forward-difference Jacobian.
    LevenbergMarquardt,
}

/// One identified mode paired with a model mode.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModePair {
    /// Index in the identified list.
    pub identified_index: usize,
    /// Index in the model's frequency list.
    pub model_index: usize,
    /// Identified frequency f̂ [Hz].
    pub identified_hz: f64,
    /// Model frequency before updating [Hz].
    pub initial_hz: f64,
    /// Model frequency after updating [Hz].
    pub updated_hz: f64,
}

/// Result of model updating.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UpdatedModel {
    /// Stiffness scale α (multiplies E) [-].
    pub stiffness_scale: f64,
    /// Mass scale β [-], when fitted.
    pub mass_scale: Option<f64>,
    /// Paired modes with frequencies before and after.
    pub pairs: Vec<ModePair>,
    /// Root-mean-square of f_model − f̂ over the pairs, before updating [Hz].
    pub initial_rms_error_hz: f64,
    /// The same after updating [Hz].
    pub updated_rms_error_hz: f64,
    /// Method used.
    pub method: UpdatingMethod,
    /// Iterations (0 for the closed form).
    pub iterations: usize,
    /// Every frequency of the updated model [Hz] (higher modes included, for the cut-off mode).
    pub updated_frequencies_hz: Vec<f64>,
}

/// Pairs identified modes with model modes by order, within kind when kinds are given: the
/// n-th identified mode of kind K goes with the n-th model mode of kind K; without kinds, the
/// n-th identified mode goes with the n-th model mode. Either every identified mode has a kind
/// or none has. Returns (identified index, model index) pairs.
pub fn pair_modes(
    identified: &[IdentifiedFrequency],
    model_kinds: Option<&[ModeKind]>,
    model_count: usize,
) -> Result<Vec<(usize, usize)>, SignalError> {
    let with_kind = identified.iter().filter(|m| m.kind.is_some()).count();
    if with_kind != 0 && with_kind != identified.len() {
        return Err(SignalError::MixedModeKinds {
            with_kind,
            without_kind: identified.len() - with_kind,
        });
    }
    let mut pairs = Vec::with_capacity(identified.len());
    match model_kinds {
        Some(kinds) if with_kind > 0 => {
            for (i, m) in identified.iter().enumerate() {
                let kind = m.kind.expect("checked above");
                let rank = identified[..i]
                    .iter()
                    .filter(|o| o.kind == Some(kind))
                    .count();
                let model_index = kinds
                    .iter()
                    .enumerate()
                    .filter(|(_, k)| **k == kind)
                    .nth(rank)
                    .map(|(j, _)| j)
                    .filter(|&j| j < model_count)
                    .ok_or(SignalError::NoModelModeToPair {
                        identified_index: i,
                        kind: Some(kind),
                        rank,
                    })?;
                pairs.push((i, model_index));
            }
        }
        _ => {
            for i in 0..identified.len() {
                if i >= model_count {
                    return Err(SignalError::NoModelModeToPair {
                        identified_index: i,
                        kind: None,
                        rank: i,
                    });
                }
                pairs.push((i, i));
            }
        }
    }
    Ok(pairs)
}

/// The closed-form stiffness scale: frequencies scale as √α, so min_α Σ(√α f_i − f̂_i)² gives
/// √α = Σ f_i f̂_i / Σ f_i².
pub fn stiffness_scale_closed_form(
    model_hz: &[f64],
    identified_hz: &[f64],
) -> Result<f64, SignalError> {
    let num: f64 = model_hz.iter().zip(identified_hz).map(|(f, g)| f * g).sum();
    let den: f64 = model_hz.iter().map(|f| f * f).sum();
    let root = num / den;
    if model_hz.is_empty()
        || model_hz.len() != identified_hz.len()
        || !(root.is_finite() && root > 0.0)
    {
        return Err(SignalError::BadFrequencies {
            model: model_hz.to_vec(),
            identified: identified_hz.to_vec(),
        });
    }
    Ok(root * root)
}

fn rms(a: &[f64], b: &[f64]) -> f64 {
    (a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>() / a.len().max(1) as f64).sqrt()
}

/// Least-squares model updating. `model(&scales)` returns the model's natural frequencies [Hz]
/// in ascending order for `scales = [α]` (stiffness only) or `[α, β]` (with `fit_mass`);
/// `(1, 1)` is the unmodified model. Residuals r_i = f_model,m(i)(α, β) − f̂_i over the pairs of
/// [`pair_modes`].
///
/// Starts from the closed form for the stiffness (exact when the closure scales every
/// stiffness uniformly, for example E of a grillage) and β = 1, then Levenberg–Marquardt on
/// θ = ln(α) or ln(α, β) (so the scales stay positive), Jacobian by forward differences, damping
/// λ·diag(JᵀJ) adapted ×10/÷10: it refines α when the closure scales only part of the stiffness
/// (EI of a beam on elastic supports) and fits β. The method reported is `ClosedForm` when the
/// refinement left the closed form unchanged.
/// Fails with [`SignalError::NotIdentifiable`] when the two Jacobian columns are parallel
/// (|cos| > 1 − 10⁻⁸), as for uniform stiffness and uniform mass scales.
pub fn update_model<F, E>(
    model: F,
    model_kinds: Option<&[ModeKind]>,
    identified: &[IdentifiedFrequency],
    options: &UpdatingOptions,
) -> Result<UpdatedModel, SignalError>
where
    F: Fn(&[f64]) -> Result<Vec<f64>, E>,
    E: std::fmt::Display,
{
    let parameters = if options.fit_mass { 2 } else { 1 };
    check_identified(identified, parameters)?;
    let evaluate = |scales: &[f64]| model_frequencies(&model, scales);
    let unit = vec![1.0; parameters];
    let initial = evaluate(&unit)?;
    let pairs = pair_modes(identified, model_kinds, initial.len())?;
    let target: Vec<f64> = pairs
        .iter()
        .map(|&(i, _)| identified[i].frequency_hz)
        .collect();
    let paired = |all: &[f64]| -> Vec<f64> { pairs.iter().map(|&(_, j)| all[j]).collect() };
    let initial_paired = paired(&initial);

    // Starting point: the closed form for the stiffness (exact when the closure scales every
    // stiffness uniformly), the unmodified mass.
    let alpha0 = stiffness_scale_closed_form(&initial_paired, &target)?;
    let residual = |theta: &[f64]| -> Result<Vec<f64>, SignalError> {
        let scales: Vec<f64> = theta.iter().map(|t| t.exp()).collect();
        let all = evaluate(&scales)?;
        check_paired_count(&pairs, &all, scales)?;
        Ok(paired(&all)
            .iter()
            .zip(&target)
            .map(|(f, g)| f - g)
            .collect())
    };
    let mut theta = vec![0.0; parameters];
    theta[0] = alpha0.ln();
    let (theta, iterations) = levenberg_marquardt(residual, theta, options)?;
    // The closed form stands when the refinement did not move it (a uniform stiffness scale).
    let moved =
        (theta[0] - alpha0.ln()).abs() > 1e-8 || theta.iter().skip(1).any(|t| t.abs() > 1e-8);
    let method = if moved {
        UpdatingMethod::LevenbergMarquardt
    } else {
        UpdatingMethod::ClosedForm
    };
    let scales: Vec<f64> = theta.iter().map(|t| t.exp()).collect();
    let updated = evaluate(&scales)?;
    check_paired_count(&pairs, &updated, scales.clone())?;
    let updated_paired = paired(&updated);
    Ok(UpdatedModel {
        stiffness_scale: scales[0],
        mass_scale: scales.get(1).copied(),
        pairs: pairs
            .iter()
            .enumerate()
            .map(|(n, &(i, j))| ModePair {
                identified_index: i,
                model_index: j,
                identified_hz: target[n],
                initial_hz: initial_paired[n],
                updated_hz: updated_paired[n],
            })
            .collect(),
        initial_rms_error_hz: rms(&initial_paired, &target),
        updated_rms_error_hz: rms(&updated_paired, &target),
        method,
        iterations,
        updated_frequencies_hz: updated,
    })
}

/// Checks the identified frequencies: at least one per fitted parameter, each positive and
/// finite.
fn check_identified(
    identified: &[IdentifiedFrequency],
    parameters: usize,
) -> Result<(), SignalError> {
    if identified.len() < parameters {
        return Err(SignalError::TooFewModes {
            identified: identified.len(),
            parameters,
        });
    }
    if let Some(i) = identified
        .iter()
        .position(|m| !(m.frequency_hz.is_finite() && m.frequency_hz > 0.0))
    {
        return Err(SignalError::BadFrequencies {
            model: Vec::new(),
            identified: vec![identified[i].frequency_hz],
        });
    }
    Ok(())
}

/// The model's frequencies at `scales`, refused when the model fails or returns a non-finite
/// frequency.
fn model_frequencies<F, E>(model: &F, scales: &[f64]) -> Result<Vec<f64>, SignalError>
where
    F: Fn(&[f64]) -> Result<Vec<f64>, E>,
    E: std::fmt::Display,
{
    let f = model(scales).map_err(|e| SignalError::ModelFailed {
        scales: scales.to_vec(),
        message: e.to_string(),
    })?;
    if f.iter().any(|v| !v.is_finite()) {
        return Err(SignalError::ModelFailed {
            scales: scales.to_vec(),
            message: format!("non-finite frequencies {f:?}"),
        });
    }
    Ok(f)
}

/// Checks that the model at `scales` returned every paired model mode.
fn check_paired_count(
    pairs: &[(usize, usize)],
    all: &[f64],
    scales: Vec<f64>,
) -> Result<(), SignalError> {
    if pairs.iter().any(|&(_, j)| j >= all.len()) {
        return Err(SignalError::ModelFailed {
            scales,
            message: format!("the model returned only {} frequencies", all.len()),
        });
    }
    Ok(())
}

/// Σ_i a_i b_i, in index order.
fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>()
}

/// Levenberg–Marquardt on θ from `theta` for one or two parameters (a 2 × 2 normal system
/// needs no library): forward-difference Jacobian J, normal equations (JᵀJ + λ diag(JᵀJ)) δ =
/// −Jᵀr, a step accepted when it does not raise the cost Σ r², λ ÷ 10 on acceptance (≥ 1e-12)
/// and × 10 on refusal. Stops when a step is below the tolerance in every parameter, when no
/// step is accepted, or at zero cost. Returns θ and the number of iterations.
fn levenberg_marquardt(
    residual: impl Fn(&[f64]) -> Result<Vec<f64>, SignalError>,
    mut theta: Vec<f64>,
    options: &UpdatingOptions,
) -> Result<(Vec<f64>, usize), SignalError> {
    let parameters = theta.len();
    let mut r = residual(&theta)?;
    let mut cost: f64 = r.iter().map(|v| v * v).sum();
    let mut lambda = 1e-3;
    let mut iterations = 0;
    while iterations < options.max_iterations {
        iterations += 1;
        let jac = forward_difference_jacobian(&residual, &theta, &r, options)?;
        let (jtj, g) = normal_equations(&jac, &r);
        if parameters == 2 {
            let cosine = jtj[0][1] / (jtj[0][0] * jtj[1][1]).sqrt();
            if cosine.is_nan() || cosine.abs() >= 1.0 - 1e-8 {
                return Err(SignalError::NotIdentifiable { cosine });
            }
        }
        let mut accepted = false;
        let mut small = false;
        for _ in 0..30 {
            let step = damped_step(&jtj, &g, lambda, parameters);
            small = step.iter().all(|s| s.abs() < options.tolerance);
            if small || step.iter().any(|s| !s.is_finite()) {
                break;
            }
            let trial: Vec<f64> = theta.iter().zip(&step).map(|(t, s)| t + s).collect();
            let rt = residual(&trial)?;
            let ct: f64 = rt.iter().map(|v| v * v).sum();
            if ct <= cost {
                theta = trial;
                r = rt;
                cost = ct;
                lambda = (lambda / 10.0).max(1e-12);
                accepted = true;
                break;
            }
            lambda *= 10.0;
        }
        if small || !accepted || cost == 0.0 {
            return Ok((theta, iterations));
        }
    }
    Err(SignalError::NoConvergence {
        iterations,
        rms_error_hz: (cost / r.len() as f64).sqrt(),
    })
}

/// The forward-difference Jacobian, one column per parameter p:
/// J_ip = (r_i(θ + h e_p) − r_i(θ)) / h with h the option's step.
fn forward_difference_jacobian(
    residual: &impl Fn(&[f64]) -> Result<Vec<f64>, SignalError>,
    theta: &[f64],
    r: &[f64],
    options: &UpdatingOptions,
) -> Result<Vec<Vec<f64>>, SignalError> {
    let h = options.finite_difference_step;
    let mut jac = vec![vec![0.0; r.len()]; theta.len()];
    for p in 0..theta.len() {
        let mut t = theta.to_vec();
        t[p] += h;
        let rp = residual(&t)?;
        for i in 0..r.len() {
            jac[p][i] = (rp[i] - r[i]) / h;
        }
    }
    Ok(jac)
}

/// The normal equations' JᵀJ and gradient g = Jᵀr (unused entries 0 for one parameter).
fn normal_equations(jac: &[Vec<f64>], r: &[f64]) -> ([[f64; 2]; 2], [f64; 2]) {
    let mut jtj = [[0.0; 2]; 2];
    let mut g = [0.0; 2];
    for p in 0..jac.len() {
        g[p] = dot(&jac[p], r);
        for q in 0..jac.len() {
            jtj[p][q] = dot(&jac[p], &jac[q]);
        }
    }
    (jtj, g)
}

/// The damped Gauss–Newton step δ = −(JᵀJ + λ diag(JᵀJ))⁻¹ g: a division for one parameter,
/// Cramer's rule for two.
fn damped_step(jtj: &[[f64; 2]; 2], g: &[f64; 2], lambda: f64, parameters: usize) -> Vec<f64> {
    if parameters == 1 {
        vec![-g[0] / (jtj[0][0] * (1.0 + lambda))]
    } else {
        let a = [
            [jtj[0][0] * (1.0 + lambda), jtj[0][1]],
            [jtj[1][0], jtj[1][1] * (1.0 + lambda)],
        ];
        let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
        vec![
            -(a[1][1] * g[0] - a[0][1] * g[1]) / det,
            -(a[0][0] * g[1] - a[1][0] * g[0]) / det,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::{discretise, MeshOptions};
    use crate::modal::{solve_modes, ModalOptions};
    use crate::model::{BeamSection, BridgeModel, ContinuousBeam, SupportKind};

    /// The two-span beam of examples/bridges/two-span-beam.toml (2 × 20 m, EI = 4.86535e10 N·m²,
    /// m̄ = 18358 kg/m) with 3000 kg/m of pavement; the middle support a spring when given.
    fn two_span(middle_spring: Option<f64>) -> ContinuousBeam {
        let mut beam = ContinuousBeam::pinned(
            vec![20.0, 20.0],
            BeamSection {
                flexural_rigidity: 4.86535e10,
                mass_per_length: 18358.0,
            },
        );
        beam.added_mass_per_length = 3000.0;
        if let Some(k) = middle_spring {
            beam.supports[1] = SupportKind::Elastic {
                vertical_stiffness: k,
                rotational_stiffness: 0.0,
            };
        }
        beam
    }

    /// Frequencies [Hz] of the first four modes with EI × α and the pavement × β.
    fn frequencies(base: &ContinuousBeam, scales: &[f64]) -> Result<Vec<f64>, String> {
        let mut beam = base.clone();
        beam.section.flexural_rigidity *= scales[0];
        beam.added_mass_per_length *= scales.get(1).copied().unwrap_or(1.0);
        let fe = discretise(
            &BridgeModel::ContinuousBeam(beam),
            &MeshOptions {
                element_length: 2.0,
                ..MeshOptions::default()
            },
        )
        .map_err(|e| e.to_string())?;
        let basis = solve_modes(
            &fe,
            &ModalOptions {
                mode_count: 4,
                ..ModalOptions::default()
            },
        )
        .map_err(|e| e.to_string())?;
        Ok(basis.modes.iter().map(|m| m.frequency_hz()).collect())
    }

    fn targets(f: &[f64], count: usize) -> Vec<IdentifiedFrequency> {
        f[..count]
            .iter()
            .map(|&frequency_hz| IdentifiedFrequency {
                frequency_hz,
                kind: None,
            })
            .collect()
    }

    #[test]
    fn updating_recovers_a_stiffness_scale_of_1_1_from_the_models_own_frequencies() {
        // Reference: the model itself (frequencies of EI × 1.1). Rigid supports: f ∝ √α
        // exactly, so the closed form is exact up to the eigen-solver's tolerance (1e-10).
        let base = two_span(None);
        let measured = frequencies(&base, &[1.1]).unwrap();
        let r = update_model(
            |s: &[f64]| frequencies(&base, s),
            None,
            &targets(&measured, 3),
            &UpdatingOptions::default(),
        )
        .unwrap();
        assert!(
            (r.stiffness_scale - 1.1).abs() < 1e-8,
            "{}",
            r.stiffness_scale
        );
        assert_eq!(r.method, UpdatingMethod::ClosedForm);
        // Frequencies match to the solver's accuracy.
        assert!(r.updated_rms_error_hz < 1e-7, "{}", r.updated_rms_error_hz);
    }

    #[test]
    fn updating_refines_the_stiffness_when_springs_are_not_scaled_and_fits_the_pavement_mass() {
        // Reference: the model itself. A 5e7 N/m middle spring (about 1.4 × the 48EI/L³ of
        // the 40 m beam) is not scaled with EI: the frequencies are no longer ∝ √α, the closed
        // form is only a start, and stiffness and pavement mass act differently on the
        // symmetric mode (which moves the spring) and the antisymmetric one (which does not).
        let base = two_span(Some(5e7));
        let measured = frequencies(&base, &[1.1]).unwrap();
        let r = update_model(
            |s: &[f64]| frequencies(&base, s),
            None,
            &targets(&measured, 3),
            &UpdatingOptions::default(),
        )
        .unwrap();
        // Levenberg–Marquardt to its 1e-10 step tolerance with a 1e-6 finite-difference
        // Jacobian: α to 1e-6.
        assert!(
            (r.stiffness_scale - 1.1).abs() < 1e-6,
            "{}",
            r.stiffness_scale
        );
        assert_eq!(r.method, UpdatingMethod::LevenbergMarquardt);

        let measured = frequencies(&base, &[1.1, 1.3]).unwrap();
        let r = update_model(
            |s: &[f64]| frequencies(&base, s),
            None,
            &targets(&measured, 3),
            &UpdatingOptions {
                fit_mass: true,
                ..UpdatingOptions::default()
            },
        )
        .unwrap();
        // The pavement is 14 % of the mass: β is less well determined than α; 1e-4 on both.
        assert!(
            (r.stiffness_scale - 1.1).abs() < 1e-4,
            "{}",
            r.stiffness_scale
        );
        let beta = r.mass_scale.unwrap();
        assert!((beta - 1.3).abs() < 1e-4, "{beta}");
    }

    #[test]
    fn uniform_stiffness_and_pavement_scales_of_a_uniform_beam_are_not_identifiable() {
        // ω² ∝ αEI/(m̄ + βm̄_a) for every mode of a uniform beam on rigid supports: the two
        // Jacobian columns are parallel.
        let base = two_span(None);
        let measured = frequencies(&base, &[1.1, 1.3]).unwrap();
        let e = update_model(
            |s: &[f64]| frequencies(&base, s),
            None,
            &targets(&measured, 3),
            &UpdatingOptions {
                fit_mass: true,
                ..UpdatingOptions::default()
            },
        )
        .unwrap_err();
        assert!(matches!(e, SignalError::NotIdentifiable { .. }), "{e:?}");
    }
}
