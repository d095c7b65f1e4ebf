//! The outputs of one fatigue detail under a crossing ([`DetailFatigue`], issue 51): the rows
//! that summary.json's `fatigue` entries, `fatigue.csv`, the Python `DetailFatigue` attributes
//! and docs/outputs.md all read.

use serde::ser::{Serialize, SerializeMap, Serializer};

use super::{OutputValue, Unit};
use crate::fatigue::DetailFatigue;

/// One output quantity of a fatigue detail.
#[derive(Debug, Clone, Copy)]
pub struct FatigueOutput {
    /// The name in summary.json, fatigue.csv and of the Python attribute.
    pub name: &'static str,
    /// The label in tables and reports.
    pub label: &'static str,
    /// Its unit.
    pub unit: Unit,
    /// What it is, with the equation or the source.
    pub meaning: &'static str,
    /// How it is read from a detail's result.
    pub value: fn(&DetailFatigue) -> OutputValue<'_>,
}

/// Every output of a fatigue detail, in the order of summary.json's entries and fatigue.csv's
/// columns.
pub const FATIGUE_OUTPUTS: &[FatigueOutput] = &[
    FatigueOutput {
        name: "detail",
        label: "detail",
        unit: Unit::Text,
        meaning: "the detail's name",
        value: |f| OutputValue::Text(&f.detail.name),
    },
    FatigueOutput {
        name: "station",
        label: "station",
        unit: Unit::Text,
        meaning: "the station whose effect stresses the detail",
        value: |f| OutputValue::Text(&f.detail.station),
    },
    FatigueOutput {
        name: "quantity",
        label: "effect",
        unit: Unit::Text,
        meaning: "bending_moment (direct stress) or shear_force (shear stress)",
        value: |f| OutputValue::Text(f.detail.quantity.name()),
    },
    FatigueOutput {
        name: "fibre",
        label: "fibre",
        unit: Unit::Text,
        meaning: "where on the section: bottom_flange, weld_toe, top_flange, neutral_axis, a \
                  height, or section_modulus / web_area as given",
        value: |f| OutputValue::Text(&f.detail.fibre),
    },
    FatigueOutput {
        name: "curve",
        label: "S–N curve",
        unit: Unit::Text,
        meaning: "the fatigue strength curve: EN 1993-1-9 §7.1 Figure 7.1 or 7.2, or AASHTO \
                  LRFD Table 6.6.1.2.5-1 (docs/fatigue.md)",
        value: |f| OutputValue::Text(&f.curve_label),
    },
    FatigueOutput {
        name: "fatigue_daf",
        label: "fatigue DAF",
        unit: Unit::Dimensionless,
        meaning: "(D_dynamic/D_static)^(1/m) on the detail's curve, m its slope at 2×10⁶ \
                  cycles (3 direct, 5 shear): the factor on the static stress ranges that gives \
                  the dynamic damage; empty where the static history does no damage (every \
                  range below the cut-off)",
        value: |f| OutputValue::OptionalNumber(f.amplification.fatigue_daf),
    },
    FatigueOutput {
        name: "fatigue_daf_straight_line",
        label: "fatigue DAF, no cut-off",
        unit: Unit::Dimensionless,
        meaning: "(Σ n Δσ^m)_dynamic/(Σ n Δσ^m)_static)^(1/m): the fatigue DAF on a straight \
                  line of slope m without cut-off, whatever the category",
        value: |f| OutputValue::OptionalNumber(f.amplification.fatigue_daf_straight_line),
    },
    FatigueOutput {
        name: "fatigue_daf_change",
        label: "change",
        unit: Unit::Dimensionless,
        meaning: "the convergence indicator of fatigue_daf in the modes: its largest change when \
                  read from the static-corrected history with the first K modes, K over the last \
                  ⌈N/2⌉ kept (as daf_change reads DAF(K))",
        value: |f| OutputValue::OptionalNumber(f.convergence.and_then(|c| c.fatigue_daf_change)),
    },
    FatigueOutput {
        name: "fatigue_daf_straight_line_change",
        label: "change, no cut-off",
        unit: Unit::Dimensionless,
        meaning: "the same of fatigue_daf_straight_line",
        value: |f| OutputValue::OptionalNumber(f.convergence.and_then(|c| c.straight_line_change)),
    },
    FatigueOutput {
        name: "damage_ratio",
        label: "D ratio",
        unit: Unit::Dimensionless,
        meaning: "D_dynamic/D_static on the detail's curve",
        value: |f| OutputValue::OptionalNumber(f.amplification.damage_ratio),
    },
    FatigueOutput {
        name: "dynamic_damage",
        label: "D dynamic",
        unit: Unit::Dimensionless,
        meaning: "Miner's sum Σ n/N_R of the crossing's converged (static-corrected) stress \
                  history, rainflow-counted (ASTM E1049-85 §5.4.4, residue as half cycles)",
        value: |f| OutputValue::Number(f.dynamic.sum.damage),
    },
    FatigueOutput {
        name: "static_damage",
        label: "D static",
        unit: Unit::Dimensionless,
        meaning: "Miner's sum of the exact static stress history (the influence line under the \
                  static loads)",
        value: |f| OutputValue::Number(f.static_history.sum.damage),
    },
    FatigueOutput {
        name: "crossings_to_failure",
        label: "crossings to failure",
        unit: Unit::Count,
        meaning: "1/D_dynamic: the number of such crossings that exhausts the detail; empty \
                  where the crossing does no damage",
        value: |f| {
            let damage = f.dynamic.sum.damage;
            OutputValue::OptionalNumber((damage > 0.0).then(|| 1.0 / damage))
        },
    },
    FatigueOutput {
        name: "dynamic_cycles",
        label: "cycles dynamic",
        unit: Unit::Count,
        meaning: "the cycles counted in the dynamic stress history, half cycles as 0.5",
        value: |f| OutputValue::Number(f.dynamic.sum.cycles),
    },
    FatigueOutput {
        name: "static_cycles",
        label: "cycles static",
        unit: Unit::Count,
        meaning: "the cycles counted in the static stress history",
        value: |f| OutputValue::Number(f.static_history.sum.cycles),
    },
    FatigueOutput {
        name: "dynamic_damaging_cycles",
        label: "damaging cycles dynamic",
        unit: Unit::Count,
        meaning: "the dynamic cycles at or above the curve's cut-off",
        value: |f| OutputValue::Number(f.dynamic.sum.damaging_cycles),
    },
    FatigueOutput {
        name: "dynamic_max_range",
        label: "max Δσ dynamic",
        unit: Unit::Pascal,
        meaning: "the largest stress range of the dynamic history (k_f included)",
        value: |f| OutputValue::Number(f.dynamic.sum.max_range),
    },
    FatigueOutput {
        name: "static_max_range",
        label: "max Δσ static",
        unit: Unit::Pascal,
        meaning: "the largest stress range of the static history",
        value: |f| OutputValue::Number(f.static_history.sum.max_range),
    },
    FatigueOutput {
        name: "dynamic_equivalent_range",
        label: "Δσ_eq dynamic",
        unit: Unit::Pascal,
        meaning: "(Σ n Δσ^m / Σ n)^(1/m) of the dynamic cycles (EN 1993-1-9 Annex A.5, no \
                  cut-off)",
        value: |f| OutputValue::Number(f.dynamic.sum.equivalent_range()),
    },
    FatigueOutput {
        name: "static_equivalent_range",
        label: "Δσ_eq static",
        unit: Unit::Pascal,
        meaning: "(Σ n Δσ^m / Σ n)^(1/m) of the static cycles",
        value: |f| OutputValue::Number(f.static_history.sum.equivalent_range()),
    },
    FatigueOutput {
        name: "dynamic_max_stress",
        label: "max σ dynamic",
        unit: Unit::Pascal,
        meaning: "the largest stress of the dynamic history, tension positive (traffic only: \
                  no dead load)",
        value: |f| OutputValue::Number(f.dynamic.max_stress),
    },
    FatigueOutput {
        name: "dynamic_min_stress",
        label: "min σ dynamic",
        unit: Unit::Pascal,
        meaning: "the smallest stress of the dynamic history",
        value: |f| OutputValue::Number(f.dynamic.min_stress),
    },
    FatigueOutput {
        name: "cut_off",
        label: "cut-off",
        unit: Unit::Pascal,
        meaning: "the range below which a cycle does no damage: Δσ_L (0.405 Δσ_C) or Δτ_L \
                  (0.457 Δτ_C) over γ_Ff γ_Mf; 0 on AASHTO's line",
        value: |f| OutputValue::Number(f.detail.curve.cut_off()),
    },
    FatigueOutput {
        name: "stress_concentration",
        label: "k_f",
        unit: Unit::Dimensionless,
        meaning: "the stress-concentration factor on the nominal stress",
        value: |f| OutputValue::Number(f.detail.stress_concentration),
    },
];

