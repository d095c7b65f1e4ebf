//! Europe, EN 1991-2:2003 (Eurocode 1, Part 2: Traffic loads on bridges) Annex B: the fatigue
//! dynamic amplification φ_fat by surface roughness, with Δφ_fat of §4.6.1(6) near a joint.

use super::{factor, CodeEntry, CodeImpactFactor, CodeInputs, CodeLocation, DesignCode};
use crate::fe::Quantity;
use crate::road::RoughnessClass;

/// EN 1991-2 in the registry of [`super::REGISTRY`].
pub(super) const ENTRY: CodeEntry = CodeEntry {
    code: DesignCode::En1991,
    name: "EN 1991-2:2003",
    short_label: |_| "EN fat",
    factors,
};

/// Surface roughness of EN 1991-2:2003 Annex B.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EurocodeRoughness {
    /// "Good" roughness: φ_fat = 1.2.
    Good,
    /// "Medium" roughness: φ_fat = 1.4.
    Medium,
}

/// EN 1991-2:2003 Annex B (fatigue life assessment of road bridges), B(6): the damage-equivalent
/// dynamic amplification factor φ_fat of a surface's roughness, less one. (The load models of
/// §4.3 for the ultimate limit state include dynamic amplification in their values and have no
/// separate factor.)
pub fn en_1991_2_fatigue_impact_factor(roughness: EurocodeRoughness) -> f64 {
    match roughness {
        EurocodeRoughness::Good => 0.2,
        EurocodeRoughness::Medium => 0.4,
    }
}

/// EN 1991-2:2003 §4.6.1(6), Figure 4.7: the additional amplification factor near an expansion
/// joint, Δφ_fat = 1.30 (1 − D/26) ≥ 1 for a section D [m] from the joint (D ≤ 6 m); 1 beyond.
pub fn en_1991_2_joint_factor(distance_to_joint: f64) -> f64 {
    if distance_to_joint > 6.0 {
        return 1.0;
    }
    (1.30 * (1.0 - distance_to_joint.max(0.0) / 26.0)).max(1.0)
}

/// EN 1991-2: [`fatigue_factor`] at the location, for every quantity; none without the road's
/// roughness or on a road rougher than the annex covers.
fn factors(
    inputs: &CodeInputs,
    location: CodeLocation,
    _quantity: Quantity,
) -> Vec<CodeImpactFactor> {
    fatigue_factor(inputs, location.position)
        .into_iter()
        .collect()
}

/// EN 1991-2 Annex B: φ_fat of the road's roughness (ISO 8608 classes A and B read as "good",
/// C as "medium"; none for rougher roads, which the clause does not cover), times Δφ_fat of
/// §4.6.1(6) within 6 m of an expansion joint, taken at the bridge's ends.
fn fatigue_factor(inputs: &CodeInputs, position: f64) -> Option<CodeImpactFactor> {
    let psd = inputs.psd_at_reference?;
    let class = if psd <= 0.0 {
        RoughnessClass::A
    } else {
        RoughnessClass::iso_class_of(psd)?
    };
    let roughness = match class {
        RoughnessClass::A | RoughnessClass::B => EurocodeRoughness::Good,
        RoughnessClass::C => EurocodeRoughness::Medium,
        _ => return None,
    };
    let length: f64 = inputs.span_lengths.iter().sum();
    let distance = position.min(length - position).max(0.0);
    let joint = en_1991_2_joint_factor(distance);
    let phi = (1.0 + en_1991_2_fatigue_impact_factor(roughness)) * joint;
    let name = if roughness == EurocodeRoughness::Good {
        "good"
    } else {
        "medium"
    };
    Some(factor(
        DesignCode::En1991,
        "fatigue_roughness",
        "Annex B (fatigue), §4.6.1(6)",
        format!(
            "{name} roughness (ISO 8608 class {}), {distance:.2} m from the end joint (Δφ_fat = {joint:.3})",
            class.name()
        ),
        phi - 1.0,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// EN 1991-2 Figure 4.7: 1.30 at the joint, 1.30 (1 − 6/26) = 1.0 at 6 m, 1 beyond.
    #[test]
    fn en_1991_2_joint_factor_follows_figure_4_7() {
        assert!((en_1991_2_joint_factor(0.0) - 1.30).abs() < 1e-15);
        assert!((en_1991_2_joint_factor(3.0) - 1.30 * 23.0 / 26.0).abs() < 1e-15);
        assert!((en_1991_2_joint_factor(6.0) - 1.0).abs() < 1e-15);
        assert_eq!(en_1991_2_joint_factor(10.0), 1.0);
    }
}
