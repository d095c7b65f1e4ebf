//! Australia, AS 5100.2:2017 (Bridge design, Part 2: Design loads) §7.7.2: the dynamic load
//! allowance α by design load.

use super::{factor, CodeEntry, CodeImpactFactor, CodeInputs, CodeLocation, DesignCode};
use crate::fe::Quantity;

/// AS 5100.2 in the registry of [`super::REGISTRY`].
pub(super) const ENTRY: CodeEntry = CodeEntry {
    code: DesignCode::As5100,
    name: "AS 5100.2:2017",
    short_label: |_| "AS 5100",
    factors,
};

/// The design loads of AS 5100.2:2017 Table 7.7.2.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum As5100Load {
    /// W80 wheel load and A160 axle load: 0.40.
    SingleAxleOrWheel,
    /// M1600 tri-axle group: 0.35.
    TriaxleGroup,
    /// M1600 moving traffic load: 0.30.
    MovingTraffic,
}

/// AS 5100.2:2017 §7.7.2, Table 7.7.2: the dynamic load allowance α of a design load.
pub fn as_5100_dynamic_load_allowance(load: As5100Load) -> f64 {
    match load {
        As5100Load::SingleAxleOrWheel => 0.40,
        As5100Load::TriaxleGroup => 0.35,
        As5100Load::MovingTraffic => 0.30,
    }
}

/// AS 5100.2: the M1600 moving traffic load's α = 0.30 of Table 7.7.2, for every station and
/// quantity.
fn factors(
    _inputs: &CodeInputs,
    _location: CodeLocation,
    _quantity: Quantity,
) -> Vec<CodeImpactFactor> {
    vec![factor(
        DesignCode::As5100,
        "moving_traffic",
        "§7.7.2, Table 7.7.2",
        "M1600 moving traffic load".to_string(),
        as_5100_dynamic_load_allowance(As5100Load::MovingTraffic),
    )]
}
