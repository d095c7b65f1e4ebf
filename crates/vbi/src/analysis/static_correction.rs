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
//!
//! The series are streamed: [`stream_runs`] hands each run's coordinates to its [`PanelSink`]
//! one panel of [`LANES`] instants at a time, plain and then corrected, so that no run's table
//! of coordinates is copied whole (a study's batch held twice its histories' size before).

use super::partial_sums::{fill_panel, LANES};
use crate::deck::DeckWalk;
use crate::influence::InfluenceLines;
use crate::modal::{ModalBasis, Quantity};
use crate::solver::ResponseHistory;

/// What receives a run's series, one panel of instants `start..start + len` at a time (the
/// panels of [`fill_panel`]: `panel[k · LANES + j]` is mode k at instant start + j), in the
/// order of time.
pub(crate) trait PanelSink {
    /// The plain coordinates qₖ.
    fn plain(&mut self, panel: &[f64], instants: (usize, usize));
    /// The corrected coordinates yₖ = qₖ − Fₖ/ωₖ², and Q of the run's t-th target at instant
    /// start + j in `quasi_static[t][j]` [m, N·m or N].
    fn corrected(&mut self, panel: &[f64], quasi_static: &[[f64; LANES]], instants: (usize, usize));
}

/// One run of [`stream_runs`]: its history, its (station, quantity) targets and its sink.
pub(crate) struct StreamedRun<'a, S> {
    pub history: &'a ResponseHistory,
    pub targets: &'a [(usize, Quantity)],
    pub sink: S,
}

/// Streams the plain series of every run through its sink, and the corrected series of every
/// run that has them; whether each run has them, in order. A run has none when a mode has no
/// positive finite frequency (a correction by 1/ωₖ² does not exist then) or its recorded
/// contact forces are incomplete; a target without an influence line keeps Q = 0.
///
/// The runs whose contacts take the first corrected run's paths (the same lateral positions,
/// and positions equal bit for bit at every instant: the road samples of one crossing) are
/// streamed together: each contact's stencil and mode values φ(x_w) are computed once per
/// instant for all of them. Each run's sums are taken in the same order either way, so every
/// run gets its own result bit for bit.
pub(crate) fn stream_runs<S: PanelSink>(
    basis: &ModalBasis,
    influence: &InfluenceLines,
    runs: &mut [StreamedRun<S>],
) -> Vec<bool> {
    let flexibility: Vec<f64> = basis
        .modes
        .iter()
        .map(|m| 1.0 / (m.circular_frequency * m.circular_frequency))
        .collect();
    let modes_correct = flexibility.iter().all(|g| g.is_finite() && *g > 0.0);
    let correctable = |history: &ResponseHistory| {
        let recorded = history.step_count.saturating_mul(history.contacts.len());
        modes_correct
            && history.contact_force.len() == recorded
            && history.contact_position.len() == recorded
    };
    let corrected: Vec<bool> = runs.iter().map(|run| correctable(run.history)).collect();
    let leader = corrected.iter().position(|&c| c).map(|r| runs[r].history);
    let shares_paths = |history: &ResponseHistory| {
        leader.is_some_and(|first| {
            history.step_count == first.step_count
                && history.has_wheel_paths(&first.contacts, &first.contact_position)
        })
    };
    let pass = StreamPass {
        basis,
        influence,
        flexibility: &flexibility,
    };
    let mut together = Vec::new();
    for (run, &correct) in runs.iter_mut().zip(&corrected) {
        match (correct, shares_paths(run.history)) {
            (true, true) => together.push(run),
            (correct, _) => pass.stream(&mut [run], correct),
        }
    }
    pass.stream(&mut together, true);
    corrected
}

/// What a pass over runs reads besides the runs.
struct StreamPass<'a> {
    basis: &'a ModalBasis,
    influence: &'a InfluenceLines,
    /// 1/ωₖ² [s²].
    flexibility: &'a [f64],
}

impl StreamPass<'_> {
    /// Streams runs that share their paths (the first's), with their corrected series when
    /// `correct` (checked possible by the caller).
    fn stream<S: PanelSink>(&self, runs: &mut [&mut StreamedRun<S>], correct: bool) {
        let Some(first) = runs.first().map(|run| run.history) else {
            return;
        };
        let n = self.basis.mode_count();
        let width = n.max(1) * LANES;
        let mut panels = vec![0.0; width * runs.len()];
        let mut quasi_static: Vec<Vec<[f64; LANES]>> = runs
            .iter()
            .map(|run| vec![[0.0; LANES]; run.targets.len()])
            .collect();
        let same_targets = runs
            .iter()
            .map(|run| run.targets == runs[0].targets)
            .collect();
        // The contacts' walks along the deck only where the series are corrected.
        let mut wheels = correct.then(|| Wheels::new(self, (first, runs[0].targets), same_targets));
        for start in (0..first.step_count).step_by(LANES) {
            let instants = (start, LANES.min(first.step_count - start));
            for (run, panel) in runs.iter_mut().zip(panels.chunks_exact_mut(width)) {
                fill_panel(&run.history.modal_displacement, n, instants, panel);
                run.sink.plain(panel, instants);
            }
            let Some(wheels) = wheels.as_mut() else {
                continue;
            };
            quasi_static
                .iter_mut()
                .flatten()
                .for_each(|q| *q = [0.0; LANES]);
            for j in 0..instants.1 {
                let instant = (start + j, j);
                wheels.correct(self, runs, instant, (&mut panels, &mut quasi_static));
            }
            let each = runs.iter_mut().zip(panels.chunks_exact(width));
            for ((run, panel), quasi_static) in each.zip(&quasi_static) {
                run.sink.corrected(panel, quasi_static, instants);
            }
        }
    }
}

