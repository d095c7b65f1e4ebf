//! The check modes of a run ([`ModalBasis::check_modes`](crate::modal::ModalBasis::check_modes)):
//! modes above the basis, integrated against the run's contact forces without feeding back,
//! for the convergence indicator of every DAF ([`super::DafConvergence`]).
//!
//! Each check mode obeys q̈ + 2ζωq̇ + ω²q = F(t), F(t) = −Σ_w P_w(t) φ(x_w(t)) (the kept modes'
//! modal force, [`super::static_correction`]), from rest at the run's first instant (the
//! solver's bridge starts at rest). Between two instants F is taken linear, and the step is
//! exact for that force (the piecewise-exact method of Nigam & Jennings 1969, Bull. Seismol.
//! Soc. Am. 59; Chopra, Dynamics of Structures, §5.2), for any ωΔt: the check modes reach up to
//! twice the highest kept frequency, which the crossing's step need not resolve. The exact
//! step is the matrix exponential of the system augmented with the force and its slope (Van
//! Loan 1978, IEEE Trans. Autom. Control 23): with u = q, v = q̇/ω, f = F/ω², g = Ḟ/ω³,
//!
//!   d/dt [u v f g]ᵀ = ω A [u v f g]ᵀ,   A = [[0, 1, 0, 0], [−1, −2ζ, 1, 0], [0, 0, 0, 1], [0, 0, 0, 0]],
//!
//! so [u v f g](t + Δt) = exp(ωΔt A) [u v f g](t), g = (F_{i+1} − F_i)/(Δt ω³). The analysis
//! adds y = q − F/ω² (the mode-acceleration series' coordinate) of each check mode to the
//! static-corrected partial sums after the N kept modes.

/// The exact step of one check mode over Δt: the first two rows of exp(ωΔt A).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ExactStep {
    /// ω [rad/s].
    circular_frequency: f64,
    /// Δt [s].
    time_step: f64,
    /// Rows u and v of exp(ωΔt A) [-].
    rows: [[f64; 4]; 2],
}

impl ExactStep {
    /// The step of a mode of circular frequency ω > 0 [rad/s] and damping ratio ζ ≥ 0 [-]
    /// over Δt > 0 [s].
    pub(crate) fn new(circular_frequency: f64, damping_ratio: f64, time_step: f64) -> Self {
        let scale = circular_frequency * time_step;
        let z = damping_ratio;
        let a = [
            [0.0, scale, 0.0, 0.0],
            [-scale, -2.0 * z * scale, scale, 0.0],
            [0.0, 0.0, 0.0, scale],
            [0.0, 0.0, 0.0, 0.0],
        ];
        let e = exponential(a);
        ExactStep {
            circular_frequency,
            time_step,
            rows: [e[0], e[1]],
        }
    }

    /// (q, q̇) after the step from (q, q̇) under the force F going linearly from `forces.0` to
    /// `forces.1` [kg^½·m, kg^½·m/s; forces per unit modal mass, m·kg^½/s²].
    pub(crate) fn advance(&self, (q, velocity): (f64, f64), forces: (f64, f64)) -> (f64, f64) {
        let w = self.circular_frequency;
        let state = [
            q,
            velocity / w,
            forces.0 / (w * w),
            (forces.1 - forces.0) / (self.time_step * w * w * w),
        ];
        let row = |r: &[f64; 4]| r.iter().zip(&state).map(|(a, b)| a * b).sum::<f64>();
        (row(&self.rows[0]), row(&self.rows[1]) * w)
    }
}

