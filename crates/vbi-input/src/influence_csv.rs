//! The influence lines that another program gives for the stations of an imported modal basis
//! (`influence_lines_csv`, docs/input-format.md): the static reference of its runs, exact where
//! the modes' flexibility is truncated.
//!
//! Header `station,line_y_m,x_m,deflection_m_per_n,moment_n_m_per_n`: for each station and each
//! deck line, one row per node of the line (the nodes of shapes.csv, in ascending x), giving the
//! deflection at the station (upwards positive) and its sagging moment under a unit downward
//! load at that node.

use std::collections::BTreeMap;
use std::path::Path;

use vbi::model::imported_modes::{ImportedInfluenceLine, ModalImport};

use crate::csv_table::Table;
use crate::source::InputError;

/// The largest deflection under a unit load that a line may give [m/N]: a metre under one
/// newton is beyond any bridge (real ordinates are 1e-9 to 1e-5 m/N); a larger value is a unit
/// error or a corrupt cell.
const LARGEST_DEFLECTION_PER_NEWTON: f64 = 1.0;
/// The largest moment under a unit load that a line may give [N·m/N = m]: a moment ordinate is
/// at most a span's length (L/4 at a simple span's middle), and 10 km holds any span.
const LARGEST_MOMENT_PER_NEWTON: f64 = 1.0e4;

const HEADER: &str = "`station,line_y_m,x_m,deflection_m_per_n,moment_n_m_per_n`";

/// Reads `path` against the stations and lines of `data`: every station of station_moments.csv
/// on every line of shapes.csv, at the line's nodes.
pub fn read_influence_lines(
    path: &Path,
    data: &ModalImport,
) -> Result<Vec<ImportedInfluenceLine>, InputError> {
    let table = Table::read(path)?;
    let names = [
        "station",
        "line_y_m",
        "x_m",
        "deflection_m_per_n",
        "moment_n_m_per_n",
    ];
    for (i, name) in names.iter().enumerate() {
        if table.column(name) != Some(i) {
            return Err(table.error(
                1,
                i.min(table.header.len().saturating_sub(1)),
                format!("expected column `{name}` here; the header must be {HEADER}"),
            ));
        }
    }
    // (station, line) → (its line's nodes, values read so far).
    let mut lines: BTreeMap<(usize, usize), ImportedInfluenceLine> = BTreeMap::new();
    // The file line of the last row of each (station, line), for a line left incomplete.
    let mut last_rows: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    for (line, row) in &table.rows {
        let name = row[0].as_str();
        let Some(s) = data.stations.iter().position(|s| s.station.name == name) else {
            return Err(table.error(
                *line,
                0,
                format!("`{name}` is not a station of station_moments_csv"),
            ));
        };
        let y = table.number(*line, row, 1, "m")?;
        let Some(l) = data.lines.iter().position(|d| d.lateral_position == y) else {
            return Err(table.error(
                *line,
                1,
                format!("{y} m is not the line_y_m of a deck line of shapes_csv"),
            ));
        };
        let x = table.number(*line, row, 2, "m")?;
        let entry = lines
            .entry((s, l))
            .or_insert_with(|| ImportedInfluenceLine {
                station: name.to_string(),
                lateral_position: y,
                deflection: Vec::new(),
                moment: Vec::new(),
            });
        let nodes = &data.lines[l].node_positions;
        let expected = nodes.get(entry.deflection.len()).copied();
        if expected.is_none_or(|node| (x - node).abs() > 1e-9 * node.abs().max(1.0)) {
            return Err(table.error(
                *line,
                2,
                match expected {
                    Some(node) => format!(
                        "{x} m is not allowed; the next node of the line at y = {y} m is at \
                         {node} m (one row per node of shapes_csv, in ascending x)"
                    ),
                    None => format!(
                        "the line at y = {y} m has {} nodes; this row is one too many",
                        nodes.len()
                    ),
                },
            ));
        }
        entry.deflection.push(table.number_within(
            *line,
            row,
            3,
            "m/N",
            LARGEST_DEFLECTION_PER_NEWTON,
        )?);
        entry.moment.push(table.number_within(
            *line,
            row,
            4,
            "N·m/N",
            LARGEST_MOMENT_PER_NEWTON,
        )?);
        last_rows.insert((s, l), *line);
    }
    for (s, station) in data.stations.iter().enumerate() {
        for (l, deck_line) in data.lines.iter().enumerate() {
            let found = lines.get(&(s, l)).map_or(0, |e| e.deflection.len());
            if found != deck_line.node_positions.len() {
                // At the last row of that station and line, or at the header if it has none.
                let row = last_rows.get(&(s, l)).copied().unwrap_or(1);
                return Err(table.error(
                    row,
                    2,
                    format!(
                        "station `{}` has {found} rows on the line at y = {} m, which has {} \
                         nodes; give every station on every line at every node",
                        station.station.name,
                        deck_line.lateral_position,
                        deck_line.node_positions.len()
                    ),
                ));
            }
        }
    }
    Ok(lines.into_values().collect())
}
