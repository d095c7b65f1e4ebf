//! The tyre contact active set: which tyres are in flight (`SolverOptions::tyre_separation`).
//!
//! A tyre carries a compressive force only. Each time step is solved with the current set; a
//! tyre in contact whose force came out tensile (P̃_w + s_w < 0) leaves the road, a tyre in
//! flight whose would-be force (the force it would carry if it were pressed onto the road,
//! negative while there is a gap) came out compressive lands; the step is solved again until
//! the set holds, at most [`MAX_CONTACT_PASSES`] passes after the first, after which the last
//! pass is kept and reported ([`SolverWarning::ContactSetUnsettled`]).

use super::SolverWarning;

/// Passes of the contact active set per time step before the set is accepted as it stands.
pub(super) const MAX_CONTACT_PASSES: usize = 10;

/// What the active set does after a pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum PassOutcome {
    /// No tyre changed state: the step is done.
    Settled,
    /// Some tyre lifted off or landed: solve the step again.
    Changed,
    /// The pass limit was reached: the step is kept as it stands.
    Unsettled,
}

/// The force a tyre reports at the end of a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct TyreOutcome {
    /// The contact force P_w [N], compressive positive; zero in flight.
    pub(super) force: f64,
    /// Whether the tyre has lost contact (in flight, or a tensile bonded force).
    pub(super) lost: bool,
    /// The measure of the loss: the would-be force in flight, else the force itself [N].
    pub(super) measure: f64,
}

/// The tyres in flight, their would-be forces, and the steps whose set did not settle.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct ContactSet {
    /// Whether each tyre is in flight.
    in_flight: Vec<bool>,
    /// The would-be force of each tyre in flight, from the last pass's final state [N].
    would_be_force: Vec<f64>,
    /// First time and number of steps whose contact set did not settle.
    unsettled: Option<(f64, usize)>,
}

impl ContactSet {
    /// Every one of `tyre_count` tyres in contact.
    pub(super) fn new(tyre_count: usize) -> ContactSet {
        ContactSet {
            in_flight: vec![false; tyre_count],
            would_be_force: vec![0.0; tyre_count],
            unsettled: None,
        }
    }

    /// Whether tyre `w` is in flight.
    #[inline]
    pub(super) fn is_in_flight(&self, w: usize) -> bool {
        self.in_flight[w]
    }

    /// Records the would-be force of tyre `w` (in flight) at the pass's final state.
    #[inline]
    pub(super) fn set_would_be_force(&mut self, w: usize, force: f64) {
        self.would_be_force[w] = force;
    }

    /// After pass number `passes` (0 for the first) of the step at `time`, with the predicted
    /// forces P̃ and the increments s of that pass (and the would-be forces of the tyres in
    /// flight set): at the pass limit the step is counted as unsettled and kept; otherwise the
    /// tyres in flight whose would-be force is compressive land and the tyres in contact whose
    /// force P̃_w + s_w is tensile lift off.
    pub(super) fn next_pass(
        &mut self,
        passes: usize,
        time: f64,
        predicted_force: &[f64],
        increments: &[f64],
    ) -> PassOutcome {
        if passes >= MAX_CONTACT_PASSES {
            self.unsettled.get_or_insert((time, 0)).1 += 1;
            return PassOutcome::Unsettled;
        }
        let mut changed = false;
        for w in 0..self.in_flight.len() {
            let lands = self.in_flight[w] && self.would_be_force[w] > 0.0;
            let lifts = !self.in_flight[w] && predicted_force[w] + increments[w] < 0.0;
            if lands || lifts {
                self.in_flight[w] = !self.in_flight[w];
                changed = true;
            }
        }
        if changed {
            PassOutcome::Changed
        } else {
            PassOutcome::Settled
        }
    }

    /// The force of tyre `w` at the end of the step: in flight no force, and the loss is
    /// measured by the would-be (tensile) force; in contact P̃_w + s_w, a loss if tensile (only
    /// possible without tyre separation).
    #[inline]
    pub(super) fn outcome(&self, w: usize, predicted_force: f64, increment: f64) -> TyreOutcome {
        if self.in_flight[w] {
            TyreOutcome {
                force: 0.0,
                lost: true,
                measure: self.would_be_force[w],
            }
        } else {
            let force = predicted_force + increment;
            TyreOutcome {
                force,
                lost: force < 0.0,
                measure: force,
            }
        }
    }