/// The row of a fatigue output by its name.
pub fn fatigue_output(name: &str) -> Option<&'static FatigueOutput> {
    FATIGUE_OUTPUTS.iter().find(|row| row.name == name)
}

/// A detail's entry as summary.json writes it: every row of [`FATIGUE_OUTPUTS`], in order.
#[derive(Debug, Clone, Copy)]
pub struct FatigueEntry<'a>(pub &'a DetailFatigue);

impl Serialize for FatigueEntry<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(FATIGUE_OUTPUTS.len()))?;
        for row in FATIGUE_OUTPUTS {
            map.serialize_entry(row.name, &(row.value)(self.0))?;
        }
        map.end()
    }
}

/// The table of a fatigue detail's outputs for docs/outputs.md.
pub fn fatigue_outputs_markdown() -> String {
    let mut table = String::from("| field | unit | meaning |\n|---|---|---|");
    for row in FATIGUE_OUTPUTS {
        table.push_str(&format!(
            "\n| `{}` | {} | {} |",
            row.name,
            row.unit.description(),
            row.meaning
        ));
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/outputs.md holds the table generated from [`FATIGUE_OUTPUTS`].
    #[test]
    fn the_outputs_document_holds_the_generated_table_of_fatigue_outputs() {
        let document = include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../docs/outputs.md"
        ));
        let begin = "<!-- fatigue outputs: generated from vbi::outputs -->\n";
        let end = "\n<!-- end of fatigue outputs -->";
        let start = document.find(begin).expect("begin marker") + begin.len();
        let stop = document[start..].find(end).expect("end marker") + start;
        assert_eq!(
            &document[start..stop],
            fatigue_outputs_markdown(),
            "regenerate: cargo test -p vbi --lib print_fatigue_outputs -- --ignored --nocapture"
        );
    }

    /// Prints the table of fatigue outputs for docs/outputs.md.
    #[test]
    #[ignore]
    fn print_fatigue_outputs() {
        println!("{}", fatigue_outputs_markdown());
    }

    #[test]
    fn every_fatigue_output_has_one_row_with_a_name_label_and_meaning() {
        let mut names: Vec<&str> = FATIGUE_OUTPUTS.iter().map(|row| row.name).collect();
        names.sort_unstable();
        let count = names.len();
        names.dedup();
        assert_eq!(names.len(), count, "a name stands in two rows");
        assert!(FATIGUE_OUTPUTS
            .iter()
            .all(|row| !row.label.is_empty() && !row.meaning.is_empty()));
    }
}