/// The contacts of runs that share their paths, walked along the deck once for all of them.
struct Wheels<'a> {
    /// The run whose contact positions are read.
    paths: &'a ResponseHistory,
    mode_walks: Vec<DeckWalk<'a>>,
    field_walks: Vec<DeckWalk<'a>>,
    same_deck: bool,
    /// φₖ(x_w) of the current contact.
    shape: Vec<f64>,
    /// −Fₖ of each run at the current instant (chunks of N.max(1)).
    forces: Vec<f64>,
    /// The first run's targets, which the runs that have the same read from `lines`.
    targets: &'a [(usize, Quantity)],
    /// Whether each run has the first run's targets.
    same_targets: Vec<bool>,
    /// IL(x_w) of each of the first run's targets at the current contact (None: no line).
    lines: Vec<Option<f64>>,
}

impl<'a> Wheels<'a> {
    /// The wheels of `paths`, for runs whose first has `targets` (`same_targets`: whether each
    /// run has them too).
    fn new(
        pass: &StreamPass<'a>,
        (paths, targets): (&'a ResponseHistory, &'a [(usize, Quantity)]),
        same_targets: Vec<bool>,
    ) -> Self {
        let walks = |deck| -> Vec<DeckWalk<'a>> {
            let lateral = paths.contacts.iter().map(|c| c.lateral_position);
            lateral.map(|y| DeckWalk::new(deck, y)).collect()
        };
        let n = pass.basis.mode_count();
        Wheels {
            paths,
            mode_walks: walks(&pass.basis.deck),
            field_walks: walks(&pass.influence.deck),
            same_deck: pass.influence.deck == pass.basis.deck,
            shape: vec![0.0; n],
            forces: vec![0.0; n.max(1) * same_targets.len()],
            targets,
            same_targets,
            lines: vec![None; targets.len()],
        }
    }

    /// Corrects lane j of every run's panel for instant i, `(i, j)`, and adds each target's Q
    /// there: Fₖ = −Σ_w P_w φₖ(x_w), yₖ = qₖ − Fₖ/ωₖ², Q = Σ_w P_w IL(x_w), the contacts in order.
    fn correct<S>(
        &mut self,
        pass: &StreamPass,
        runs: &[&mut StreamedRun<S>],
        (i, j): (usize, usize),
        (panels, quasi_static): (&mut [f64], &mut [Vec<[f64; LANES]>]),
    ) {
        let (basis, influence) = (pass.basis, pass.influence);
        let n = basis.mode_count();
        let contacts = self.paths.contacts.len();
        let chunk = n.max(1);
        self.forces.fill(0.0);
        let mut loaded = false;
        for w in 0..contacts {
            let x = self.paths.contact_position[i * contacts + w];
            let stencil = self.mode_walks[w].stencil(x);
            if stencil.is_empty() {
                continue;
            }
            loaded = true;
            stencil.values_many(
                &basis.deck_deflection,
                &basis.deck_slope,
                n,
                &mut self.shape,
            );
            let field_stencil = match self.same_deck {
                true => stencil,
                false => self.field_walks[w].stencil(x),
            };
            // Each line's value at the contact, once for the runs with the first's targets.
            let line = |&(s, quantity): &(usize, Quantity)| {
                let field = influence.field(s, quantity, x)?;
                Some(field_stencil.evaluate(field).0)
            };
            for (value, target) in self.lines.iter_mut().zip(self.targets) {
                *value = line(target);
            }
            let each = runs.iter().zip(self.forces.chunks_exact_mut(chunk));
            let each = each.zip(quasi_static.iter_mut()).zip(&self.same_targets);
            for (((run, force), quasi_static), &same_targets) in each {
                let p = run.history.contact_force[i * contacts + w];
                for (f, phi) in force.iter_mut().zip(&self.shape) {
                    *f -= p * phi;
                }
                let add = |values: &mut [f64; LANES], value: Option<f64>| {
                    if let Some(value) = value {
                        values[j] += p * value;
                    }
                };
                match same_targets {
                    true => quasi_static
                        .iter_mut()
                        .zip(&self.lines)
                        .for_each(|(v, &l)| add(v, l)),
                    false => (quasi_static.iter_mut().zip(run.targets))
                        .for_each(|(v, target)| add(v, line(target))),
                }
            }
        }
        if loaded {
            let width = chunk * LANES;
            let each = panels
                .chunks_exact_mut(width)
                .zip(self.forces.chunks_exact(chunk));
            for (panel, force) in each {
                for (k, (f, g)) in force.iter().zip(pass.flexibility).enumerate() {
                    panel[k * LANES + j] -= f * g;
                }
            }
        }
    }
}
