//! Vehicles catching each other up: two vehicles in the same lane and direction whose gap closes
//! during the event (a faster follower, a braking leader) would drive through each other, which
//! the model cannot represent, so such traffic is refused before any work.
//!
//! The gap between the leader's last contact and the follower's front axle, both in the travel
//! coordinate of their direction, is g(t) = s_L(t) − ℓ_L − s_F(t) (ℓ_L the leader's trailing
//! length). Each travel law is piecewise uniformly accelerated ([`super::law`]), so between
//! consecutive phase starts of either law g is one quadratic,
//! g(t_a + τ) = g_a + (v_L − v_F) τ + ½ (a_L − a_F) τ²,
//! and its first zero is found exactly, piece by piece, as the smallest root τ ≥ 0 of that
//! quadratic through which g decreases (a touch, g = 0 with g′ = 0, is not a closing).

use super::apart::footprint;
use super::law::{TravelDirection, TravelLaw};
use super::VehicleRun;

/// Where and when a following vehicle's front axle reaches a leading vehicle's last contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CatchingUp {
    /// Index of the vehicle ahead in the crossing's list.
    pub leader: usize,
    /// Index of the vehicle behind, which catches the leader up.
    pub follower: usize,
    /// The time the gap closes [s].
    pub time: f64,
    /// The follower's front-axle travel coordinate then [m] (distance past the deck entry of
    /// their direction; negative on the approach).
    pub travel: f64,
    /// The same point as a deck position x [m] (x = s forward, L − s backward).
    pub position: f64,
}

/// The earliest closing of a gap between two vehicles in the same direction whose lanes meet
/// (their contacts' lateral ranges touch), from t = 0 until the last contact of the event's last
/// vehicle leaves the deck of length L [m]; `None` when every gap stays open. Vehicles that
/// overlap at t = 0 are [`super::check_vehicles_apart`]'s to refuse.
pub fn first_catching_up(vehicles: &[VehicleRun], deck_length: f64) -> Option<CatchingUp> {
    let laws: Vec<TravelLaw> = vehicles
        .iter()
        .map(|r| TravelLaw::new(r.start_position, &r.speed))
        .collect();
    let end = event_end(vehicles, &laws, deck_length);
    let mut first: Option<CatchingUp> = None;
    for (i, a) in vehicles.iter().enumerate() {
        for (j, b) in vehicles.iter().enumerate().skip(i + 1) {
            if !same_lane(a, b, deck_length) {
                continue;
            }
            let (leader, follower) = if a.start_position >= b.start_position {
                (i, j)
            } else {
                (j, i)
            };
            let trailing = vehicles[leader].vehicle.trailing_length();
            let Some(time) = first_closing(&laws[leader], trailing, &laws[follower], end) else {
                continue;
            };
            if first.is_some_and(|f| f.time <= time) {
                continue;
            }
            let travel = laws[follower].at(time).0;
            let position = match vehicles[follower].direction {
                TravelDirection::Forward => travel,
                TravelDirection::Backward => deck_length - travel,
            };
            first = Some(CatchingUp {
                leader,
                follower,
                time,
                travel,
                position,
            });
        }
    }
    first
}

/// The time the last contact of the last vehicle leaves the deck [s]: the largest over the
/// vehicles of t(s = L + ℓ).
fn event_end(vehicles: &[VehicleRun], laws: &[TravelLaw], deck_length: f64) -> f64 {
    vehicles
        .iter()
        .zip(laws)
        .map(|(run, law)| law.time_at_travel(deck_length + run.vehicle.trailing_length()))
        .fold(0.0, f64::max)
}

/// Same direction, and lateral ranges of the contacts that meet.
fn same_lane(a: &VehicleRun, b: &VehicleRun, deck_length: f64) -> bool {
    let ((_, ya), (_, yb)) = (footprint(a, deck_length), footprint(b, deck_length));
    a.direction == b.direction && ya.0 <= yb.1 && yb.0 <= ya.1
}

