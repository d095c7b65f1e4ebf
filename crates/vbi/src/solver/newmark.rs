//! Newmark-β time integration of a set of DOFs (the modal coordinates, or the vehicle's DOFs)
//! with the end-of-step accelerations a as unknowns (paper §3.3):
//!
//! predictor  ũ = u + Δt u̇ + Δt²(½ − β) ü,   ṽ = u̇ + Δt(1 − γ) ü,
//! corrector  u = ũ + βΔt² a,                 u̇ = ṽ + γΔt a.
//!
//! At the first instant the "predictor" is the initial state itself and the corrector has
//! βΔt² = γΔt = 0: the same equations then give the initial accelerations.

/// The constants of the Newmark scheme for one time step.
#[derive(Debug, Clone, Copy)]
pub(super) struct NewmarkConstants {
    /// β [-].
    pub(super) beta: f64,
    /// γ [-].
    pub(super) gamma: f64,
    /// Δt [s].
    pub(super) time_step: f64,
    /// βΔt² [s²].
    pub(super) beta_dt2: f64,
    /// γΔt [s].
    pub(super) gamma_dt: f64,
    /// Δt²(½ − β) [s²], the acceleration term of the displacement predictor.
    displacement_predictor: f64,
    /// Δt(1 − γ) [s], the acceleration term of the velocity predictor.
    velocity_predictor: f64,
}

impl NewmarkConstants {
    /// The constants for β, γ and Δt.
    pub(super) fn new(beta: f64, gamma: f64, time_step: f64) -> NewmarkConstants {
        let dt = time_step;
        NewmarkConstants {
            beta,
            gamma,
            time_step,
            beta_dt2: beta * dt * dt,
            gamma_dt: gamma * dt,
            displacement_predictor: dt * dt * (0.5 - beta),
            velocity_predictor: dt * (1.0 - gamma),
        }
    }

    /// (βΔt², γΔt) of the corrector; (0, 0) at the first instant.
    #[inline]
    pub(super) fn corrector(&self, initial: bool) -> (f64, f64) {
        if initial {
            (0.0, 0.0)
        } else {
            (self.beta_dt2, self.gamma_dt)
        }
    }
}

/// Displacements, velocities and accelerations of a set of DOFs, and the predictor of the step.
pub(super) struct NewmarkState {
    /// u.
    pub(super) displacement: Vec<f64>,
    /// u̇.
    pub(super) velocity: Vec<f64>,
    /// ü (the unknown a of the step once solved).
    pub(super) acceleration: Vec<f64>,
    /// ũ.
    pub(super) predicted_displacement: Vec<f64>,
    /// ṽ.
    pub(super) predicted_velocity: Vec<f64>,
}

impl NewmarkState {
    /// At rest with the given displacements.
    pub(super) fn at_rest(displacement: Vec<f64>) -> NewmarkState {
        let n = displacement.len();
        NewmarkState {
            displacement,
            velocity: vec![0.0; n],
            acceleration: vec![0.0; n],
            predicted_displacement: vec![0.0; n],
            predicted_velocity: vec![0.0; n],
        }
    }

    /// The predictor (ũ, ṽ) of the step; at the first instant the state itself.
    #[inline]
    pub(super) fn predict(&mut self, newmark: &NewmarkConstants, initial: bool) {
        if initial {
            self.predicted_displacement
                .copy_from_slice(&self.displacement);
            self.predicted_velocity.copy_from_slice(&self.velocity);
            return;
        }
        let (dt, c1, c2) = (
            newmark.time_step,
            newmark.displacement_predictor,
            newmark.velocity_predictor,
        );
        let rows = self
            .displacement
            .iter()
            .zip(&self.velocity)
            .zip(&self.acceleration);
        let predicted = self
            .predicted_displacement
            .iter_mut()
            .zip(self.predicted_velocity.iter_mut());
        for ((u_pred, v_pred), ((u, v), a)) in predicted.zip(rows) {
            *u_pred = u + dt * v + c1 * a;
            *v_pred = v + c2 * a;
        }
    }

