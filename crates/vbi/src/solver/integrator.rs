//! The coupled time step and its public stepping API, [`Integrator`].
//!
//! One instant t_i = i·Δt is computed as: contact kinematics (where each contact is, and the
//! road under it) → Newmark predictors → contact shapes φ, φ′ → predicted tyre forces P̃ →
//! modal and vehicle loads f_q, f_Z → uncoupled accelerations y, u → the on-deck products of
//! the tyre system → the contact active set, each pass solving the T × T system for the
//! tyre-force increments s, the accelerations and the Newmark corrector → contact forces,
//! losses and recording. The first instant (i = 0) takes the same path with βΔt² = γΔt = 0
//! and no increments: it gives the initial accelerations from the static equilibrium.

use super::contact::{ContactSet, PassOutcome};
use super::kinematics::ContactPoints;
use super::loads::StepLoads;
use super::newmark::NewmarkState;
use super::recorder::{Recorder, RunDescription};
use super::setup::Setup;
use super::step_geometry::StepGeometry;
use super::tyre_system::TyreSystem;
use super::{
    ContactPath, Crossing, Recording, ResponseHistory, SolverError, SolverOptions, SolverWarning,
};
use crate::modal::ModalBasis;

/// A crossing being integrated, one time step at a time.
///
/// [`Integrator::new`] sets the crossing up and computes its first instant (t = 0: the vehicle
/// in static equilibrium on the road, the bridge at rest, the initial accelerations);
/// [`Integrator::step`] advances by one time step Δt; [`Integrator::finish`] returns the
/// recorded [`ResponseHistory`]. Between steps the state of the current instant can be read.
/// [`simulate`](super::simulate) is this loop:
///
/// ```
/// # use vbi::solver::{Integrator, Crossing, ResponseHistory, SolverError, SolverOptions};
/// # use vbi::modal::ModalBasis;
/// fn simulate(
///     basis: &ModalBasis,
///     crossing: &Crossing,
///     options: &SolverOptions,
/// ) -> Result<ResponseHistory, SolverError> {
///     let mut integrator = Integrator::new(basis, crossing, options)?;
///     while !integrator.is_finished() {
///         integrator.step()?;
///     }
///     integrator.finish()
/// }
/// ```
pub struct Integrator<'a> {
    basis: &'a ModalBasis,
    crossing: &'a Crossing,
    tyre_separation: bool,
    setup: Setup,
    /// Index i of the current instant t_i = i·Δt.
    step: usize,
    points: ContactPoints,
    /// The shapes and deck coupling of the current instant, when the crossing runs alone
    /// (a batch lends its shared one to [`Integrator::step_sharing`]).
    geometry: StepGeometry<'a>,
    /// Modal coordinates q.
    bridge: NewmarkState,
    /// Whether the bridge's state is that of rest, unchanged by a step without load: true once
    /// a step with no contact on the deck left q, q̇ and q̈ as they were, bit for bit, and until a
    /// contact reaches the deck ([`Integrator::advance`] then leaves the bridge as it is).
    bridge_at_rest: bool,
    /// Whether a bridge at rest is left as it is (false: every step computes it, for the test
    /// of the shortcut).
    #[cfg(test)]
    rest_shortcut: bool,
    /// Vehicle DOFs Z.
    vehicle: NewmarkState,
    loads: StepLoads<'a>,
    system: TyreSystem,
    contact_set: ContactSet,
    recorder: Recorder,
}

