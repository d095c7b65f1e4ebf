//! The static-corrected (mode-acceleration) series of a run.
//!
//! The plain partial sum R_K(t) = Σ_{k≤K} cₖ qₖ(t) misses, for every K < ∞, the quasi-static
//! response of the truncated modes to the wheel loads; for a bending moment under a concentrated
//! load that part converges slowly (the paper's CM_M up to 40). The mode-acceleration method
//! (Williams 1945; Cornwell, Craig & Johnson 1983, Earthq. Eng. Struct. Dyn. 11) adds it back
//! exactly through the full-stiffness influence lines:
//!
//!   R̃_K(t) = Q(t) + Σ_{k≤K} cₖ (qₖ(t) − Fₖ(t)/ωₖ²),   Q(t) = Σ_w P_w(t) · IL(x_w(t), y_w),
//!
//! with Fₖ(t) = −Σ_w P_w(t) φₖ(x_w, y_w) the modal force of the recorded contact forces P_w
//! (compressive positive; φ is upwards positive, the solver's Eq. 25 sign). The modal equation
//! q̈ₖ + 2ζₖωₖq̇ₖ + ωₖ²qₖ = Fₖ makes qₖ − Fₖ/ωₖ² = −(q̈ₖ + 2ζₖωₖq̇ₖ)/ωₖ², the inertia and damping
//! part. With every mode of the FE model the two deflection series are equal (Σ φφᵀ/ω² = K⁻¹);
//! the moment series differ then only by the element-local share of a wheel load standing in an
//! element next to the station, which the influence line (read from the unloaded side) has
//! exactly. With few modes R̃_K is already close to its limit; in the static limit (v → 0) it
//! tends to the exact static response, so DAF → 1, where the plain series tends to the truncated
//! modes' static sum instead.

use super::partial_sums::Panels;
use crate::deck::DeckWalk;
use crate::influence::InfluenceLines;
use crate::modal::{ModalBasis, Quantity};
use crate::solver::ResponseHistory;

/// What the static-corrected series of some stations need from one run.
pub(crate) struct CorrectedSeries {
    /// yₖ(t) = qₖ(t) − Fₖ(t)/ωₖ².
    pub coordinates: Panels,
    /// Q(t) of each requested (station, quantity) [m, N·m or N].
    pub quasi_static: Vec<Vec<f64>>,
}

/// The corrected series for `targets` (station, quantity), from the run's modal coordinates
/// `coordinates` (the panels of `history.modal_displacement`, corrected in place); None when a
/// mode has no positive finite frequency (a correction by 1/ωₖ² does not exist then) or the
/// recorded contact forces are incomplete. A target without an influence line keeps Q = 0.
pub(crate) fn corrected_series(
    basis: &ModalBasis,
    influence: &InfluenceLines,
    history: &ResponseHistory,
    coordinates: Panels,
    targets: &[(usize, Quantity)],
) -> Option<CorrectedSeries> {
    let job = CorrectionJob {
        history,
        coordinates,
        targets,
    };
    corrected_series_sharing_paths(basis, influence, vec![job])
        .pop()
        .flatten()
}

/// One run's part of [`corrected_series_sharing_paths`]: its history, the panels of its modal
/// coordinates (which become its corrected coordinates: a run's table is not copied) and its
/// (station, quantity) targets.
pub(crate) struct CorrectionJob<'a> {
    pub history: &'a ResponseHistory,
    pub coordinates: Panels,
    pub targets: &'a [(usize, Quantity)],
}

