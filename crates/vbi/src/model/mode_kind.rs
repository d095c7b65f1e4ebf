//! What a mode mostly does: the kinds that the modal analysis classifies modes into, and that
//! an imported basis may give.

use serde::{Deserialize, Serialize};

/// What a mode mostly does, from its kinetic-energy shares by direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ModeKind {
    /// Vertical bending of the deck (vertical translation, the same across the deck, dominates).
    VerticalBending,
    /// Differential bending: vertical motion symmetric about the deck's axis but not the same
    /// across it (the centre girders against the edge girders), a symmetric transverse mode of
    /// a grillage. It loads the girders unequally but does not twist the deck.
    DifferentialBending,
    /// Torsion of the deck (rotation about the bridge axis, or vertical motion antisymmetric
    /// about the deck's axis, dominates).
    Torsion,
    /// Lateral (transverse horizontal) motion dominates.
    Lateral,
    /// Longitudinal motion dominates.
    Longitudinal,
}

impl ModeKind {
    /// The kind's name in inputs and outputs (its serde name).
    pub fn name(self) -> &'static str {
        match self {
            ModeKind::VerticalBending => "vertical_bending",
            ModeKind::DifferentialBending => "differential_bending",
            ModeKind::Torsion => "torsion",
            ModeKind::Lateral => "lateral",
            ModeKind::Longitudinal => "longitudinal",
        }
    }

    /// Every kind, in the order of their names in messages.
    pub const ALL: [ModeKind; 5] = [
        ModeKind::VerticalBending,
        ModeKind::DifferentialBending,
        ModeKind::Torsion,
        ModeKind::Lateral,
        ModeKind::Longitudinal,
    ];

    /// The kind of that [`name`](ModeKind::name), if any.
    pub fn from_name(name: &str) -> Option<ModeKind> {
        ModeKind::ALL.into_iter().find(|kind| kind.name() == name)
    }

    /// Every kind's name, as `a, b, c or d` (for messages).
    pub fn names_in_words() -> String {
        let names: Vec<&str> = ModeKind::ALL.iter().map(|kind| kind.name()).collect();
        let (last, rest) = names.split_last().expect("ModeKind::ALL is not empty");
        format!("{} or {last}", rest.join(", "))
    }

    /// The kinds kept by default where modes are filtered by kind: the modes that carry vertical
    /// wheel loads, vertical and differential bending and torsion.
    pub const VERTICAL: [ModeKind; 3] = [
        ModeKind::VerticalBending,
        ModeKind::DifferentialBending,
        ModeKind::Torsion,
    ];
}
