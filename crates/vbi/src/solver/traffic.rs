//! The vehicles of a crossing as one multibody system: their DOFs and contacts stacked in the
//! order of [`Crossing::vehicles`], M, C and K block-diagonal (vehicles interact only through
//! the bridge), and where each contact runs on the deck.
//!
//! The solver's vehicle equations (Eq. 19) are then those of one vehicle whose d DOFs are the
//! vehicles' DOFs one after the other; the suspension block B = M + γΔt C_s + βΔt² K_s stays
//! block-diagonal, so its inverse is too.

use nalgebra::DMatrix;

use super::motion::TravelDirection;
use super::pitching::{pitch_loads, PitchLoad};
use super::Crossing;
use crate::road::Track;
use crate::vehicle::{ContactKind, TyreContact, VehicleModel};

/// Where one contact runs: its vehicle, its deck lateral position and its road track.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Placement {
    /// Index of the vehicle in [`Crossing::vehicles`].
    pub(super) vehicle: usize,
    /// Lateral position y on the deck [m]: y_vehicle + y_c forward, y_vehicle − y_c backward
    /// (the vehicle's left is the deck's right when it travels backward).
    pub(super) lateral: f64,
    /// Road track under a tyre (in the vehicle's own sense: its left tyres on the left track);
    /// None for a moving force.
    pub(super) track: Option<Track>,
}

/// The vehicles of a crossing stacked into one model.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Traffic {
    /// The stacked model: the single vehicle itself when there is one; otherwise DOFs named
    /// `v<i>_<name>` (i from 1), block-diagonal matrices, contacts in vehicle order, and the
    /// pitch load of `pitch_loads` (which also knows each entry's vehicle, so its acceleration).
    pub(super) model: VehicleModel,
    /// Where each contact of `model` runs.
    pub(super) placements: Vec<Placement>,
    /// The pitch loads of braking and acceleration, each with its vehicle (stacked DOFs).
    pub(super) pitch_loads: Vec<PitchLoad>,
}

impl Traffic {
    /// The vehicles of `crossing`, stacked.
    pub(super) fn new(crossing: &Crossing) -> Traffic {
        let placements = crossing
            .vehicles
            .iter()
            .enumerate()
            .flat_map(|(v, run)| {
                let sign = match run.direction {
                    TravelDirection::Forward => 1.0,
                    TravelDirection::Backward => -1.0,
                };
                run.vehicle.contacts.iter().map(move |c| Placement {
                    vehicle: v,
                    lateral: run.lateral_position + sign * c.lateral_offset,
                    track: matches!(c.kind, ContactKind::Tyre { .. })
                        .then(|| Track::of_lateral_offset(c.lateral_offset)),
                })
            })
            .collect();
        let pitch_loads = pitch_loads(crossing);
        let model = match crossing.vehicles.as_slice() {
            [single] => single.vehicle.clone(),
            vehicles => VehicleModel {
                pitch_load_per_acceleration: pitch_loads
                    .iter()
                    .map(|load| (load.dof, load.coefficient))
                    .collect(),
                ..stack(vehicles.iter().map(|run| &run.vehicle))
            },
        };
        Traffic {
            model,
            placements,
            pitch_loads,
        }
    }
}

/// Several vehicle models as one: DOFs and contacts concatenated, matrices block-diagonal,
/// couplings shifted to the stacked DOF numbers.
fn stack<'a>(vehicles: impl Iterator<Item = &'a VehicleModel> + Clone) -> VehicleModel {
    let d: usize = vehicles.clone().map(VehicleModel::dof_count).sum();
    let mut model = VehicleModel {
        name: vehicles
            .clone()
            .map(|v| v.name.as_str())
            .collect::<Vec<_>>()
            .join(" + "),
        dof_names: Vec::with_capacity(d),
        mass_matrix: DMatrix::zeros(d, d),
        damping_matrix: DMatrix::zeros(d, d),
        stiffness_matrix: DMatrix::zeros(d, d),
        contacts: Vec::new(),
        pitch_load_per_acceleration: Vec::new(),
    };
    let mut first = 0;
    for (i, vehicle) in vehicles.enumerate() {
        let n = vehicle.dof_count();
        model.dof_names.extend(
            vehicle
                .dof_names
                .iter()
                .map(|name| format!("v{}_{name}", i + 1)),
        );
        for (target, source) in [
            (&mut model.mass_matrix, &vehicle.mass_matrix),
            (&mut model.damping_matrix, &vehicle.damping_matrix),
            (&mut model.stiffness_matrix, &vehicle.stiffness_matrix),
        ] {
            target.view_mut((first, first), (n, n)).copy_from(source);
        }
        model
            .contacts
            .extend(vehicle.contacts.iter().map(|c| shifted(c, first)));
        first += n;
    }
    model
}

/// A contact whose coupling refers to DOFs numbered from `first`.
fn shifted(contact: &TyreContact, first: usize) -> TyreContact {
    let kind = match &contact.kind {
        ContactKind::Force => ContactKind::Force,
        ContactKind::Tyre {
            stiffness,
            damping,
            coupling,
        } => ContactKind::Tyre {
            stiffness: *stiffness,
            damping: *damping,
            coupling: coupling.iter().map(|&(dof, f)| (dof + first, f)).collect(),
        },
    };
    TyreContact {
        kind,
        ..contact.clone()
    }
}
