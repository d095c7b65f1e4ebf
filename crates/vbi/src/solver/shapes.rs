//! Contact shapes: the values φ and slopes φ′ of all N modes at each tyre on the deck,
//! φₖ = ⟨N_w⟩Φₖ and φ′ₖ = ⟨N_w⟩′Φₖ (Eq. 26: Hermite along the girder lines, lever rule across
//! them). They depend on the tyres' positions only (not on the road), at O(T·N) per step.

use super::element_cache::ElementCache;
use super::kinematics::ContactPoints;
use super::tyre::Tyre;
use crate::modal::ModalBasis;

/// The mode values and slopes at the tyres of one instant (tyre-major, N per tyre).
pub(super) struct ContactShapes {
    /// Number of modes N.
    mode_count: usize,
    /// Whether each tyre is on the deck (where the deck stencil has terms).
    on_deck: Vec<bool>,
    /// φ of each tyre on the deck, T × N.
    values: Vec<f64>,
    /// φ′ of each tyre on the deck, T × N.
    slopes: Vec<f64>,
    /// The per-element cubic of each tyre.
    caches: Vec<ElementCache>,
}

impl ContactShapes {
    /// Buffers for `tyre_count` tyres and `mode_count` modes.
    pub(super) fn new(tyre_count: usize, mode_count: usize) -> ContactShapes {
        ContactShapes {
            mode_count,
            on_deck: vec![false; tyre_count],
            values: vec![0.0; tyre_count * mode_count],
            slopes: vec![0.0; tyre_count * mode_count],
            caches: (0..tyre_count)
                .map(|_| ElementCache::new(mode_count))
                .collect(),
        }
    }

    /// The shapes at the tyres' positions of `points`: a tyre is on the deck exactly where
    /// `DeckGeometry::stencil` has terms (0 ≤ x ≤ L and a non-zero lateral weight); its shapes
    /// come from its element cache, or from the stencil where the lines it reads do not share
    /// the element. Shapes of a tyre off the deck are left as they were and never read.
    pub(super) fn evaluate(&mut self, basis: &ModalBasis, tyres: &[Tyre], points: &ContactPoints) {
        let n = self.mode_count;
        let deck_length = basis.deck.length;
        for (w, t) in tyres.iter().enumerate() {
            let x = points.position[t.contact];
            self.on_deck[w] =
                (0.0..=deck_length).contains(&x) && t.weights.iter().any(|&(_, l)| l != 0.0);
            if self.on_deck[w] {
                let pw = &mut self.values[w * n..(w + 1) * n];
                let sw = &mut self.slopes[w * n..(w + 1) * n];
                let cached = self.caches[w].evaluate(
                    &basis.deck,
                    &t.weights,
                    &basis.deck_deflection,
                    &basis.deck_slope,
                    n,
                    x,
                    pw,
                    sw,
                );
                if !cached {
                    let stencil = basis.deck.stencil(x, t.lateral);
                    stencil.evaluate_many(&basis.deck_deflection, &basis.deck_slope, n, pw, sw);
                }
            }
        }
    }

    /// Whether tyre `w` is on the deck.
    #[inline]
    pub(super) fn is_on_deck(&self, w: usize) -> bool {
        self.on_deck[w]
    }

    /// Whether any tyre is on the deck.
    #[inline]
    pub(super) fn any_on_deck(&self) -> bool {
        self.on_deck.iter().any(|&o| o)
    }

    /// (φ, φ′) of tyre `w` when it is on the deck.
    #[inline]
    pub(super) fn of(&self, w: usize) -> Option<(&[f64], &[f64])> {
        let n = self.mode_count;
        self.on_deck[w].then(|| {
            (
                &self.values[w * n..(w + 1) * n],
                &self.slopes[w * n..(w + 1) * n],
            )
        })
    }
}
