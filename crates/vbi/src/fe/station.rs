//! Stations: the cross-sections of the FE model where responses are recorded, and the
//! quantities read there. The FE model defines them (with the functionals that read them,
//! [`StationFunctional`](super::StationFunctional)); the modal basis and the influence lines
//! carry copies.

use serde::{Deserialize, Serialize};

/// Which part of the cross-section a station reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind", content = "index")]
pub enum StationTarget {
    /// One girder (deck line index, 0 = rightmost).
    Girder(usize),
    /// The whole section: mean deflection of the girders, sum of their moments.
    Section,
}

/// A cross-section of interest where responses are recorded.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Station {
    /// Name, for example `span1_mid_g2` or `support2_section`.
    pub name: String,
    /// Longitudinal position x [m] from the first support.
    pub position: f64,
    /// Girder or whole section.
    pub target: StationTarget,
    /// True over an interior support, where the moment of interest is hogging.
    pub over_support: bool,
    /// True where a support (end or interior, rigid or elastic) bears the deck at this
    /// station: the support reaction is read here, and not the shear force, which jumps there
    /// by the reaction (default false).
    #[serde(default)]
    pub support: bool,
}

impl Station {
    /// The quantities an FE model reads at this station: deflection, bending moment, and the
    /// support reaction at a support or the shear force elsewhere.
    pub fn quantities(&self) -> [Quantity; 3] {
        [
            Quantity::Deflection,
            Quantity::BendingMoment,
            self.force_quantity(),
        ]
    }

    /// The force read at this station: the support reaction at a support, the shear force
    /// elsewhere.
    pub fn force_quantity(&self) -> Quantity {
        if self.support {
            Quantity::SupportReaction
        } else {
            Quantity::ShearForce
        }
    }
}

/// Quantities recorded at stations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Vertical deflection [m], positive upwards.
    Deflection,
    /// Bending moment [N·m], positive sagging (tension at the bottom).
    BendingMoment,
    /// Vertical shear force [N], V = dM/dx: the upward force on the part of the bridge left of
    /// the section (the left support's reaction less the loads between it and the section).
    ShearForce,
    /// Vertical support reaction [N], upward positive: the force the bearings at the station
    /// (one girder's, or the whole support line's) exert on the bridge.
    SupportReaction,
}

impl Quantity {
    /// Every quantity, in the order of a station's entries.
    pub const ALL: [Quantity; 4] = [
        Quantity::Deflection,
        Quantity::BendingMoment,
        Quantity::ShearForce,
        Quantity::SupportReaction,
    ];

    /// The quantity's name in outputs (its serde name).
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Deflection => "deflection",
            Quantity::BendingMoment => "bending_moment",
            Quantity::ShearForce => "shear_force",
            Quantity::SupportReaction => "support_reaction",
        }
    }

    /// The quantity of that [`name`](Quantity::name), if any.
    pub fn from_name(name: &str) -> Option<Quantity> {
        Quantity::ALL.into_iter().find(|q| q.name() == name)
    }

    /// The SI unit of the quantity's values.
    pub fn unit(self) -> &'static str {
        match self {
            Quantity::Deflection => "m",
            Quantity::BendingMoment => "N·m",
            Quantity::ShearForce | Quantity::SupportReaction => "N",
        }
    }
}
