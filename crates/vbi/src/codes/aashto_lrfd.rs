//! USA, AASHTO LRFD Bridge Design Specifications §3.6.2: the dynamic load allowance IM by
//! component and limit state.

use super::{factor, CodeEntry, CodeImpactFactor, CodeInputs, CodeLocation, DesignCode};
use crate::fe::Quantity;

/// AASHTO LRFD in the registry of [`super::REGISTRY`].
pub(super) const ENTRY: CodeEntry = CodeEntry {
    code: DesignCode::AashtoLrfd,
    name: "AASHTO LRFD",
    short_label: |provision| {
        if provision.starts_with("fatigue") {
            "LRFD fat"
        } else {
            "LRFD"
        }
    },
    factors,
};

/// The limit states and components of AASHTO LRFD Table 3.6.2.1-1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LrfdCase {
    /// Deck joints, all limit states: 75 %.
    DeckJoints,
    /// All other components, fatigue and fracture limit state: 15 %.
    Fatigue,
    /// All other components, all other limit states (strength, service): 33 %.
    StrengthAndService,
}

/// AASHTO LRFD Bridge Design Specifications §3.6.2.1, Table 3.6.2.1-1: the dynamic load
/// allowance IM applied to the design truck or tandem (not to the lane load). Wood components
/// take half of it (§3.6.2.3).
pub fn aashto_lrfd_dynamic_load_allowance(case: LrfdCase) -> f64 {
    match case {
        LrfdCase::DeckJoints => 0.75,
        LrfdCase::Fatigue => 0.15,
        LrfdCase::StrengthAndService => 0.33,
    }
}

/// AASHTO LRFD: two values for every station and quantity, the strength and service limit
/// states (33 %) and the fatigue and fracture limit state (15 %) of Table 3.6.2.1-1 (vbi's
/// stations are not deck joints).
fn factors(
    _inputs: &CodeInputs,
    _location: CodeLocation,
    _quantity: Quantity,
) -> Vec<CodeImpactFactor> {
    [
        (
            "strength_service",
            LrfdCase::StrengthAndService,
            "strength and service limit states",
        ),
        (
            "fatigue",
            LrfdCase::Fatigue,
            "fatigue and fracture limit state",
        ),
    ]
    .into_iter()
    .map(|(provision, case, limit_state)| {
        factor(
            DesignCode::AashtoLrfd,
            provision,
            "§3.6.2.1, Table 3.6.2.1-1",
            format!("{limit_state}, components other than deck joints"),
            aashto_lrfd_dynamic_load_allowance(case),
        )
    })
    .collect()
}