/// exp(A) of a 4 × 4 matrix by scaling and squaring with a Taylor series: A is scaled by 2⁻ˢ
/// to a 1-norm ≤ 1/2, where 20 terms leave a truncation below 10⁻²⁰, then squared s times.
/// Written here because the step needs only this one small, well-scaled exponential (the
/// matrix's entries are ωΔt, 2ζωΔt and 1 × ωΔt; faer has no matrix exponential).
fn exponential(a: [[f64; 4]; 4]) -> [[f64; 4]; 4] {
    let norm = (0..4)
        .map(|c| (0..4).map(|r| a[r][c].abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let squarings = if norm > 0.5 {
        (norm / 0.5).log2().ceil() as i32
    } else {
        0
    };
    let factor = 0.5f64.powi(squarings);
    let scaled = a.map(|row| row.map(|v| v * factor));
    let mut result = identity();
    let mut term = identity();
    for k in 1..=20 {
        term = product(&term, &scaled).map(|row| row.map(|v| v / k as f64));
        for (r, row) in result.iter_mut().enumerate() {
            for (c, value) in row.iter_mut().enumerate() {
                *value += term[r][c];
            }
        }
    }
    for _ in 0..squarings {
        result = product(&result, &result);
    }
    result
}

fn identity() -> [[f64; 4]; 4] {
    let mut i = [[0.0; 4]; 4];
    for (k, row) in i.iter_mut().enumerate() {
        row[k] = 1.0;
    }
    i
}

fn product(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4]) -> [[f64; 4]; 4] {
    let mut p = [[0.0; 4]; 4];
    for r in 0..4 {
        for c in 0..4 {
            p[r][c] = (0..4).map(|k| a[r][k] * b[k][c]).sum();
        }
    }
    p
}

/// The check modes of one run as its instants come: their steps, states and last forces.
pub(crate) struct CheckModeStates {
    steps: Vec<ExactStep>,
    /// 1/ω² of each check mode [s²].
    flexibility: Vec<f64>,
    /// (q, q̇) of each check mode at the last instant.
    states: Vec<(f64, f64)>,
    /// F of each check mode at the last instant.
    last_forces: Vec<f64>,
    /// Whether the first instant has been taken.
    started: bool,
}

impl CheckModeStates {
    /// The check modes (ω, ζ) of a run with time step Δt [s], at rest.
    pub(crate) fn new(modes: &[crate::modal::Mode], time_step: f64) -> Self {
        let steps = modes
            .iter()
            .map(|m| ExactStep::new(m.circular_frequency, m.damping_ratio, time_step))
            .collect();
        CheckModeStates {
            steps,
            flexibility: modes
                .iter()
                .map(|m| 1.0 / (m.circular_frequency * m.circular_frequency))
                .collect(),
            states: vec![(0.0, 0.0); modes.len()],
            last_forces: vec![0.0; modes.len()],
            started: false,
        }
    }

    /// The number of check modes C.
    pub(crate) fn mode_count(&self) -> usize {
        self.steps.len()
    }

    /// Takes the next instant's modal forces Fₖ and gives each check mode's y = q − F/ω² there
    /// (the first instant: the modes at rest, q = 0).
    pub(crate) fn next_instant(&mut self, forces: &[f64], corrected: &mut [f64]) {
        for (k, &force) in forces.iter().enumerate() {
            if self.started {
                self.states[k] =
                    self.steps[k].advance(self.states[k], (self.last_forces[k], force));
            }
            self.last_forces[k] = force;
            corrected[k] = self.states[k].0 - force * self.flexibility[k];
        }
        self.started = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// q(t) of q̈ + 2ζωq̇ + ω²q = F₀ from rest (Chopra, Dynamics of Structures, Eq. 4.3.3 with
    /// unit mass): F₀/ω² [1 − e^{−ζωt}(cos ω_D t + ζ/√(1−ζ²) sin ω_D t)].
    fn step_response(w: f64, z: f64, force: f64, t: f64) -> f64 {
        let wd = w * (1.0 - z * z).sqrt();
        let decay = (-z * w * t).exp();
        force / (w * w)
            * (1.0 - decay * ((wd * t).cos() + z / (1.0 - z * z).sqrt() * (wd * t).sin()))
    }

    #[test]
    fn exact_step_follows_the_closed_form_step_response_for_any_omega_dt() {
        // ωΔt from 0.01 (resolved) to 3 (far coarser than a crossing resolves), ζ 0 to 0.2.
        for (w, z, dt) in [
            (10.0, 0.0, 1e-3),
            (300.0, 0.02, 1e-3),
            (660.0, 0.2, 4.5e-3),
            (50.0, 0.05, 0.02),
        ] {
            let step = ExactStep::new(w, z, dt);
            let mut state = (0.0, 0.0);
            let force = 3.0;
            // F₀ at both ends of every step: a force constant from t = 0.
            for i in 1..=400 {
                state = step.advance(state, (force, force));
                let want = step_response(w, z, force, i as f64 * dt);
                let scale = force / (w * w);
                assert!(
                    (state.0 - want).abs() <= 1e-9 * scale,
                    "ω {w} ζ {z} Δt {dt} step {i}: {} vs {want}",
                    state.0
                );
            }
        }
    }

    #[test]
    fn exact_step_follows_the_closed_form_ramp_response_undamped() {
        // F = a t from rest, ζ = 0: q = a/ω² (t − sin ωt / ω), q̇ = a/ω² (1 − cos ωt).
        let (w, a, dt) = (400.0, 5.0, 2e-3);
        let step = ExactStep::new(w, 0.0, dt);
        let mut state = (0.0, 0.0);
        for i in 1..=300 {
            let (t0, t1) = ((i - 1) as f64 * dt, i as f64 * dt);
            state = step.advance(state, (a * t0, a * t1));
            let q = a / (w * w) * (t1 - (w * t1).sin() / w);
            let v = a / (w * w) * (1.0 - (w * t1).cos());
            assert!(
                (state.0 - q).abs() <= 1e-12 * a / (w * w),
                "step {i}: {} vs {q}",
                state.0
            );
            assert!(
                (state.1 - v).abs() <= 1e-12 * a / (w * w) * w,
                "step {i}: {} vs {v}",
                state.1
            );
        }
    }

    #[test]
    fn a_mode_in_static_equilibrium_stays_there_and_its_corrected_coordinate_is_zero() {
        let mode = crate::modal::Mode {
            circular_frequency: 250.0,
            damping_ratio: 0.03,
            kind: crate::modal::ModeKind::VerticalBending,
            residual: 0.0,
        };
        let mut states = CheckModeStates::new(&[mode], 1e-3);
        let force = 7.0;
        states.states[0] = (force / (250.0f64 * 250.0), 0.0);
        states.started = true;
        states.last_forces[0] = force;
        let mut y = [f64::NAN];
        for _ in 0..100 {
            states.next_instant(&[force], &mut y);
            assert!(
                y[0].abs() <= 1e-15 * force / (250.0f64 * 250.0) * 10.0,
                "{}",
                y[0]
            );
        }
    }
}