/// [`corrected_series`] of several runs whose contacts take the same paths (the same lateral
/// positions, and positions equal bit for bit at every instant: the road samples of one
/// crossing): each contact's stencil and mode values φ(x_w) are computed once per instant for
/// all of them, and each run's sums are taken in the order of [`corrected_series`], so every
/// run gets its own result bit for bit. A run whose paths differ from the first run's is
/// computed on its own.
pub(crate) fn corrected_series_sharing_paths(
    basis: &ModalBasis,
    influence: &InfluenceLines,
    jobs: Vec<CorrectionJob>,
) -> Vec<Option<CorrectedSeries>> {
    let Some(first) = jobs.first().map(|job| job.history) else {
        return Vec::new();
    };
    let flexibility: Vec<f64> = basis
        .modes
        .iter()
        .map(|m| 1.0 / (m.circular_frequency * m.circular_frequency))
        .collect();
    let valid = |job: &CorrectionJob| {
        let (steps, contacts) = (job.history.step_count, job.history.contacts.len());
        !flexibility.iter().any(|g| !g.is_finite() || *g <= 0.0)
            && job.history.contact_force.len() == steps * contacts
            && job.history.contact_position.len() == steps * contacts
    };
    let shares_paths = |job: &CorrectionJob| {
        (job.history.step_count == first.step_count)
            && job
                .history
                .has_wheel_paths(&first.contacts, &first.contact_position)
    };
    let mut sharing: Vec<(usize, CorrectionJob)> = Vec::new();
    let mut results: Vec<Option<CorrectedSeries>> = jobs.iter().map(|_| None).collect();
    for (j, job) in jobs.into_iter().enumerate() {
        if !valid(&job) {
            continue;
        }
        if j == 0 || shares_paths(&job) {
            sharing.push((j, job));
        } else {
            let alone = correct_together(basis, influence, &flexibility, vec![job]);
            results[j] = alone.into_iter().next();
        }
    }
    let (indices, together): (Vec<usize>, Vec<CorrectionJob>) = sharing.into_iter().unzip();
    let corrected = correct_together(basis, influence, &flexibility, together);
    for (j, series) in indices.into_iter().zip(corrected) {
        results[j] = Some(series);
    }
    results
}

/// The corrected series of runs that share their paths (checked valid by the caller), each
/// run's coordinates corrected in place.
fn correct_together(
    basis: &ModalBasis,
    influence: &InfluenceLines,
    flexibility: &[f64],
    jobs: Vec<CorrectionJob>,
) -> Vec<CorrectedSeries> {
    let Some(first) = jobs.first().map(|job| job.history) else {
        return Vec::new();
    };
    let n = basis.mode_count();
    let (steps, contacts) = (first.step_count, first.contacts.len());
    let same_deck = influence.deck == basis.deck;
    let (runs, mut series): (Vec<_>, Vec<CorrectedSeries>) = jobs
        .into_iter()
        .map(|job| {
            let quasi_static = vec![vec![0.0; steps]; job.targets.len()];
            let series = CorrectedSeries {
                coordinates: job.coordinates,
                quasi_static,
            };
            ((job.history, job.targets), series)
        })
        .unzip();
    let mut shape = vec![0.0; n];
    // One force vector per run (never empty: chunks of n.max(1)).
    let chunk = n.max(1);
    let mut forces = vec![0.0; chunk * runs.len()];
    let walks = |deck| -> Vec<DeckWalk> {
        let lateral = first.contacts.iter().map(|c| c.lateral_position);
        lateral.map(|y| DeckWalk::new(deck, y)).collect()
    };
    let mut mode_walks = walks(&basis.deck);
    let mut field_walks = walks(&influence.deck);
    for i in 0..steps {
        forces.fill(0.0);
        let mut loaded = false;
        for w in 0..contacts {
            let x = first.contact_position[i * contacts + w];
            let stencil = mode_walks[w].stencil(x);
            if stencil.is_empty() {
                continue;
            }
            loaded = true;
            stencil.values_many(&basis.deck_deflection, &basis.deck_slope, n, &mut shape);
            let field_stencil = if same_deck {
                stencil
            } else {
                field_walks[w].stencil(x)
            };
            for ((&(history, targets), run), force) in runs
                .iter()
                .zip(&mut series)
                .zip(forces.chunks_exact_mut(chunk))
            {
                let p = history.contact_force[i * contacts + w];
                for (f, phi) in force.iter_mut().zip(&shape) {
                    *f -= p * phi;
                }
                for (values, &(s, quantity)) in run.quasi_static.iter_mut().zip(targets) {
                    if let Some(field) = influence.field(s, quantity, x) {
                        values[i] += p * field_stencil.evaluate(field).0;
                    }
                }
            }
        }
        if loaded {
            for (run, force) in series.iter_mut().zip(forces.chunks_exact(chunk)) {
                for (k, (f, g)) in force.iter().zip(flexibility).enumerate() {
                    *run.coordinates.at_mut(i, k) -= f * g;
                }
            }
        }
    }
    series
}

impl CorrectedSeries {
    /// Q(t) of the t-th requested (station, quantity).
    pub fn quasi_static(&self, target: usize) -> &[f64] {
        &self.quasi_static[target]
    }
}
