//! Canada, CSA S6 (Canadian Highway Bridge Design Code) §3.8.4.5.3: the dynamic load allowance
//! by the number of axles.

use super::{factor, CodeEntry, CodeImpactFactor, CodeInputs, CodeLocation, DesignCode};
use crate::fe::Quantity;

/// CSA S6 in the registry of [`super::REGISTRY`].
pub(super) const ENTRY: CodeEntry = CodeEntry {
    code: DesignCode::CsaS6,
    name: "CSA S6",
    short_label: |_| "CSA S6",
    factors,
};

/// CSA S6 (Canadian Highway Bridge Design Code) §3.8.4.5.3: the dynamic load allowance of the
/// CL-W truck by the number of its axles that load the component: 0.40 for one axle, 0.30 for
/// two, 0.25 for three or more (deck joints: 0.50).
pub fn csa_s6_dynamic_load_allowance(axle_count: usize) -> f64 {
    match axle_count {
        0 | 1 => 0.40,
        2 => 0.30,
        _ => 0.25,
    }
}

/// CSA S6: the allowance of the scenario's own vehicle's axle count, for every station and
/// quantity; none when the axle count is unknown (0).
fn factors(
    inputs: &CodeInputs,
    _location: CodeLocation,
    _quantity: Quantity,
) -> Vec<CodeImpactFactor> {
    if inputs.axle_count == 0 {
        return Vec::new();
    }
    vec![factor(
        DesignCode::CsaS6,
        "axles",
        "§3.8.4.5.3",
        format!("{} axles of the vehicle", inputs.axle_count),
        csa_s6_dynamic_load_allowance(inputs.axle_count),
    )]
}
