//! The outputs of one station entry ([`StationDaf`]: a station and a quantity): the static and
//! dynamic extremes, the converged DAF with its convergence indicator, the paper's plain sums,
//! the modal participation and the cut-off modes.

use serde::ser::{Serialize, SerializeMap, Serializer};

use super::{OutputValue, Unit};
use crate::analysis::StationDaf;

/// One output quantity of a station entry.
#[derive(Debug, Clone, Copy)]
pub struct StationOutput {
    /// The name in summary.json and of the Python attribute.
    pub name: &'static str,
    /// The label in tables and reports.
    pub label: &'static str,
    /// Its unit.
    pub unit: Unit,
    /// What it is, with the equation or the source where it has one.
    pub meaning: &'static str,
    /// Whether the station entries of `vbi run`'s summary.json carry it (the others are read in
    /// Python and from histories).
    pub in_run_summary: bool,
    /// The column of a study's `station_records.csv` (and the key of the journal's station
    /// records) that records it, if a study records it.
    pub study_column: Option<&'static str>,
    /// How it is read from an entry.
    pub value: fn(&StationDaf) -> OutputValue<'_>,
}

/// Every output of a station entry, in the order of summary.json's entries (with the rows that
/// only Python reads in between).
pub const STATION_OUTPUTS: &[StationOutput] = &[
    StationOutput {
        name: "name",
        label: "station",
        unit: Unit::Text,
        meaning: "the station's name",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::Text(&e.name),
    },
    StationOutput {
        name: "quantity",
        label: "quantity",
        unit: Unit::Text,
        meaning: "deflection, bending_moment, shear_force or support_reaction",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::Text(e.quantity.name()),
    },
    StationOutput {
        name: "static_max",
        label: "static max",
        unit: Unit::OfQuantity,
        meaning: "the static extreme, signed: the exact influence line under the vehicles' \
                  static loads at every instant (full stiffness)",
        in_run_summary: true,
        study_column: Some("static_max"),
        value: |e| OutputValue::Number(e.static_max),
    },
    StationOutput {
        name: "static_max_time_s",
        label: "time of static max",
        unit: Unit::Second,
        meaning: "the time of the static extreme, between the time steps for deflections and \
                  moments (the extreme of the influence line under the axle group)",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::Number(e.static_max_time),
    },
    StationOutput {
        name: "dynamic_max",
        label: "dynamic max",
        unit: Unit::OfQuantity,
        meaning: "the dynamic extreme in the governing direction, signed, of the converged \
                  (static-corrected, mode-acceleration) series with all N modes",
        in_run_summary: true,
        study_column: Some("dynamic_max"),
        value: |e| OutputValue::Number(e.converged.dynamic_max),
    },
    StationOutput {
        name: "dynamic_max_time_s",
        label: "time of dynamic max",
        unit: Unit::Second,
        meaning: "the time of the converged dynamic extreme, between the time steps for \
                  deflections and moments",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::Number(e.converged.dynamic_max_time),
    },
    StationOutput {
        name: "daf",
        label: "DAF",
        unit: Unit::Dimensionless,
        meaning: "the converged DAF = dynamic max / static max; undefined where the static \
                  response vanishes",
        in_run_summary: true,
        study_column: Some("daf"),
        value: |e| OutputValue::OptionalNumber(e.converged.daf),
    },
    StationOutput {
        name: "static_max_single_vehicle",
        label: "static max, one vehicle",
        unit: Unit::OfQuantity,
        meaning: "with two or more vehicles: the largest static extreme of any one vehicle alone, \
                  in the direction of static max (which is the static envelope of the whole \
                  event, the reference of daf); empty with one vehicle and for shear forces and \
                  reactions",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::OptionalNumber(e.static_max_single_vehicle),
    },
    StationOutput {
        name: "daf_single_vehicle",
        label: "DAF, one vehicle",
        unit: Unit::Dimensionless,
        meaning: "dynamic max / static max, one vehicle: the DAF against the heaviest single \
                  vehicle's static effect (with two or more vehicles)",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::OptionalNumber(e.daf_single_vehicle),
    },
    StationOutput {
        name: "impact_factor",
        label: "IM",
        unit: Unit::Dimensionless,
        meaning: "IM = DAF − 1 of the converged DAF",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::OptionalNumber(e.impact_factor),
    },
    StationOutput {
        name: "daf_change",
        label: "change",
        unit: Unit::Dimensionless,
        meaning: "the convergence indicator in the modes: the largest change of the converged \
                  DAF(K) from DAF(N) over the last ⌈N/2⌉ modes kept, or twice that over the \
                  check modes (daf_by_check_modes) where larger",
        in_run_summary: true,
        study_column: Some("daf_change"),
        value: |e| OutputValue::OptionalNumber(e.convergence.map(|c| c.change)),
    },
    StationOutput {
        name: "daf_change_dt",
        label: "Δt change",
        unit: Unit::Dimensionless,
        meaning: "the convergence indicator in the time step: DAF(Δt) − DAF(2Δt), from the \
                  crossing run again at twice the step (three times the error of DAF(Δt) at the \
                  scheme's second order; empty where the run was not checked: a given \
                  time_step_s, or time_step_check = false)",
        in_run_summary: true,
        study_column: Some("daf_change_dt"),
        value: |e| OutputValue::OptionalNumber(e.time_step_convergence.map(|c| c.change)),
    },
    StationOutput {
        name: "converged",
        label: "converged",
        unit: Unit::Flag,
        meaning: "whether the change is within the convergence tolerance of the DAF",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::OptionalFlag(e.convergence.map(|c| c.converged)),
    },
    StationOutput {
        name: "daf_by_modes",
        label: "DAF(K)",
        unit: Unit::Dimensionless,
        meaning: "the converged DAF with the first K modes, K = 1…N",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::Series(&e.converged.daf_by_modes),
    },
    StationOutput {
        name: "daf_by_check_modes",
        label: "DAF(K > N)",
        unit: Unit::Dimensionless,
        meaning: "the converged DAF continued over the check modes, K = N + 1…N + C: the modes \
                  above N up to twice the highest solved frequency, integrated against the \
                  crossing's contact forces without feeding back (not in the headline; what the \
                  convergence indicator reads beyond N)",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::Series(&e.converged.daf_by_check_modes),
    },
    StationOutput {
        name: "convergence_mode",
        label: "CM",
        unit: Unit::Count,
        meaning: "the convergence mode of the converged series (1-based)",
        in_run_summary: true,
        study_column: Some("cm"),
        value: |e| OutputValue::Count(e.converged.convergence_mode),
    },
    StationOutput {
        name: "static_corrected",
        label: "static-corrected",
        unit: Unit::Flag,
        meaning: "whether the converged series is the static-corrected one (false: the \
                  paper's plain sum for want of it; a warning says why)",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::Flag(e.static_corrected),
    },
    StationOutput {
        name: "dynamic_max_paper",
        label: "paper's dynamic max",
        unit: Unit::OfQuantity,
        meaning: "the paper's dynamic extreme: the plain modal sum of all N modes, signed",
        in_run_summary: true,
        study_column: Some("dynamic_max_paper"),
        value: |e| OutputValue::Number(e.paper.dynamic_max),
    },
    StationOutput {
        name: "daf_paper",
        label: "paper DAF",
        unit: Unit::Dimensionless,
        meaning: "the paper's DAF (Eqs. 15–16) from the plain sum of all N modes; for a shear force or a support reaction the plain sum, which converges slowly and not to the response, is no DAF (docs/theory.md)",
        in_run_summary: true,
        study_column: Some("daf_paper"),
        value: |e| OutputValue::OptionalNumber(e.paper.daf),
    },
    StationOutput {
        name: "daf_paper_by_modes",
        label: "paper DAF(K)",
        unit: Unit::Dimensionless,
        meaning: "the paper's DAF(K), K = 1…N, from plain partial modal sums (Figs. 12–20)",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::Series(&e.paper.daf_by_modes),
    },
    StationOutput {
        name: "convergence_mode_paper",
        label: "paper CM",
        unit: Unit::Count,
        meaning: "the convergence mode CM of the paper's series (1-based); it depends on N \
                  where the plain sum has not converged",
        in_run_summary: true,
        study_column: Some("cm_paper"),
        value: |e| OutputValue::Count(e.paper.convergence_mode),
    },
    StationOutput {
        name: "participation",
        label: "MPS",
        unit: Unit::Dimensionless,
        meaning: "the modal participation MPS_k at the station, k = 1…N (sums to 1)",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::Series(&e.participation),
    },
    StationOutput {
        name: "cumulative_participation",
        label: "cumulative MPS",
        unit: Unit::Dimensionless,
        meaning: "the cumulative modal participation, k = 1…N",
        in_run_summary: false,
        study_column: None,
        value: |e| OutputValue::Series(&e.cumulative_participation),
    },
    StationOutput {
        name: "cutoff_k1",
        label: "K1",
        unit: Unit::Count,
        meaning: "the cut-off mode K1 (1-based): the first mode at which the cumulative \
                  participation reaches the K1 level",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::Count(e.cutoff_k1),
    },
    StationOutput {
        name: "cutoff_k2",
        label: "K2",
        unit: Unit::Count,
        meaning: "the cut-off mode K2 (1-based): the first mode at which the cumulative \
                  participation reaches the K2 level",
        in_run_summary: true,
        study_column: None,
        value: |e| OutputValue::Count(e.cutoff_k2),
    },
];