impl<'a> Integrator<'a> {
    /// Sets up the crossing (validation, time step, constants, static equilibrium) and
    /// computes its first instant, t = 0.
    pub fn new(
        basis: &'a ModalBasis,
        crossing: &'a Crossing,
        options: &SolverOptions,
    ) -> Result<Integrator<'a>, SolverError> {
        Integrator::recording(basis, crossing, options, Recording::Everything)
    }

    /// [`Integrator::new`], recording what `recording` asks for.
    pub fn recording(
        basis: &'a ModalBasis,
        crossing: &'a Crossing,
        options: &SolverOptions,
        recording: Recording,
    ) -> Result<Integrator<'a>, SolverError> {
        let setup = Setup::new(basis, crossing, options)?;
        let (n, d) = (basis.mode_count(), setup.vehicle.dof_count);
        let t_count = setup.tyres.len();
        let contact_count = setup.traffic.contacts.len();
        let mut integrator = Integrator {
            basis,
            crossing,
            tyre_separation: options.tyre_separation,
            step: 0,
            points: setup.kinematics.points(),
            geometry: StepGeometry::new(basis, &setup, false),
            bridge: NewmarkState::at_rest(vec![0.0; n]),
            bridge_at_rest: false,
            #[cfg(test)]
            rest_shortcut: true,
            vehicle: NewmarkState::at_rest(setup.initial_vehicle_displacement.clone()),
            loads: StepLoads::new(basis, t_count, &setup.forces, d),
            system: TyreSystem::new(&setup.vehicle),
            contact_set: ContactSet::new(t_count),
            recorder: Recorder::new(
                setup.instant_count,
                (n, d, contact_count),
                &setup.forces,
                recording,
            ),
            setup,
        };
        integrator.advance_alone()?;
        Ok(integrator)
    }

    /// Advances by one time step Δt to the next instant; an error, changing nothing, once the
    /// run is finished ([`Integrator::is_finished`]).
    pub fn step(&mut self) -> Result<(), SolverError> {
        if self.is_finished() {
            return Err(SolverError::AlreadyFinished {
                steps: self.setup.instant_count - 1,
            });
        }
        self.step += 1;
        self.advance_alone()
    }

    /// [`Integrator::step`] with the position-dependent quantities of the instant taken from
    /// (or computed into) `geometry`, which crossings that differ only in their road share:
    /// the numbers are those of [`Integrator::step`], bit for bit.
    pub(super) fn step_sharing(
        &mut self,
        geometry: &mut StepGeometry<'a>,
    ) -> Result<(), SolverError> {
        if self.is_finished() {
            return Err(SolverError::AlreadyFinished {
                steps: self.setup.instant_count - 1,
            });
        }
        self.step += 1;
        self.advance(geometry)
    }

    /// Buffers for the position-dependent quantities of this crossing's instants, to share
    /// with the crossings that [`Integrator::can_share_geometry_with`] it (`shared`: there are
    /// such crossings, [`StepGeometry::new`]).
    pub(super) fn new_step_geometry(&self, shared: bool) -> StepGeometry<'a> {
        StepGeometry::new(self.basis, &self.setup, shared)
    }

    /// Whether `other` has the same vehicles, motion, time grid and constants, so that the two
    /// can share their [`StepGeometry`] instant by instant (their roads may differ).
    pub(super) fn can_share_geometry_with(&self, other: &Integrator) -> bool {
        std::ptr::eq(self.basis, other.basis)
            && self.crossing.vehicles == other.crossing.vehicles
            && self.setup.instant_count == other.setup.instant_count
            && self.setup.newmark.time_step.to_bits() == other.setup.newmark.time_step.to_bits()
            && self.setup.newmark.beta.to_bits() == other.setup.newmark.beta.to_bits()
            && self.setup.newmark.gamma.to_bits() == other.setup.newmark.gamma.to_bits()
            && self.step == other.step
    }

    /// True once the last instant of the run has been computed: the last contact has left the
    /// deck and the free-vibration window has passed.
    pub fn is_finished(&self) -> bool {
        self.step + 1 >= self.setup.instant_count
    }

    /// The history recorded so far: the whole run once [`Integrator::is_finished`], or the
    /// instants up to the current one. Errs if a recorded modal coordinate is not finite.
    pub fn finish(self) -> Result<ResponseHistory, SolverError> {
        let run = RunDescription {
            time_step: self.setup.newmark.time_step,
            mode_count: self.basis.mode_count(),
            speed: self.setup.kinematics.initial_speed(),
            newmark: (self.setup.newmark.beta, self.setup.newmark.gamma),
            contacts: self.contact_paths(),
            vehicle_dof_names: self.setup.traffic.dof_names.clone(),
        };
        let unsettled = self.contact_set.unsettled_warning();
        self.recorder.finish(run, self.setup.warnings, unsettled)
    }

    /// The contacts' paths (vehicle, offset, lateral position, static load), in the stacked
    /// contact order: [`ResponseHistory::contacts`].
    pub fn contact_paths(&self) -> Vec<ContactPath> {
        let traffic = &self.setup.traffic;
        traffic
            .contacts
            .iter()
            .zip(&traffic.placements)
            .map(|(c, placement)| ContactPath {
                vehicle: placement.vehicle,
                longitudinal_offset: c.longitudinal_offset,
                lateral_position: placement.lateral,
                static_load: c.static_load,
            })
            .collect()
    }

    /// Position x of every contact at every instant of the run [m], step-major: the table
    /// [`ResponseHistory::contact_position`] that the run records, bit for bit, computed from
    /// the travel laws before the run (the positions do not depend on the response). With
    /// [`Integrator::contact_paths`], the run's [`WheelPaths`](super::WheelPaths).
    pub fn contact_positions_of_run(&self) -> Vec<f64> {
        let kinematics = &self.setup.kinematics;
        let mut points = kinematics.points();
        let contacts = points.position.len();
        let mut positions = Vec::with_capacity(self.setup.instant_count * contacts);
        for step in 0..self.setup.instant_count {
            kinematics.locate_on_deck(self.time_at(step), &mut points);
            positions.extend_from_slice(&points.position);
        }
        positions
    }

    /// Index i of the current instant.
    pub fn step_index(&self) -> usize {
        self.step
    }

    /// Number of instants of the whole run (time steps + 1).
    pub fn step_count(&self) -> usize {
        self.setup.instant_count
    }

    /// Time step Δt [s].
    pub fn time_step(&self) -> f64 {
        self.setup.newmark.time_step
    }

    /// Time t_i = i·Δt of the current instant [s].
    pub fn time(&self) -> f64 {
        self.time_at(self.step)
    }

    /// Time t_i = i·Δt of instant `step` [s]: the one computation of an instant's time, so that
    /// [`Integrator::contact_positions_of_run`] finds the step's positions bit for bit.
    fn time_at(&self, step: usize) -> f64 {
        step as f64 * self.setup.newmark.time_step
    }

    /// Deck position x of the first vehicle's front axle at the current instant [m].
    pub fn front_axle_position(&self) -> f64 {
        self.points.front_axle_position
    }

    /// Deck position x of every contact at the current instant [m], in the stacked contact
    /// order (the vehicles of the crossing one after the other).
    pub fn contact_positions(&self) -> &[f64] {
        &self.points.position
    }

    /// Modal coordinates qₖ [kg^½·m], k = 1…N.
    pub fn modal_displacements(&self) -> &[f64] {
        &self.bridge.displacement
    }

    /// Modal velocities q̇ₖ [kg^½·m/s].
    pub fn modal_velocities(&self) -> &[f64] {
        &self.bridge.velocity
    }

    /// Modal accelerations q̈ₖ [kg^½·m/s²].
    pub fn modal_accelerations(&self) -> &[f64] {
        &self.bridge.acceleration
    }

    /// Vehicle displacements Z from static equilibrium [m, rad], in the vehicle's DOF order.
    pub fn vehicle_displacements(&self) -> &[f64] {
        &self.vehicle.displacement
    }

    /// Vehicle velocities Ż [m/s, rad/s].
    pub fn vehicle_velocities(&self) -> &[f64] {
        &self.vehicle.velocity
    }

    /// Vehicle accelerations Z̈ [m/s², rad/s²].
    pub fn vehicle_accelerations(&self) -> &[f64] {
        &self.vehicle.acceleration
    }

    /// Total contact force P_w of every contact [N], compressive positive, static load
    /// included, in the vehicle's contact order (zero for a tyre in flight).
    pub fn contact_forces(&self) -> &[f64] {
        self.recorder.contact_forces()
    }

    /// Whether contact `contact` (index into the stacked contacts) is on the road: false
    /// for a tyre in flight, true for every other tyre and for a moving force.
    ///
    /// # Panics
    /// If `contact` is not a contact of the crossing's vehicles.
    pub fn is_in_contact(&self, contact: usize) -> bool {
        assert!(
            contact < self.setup.traffic.contacts.len(),
            "no contact {contact}"
        );
        match self.setup.tyres.iter().position(|t| t.contact == contact) {
            Some(w) => !self.contact_set.is_in_flight(w),
            None => true,
        }
    }

    /// The warnings known before stepping (under-resolved modes or road).
    pub fn warnings(&self) -> &[SolverWarning] {
        &self.setup.warnings
    }

    /// [`Integrator::advance`] with the crossing's own geometry.
    fn advance_alone(&mut self) -> Result<(), SolverError> {
        let mut geometry = std::mem::replace(&mut self.geometry, StepGeometry::none());
        let result = self.advance(&mut geometry);
        self.geometry = geometry;
        result
    }

    /// Computes the current instant `self.step` (the paper's Eqs. 23–29 at t_i).
    ///
    /// While no contact is on the deck and the bridge is at rest (a vehicle on the approach
    /// road), the step leaves the bridge as it is: a step without load maps the state of rest
    /// to itself, bit for bit, so computing it would give the same numbers (checked, not
    /// assumed: [`Integrator::bridge_at_rest`] is set only after a computed step left the state
    /// unchanged). The approach is about half of a study's time steps.
    fn advance(&mut self, geometry: &mut StepGeometry<'a>) -> Result<(), SolverError> {
        let time = self.time_at(self.step);
        let setup = &self.setup;
        let newmark = &setup.newmark;
        let initial = self.step == 0;
        setup.kinematics.locate_on_deck(time, &mut self.points);
        geometry.update(self.basis, setup, self.step, &self.points);
        geometry.road_under_tyres(&setup.kinematics, &self.crossing.road, &mut self.points);
        let unloaded = setup.forces.is_empty() && !geometry.shapes.any_on_deck();
        let bridge_still = !initial && unloaded && self.bridge_at_rest && self.rest_shortcut();
        let rest_before = (!initial && unloaded && !bridge_still && self.bridge.is_still())
            .then(|| self.bridge.state_bits());
        if !bridge_still {
            self.bridge
                .predict_each(newmark, &setup.modal.displacement_predictor, initial);
        }
        self.vehicle.predict(newmark, initial);
        let shapes = &geometry.shapes;
        let loads = &mut self.loads;
        loads.predict_tyre_forces(
            &setup.tyres,
            shapes,
            &self.points,
            &self.bridge,
            &self.vehicle,
        );
        if !bridge_still {
            loads.assemble_modal(
                self.basis,
                &setup.modal,
                &self.bridge,
                &setup.forces,
                shapes,
                &self.points,
            );
        }
        loads.assemble_vehicle(&setup.vehicle, &setup.tyres, &self.vehicle);
        loads.add_pitch_moments(&setup.traffic.pitch_loads, &self.points);
        if bridge_still {
            loads.uncoupled_vehicle_accelerations(&setup.vehicle, initial);
        } else {
            loads.uncoupled_accelerations(&setup.modal, &setup.vehicle, initial);
        }
        self.system
            .deck_right_hand_side(&geometry.coupling, &loads.modal_uncoupled);
        self.settle_contact_set(geometry, time, initial, bridge_still)?;
        self.bridge_at_rest = match rest_before {
            Some(before) => before == self.bridge.state_bits(),
            None => bridge_still,
        };
        self.record(time)
    }

    /// Whether a bridge at rest is left as it is (always, but in the test of the shortcut).
    #[inline]
    fn rest_shortcut(&self) -> bool {
        #[cfg(test)]
        {
            self.rest_shortcut
        }
        #[cfg(not(test))]
        {
            true
        }
    }

    /// Whether the last step left the bridge at rest as it was (the test of the shortcut).
    #[cfg(test)]
    pub(super) fn bridge_left_at_rest(&self) -> bool {
        self.bridge_at_rest
    }

    /// Makes every step compute the bridge, at rest or not (the reference of the shortcut's
    /// test).
    #[cfg(test)]
    pub(super) fn without_rest_shortcut(mut self) -> Self {
        self.rest_shortcut = false;
        self
    }

    /// The passes of the contact active set ([`super::contact`]): solve with the current set,
    /// then let tyres lift off or land, until the set holds.
    fn settle_contact_set(
        &mut self,
        geometry: &mut StepGeometry<'a>,
        time: f64,
        initial: bool,
        bridge_still: bool,
    ) -> Result<(), SolverError> {
        let mut passes = 0;
        loop {
            self.solve_increments(geometry, time, initial)?;
            self.correct(geometry, initial, bridge_still);
            if initial || !self.tyre_separation {
                return Ok(());
            }
            self.update_would_be_forces(geometry);
            let outcome = self.contact_set.next_pass(
                passes,
                time,
                &self.loads.predicted_force,
                self.system.increments(),
            );
            match outcome {
                PassOutcome::Settled | PassOutcome::Unsettled => return Ok(()),
                PassOutcome::Changed => passes += 1,
            }
        }
    }

    /// The tyre-force increments s of one pass ([`super::tyre_system`]): none at the first
    /// instant (where βΔt² = γΔt = 0 makes every coefficient vanish) or without tyres; else the
    /// coupled system of the vehicles with a tyre on the deck, assembled, factorised and
    /// solved, and each other vehicle's own system.
    fn solve_increments(
        &mut self,
        geometry: &mut StepGeometry<'a>,
        time: f64,
        initial: bool,
    ) -> Result<(), SolverError> {
        let (setup, system) = (&self.setup, &mut self.system);
        system.clear_increments();
        if initial || setup.tyres.is_empty() {
            return Ok(());
        }
        let solved = system.solve(
            &mut geometry.coupling,
            &setup.tyres,
            &setup.vehicle,
            &self.loads.vehicle_uncoupled,
            &self.contact_set,
            &self.loads.predicted_force,
        );
        if !solved {
            return Err(SolverError::SingularSystem { time });
        }
        Ok(())
    }

    /// The accelerations of the pass's increments and the Newmark corrector of q and Z (of Z
    /// alone when the bridge is left at rest).
    fn correct(&mut self, geometry: &StepGeometry, initial: bool, bridge_still: bool) {
        let corrector = self.setup.newmark.corrector(initial);
        if bridge_still {
            let (u, zdd) = (
                &self.loads.vehicle_uncoupled,
                &mut self.vehicle.acceleration,
            );
            self.system
                .vehicle_accelerations(&self.setup.vehicle, u, zdd);
            self.vehicle.correct(corrector);
            return;
        }
        let uncoupled = (
            &self.loads.modal_uncoupled[..],
            &self.loads.vehicle_uncoupled[..],
        );
        let accelerations = (
            &mut self.bridge.acceleration[..],
            &mut self.vehicle.acceleration[..],
        );
        self.system.accelerations(
            &geometry.coupling,
            &self.setup.vehicle,
            uncoupled,
            accelerations,
        );
        self.bridge
            .correct_each(&self.setup.modal.beta_dt2, corrector.1);
        self.vehicle.correct(corrector);
    }

    /// The would-be force of every tyre in flight, from the pass's final state.
    fn update_would_be_forces(&mut self, geometry: &StepGeometry) {
        let ((q, qd), (z, zd)) = (self.bridge.current(), self.vehicle.current());
        for (w, t) in self.setup.tyres.iter().enumerate() {
            if self.contact_set.is_in_flight(w) {
                let force = t.force_at((q, qd, z, zd), geometry.shapes.of(w), &self.points);
                self.contact_set.set_would_be_force(w, force);
            }
        }
    }

    /// Contact forces and losses of the instant, the exit, the record, and the check that the
    /// step stayed finite.
    fn record(&mut self, time: f64) -> Result<(), SolverError> {
        let s = self.system.increments();
        for (w, t) in self.setup.tyres.iter().enumerate() {
            let outcome = self
                .contact_set
                .outcome(w, self.loads.predicted_force[w], s[w]);
            self.recorder.set_tyre_force(t.contact, outcome, time);
        }
        let left_deck = self.setup.kinematics.has_left_deck(&self.points);
        self.recorder.note_exit(self.step, left_deck);
        self.recorder.record(
            (self.points.front_axle_position, &self.points.position),
            (
                &self.bridge.displacement,
                &self.bridge.velocity,
                &self.bridge.acceleration,
            ),
            (&self.vehicle.displacement, &self.vehicle.acceleration),
        );
        let (q, zdd) = (&self.bridge.displacement, &self.vehicle.acceleration);
        if !q[0].is_finite()
            || s.iter().any(|x| !x.is_finite())
            || zdd.iter().any(|x| !x.is_finite())
        {
            return Err(SolverError::NonFinite { time });
        }
        Ok(())
    }
}
