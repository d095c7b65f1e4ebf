//! Australia, AS 5100.2:2017 (Bridge design, Part 2: Design loads) §7.7.2: the dynamic load
//! allowance α by design load.

use super::{factor, CodeEntry, CodeImpactFactor, CodeInputs, CodeLocation, DesignCode};
use crate::fe::Quantity;

/// AS 5100.2 in the registry of [`super::REGISTRY`].
pub(super) const ENTRY: CodeEntry = CodeEntry {
    code: DesignCode::As5100,
    name: "AS 5100.2:2017",
    short_label: |provision| match provision {
        "single_axle_or_wheel" => "AS W80/A160",
        "triaxle_group" => "AS tri-axle",
        _ => "AS M1600",
    },
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

/// AS 5100.2: the α of each design load of Table 7.7.2, one row per load, for every station and
/// quantity: the clause reads α by the load applied, not by the component (issue 46: vbi showed
/// the moving traffic load's 0.30 alone), and which load governs a component is the designer's
/// load case, which a crossing does not know.
fn factors(
    _inputs: &CodeInputs,
    _location: CodeLocation,
    _quantity: Quantity,
) -> Vec<CodeImpactFactor> {
    [
        (
            As5100Load::MovingTraffic,
            "moving_traffic",
            "M1600 moving traffic load",
        ),
        (
            As5100Load::TriaxleGroup,
            "triaxle_group",
            "M1600 tri-axle group",
        ),
        (
            As5100Load::SingleAxleOrWheel,
            "single_axle_or_wheel",
            "W80 wheel load, A160 axle load",
        ),
    ]
    .into_iter()
    .map(|(load, provision, basis)| {
        factor(
            DesignCode::As5100,
            provision,
            "§7.7.2, Table 7.7.2",
            basis.to_string(),
            as_5100_dynamic_load_allowance(load),
        )
    })
    .collect()
}