    /// The warning of the steps whose set did not settle, if any.
    pub(super) fn unsettled_warning(&self) -> Option<SolverWarning> {
        self.unsettled
            .map(|(first_time, steps)| SolverWarning::ContactSetUnsettled {
                first_time,
                steps,
                passes: MAX_CONTACT_PASSES,
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tyres in flight, in order.
    fn in_flight(set: &ContactSet) -> Vec<usize> {
        (0..set.in_flight.len())
            .filter(|&w| set.is_in_flight(w))
            .collect()
    }

    #[test]
    fn a_tensile_tyre_lifts_off_and_a_compressive_one_stays() {
        let mut set = ContactSet::new(3);
        // P̃ + s: 100, −1, 0 (zero is not tensile).
        let outcome = set.next_pass(0, 0.1, &[50.0, -3.0, 2.0], &[50.0, 2.0, -2.0]);
        assert_eq!(outcome, PassOutcome::Changed);
        assert_eq!(in_flight(&set), vec![1]);
        assert!(set.is_in_flight(1) && !set.is_in_flight(0));
    }

    #[test]
    fn a_tyre_in_flight_lands_when_its_would_be_force_is_compressive() {
        let mut set = ContactSet::new(2);
        set.next_pass(0, 0.0, &[-1.0, -1.0], &[0.0, 0.0]);
        assert_eq!(in_flight(&set).len(), 2);
        // Tyre 0 still has a gap (tensile would-be force), tyre 1 touches the road again; the
        // forces of tyres in flight are not looked at.
        set.set_would_be_force(0, -5.0);
        set.set_would_be_force(1, 5.0);
        let outcome = set.next_pass(1, 0.0, &[1e6, 1e6], &[0.0, 0.0]);
        assert_eq!(outcome, PassOutcome::Changed);
        assert_eq!(in_flight(&set), vec![0]);
        // Zero would-be force does not land.
        set.set_would_be_force(0, 0.0);
        assert_eq!(
            set.next_pass(2, 0.0, &[1.0, 1.0], &[0.0, 0.0]),
            PassOutcome::Settled
        );
        assert!(set.is_in_flight(0));
    }

    #[test]
    fn a_set_that_holds_is_settled_and_unchanged() {
        let mut set = ContactSet::new(2);
        let before = set.clone();
        assert_eq!(
            set.next_pass(0, 0.0, &[10.0, 20.0], &[-5.0, 0.0]),
            PassOutcome::Settled
        );
        assert_eq!(set, before);
        assert_eq!(set.unsettled_warning(), None);
    }

    #[test]
    fn the_pass_limit_keeps_the_set_and_counts_the_step_from_its_first_time() {
        let mut set = ContactSet::new(1);
        for (time, expected_steps) in [(0.5, 1), (0.7, 2)] {
            // Would lift off, but the limit is reached: nothing changes.
            let outcome = set.next_pass(MAX_CONTACT_PASSES, time, &[-1.0], &[0.0]);
            assert_eq!(outcome, PassOutcome::Unsettled);
            assert!(!set.is_in_flight(0));
            assert_eq!(
                set.unsettled_warning(),
                Some(SolverWarning::ContactSetUnsettled {
                    first_time: 0.5,
                    steps: expected_steps,
                    passes: MAX_CONTACT_PASSES,
                })
            );
        }
    }

    #[test]
    fn outcomes_report_no_force_in_flight_and_tensile_bonded_forces_as_losses() {
        let mut set = ContactSet::new(2);
        set.next_pass(0, 0.0, &[-2.0, 3.0], &[0.0, 0.0]);
        set.set_would_be_force(0, -40.0);
        assert_eq!(
            set.outcome(0, -2.0, 0.5),
            TyreOutcome {
                force: 0.0,
                lost: true,
                measure: -40.0
            }
        );
        assert_eq!(
            set.outcome(1, 3.0, 1.0),
            TyreOutcome {
                force: 4.0,
                lost: false,
                measure: 4.0
            }
        );
        // Bonded (no separation): a tensile force is the loss and its measure.
        assert_eq!(
            ContactSet::new(1).outcome(0, 1.0, -3.0),
            TyreOutcome {
                force: -2.0,
                lost: true,
                measure: -2.0
            }
        );
    }
}
