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
/// `coordinates` (the panels of `history.modal_displacement`); None when a mode has no positive
/// finite frequency (a correction by 1/ωₖ² does not exist then) or the recorded contact forces
/// are incomplete. A target without an influence line keeps Q = 0.
pub(crate) fn corrected_series(
    basis: &ModalBasis,
    influence: &InfluenceLines,
    history: &ResponseHistory,
    coordinates: &Panels,
    targets: &[(usize, Quantity)],
) -> Option<CorrectedSeries> {
    let n = basis.mode_count();
    let steps = history.step_count;
    let contacts = history.contacts.len();
    let flexibility: Vec<f64> = basis
        .modes
        .iter()
        .map(|m| 1.0 / (m.circular_frequency * m.circular_frequency))
        .collect();
    if flexibility.iter().any(|g| !g.is_finite() || *g <= 0.0)
        || history.contact_force.len() != steps * contacts
        || history.contact_position.len() != steps * contacts
    {
        return None;
    }
    let same_deck = influence.deck == basis.deck;
    let mut coordinates = coordinates.clone();
    let mut quasi_static = vec![vec![0.0; steps]; targets.len()];
    let mut shape = vec![0.0; n];
    let mut force = vec![0.0; n];
    let walks = |deck| -> Vec<DeckWalk> {
        let lateral = history.contacts.iter().map(|c| c.lateral_position);
        lateral.map(|y| DeckWalk::new(deck, y)).collect()
    };
    let mut mode_walks = walks(&basis.deck);
    let mut field_walks = walks(&influence.deck);
    for i in 0..steps {
        force.fill(0.0);
        let mut loaded = false;
        for w in 0..contacts {
            let x = history.contact_position[i * contacts + w];
            let stencil = mode_walks[w].stencil(x);
            if stencil.is_empty() {
                continue;
            }
            loaded = true;
            let p = history.contact_force[i * contacts + w];
            stencil.values_many(&basis.deck_deflection, &basis.deck_slope, n, &mut shape);
            for (f, phi) in force.iter_mut().zip(&shape) {
                *f -= p * phi;
            }
            let field_stencil = if same_deck {
                stencil
            } else {
                field_walks[w].stencil(x)
            };
            for (values, &(s, quantity)) in quasi_static.iter_mut().zip(targets) {
                if let Some(field) = influence.field(s, quantity, x) {
                    values[i] += p * field_stencil.evaluate(field).0;
                }
            }
        }
        if loaded {
            for (k, (f, g)) in force.iter().zip(&flexibility).enumerate() {
                *coordinates.at_mut(i, k) -= f * g;
            }
        }
    }
    Some(CorrectedSeries {
        coordinates,
        quasi_static,
    })
}

impl CorrectedSeries {
    /// Q(t) of the t-th requested (station, quantity).
    pub fn quasi_static(&self, target: usize) -> &[f64] {
        &self.quasi_static[target]
    }
}
