//! The recorder: the histories of a run being written, one instant at a time, and the contact
//! losses, turned into the [`ResponseHistory`] at the end.

use super::contact::TyreOutcome;
use super::tyre::MovingForce;
use super::{ContactLoss, ContactPath, Recording, ResponseHistory, SolverError, SolverWarning};

/// What a [`ResponseHistory`] states about its run besides the recorded histories.
pub(super) struct RunDescription {
    /// Time step Δt [s].
    pub(super) time_step: f64,
    /// Number of modes N.
    pub(super) mode_count: usize,
    /// Speed v of the first vehicle at t = 0 [m/s].
    pub(super) speed: f64,
    /// Newmark β and γ [-].
    pub(super) newmark: (f64, f64),
    /// Contact paths, in the vehicle's contact order.
    pub(super) contacts: Vec<ContactPath>,
    /// Vehicle DOF names.
    pub(super) vehicle_dof_names: Vec<String>,
}

/// The histories being written (step-major tables), the contact forces of the current instant
/// and the contact losses.
pub(super) struct Recorder {
    front_axle_position: Vec<f64>,
    contact_position: Vec<f64>,
    modal_displacement: Vec<f64>,
    modal_velocity: Vec<f64>,
    modal_acceleration: Vec<f64>,
    contact_force: Vec<f64>,
    vehicle_displacement: Vec<f64>,
    vehicle_acceleration: Vec<f64>,
    /// P_w of every contact at the current instant (moving forces: their constant load).
    current_contact_force: Vec<f64>,
    /// Intervals of lost contact, in the order they started.
    contact_losses: Vec<ContactLoss>,
    /// The open loss interval of each contact (index into `contact_losses`).
    open_loss: Vec<Option<usize>>,
    /// First instant at which every contact has left the deck.
    exit_step: Option<usize>,
    /// First instant recorded with a modal coordinate that is not finite (checked as each
    /// instant is recorded, while its q is in the cache).
    first_non_finite: Option<usize>,
    /// Number of instants recorded.
    instants: usize,
    /// What is recorded.
    recording: Recording,
}

impl Recorder {
    /// Room for `instant_count` instants of `mode_count` modes, `dof_count` vehicle DOFs and
    /// `contact_count` contacts, of which `forces` are moving forces, for what `recording` keeps.
    pub(super) fn new(
        instant_count: usize,
        (mode_count, dof_count, contact_count): (usize, usize, usize),
        forces: &[MovingForce],
        recording: Recording,
    ) -> Recorder {
        // Values kept per instant: the front axle, q, each of q̇ and q̈, the contacts' positions
        // and forces, each of Z and Z̈.
        let (front, modes, rates, contacts, vehicle) = match recording {
            Recording::Everything => (1, mode_count, mode_count, contact_count, dof_count),
            Recording::ForDafAnalysis => (1, mode_count, 0, contact_count, 0),
            Recording::OutcomeOnly => (0, 0, 0, 0, 0),
        };
        let mut current_contact_force = vec![0.0; contact_count];
        for force in forces {
            current_contact_force[force.contact] = force.load;
        }
        let table = |per_instant: usize| Vec::with_capacity(instant_count * per_instant);
        let modal_displacement = table(modes);
        let (modal_velocity, modal_acceleration) = (table(rates), table(rates));
        let contact_position = table(contacts);
        let contact_force = table(contacts);
        let vehicle_displacement = table(vehicle);
        let vehicle_acceleration = table(vehicle);
        Recorder {
            front_axle_position: table(front),
            contact_position,
            modal_displacement,
            modal_velocity,
            modal_acceleration,
            contact_force,
            vehicle_displacement,
            vehicle_acceleration,
            current_contact_force,
            contact_losses: Vec::new(),
            open_loss: vec![None; contact_count],
            exit_step: None,
            first_non_finite: None,
            instants: 0,
            recording,
        }
    }

    /// The contact forces of the current instant, per contact [N].
    #[inline]
    pub(super) fn contact_forces(&self) -> &[f64] {
        &self.current_contact_force
    }

    /// Number of instants recorded.
    #[inline]
    pub(super) fn recorded_instants(&self) -> usize {
        self.instants
    }

