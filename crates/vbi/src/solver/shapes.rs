//! Contact shapes: the values φ and slopes φ′ of all N modes at each tyre on the deck,
//! φₖ = ⟨N_w⟩Φₖ and φ′ₖ = ⟨N_w⟩′Φₖ (Eq. 26: Hermite along the girder lines, lever rule across
//! them). They depend on the tyres' positions only (not on the road), at O(T·N) per step.

use super::kinematics::ContactPoints;
use super::tyre::Tyre;
use crate::deck::DeckReader;
use crate::modal::ModalBasis;

/// The mode values and slopes at the tyres of one instant (tyre-major, N per tyre).
pub(super) struct ContactShapes<'a> {
    /// Number of modes N.
    mode_count: usize,
    /// Whether each tyre is on the deck (where the deck stencil has terms).
    on_deck: Vec<bool>,
    /// φ of each tyre on the deck, T × N.
    values: Vec<f64>,
    /// φ′ of each tyre on the deck, T × N.
    slopes: Vec<f64>,
    /// Whether φ and φ′ are also arranged mode by mode, for the deck sums side by side
    /// ([`ContactShapes::deck_sums`]): worth its copy only where several crossings share the
    /// shapes (a lone crossing's tyres sum one at a time, [`super::tyre::Tyre::force`]).
    by_mode: bool,
    /// The tyres on the deck, in tyre order (when `by_mode`).
    deck_tyres: Vec<usize>,
    /// φ of the tyres on the deck mode by mode, N × m (m = `deck_tyres.len()`): row k holds
    /// φₖ of every tyre on the deck, so that their deck sums advance side by side.
    values_by_mode: Vec<f64>,
    /// φ′ likewise, N × m.
    slopes_by_mode: Vec<f64>,
    /// The reader of the mode shapes at each tyre (its element cubic, or the stencil).
    readers: Vec<DeckReader<'a>>,
}

impl<'a> ContactShapes<'a> {
    /// Buffers for `tyres` and the modes of `basis`; `by_mode`: the shapes are also arranged
    /// mode by mode (shapes that crossings share).
    pub(super) fn new(basis: &'a ModalBasis, tyres: &[Tyre], by_mode: bool) -> ContactShapes<'a> {
        let (tyre_count, mode_count) = (tyres.len(), basis.mode_count());
        let by_mode_length = if by_mode { tyre_count * mode_count } else { 0 };
        ContactShapes {
            mode_count,
            on_deck: vec![false; tyre_count],
            values: vec![0.0; tyre_count * mode_count],
            slopes: vec![0.0; tyre_count * mode_count],
            by_mode,
            deck_tyres: Vec::with_capacity(tyre_count),
            values_by_mode: vec![0.0; by_mode_length],
            slopes_by_mode: vec![0.0; by_mode_length],
            readers: tyres
                .iter()
                .map(|t| DeckReader::new(&basis.deck, t.lateral, mode_count))
                .collect(),
        }
    }

    /// A placeholder without tyres (while an integrator lends out its own shapes).
    pub(super) fn none() -> ContactShapes<'a> {
        ContactShapes {
            mode_count: 0,
            on_deck: Vec::new(),
            values: Vec::new(),
            slopes: Vec::new(),
            by_mode: false,
            deck_tyres: Vec::new(),
            values_by_mode: Vec::new(),
            slopes_by_mode: Vec::new(),
            readers: Vec::new(),
        }
    }

    /// The shapes at the tyres' positions of `points`: a tyre is on the deck exactly where
    /// `DeckGeometry::stencil` has terms (0 ≤ x ≤ L and a non-zero lateral weight); its shapes
    /// are read by its [`DeckReader`] (the element cubic, or the stencil where the lines it
    /// reads do not share the element: the analysis's route, bit for bit). Shapes of a tyre off
    /// the deck are left as they were and never read.
    pub(super) fn evaluate(&mut self, basis: &ModalBasis, tyres: &[Tyre], points: &ContactPoints) {
        // n ≥ 1 (the set-up refuses a basis without modes), as `chunks_exact_mut` needs.
        let n = self.mode_count;
        let fields = (&basis.deck_deflection[..], &basis.deck_slope[..]);
        let shapes = self
            .values
            .chunks_exact_mut(n)
            .zip(self.slopes.chunks_exact_mut(n));
        let tyre_readers = tyres.iter().zip(&mut self.readers);
        for (((t, reader), (pw, sw)), on_deck) in tyre_readers.zip(shapes).zip(&mut self.on_deck) {
            let x = points.position[t.contact];
            *on_deck = reader.values_and_slopes(fields, x, pw, sw);
        }
        if self.by_mode {
            self.arrange_by_mode();
        }
    }

    /// The tyres on the deck and their φ, φ′ mode by mode.
    fn arrange_by_mode(&mut self) {
        let n = self.mode_count;
        self.deck_tyres.clear();
        self.deck_tyres
            .extend((0..self.on_deck.len()).filter(|&w| self.on_deck[w]));
        let m = self.deck_tyres.len();
        if m == 0 {
            return;
        }
        // Row by row (contiguous stores, strided loads: the cheaper way round).
        let (values, slopes) = (&self.values, &self.slopes);
        let rows = self.values_by_mode[..n * m]
            .chunks_exact_mut(m)
            .zip(self.slopes_by_mode[..n * m].chunks_exact_mut(m));
        for (k, (value_row, slope_row)) in rows.enumerate() {
            let entries = value_row.iter_mut().zip(slope_row.iter_mut());
            for ((value, slope), &w) in entries.zip(&self.deck_tyres) {
                *value = values[w * n + k];
                *slope = slopes[w * n + k];
            }
        }
    }

