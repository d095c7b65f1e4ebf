//! Fatigue of steel details under the bridge's stress histories (issue 51): rainflow counting
//! (ASTM E1049-85), S–N curves (EN 1993-1-9, AASHTO LRFD), Miner's sum, equivalent stress
//! ranges, and the fatigue amplification of a dynamic history over the static one.
//!
//! ```text
//! effect history (M or V) -section, k_f-> stress history -rainflow-> cycles -S–N, Miner-> D
//! fatigue DAF = (D_dynamic / D_static)^{1/m}
//! ```
//!
//! Physics only, at the bottom of the library: [`crate::crossing`] evaluates a crossing's details
//! on its histories, [`crate::lifetime`] a traffic history's.

mod damage;
mod detail;
mod rainflow;
mod section;
mod sn_curve;
mod summary;

#[cfg(test)]
mod tests;

pub use damage::{DamageSum, FatigueAmplification};
pub use detail::{DetailFatigue, FatigueConvergence, FatigueDetail, HistoryDamage};
pub use rainflow::{count_by_range, rainflow, Cycle, RainflowCounter};
pub use section::{ConcreteSlab, Fibre, GirderSection, Plate, SectionError};
pub use sn_curve::{
    AashtoCategory, SnCurve, StressKind, CUT_OFF_CYCLES, EUROCODE_DIRECT_CATEGORIES_MPA,
    EUROCODE_SHEAR_CATEGORIES_MPA, KNEE_CYCLES, REFERENCE_CYCLES,
};
pub use summary::DetailFatigueSummary;
