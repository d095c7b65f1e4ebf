//! The outputs of one fatigue detail over a lifetime of traffic ([`DetailFatigueSummary`],
//! issue 51): the columns of `vbi lifetime`'s fatigue.csv and of Python's `fatigue` frame.

use super::{OutputValue, Unit};
use crate::fatigue::DetailFatigueSummary;

/// One output of a detail's lifetime fatigue.
#[derive(Debug, Clone, Copy)]
pub struct LifetimeFatigueOutput {
    /// The column's name.
    pub name: &'static str,
    /// Its unit.
    pub unit: Unit,
    /// What it is.
    pub meaning: &'static str,
    /// How it is read.
    pub value: fn(&DetailFatigueSummary) -> OutputValue<'_>,
}

/// Every output of a detail's lifetime fatigue, in the order of fatigue.csv's columns.
pub const LIFETIME_FATIGUE_OUTPUTS: &[LifetimeFatigueOutput] = &[
    LifetimeFatigueOutput {
        name: "detail",
        unit: Unit::Text,
        meaning: "the detail's name",
        value: |f| OutputValue::Text(&f.detail.name),
    },
    LifetimeFatigueOutput {
        name: "station",
        unit: Unit::Text,
        meaning: "the station of its effect",
        value: |f| OutputValue::Text(&f.detail.station),
    },
    LifetimeFatigueOutput {
        name: "quantity",
        unit: Unit::Text,
        meaning: "bending_moment or shear_force",
        value: |f| OutputValue::Text(f.detail.quantity.name()),
    },
    LifetimeFatigueOutput {
        name: "curve",
        unit: Unit::Text,
        meaning: "the S–N curve (docs/fatigue.md)",
        value: |f| OutputValue::Text(&f.curve_label),
    },
    LifetimeFatigueOutput {
        name: "record_days",
        unit: Unit::Dimensionless,
        meaning: "the record's duration [days], from its first block's start to its end",
        value: |f| OutputValue::Number(f.record_days),
    },
    LifetimeFatigueOutput {
        name: "static_damage",
        unit: Unit::Dimensionless,
        meaning: "Miner's sum of the record's static stress history, counted by rainflow as one \
                  history across its events (ASTM E1049-85 §5.4.4, the residue as half cycles)",
        value: |f| OutputValue::Number(f.sum.damage),
    },
    LifetimeFatigueOutput {
        name: "static_damage_per_year",
        unit: Unit::Dimensionless,
        meaning: "D × one year (365.25 days) / the record's duration",
        value: |f| OutputValue::Number(f.damage_per_year),
    },
    LifetimeFatigueOutput {
        name: "static_fatigue_life_years",
        unit: Unit::Dimensionless,
        meaning: "1/D_year [years]: the years of such traffic that exhaust the detail (empty \
                  without damage)",
        value: |f| {
            OutputValue::OptionalNumber(
                f.fatigue_life_years
                    .is_finite()
                    .then_some(f.fatigue_life_years),
            )
        },
    },
    LifetimeFatigueOutput {
        name: "static_equivalent_range_2e6_100_years",
        unit: Unit::Pascal,
        meaning: "Δσ_E,2 of 100 years of such traffic (EN 1990 Table 2.1, category 5): \
                  Δσ_C (100 D_year)^(1/m) (EN 1993-1-9 §6.2, §8(3)); the detail passes where \
                  γ_Ff Δσ_E,2 ≤ Δσ_C/γ_Mf",
        value: |f| OutputValue::Number(f.equivalent_range_2e6),
    },
    LifetimeFatigueOutput {
        name: "static_cycles",
        unit: Unit::Count,
        meaning: "the cycles counted, half cycles as 0.5",
        value: |f| OutputValue::Number(f.sum.cycles),
    },
    LifetimeFatigueOutput {
        name: "static_damaging_cycles",
        unit: Unit::Count,
        meaning: "the cycles at or above the curve's cut-off",
        value: |f| OutputValue::Number(f.sum.damaging_cycles),
    },
    LifetimeFatigueOutput {
        name: "static_max_range",
        unit: Unit::Pascal,
        meaning: "the largest stress range counted",
        value: |f| OutputValue::Number(f.sum.max_range),
    },
    LifetimeFatigueOutput {
        name: "static_equivalent_range",
        unit: Unit::Pascal,
        meaning: "(Σ n Δσ^m / Σ n)^(1/m), no cut-off",
        value: |f| OutputValue::Number(f.sum.equivalent_range()),
    },
    LifetimeFatigueOutput {
        name: "largest_block_damage",
        unit: Unit::Dimensionless,
        meaning: "the largest Miner's sum of one block (a day by default)",
        value: |f| OutputValue::Number(f.largest_block_damage),
    },
    LifetimeFatigueOutput {
        name: "cut_off",
        unit: Unit::Pascal,
        meaning: "the curve's cut-off (0 on AASHTO's line)",
        value: |f| OutputValue::Number(f.detail.curve.cut_off()),
    },
];