    /// The corrector u = ũ + βΔt² a, u̇ = ṽ + γΔt a with a = `self.acceleration`;
    /// `(beta_dt2, gamma_dt)` from [`NewmarkConstants::corrector`].
    #[inline]
    pub(super) fn correct(&mut self, (beta_dt2, gamma_dt): (f64, f64)) {
        let rows = self
            .predicted_displacement
            .iter()
            .zip(&self.predicted_velocity)
            .zip(&self.acceleration);
        let state = self.displacement.iter_mut().zip(self.velocity.iter_mut());
        for ((u, v), ((u_pred, v_pred), a)) in state.zip(rows) {
            *u = u_pred + beta_dt2 * a;
            *v = v_pred + gamma_dt * a;
        }
    }

    /// The predictor of the modes, each with its own β ([`super::modal_newmark_beta`]):
    /// ũₖ = uₖ + Δt u̇ₖ + `displacement_predictor[k]` üₖ, ṽₖ = u̇ₖ + Δt(1 − γ) üₖ; at the first
    /// instant the state itself.
    #[inline]
    pub(super) fn predict_each(
        &mut self,
        newmark: &NewmarkConstants,
        displacement_predictor: &[f64],
        initial: bool,
    ) {
        if initial {
            self.predicted_displacement
                .copy_from_slice(&self.displacement);
            self.predicted_velocity.copy_from_slice(&self.velocity);
            return;
        }
        let (dt, c2) = (newmark.time_step, newmark.velocity_predictor);
        let rows = (self.displacement.iter().zip(&self.velocity))
            .zip(self.acceleration.iter().zip(displacement_predictor));
        let predicted = self
            .predicted_displacement
            .iter_mut()
            .zip(self.predicted_velocity.iter_mut());
        for ((u_pred, v_pred), ((u, v), (a, c1))) in predicted.zip(rows) {
            *u_pred = u + dt * v + c1 * a;
            *v_pred = v + c2 * a;
        }
    }

    /// The corrector of the modes, each with its own βₖΔt² (`beta_dt2`): uₖ = ũₖ + βₖΔt² aₖ,
    /// u̇ₖ = ṽₖ + γΔt aₖ; at the first instant (`gamma_dt` = 0) the state is left as predicted.
    #[inline]
    pub(super) fn correct_each(&mut self, beta_dt2: &[f64], gamma_dt: f64) {
        let initial = gamma_dt == 0.0;
        let rows = (self
            .predicted_displacement
            .iter()
            .zip(&self.predicted_velocity))
        .zip(self.acceleration.iter().zip(beta_dt2));
        let state = self.displacement.iter_mut().zip(self.velocity.iter_mut());
        for ((u, v), ((u_pred, v_pred), (a, b))) in state.zip(rows) {
            let b = if initial { 0.0 } else { *b };
            *u = u_pred + b * a;
            *v = v_pred + gamma_dt * a;
        }
    }

    /// Whether u and u̇ are zero (a state of rest, up to its accelerations).
    #[inline]
    pub(super) fn is_still(&self) -> bool {
        self.displacement
            .iter()
            .chain(&self.velocity)
            .all(|&x| x == 0.0)
    }

    /// The bits of u, u̇ and ü, to compare two states exactly.
    pub(super) fn state_bits(&self) -> Vec<u64> {
        let values = self.displacement.iter().chain(&self.velocity);
        values
            .chain(&self.acceleration)
            .map(|x| x.to_bits())
            .collect()
    }

    /// The predicted state (ũ, ṽ).
    #[inline]
    pub(super) fn predicted(&self) -> (&[f64], &[f64]) {
        (&self.predicted_displacement, &self.predicted_velocity)
    }

    /// The current state (u, u̇).
    #[inline]
    pub(super) fn current(&self) -> (&[f64], &[f64]) {
        (&self.displacement, &self.velocity)
    }
}
