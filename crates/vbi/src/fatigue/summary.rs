//! A detail's fatigue over a record of traffic, as the outputs give it.

use super::{DamageSum, FatigueDetail};

/// One detail's fatigue over a record of traffic as the outputs give it (`fatigue.csv` of
/// `vbi lifetime`, the rows of [`crate::outputs::LIFETIME_FATIGUE_OUTPUTS`]; made by
/// [`crate::lifetime::fatigue`]).
#[derive(Debug, Clone, PartialEq)]
pub struct DetailFatigueSummary {
    /// The detail.
    pub detail: FatigueDetail,
    /// Its curve in words.
    pub curve_label: String,
    /// The record's duration [days].
    pub record_days: f64,
    /// The record's cycles and Miner's sum (static history).
    pub sum: DamageSum,
    /// D per year of the record's traffic [-].
    pub damage_per_year: f64,
    /// 1/D_year [years]; ∞ without damage.
    pub fatigue_life_years: f64,
    /// Δσ_E,2 of a 100-year design working life of the traffic [Pa].
    pub equivalent_range_2e6: f64,
    /// The largest damage of a block [-].
    pub largest_block_damage: f64,
}
