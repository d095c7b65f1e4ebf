//! Damage scenarios: stiffness losses over regions of the girders, and changed supports.
//!
//! A stiffness loss multiplies Young's modulus E of the girder elements in a region
//! [x_start, x_end] (deck coordinates from the first support) by a factor 0 < f ≤ 1: a beam's EI,
//! a grillage girder's EA, EI_y, EI_z and GJ (G = E/(2(1 + ν)) with ν kept) scale by f; the mass
//! is kept, and so are the transverse members of a grillage. The mesh has nodes at both ends of
//! every region, so the damaged elements (those whose mid-point lies in the region) cover it
//! exactly. Overlapping regions multiply their factors.
//!
//! A changed support replaces the rigid vertical restraint of a support (every bearing of a
//! grillage's support line) by a vertical spring, or removes it (stiffness 0; a grillage's
//! bearings then also release torsion). Horizontal and rotational restraints are kept: the
//! change models a settled, softened or lost bearing, not a removed pier.

use serde::{Deserialize, Serialize};

use super::ModelError;

/// Reduced stiffness over a region of the deck.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StiffnessLoss {
    /// Start of the region x_start [m] from the first support; 0 ≤ x_start < x_end.
    pub start: f64,
    /// End of the region x_end [m]; at most the bridge length.
    pub end: f64,
    /// The girder (deck line index, 0 = rightmost), or None for every girder (a beam has one,
    /// index 0).
    pub girder: Option<usize>,
    /// Factor f on Young's modulus E in the region [-], 0 < f ≤ 1 (1 = intact).
    pub elastic_modulus_factor: f64,
}

/// A support whose vertical restraint is changed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SupportChange {
    /// The support (line) index, 0 at x = 0.
    pub support: usize,
    /// Vertical stiffness that replaces the rigid restraint, per bearing (one per girder) [N/m];
    /// 0 removes the support.
    pub vertical_stiffness: f64,
}

/// The damage of a bridge: none by default (the intact bridge).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Damage {
    /// Stiffness losses over regions; default none.
    #[serde(default)]
    pub stiffness_losses: Vec<StiffnessLoss>,
    /// Changed supports; default none.
    #[serde(default)]
    pub support_changes: Vec<SupportChange>,
}

impl Damage {
    /// Whether the bridge is intact (no stiffness loss, no changed support).
    pub fn is_intact(&self) -> bool {
        self.stiffness_losses.is_empty() && self.support_changes.is_empty()
    }

    /// Checks each loss against the bridge's `length` [m] and `girder_count`, and each changed
    /// support against `support_count`: a region inside [0, length] with start < end, a factor
    /// in (0, 1], an existing girder and support, a finite non-negative stiffness, and at most
    /// one change per support.
    pub fn validate(
        &self,
        length: f64,
        girder_count: usize,
        support_count: usize,
    ) -> Result<(), ModelError> {
        for (index, loss) in self.stiffness_losses.iter().enumerate() {
            let (start, end) = (loss.start, loss.end);
            if !(start.is_finite() && end.is_finite() && start >= 0.0 && end <= length)
                || start >= end
            {
                return Err(ModelError::DamageRegion {
                    index,
                    start,
                    end,
                    length,
                });
            }
            let factor = loss.elastic_modulus_factor;
            if !(factor.is_finite() && factor > 0.0 && factor <= 1.0) {
                return Err(ModelError::DamageFactor { index, factor });
            }
            if let Some(girder) = loss.girder.filter(|&g| g >= girder_count) {
                return Err(ModelError::DamageGirder {
                    index,
                    girder,
                    girder_count,
                });
            }
        }
        for (index, change) in self.support_changes.iter().enumerate() {
            if change.support >= support_count
                || self.support_changes[..index]
                    .iter()
                    .any(|c| c.support == change.support)
            {
                return Err(ModelError::SupportChange {
                    index,
                    support: change.support,
                    support_count,
                });
            }
            super::require_non_negative(
                "changed support's vertical stiffness",
                change.vertical_stiffness,
            )?;
        }
        Ok(())
    }

    /// The changed vertical stiffness of support `support` [N/m], if it is changed.
    pub fn support_stiffness(&self, support: usize) -> Option<f64> {
        self.support_changes
            .iter()
            .find(|c| c.support == support)
            .map(|c| c.vertical_stiffness)
    }

    /// The factor on E of the girder element of `girder` from x = a to x = b [m]: the product of
    /// the factors of the regions that hold its mid-point (a region's ends included).
    pub fn elastic_modulus_factor(&self, girder: usize, a: f64, b: f64) -> f64 {
        let middle = 0.5 * (a + b);
        self.stiffness_losses
            .iter()
            .filter(|loss| loss.girder.is_none_or(|g| g == girder))
            .filter(|loss| (loss.start..=loss.end).contains(&middle))
            .map(|loss| loss.elastic_modulus_factor)
            .product()
    }

    /// The ends of the regions strictly inside the bridge (0, length), for the mesh.
    pub fn region_ends(&self, length: f64) -> Vec<f64> {
        self.stiffness_losses
            .iter()
            .flat_map(|loss| [loss.start, loss.end])
            .filter(|&x| x > 0.0 && x < length)
            .collect()
    }
}