/// The first time in [0, end] at which g(t) = s_L(t) − ℓ_L − s_F(t) closes (goes from ≥ 0 to
/// < 0), piece by piece between the phase starts of both laws.
fn first_closing(leader: &TravelLaw, trailing: f64, follower: &TravelLaw, end: f64) -> Option<f64> {
    let mut starts: Vec<f64> = std::iter::once(0.0)
        .chain(leader.phase_start_times())
        .chain(follower.phase_start_times())
        .filter(|&t| t < end)
        .collect();
    starts.sort_by(f64::total_cmp);
    starts.dedup();
    starts.push(end);
    starts.windows(2).find_map(|piece| {
        let (start, length) = (piece[0], piece[1] - piece[0]);
        let ((s_l, v_l), (s_f, v_f)) = (leader.at(start), follower.at(start));
        let gap = s_l - trailing - s_f;
        let rate = v_l - v_f;
        let curvature = leader.acceleration(start) - follower.acceleration(start);
        first_decreasing_root(gap, rate, curvature, length).map(|tau| start + tau)
    })
}

/// The smallest τ in [0, length] with g(τ) = g₀ + g₁ τ + ½ g₂ τ² = 0 and g′(τ) = g₁ + g₂ τ < 0
/// (with g₀ ≥ 0: the gap closes there); a gap already shut at τ = 0 closes at once if it
/// decreases.
fn first_decreasing_root(g0: f64, g1: f64, g2: f64, length: f64) -> Option<f64> {
    let decreasing = |tau: f64| g1 + g2 * tau < 0.0 || (g1 + g2 * tau == 0.0 && g2 < 0.0);
    if g0 <= 0.0 {
        return decreasing(0.0).then_some(0.0);
    }
    let mut roots = quadratic_roots(0.5 * g2, g1, g0);
    roots.sort_by(f64::total_cmp);
    roots
        .into_iter()
        .find(|&tau| (0.0..=length).contains(&tau) && g1 + g2 * tau < 0.0)
}

/// The real roots of a x² + b x + c = 0 (c ≠ 0), in the cancellation-free form
/// q = −½ (b + sign(b) √(b² − 4ac)), x = q/a and c/q; one root when a = 0.
fn quadratic_roots(a: f64, b: f64, c: f64) -> Vec<f64> {
    if a == 0.0 {
        return if b == 0.0 { Vec::new() } else { vec![-c / b] };
    }
    let discriminant = b * b - 4.0 * a * c;
    if discriminant < 0.0 {
        return Vec::new();
    }
    let q = -0.5 * (b + b.signum() * discriminant.sqrt());
    if q == 0.0 {
        return vec![0.0];
    }
    vec![q / a, c / q]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The roots of the quadratic against hand-solved ones: (x − 1)(x − 3) = x² − 4x + 3, and
    /// the decreasing root chosen: g = 3 − 4τ + τ² closes at τ = 1 (g′ = −2) and not at 3.
    #[test]
    fn the_first_decreasing_root_of_a_hand_solved_quadratic() {
        let mut roots = quadratic_roots(1.0, -4.0, 3.0);
        roots.sort_by(f64::total_cmp);
        assert_eq!(roots, vec![1.0, 3.0]);
        assert_eq!(first_decreasing_root(3.0, -4.0, 2.0, 10.0), Some(1.0));
        // An opening gap (g = 3 + τ) never closes; a shrinking one beyond the piece neither.
        assert_eq!(first_decreasing_root(3.0, 1.0, 0.0, 10.0), None);
        assert_eq!(first_decreasing_root(3.0, -1.0, 0.0, 2.0), None);
        // g = 1 − 2τ + τ² touches zero at τ = 1 without closing.
        assert_eq!(first_decreasing_root(1.0, -2.0, 2.0, 10.0), None);
        // Shut at τ = 0: closes at once if it decreases, not if it opens.
        assert_eq!(first_decreasing_root(0.0, -1.0, 0.0, 1.0), Some(0.0));
        assert_eq!(first_decreasing_root(0.0, 1.0, 0.0, 1.0), None);
    }
}
