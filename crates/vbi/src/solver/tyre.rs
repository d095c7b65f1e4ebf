//! The contacts of the vehicle as the time loop uses them: tyres (a spring and damper under a
//! wheel, Eqs. 23–26) and moving forces (a constant load), with their constant data prepared
//! once.

use super::kinematics::ContactPoints;
use super::stacked::{Placement, StackedVehicles};
use crate::vehicle::ContactKind;

/// A tyre contact prepared for the time loop.
pub(super) struct Tyre {
    /// Index of the contact in the vehicle's contacts.
    pub(super) contact: usize,
    /// Index of its vehicle in the crossing.
    pub(super) vehicle: usize,
    /// Tyre stiffness k_w [N/m].
    pub(super) stiffness: f64,
    /// Tyre damping c_w [N·s/m].
    pub(super) damping: f64,
    /// Dense coupling vector a_w over its own vehicle's DOFs (length d_v): the wheel
    /// displacement is Z_w = a_w·Z_v.
    pub(super) coupling: Vec<f64>,
    /// The non-zero entries of a_w as (stacked DOF, coefficient), for the per-step products.
    pub(super) coupling_sparse: Vec<(usize, f64)>,
    /// Lateral position y on the deck [m].
    pub(super) lateral: f64,
    /// Static wheel load S_w [N].
    pub(super) static_load: f64,
}

/// A moving-force contact ([`ContactKind::Force`]): a constant load P_w = S_w.
pub(super) struct MovingForce {
    /// Index of the contact in the vehicle's contacts.
    pub(super) contact: usize,
    /// Lateral position y on the deck [m].
    pub(super) lateral: f64,
    /// The load S_w [N], downwards positive.
    pub(super) load: f64,
}

/// The contacts of the stacked vehicles, split into tyres and moving forces (each in the
/// stacked order, so each vehicle's tyres are consecutive), at their deck lateral positions.
pub(super) fn prepare_contacts(traffic: &StackedVehicles) -> (Vec<Tyre>, Vec<MovingForce>) {
    let mut tyres = Vec::new();
    let mut forces = Vec::new();
    for (w, c) in traffic.contacts.iter().enumerate() {
        let Placement {
            vehicle: own_vehicle,
            lateral,
            ..
        } = traffic.placements[w];
        let dofs = &traffic.dofs[own_vehicle];
        match &c.kind {
            ContactKind::Force => forces.push(MovingForce {
                contact: w,
                lateral,
                load: c.static_load,
            }),
            ContactKind::Tyre {
                stiffness,
                damping,
                coupling,
            } => {
                let mut a = vec![0.0; dofs.len()];
                for &(dof, f) in coupling {
                    a[dof - dofs.start] += f;
                }
                tyres.push(Tyre {
                    contact: w,
                    vehicle: own_vehicle,
                    stiffness: *stiffness,
                    damping: *damping,
                    coupling_sparse: a
                        .iter()
                        .enumerate()
                        .filter(|(_, &f)| f != 0.0)
                        .map(|(i, &f)| (dofs.start + i, f))
                        .collect(),
                    coupling: a,
                    lateral,
                    static_load: c.static_load,
                });
            }
        }
    }
    (tyres, forces)
}

impl Tyre {
    /// Total contact force of the tyre bonded to the road (Eqs. 23–26), compressive positive:
    /// P_w = S_w − k_w Δ_w − c_w Δ̇_w with the tyre extension Δ_w = Z_w − Y_w − r_w and its rate
    /// Δ̇_w = Ż_w − Ẏ_w − Y′_w v − r′_w v (Eq. 25), i.e.
    /// P = S + k_t (Y + r − Z_w) + c_t (Ẏ + v r′ − Ż_w), with the deck under the tyre
    /// Y = ⟨N_w⟩Φ q = φ·q and Ẏ = φ·q̇ + v φ′·q (Eq. 26), for a state (q, q̇, Z, Ż): `shapes` =
    /// (φ, φ′) of the modes at the tyre when it is on the deck (None: a rigid road),
    /// `road` = (r, r′) under it [m, -], speed of travel `v` [m/s].
    #[inline]
    pub(super) fn force(
        &self,
        (q, qd, z, zd): (&[f64], &[f64], &[f64], &[f64]),
        shapes: Option<(&[f64], &[f64])>,
        road: (f64, f64),
        v: f64,
    ) -> f64 {
        let deck_sums = match shapes {
            Some((phi, psi)) => deck_sums_of_one_tyre((phi, psi), (q, qd)),
            None => [0.0; 3],
        };
        self.force_of_deck_sums(deck_sums, (z, zd), road, v)
    }

    /// [`Tyre::force`] from the deck sums (φ·q, φ·q̇, φ′·q) of the bridge state under the tyre
    /// (zero on a rigid road): Y = φ·q and Ẏ = φ·q̇ + v φ′·q.
    #[inline]
    pub(super) fn force_of_deck_sums(
        &self,
        [a, b, c]: [f64; 3],
        (z, zd): (&[f64], &[f64]),
        (r, r_slope): (f64, f64),
        v: f64,
    ) -> f64 {
        let (y_w, yv_w) = (a, b + v * c);
        let (z_w, zv_w) = (
            sparse_dot(&self.coupling_sparse, z),
            sparse_dot(&self.coupling_sparse, zd),
        );
        self.static_load
            + self.stiffness * (y_w + r - z_w)
            + self.damping * (yv_w + v * r_slope - zv_w)
    }

    /// [`Tyre::force`] at this tyre's contact point of the instant (its road point and speed
    /// of travel).
    #[inline]
    pub(super) fn force_at(
        &self,
        state: (&[f64], &[f64], &[f64], &[f64]),
        shapes: Option<(&[f64], &[f64])>,
        points: &ContactPoints,
    ) -> f64 {
        let c = self.contact;
        self.force(state, shapes, points.road[c], points.travel_speed[c])
    }
}

/// The deck sums (φ·q, φ·q̇, φ′·q) of one tyre, each in the order k = 1…N.
#[inline]
pub(super) fn deck_sums_of_one_tyre(
    (phi, psi): (&[f64], &[f64]),
    (q, qd): (&[f64], &[f64]),
) -> [f64; 3] {
    let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
    for (((p, sl), qk), vk) in phi.iter().zip(psi).zip(q).zip(qd) {
        a += p * qk;
        b += p * vk;
        c += sl * qk;
    }
    [a, b, c]
}

/// a·x for a sparse a given as (index, value) pairs.
#[inline]
pub(super) fn sparse_dot(a: &[(usize, f64)], x: &[f64]) -> f64 {
    a.iter().map(|&(i, f)| f * x[i]).sum()
}
