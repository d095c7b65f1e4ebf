//! USA, AASHTO Standard Specifications for Highway Bridges (17th ed., 2002) §3.8.2: the impact
//! fraction I from the loaded length.

use super::{
    factor, station_span, CodeEntry, CodeImpactFactor, CodeInputs, CodeLocation, DesignCode, Place,
};
use crate::fe::Quantity;

/// AASHTO Standard in the registry of [`super::REGISTRY`].
pub(super) const ENTRY: CodeEntry = CodeEntry {
    code: DesignCode::AashtoStandard,
    name: "AASHTO Standard 2002",
    short_label: |_| "AASHTO",
    factors,
};

/// Metres per foot (exact, by the international yard of 1959).
pub const FOOT: f64 = 0.3048;

/// AASHTO Standard Specifications for Highway Bridges (17th ed., 2002) §3.8.2.1, Eq. (3-1):
/// I = 50/(L + 125) ≤ 0.30 with the loaded length L in feet (§3.8.2.2); L here in metres,
/// converted by [`FOOT`].
pub fn aashto_standard_impact_fraction(loaded_length: f64) -> f64 {
    let feet = loaded_length / FOOT;
    (50.0 / (feet + 125.0)).min(0.30)
}

/// The loaded length L of AASHTO Standard §3.8.2.2: the span for deflection and moment in a span
/// (c, e: positive moment); the mean of the two adjacent spans over an interior support (e:
/// negative moment; also the reaction there); for the shear force, the length from the section
/// to the far reaction of its span (d); `position` along the girders [m].
fn aashto_loaded_length(place: Place, position: f64, quantity: Quantity) -> f64 {
    match (place, quantity) {
        (Place::Span { start, end }, Quantity::ShearForce) => {
            (position - start).max(end - position)
        }
        _ => station_span(place),
    }
}

/// AASHTO Standard: I of Eq. (3-1) at the loaded length of §3.8.2.2 for the station and
/// quantity ([`aashto_loaded_length`]).
fn factors(
    _inputs: &CodeInputs,
    location: CodeLocation,
    quantity: Quantity,
) -> Vec<CodeImpactFactor> {
    let loaded = aashto_loaded_length(location.place, location.position, quantity);
    vec![factor(
        DesignCode::AashtoStandard,
        "loaded_length",
        "§3.8.2.1, Eq. (3-1); L by §3.8.2.2",
        format!("L = {loaded:.2} m = {:.1} ft", loaded / FOOT),
        aashto_standard_impact_fraction(loaded),
    )]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// AASHTO Standard §3.8.2.1: L = 100 ft gives I = 50/225 = 0.2222; the SI form of the same
    /// clause, I = 15.24/(L + 38.1) with L in metres, agrees; short spans are capped at 0.30.
    #[test]
    fn aashto_standard_impact_fraction_follows_eq_3_1() {
        let hundred_feet = 100.0 * FOOT;
        assert!((aashto_standard_impact_fraction(hundred_feet) - 50.0 / 225.0).abs() < 1e-14);
        for l in [20.0, 30.0, 40.0, 80.0] {
            let si = 15.24 / (l + 38.1);
            assert!((aashto_standard_impact_fraction(l) - si).abs() < 1e-12);
        }
        assert_eq!(aashto_standard_impact_fraction(10.0), 0.30);
    }
}