    /// The end-of-step force of tyre `contact` at `time`, opening, extending or closing its
    /// interval of lost contact (the interval's minimum is the most tensile measure).
    #[inline]
    pub(super) fn set_tyre_force(&mut self, contact: usize, outcome: TyreOutcome, time: f64) {
        self.current_contact_force[contact] = outcome.force;
        match (outcome.lost, self.open_loss[contact]) {
            (true, None) => {
                self.open_loss[contact] = Some(self.contact_losses.len());
                self.contact_losses.push(ContactLoss {
                    contact,
                    start_time: time,
                    end_time: time,
                    minimum_force: outcome.measure,
                });
            }
            (true, Some(idx)) => {
                let loss = &mut self.contact_losses[idx];
                loss.minimum_force = loss.minimum_force.min(outcome.measure);
                loss.end_time = time;
            }
            (false, Some(idx)) => {
                self.contact_losses[idx].end_time = time;
                self.open_loss[contact] = None;
            }
            (false, None) => {}
        }
    }

    /// Notes instant `step` as the exit (start of free vibration) if it is the first at which
    /// every contact has left the deck.
    #[inline]
    pub(super) fn note_exit(&mut self, step: usize, left_deck: bool) {
        if self.exit_step.is_none() && left_deck {
            self.exit_step = Some(step);
        }
    }

    /// Appends one instant: the first front-axle position and the contact positions, q, q̇, q̈,
    /// the current contact forces, Z, Z̈.
    #[inline]
    pub(super) fn record(
        &mut self,
        (front_axle_position, contact_position): (f64, &[f64]),
        (q, qd, qdd): (&[f64], &[f64], &[f64]),
        (z, zdd): (&[f64], &[f64]),
    ) {
        if self.first_non_finite.is_none() && !q.iter().all(|x| x.is_finite()) {
            self.first_non_finite = Some(self.instants);
        }
        self.instants += 1;
        if self.recording == Recording::OutcomeOnly {
            return;
        }
        self.front_axle_position.push(front_axle_position);
        self.contact_position.extend_from_slice(contact_position);
        self.modal_displacement.extend_from_slice(q);
        self.contact_force
            .extend_from_slice(&self.current_contact_force);
        if self.recording == Recording::Everything {
            self.modal_velocity.extend_from_slice(qd);
            self.modal_acceleration.extend_from_slice(qdd);
            self.vehicle_displacement.extend_from_slice(z);
            self.vehicle_acceleration.extend_from_slice(zdd);
        }
    }

    /// The [`ResponseHistory`] of the instants recorded. Errs if a recorded modal coordinate
    /// is not finite (the time step checks only q₁), at the first instant that has one.
    pub(super) fn finish(
        self,
        run: RunDescription,
        mut warnings: Vec<SolverWarning>,
        unsettled: Option<SolverWarning>,
    ) -> Result<ResponseHistory, SolverError> {
        let n = run.mode_count;
        if let Some(step) = self.first_non_finite {
            return Err(SolverError::NonFinite {
                time: step as f64 * run.time_step,
            });
        }
        warnings.extend(unsettled);
        let step_count = self.recorded_instants();
        Ok(ResponseHistory {
            time_step: run.time_step,
            step_count,
            mode_count: n,
            speed: run.speed,
            newmark: run.newmark,
            front_axle_position: self.front_axle_position,
            contact_position: self.contact_position,
            modal_displacement: self.modal_displacement,
            modal_velocity: self.modal_velocity,
            modal_acceleration: self.modal_acceleration,
            contacts: run.contacts,
            contact_force: self.contact_force,
            vehicle_dof_names: run.vehicle_dof_names,
            vehicle_displacement: self.vehicle_displacement,
            vehicle_acceleration: self.vehicle_acceleration,
            exit_step: self.exit_step.unwrap_or(step_count.saturating_sub(1)),
            contact_losses: self.contact_losses,
            warnings,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A run of no contacts and no vehicle DOFs.
    fn run_of(mode_count: usize) -> RunDescription {
        RunDescription {
            time_step: 0.5,
            mode_count,
            speed: 10.0,
            newmark: (0.25, 0.5),
            contacts: Vec::new(),
            vehicle_dof_names: Vec::new(),
        }
    }

    #[test]
    fn the_first_instant_with_a_coordinate_not_finite_is_the_error_s_time() {
        let run = || run_of(2);
        let record = |qs: &[[f64; 2]]| {
            let mut recorder = Recorder::new(4, (2, 0, 0), &[], Recording::Everything);
            for q in qs {
                recorder.record((0.0, &[]), (q, q, q), (&[], &[]));
            }
            recorder.finish(run(), Vec::new(), None)
        };
        let finite = [[1.0, -2.0], [0.5, 3.0]];
        assert!(record(&finite).is_ok());
        let broken = [
            [1.0, -2.0],
            [0.5, 3.0],
            [0.0, f64::NAN],
            [f64::INFINITY, 0.0],
        ];
        match record(&broken) {
            Err(SolverError::NonFinite { time }) => assert_eq!(time, 1.0, "instant 2 × 0.5 s"),
            other => panic!("expected NonFinite, got {other:?}"),
        }
    }
}
