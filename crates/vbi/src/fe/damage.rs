//! How the mesh carries a [`Damage`]: the factor on E of every girder element, and which
//! supports still hold the bridge vertically.

use super::element::FrameProperties;
use super::error::FeError;
use crate::model::Damage;

/// The factor on E of each girder element, `factors[ix * lines + line]` for the element of
/// `line` from grid point ix to ix + 1 ([`Damage::elastic_modulus_factor`]: the regions that
/// hold its mid-point). The grid has nodes at every region end, so the elements cover each
/// region exactly; a region too short to hold an element (below the grid's merging tolerance)
/// is an error rather than a loss that silently vanishes.
pub(super) fn girder_factors(
    damage: &Damage,
    xs: &[f64],
    lines: usize,
) -> Result<Vec<f64>, FeError> {
    let mut factors = Vec::with_capacity(xs.len().saturating_sub(1) * lines);
    for pair in xs.windows(2) {
        for line in 0..lines {
            factors.push(damage.elastic_modulus_factor(line, pair[0], pair[1]));
        }
    }
    for (index, loss) in damage.stiffness_losses.iter().enumerate() {
        let middle_inside =
            |pair: &[f64]| (loss.start..=loss.end).contains(&(0.5 * (pair[0] + pair[1])));
        if !xs.windows(2).any(middle_inside) {
            return Err(FeError::DamageRegionTooShort {
                index,
                start: loss.start,
                end: loss.end,
            });
        }
    }
    Ok(factors)
}

/// A frame member's properties with E scaled by `factor`: EA, EI_y, EI_z and GJ (G = E/(2(1 + ν))
/// with ν kept) scale, the masses do not.
pub(super) fn scale_stiffness(properties: FrameProperties, factor: f64) -> FrameProperties {
    FrameProperties {
        axial_rigidity: factor * properties.axial_rigidity,
        flexural_rigidity_y: factor * properties.flexural_rigidity_y,
        flexural_rigidity_z: factor * properties.flexural_rigidity_z,
        torsional_rigidity: factor * properties.torsional_rigidity,
        ..properties
    }
}

/// Whether support `support` still holds the bridge vertically: its changed stiffness is
/// positive, or, unchanged, `intact_holds`.
pub(super) fn holds_vertically(damage: &Damage, support: usize, intact_holds: bool) -> bool {
    damage
        .support_stiffness(support)
        .map_or(intact_holds, |stiffness| stiffness > 0.0)
}