/// The row of a station output by its name.
pub fn station_output(name: &str) -> Option<&'static StationOutput> {
    STATION_OUTPUTS.iter().find(|row| row.name == name)
}

/// The rows a study records for each station and quantity of its `record`, in order.
pub fn study_station_outputs() -> impl Iterator<Item = &'static StationOutput> + Clone {
    STATION_OUTPUTS
        .iter()
        .filter(|row| row.study_column.is_some())
}

/// A station entry as summary.json writes it: the rows of [`STATION_OUTPUTS`] that it carries,
/// in order, each under its name.
#[derive(Debug, Clone, Copy)]
pub struct StationEntry<'a>(pub &'a StationDaf);

impl Serialize for StationEntry<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let rows = STATION_OUTPUTS.iter().filter(|row| row.in_run_summary);
        let mut map = serializer.serialize_map(Some(rows.clone().count()))?;
        for row in rows {
            map.serialize_entry(row.name, &(row.value)(self.0))?;
        }
        map.end()
    }
}

/// The table of a station entry's outputs for docs/outputs.md: each row's name, unit, meaning,
/// and where it is written (summary.json; the study column of station_records.csv).
pub fn station_outputs_markdown() -> String {
    let mut table = String::from(
        "| field | unit | meaning | in summary.json | study column |\n|---|---|---|---|---|",
    );
    for row in STATION_OUTPUTS {
        let unit = row.unit.description();
        table.push_str(&format!(
            "\n| `{}` | {} | {} | {} | {} |",
            row.name,
            unit,
            row.meaning,
            if row.in_run_summary {
                "yes"
            } else {
                "Python only"
            },
            row.study_column
                .map(|c| format!("`{c}`"))
                .unwrap_or_else(|| "–".into()),
        ));
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/outputs.md holds the table generated from [`STATION_OUTPUTS`], so that the
    /// reference cannot drift from the code.
    #[test]
    fn the_outputs_document_holds_the_generated_table_of_station_outputs() {
        let document = include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../docs/outputs.md"
        ));
        let begin = "<!-- station outputs: generated from vbi::outputs -->\n";
        let end = "\n<!-- end of station outputs -->";
        let start = document.find(begin).expect("begin marker") + begin.len();
        let stop = document[start..].find(end).expect("end marker") + start;
        assert_eq!(
            &document[start..stop],
            station_outputs_markdown(),
            "regenerate: cargo test -p vbi --lib print_station_outputs -- --ignored --nocapture"
        );
    }

    /// Prints the table of station outputs for docs/outputs.md.
    #[test]
    #[ignore]
    fn print_station_outputs() {
        println!("{}", station_outputs_markdown());
    }

    #[test]
    fn every_station_output_has_one_row_with_a_name_label_and_meaning() {
        let mut names: Vec<&str> = STATION_OUTPUTS.iter().map(|row| row.name).collect();
        names.sort_unstable();
        let count = names.len();
        names.dedup();
        assert_eq!(names.len(), count, "a name stands in two rows");
        for row in STATION_OUTPUTS {
            assert!(
                !row.label.is_empty() && !row.meaning.is_empty(),
                "{}",
                row.name
            );
            assert!(station_output(row.name).is_some());
        }
    }
}
