//! The vehicles of a crossing as one multibody system: their DOFs and contacts stacked in the
//! order of [`Crossing::vehicles`], and where each contact runs on the deck.
//!
//! The solver's vehicle equations (Eq. 19) are then those of one vehicle whose d DOFs are the
//! vehicles' DOFs one after the other, with M, C, K and the suspension block
//! B = M + γΔt C_s + βΔt² K_s block-diagonal (vehicles interact only through the bridge), so B⁻¹
//! is block-diagonal too. No matrix over all the vehicles' DOFs is formed: the solver keeps one
//! block per vehicle, over the vehicle's DOFs in [`StackedVehicles::dofs`], from the vehicle's own
//! matrices.

use std::ops::Range;

use super::pitching::{pitch_loads, PitchLoad};
use super::Crossing;
use crate::road::Track;
use crate::traffic::law::TravelDirection;
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

/// The vehicles of a crossing stacked into one model: DOFs and contacts.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct StackedVehicles {
    /// The stacked DOF names: the single vehicle's own when there is one, otherwise
    /// `v<i>_<name>` (i from 1).
    pub(super) dof_names: Vec<String>,
    /// The stacked contacts, in vehicle order, couplings to the stacked DOFs.
    pub(super) contacts: Vec<TyreContact>,
    /// Where each contact runs.
    pub(super) placements: Vec<Placement>,
    /// The pitch loads of braking and acceleration, each with its vehicle (stacked DOFs).
    pub(super) pitch_loads: Vec<PitchLoad>,
    /// Each vehicle's DOFs in the stacked numbering (consecutive, in the crossing's order).
    pub(super) dofs: Vec<Range<usize>>,
}

impl StackedVehicles {
    /// The vehicles of `crossing`, stacked.
    pub(super) fn new(crossing: &Crossing) -> StackedVehicles {
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
        let mut first = 0;
        let dofs: Vec<Range<usize>> = crossing
            .vehicles
            .iter()
            .map(|run| {
                let range = first..first + run.vehicle.dof_count();
                first = range.end;
                range
            })
            .collect();
        let (dof_names, contacts) = match crossing.vehicles.as_slice() {
            [single] => (
                single.vehicle.dof_names.clone(),
                single.vehicle.contacts.clone(),
            ),
            vehicles => stack(vehicles.iter().map(|run| &run.vehicle), &dofs),
        };
        StackedVehicles {
            dof_names,
            contacts,
            placements,
            pitch_loads: pitch_loads(crossing),
            dofs,
        }
    }

    /// Number of stacked DOFs d.
    pub(super) fn dof_count(&self) -> usize {
        self.dof_names.len()
    }
}

/// The DOF names and contacts of several vehicle models as one: DOFs named `v<i>_<name>`,
/// contacts concatenated with their couplings shifted to the stacked DOF numbers (`dofs`).
fn stack<'a>(
    vehicles: impl Iterator<Item = &'a VehicleModel>,
    dofs: &[Range<usize>],
) -> (Vec<String>, Vec<TyreContact>) {
    let (mut dof_names, mut contacts) = (Vec::new(), Vec::new());
    for (i, (vehicle, own)) in vehicles.zip(dofs).enumerate() {
        dof_names.extend(
            vehicle
                .dof_names
                .iter()
                .map(|name| format!("v{}_{name}", i + 1)),
        );
        contacts.extend(vehicle.contacts.iter().map(|c| shifted(c, own.start)));
    }
    (dof_names, contacts)
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
