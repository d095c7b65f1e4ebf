//! China, JTJ 021-89 (General Code for Design of Highway Bridges and Culverts) §2.3.2: 1 + μ
//! from the span, the rule that JTG D60-2004 replaced by the frequency rule.

use super::{
    factor, station_span, CodeEntry, CodeImpactFactor, CodeInputs, CodeLocation, DesignCode,
};
use crate::fe::Quantity;

/// JTJ 021-89 in the registry of [`super::REGISTRY`].
pub(super) const ENTRY: CodeEntry = CodeEntry {
    code: DesignCode::Jtj021,
    name: "JTJ 021-89",
    short_label: |_| "JTJ 021",
    factors,
};

/// The superstructure rows of JTJ 021-89 Table 2.3.2.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Jtj021Superstructure {
    /// Reinforced and prestressed concrete girders, rigid frames and arch spandrel structures:
    /// 1 + μ = 1.3 for L ≤ 5 m, 1.0 for L ≥ 45 m, linear between.
    ConcreteGirder,
    /// Steel bridges: 1 + μ = 1 + 15/(37.5 + L).
    Steel,
}

/// JTJ 021-89 §2.3.2, Table 2.3.2 (the span-length rule that JTG D60-2004 replaced by the
/// frequency rule): μ from the span L [m] of the superstructure row.
pub fn jtj_021_impact_factor(row: Jtj021Superstructure, span_length: f64) -> f64 {
    match row {
        Jtj021Superstructure::ConcreteGirder => 0.3 * ((45.0 - span_length) / 40.0).clamp(0.0, 1.0),
        Jtj021Superstructure::Steel => 15.0 / (37.5 + span_length),
    }
}

/// JTJ 021-89: the concrete-girder row of Table 2.3.2 at the station's span L (over a support
/// the mean of the spans on each side, [`station_span`]), for every quantity.
fn factors(
    _inputs: &CodeInputs,
    location: CodeLocation,
    _quantity: Quantity,
) -> Vec<CodeImpactFactor> {
    let span = station_span(location.place);
    vec![factor(
        DesignCode::Jtj021,
        "span",
        "§2.3.2, Table 2.3.2 (concrete girders)",
        format!("L = {span:.2} m"),
        jtj_021_impact_factor(Jtj021Superstructure::ConcreteGirder, span),
    )]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// JTJ 021-89 Table 2.3.2: the ends of the concrete row and a midpoint, 1 + μ = 1.15 at
    /// L = 25 m; the steel row 1 + 15/(37.5 + L) at L = 30 m, 1.2222.
    #[test]
    fn jtj_021_span_rule_follows_table_2_3_2() {
        let concrete = Jtj021Superstructure::ConcreteGirder;
        assert_eq!(jtj_021_impact_factor(concrete, 3.0), 0.3);
        assert_eq!(jtj_021_impact_factor(concrete, 60.0), 0.0);
        assert!((jtj_021_impact_factor(concrete, 25.0) - 0.15).abs() < 1e-15);
        assert!((jtj_021_impact_factor(concrete, 30.0) - 0.1125).abs() < 1e-15);
        let steel = jtj_021_impact_factor(Jtj021Superstructure::Steel, 30.0);
        assert!((steel - 15.0 / 67.5).abs() < 1e-15);
    }
}