    /// Whether the shapes are arranged mode by mode ([`ContactShapes::deck_sums`] available).
    #[inline]
    pub(super) fn by_mode(&self) -> bool {
        self.by_mode
    }

    /// The tyres on the deck, in tyre order (when [`ContactShapes::by_mode`]).
    #[inline]
    pub(super) fn deck_tyres(&self) -> &[usize] {
        &self.deck_tyres
    }

    /// The deck sums of every tyre on the deck at a bridge state (q, q̇): (Σₖ φₖ qₖ, Σₖ φₖ q̇ₖ,
    /// Σₖ φ′ₖ qₖ) in `sums[i]` for the i-th of [`ContactShapes::deck_tyres`], each summed in the
    /// order k = 1…N exactly as [`super::tyre::deck_sums_of_one_tyre`] sums them (the same
    /// numbers, bit for bit). The tyres go side by side, four at a time (then two, then one):
    /// their sums are independent chains that fill the floating-point units where one tyre's
    /// three chains wait on the latency of their additions.
    #[inline]
    pub(super) fn deck_sums(&self, q: &[f64], qd: &[f64], sums: &mut [[f64; 3]]) {
        let m = self.deck_tyres.len();
        let mut first = 0;
        while m - first >= 4 {
            self.deck_sums_of::<4>(first, q, qd, &mut sums[first..first + 4]);
            first += 4;
        }
        if m - first >= 2 {
            self.deck_sums_of::<2>(first, q, qd, &mut sums[first..first + 2]);
            first += 2;
        }
        if first < m {
            self.deck_sums_of::<1>(first, q, qd, &mut sums[first..first + 1]);
        }
    }

    /// [`ContactShapes::deck_sums`] of the `W` tyres on the deck from the `first`.
    #[inline(always)]
    fn deck_sums_of<const W: usize>(
        &self,
        first: usize,
        q: &[f64],
        qd: &[f64],
        sums: &mut [[f64; 3]],
    ) {
        let (n, m) = (self.mode_count, self.deck_tyres.len());
        let (mut a, mut b, mut c) = ([0.0; W], [0.0; W], [0.0; W]);
        for (k, (qk, vk)) in q[..n].iter().zip(&qd[..n]).enumerate() {
            let p: &[f64; W] = self.values_by_mode[k * m + first..][..W]
                .try_into()
                .expect("W values");
            let sl: &[f64; W] = self.slopes_by_mode[k * m + first..][..W]
                .try_into()
                .expect("W slopes");
            for j in 0..W {
                a[j] += p[j] * qk;
                b[j] += p[j] * vk;
                c[j] += sl[j] * qk;
            }
        }
        for (j, sum) in sums.iter_mut().enumerate() {
            *sum = [a[j], b[j], c[j]];
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::tyre::deck_sums_of_one_tyre;

    /// Shapes of `tyre_count` tyres, those with `on_deck` set on the deck, with irregular values
    /// (no two sums could agree by accident) and their mode-major arrangement.
    fn shapes_on_deck(mode_count: usize, on_deck: &[bool]) -> ContactShapes<'static> {
        let mut shapes = ContactShapes::none();
        let length = on_deck.len() * mode_count;
        (shapes.mode_count, shapes.by_mode) = (mode_count, true);
        shapes.values = vec![0.0; length];
        shapes.slopes = vec![0.0; length];
        shapes.values_by_mode = vec![0.0; length];
        shapes.slopes_by_mode = vec![0.0; length];
        shapes.on_deck = on_deck.to_vec();
        for (i, (v, s)) in shapes.values.iter_mut().zip(&mut shapes.slopes).enumerate() {
            let x = i as f64;
            (*v, *s) = ((0.37 * x).sin() * 1.0e-3, (1.3 * x + 0.2).cos() / 7.0);
        }
        shapes.arrange_by_mode();
        shapes
    }

    #[test]
    fn deck_sums_side_by_side_equal_each_tyres_own_sums_bit_for_bit() {
        // 0 to 8 tyres on the deck: every combination of the groups of four, two and one.
        let n = 13;
        let q: Vec<f64> = (0..n).map(|k| (0.9 * k as f64).cos() * 3.0e-2).collect();
        let qd: Vec<f64> = (0..n).map(|k| (0.4 * k as f64 + 1.0).sin() * 0.7).collect();
        for tyre_count in 0..=12 {
            // Every third tyre off the deck.
            let on_deck: Vec<bool> = (0..tyre_count).map(|w| w % 3 != 1).collect();
            let shapes = shapes_on_deck(n, &on_deck);
            let mut sums = vec![[f64::NAN; 3]; tyre_count];
            let m = shapes.deck_tyres().len();
            shapes.deck_sums(&q, &qd, &mut sums[..m]);
            assert_eq!(m, on_deck.iter().filter(|&&o| o).count());
            for (i, &w) in shapes.deck_tyres().iter().enumerate() {
                let shape = shapes.of(w).expect("on the deck");
                let alone = deck_sums_of_one_tyre(shape, (&q, &qd));
                assert_eq!(
                    sums[i].map(f64::to_bits),
                    alone.map(f64::to_bits),
                    "tyre {w}"
                );
            }
        }
    }
}
