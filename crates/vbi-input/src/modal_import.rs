//! Imported modal data (frequencies and mode shapes from another FE program), read from CSV
//! files whose formats are documented in docs/input-format.md, "Imported modal data".
//!
//! - frequencies: `mode,frequency_hz[,damping_ratio][,kind]`, one row per mode, modes 1…N in
//!   order; an empty `damping_ratio` takes the default, an empty `kind` is classified from the
//!   shapes.
//! - shapes: `line_y_m,x_m,mode_1,…,mode_N`, one row per deck node; rows of one girder line share
//!   `line_y_m`; values are mass-normalised vertical deflections [m per unit modal coordinate].
//! - station moments (optional): `station,x_m,target,over_support,mode_1,…,mode_N`; `target` is
//!   `section` or `girder_<k>` (k = 1 for the line of lowest `line_y_m`); moments in N·m per unit
//!   modal coordinate, sagging positive.
//!
//! Errors name the file, the line, the column and what is allowed.

use std::collections::BTreeMap;
use std::path::Path;

use vbi::modal::import::{
    build_imported_basis, ImportError, ImportedLine, ImportedStation, ModalImport,
};
use vbi::modal::{ModalBasis, ModeKind, Station, StationTarget};

use crate::csv_table::Table;
use crate::source::InputError;

impl Table {
    /// The columns `mode_1 … mode_N`, in order, starting at `first`.
    fn mode_columns(
        &self,
        first: usize,
        count: usize,
        allowed: &str,
    ) -> Result<Vec<usize>, InputError> {
        let found = self.header.len().saturating_sub(first);
        if found != count {
            return Err(InputError {
                file: self.file.clone(),
                location: Some((1, 1)),
                field: None,
                message: format!(
                    "{found} mode columns for the {count} modes of the frequency file; the header must be {allowed}"
                ),
            });
        }
        for k in 0..count {
            let expected = format!("mode_{}", k + 1);
            if self.header[first + k] != expected {
                return Err(InputError {
                    file: self.file.clone(),
                    location: Some((1, first + k + 1)),
                    field: Some(self.header[first + k].clone()),
                    message: format!(
                        "expected column `{expected}` here; the header must be {allowed}"
                    ),
                });
            }
        }
        Ok((first..first + count).collect())
    }
}

const FREQUENCY_HEADER: &str = "`mode,frequency_hz[,damping_ratio][,kind]`";
const SHAPES_HEADER: &str = "`line_y_m,x_m,mode_1,…,mode_N`";
const STATIONS_HEADER: &str = "`station,x_m,target,over_support,mode_1,…,mode_N`";

/// Reads an imported modal basis from its CSV files (formats in the module documentation and
/// docs/input-format.md). `default_damping_ratio` [-] is given to modes without their own.
pub fn load_modal_import(
    frequencies_csv: &Path,
    shapes_csv: &Path,
    station_moments_csv: Option<&Path>,
    default_damping_ratio: f64,
) -> Result<ModalBasis, InputError> {
    let data = read_modal_import(
        frequencies_csv,
        shapes_csv,
        station_moments_csv,
        default_damping_ratio,
    )?;
    build_imported_basis(&data).map_err(|e| InputError {
        file: shapes_csv.display().to_string(),
        location: None,
        field: None,
        message: e.to_string(),
    })
}

/// Reads the imported modal data, checked by building their basis once (errors located in the
/// CSV files).
pub fn read_modal_import(
    frequencies_csv: &Path,
    shapes_csv: &Path,
    station_moments_csv: Option<&Path>,
    default_damping_ratio: f64,
) -> Result<ModalImport, InputError> {
    let Frequencies {
        table: frequencies,
        frequency_column: freq_col,
        damping_column: damping_col,
        frequencies_hz,
        damping_ratios,
        kinds,
        mode_lines,
    } = read_frequencies(frequencies_csv)?;
    let count = frequencies_hz.len();
    let Shapes {
        table: shapes,
        x_column: x_col,
        lines: imported_lines,
        line_starts,
    } = read_shapes(shapes_csv, count)?;
    let (station_table, stations, station_lines) = match station_moments_csv {
        Some(path) => {
            let girder_count = imported_lines.len();
            let (table, stations, lines) = read_station_moments(path, count, girder_count)?;
            (Some(table), stations, lines)
        }
        None => (None, Vec::new(), Vec::new()),
    };
    let data = ModalImport {
        frequencies_hz,
        damping_ratios,
        default_damping_ratio,
        kinds,
        lines: imported_lines,
        deck_length: None,
        stations,
        influence_lines: Vec::new(),
    };
    let checked = build_imported_basis(&data).map_err(|e| {
        let message = e.to_string();
        let line_of = |y: f64| {
            line_starts
                .iter()
                .find(|(ly, _)| *ly == y)
                .map_or(1, |(_, l)| *l)
        };
        let station_line = |name: &str| {
            data.stations
                .iter()
                .position(|s| s.station.name == name)
                .map_or(1, |i| station_lines[i])
        };
        match e {
            ImportError::BadFrequency { mode, .. } | ImportError::NotAscending { mode, .. } => {
                frequencies.error(mode_lines[mode - 1], freq_col, message)
            }
            ImportError::BadDamping { mode, .. } => frequencies.error(
                mode_lines[mode - 1],
                damping_col.unwrap_or(freq_col),
                message,
            ),
            ImportError::LineTooShort {
                lateral_position, ..
            }
            | ImportError::DuplicateLine { lateral_position }
            | ImportError::BadPosition {
                lateral_position, ..
            } => shapes.error(line_of(lateral_position), x_col, message),
            ImportError::StationGirder { ref station, .. }
            | ImportError::StationOffDeck { ref station, .. } => match &station_table {
                Some(t) => t.error(station_line(station), 1, message),
                None => shapes.error(1, 0, message),
            },
            _ => shapes.error(1, 0, message),
        }
    });
    checked.map(|_| data)
}

/// The rows of the frequencies CSV, with where each stands.
struct Frequencies {
    table: Table,
    frequency_column: usize,
    damping_column: Option<usize>,
    frequencies_hz: Vec<f64>,
    damping_ratios: Vec<Option<f64>>,
    kinds: Vec<Option<ModeKind>>,
    /// The line of each mode's row.
    mode_lines: Vec<usize>,
}

/// The frequencies CSV: `mode` (1, 2, … in order), `frequency_hz`, and optionally
/// `damping_ratio` and `kind`; at least one mode.
fn read_frequencies(frequencies_csv: &Path) -> Result<Frequencies, InputError> {
    let table = Table::read(frequencies_csv)?;
    let mode_col = table.require_column("mode", FREQUENCY_HEADER)?;
    let freq_col = table.require_column("frequency_hz", FREQUENCY_HEADER)?;
    let damping_col = table.column("damping_ratio");
    let kind_col = table.column("kind");
    let mut frequencies_hz = Vec::new();
    let mut damping_ratios = Vec::new();
    let mut kinds = Vec::new();
    let mut mode_lines = Vec::new();
    for (line, row) in &table.rows {
        let k = frequencies_hz.len() + 1;
        let mode_text = row.get(mode_col).map(String::as_str).unwrap_or("");
        if mode_text.parse::<usize>() != Ok(k) {
            return Err(table.error(*line, mode_col, format!("`{mode_text}` is not allowed; expected mode number {k} (modes are numbered 1, 2, … in order)")));
        }
        frequencies_hz.push(table.number(*line, row, freq_col, "Hz")?);
        damping_ratios.push(match damping_col {
            Some(c) if !row.get(c).is_none_or(|t| t.is_empty()) => {
                Some(table.number(*line, row, c, "-")?)
            }
            _ => None,
        });
        kinds.push(match kind_col {
            Some(c) if !row.get(c).is_none_or(|t| t.is_empty()) => {
                Some(ModeKind::from_name(&row[c]).ok_or_else(|| {
                    table.error(
                        *line,
                        c,
                        format!(
                            "`{}` is not allowed; expected {}, or empty",
                            row[c],
                            ModeKind::names_in_words()
                        ),
                    )
                })?)
            }
            _ => None,
        });
        mode_lines.push(*line);
    }
    if frequencies_hz.is_empty() {
        return Err(InputError {
            file: table.file.clone(),
            location: Some((1, 1)),
            field: None,
            message: "no mode: the file needs one row per mode after the header".into(),
        });
    }

    Ok(Frequencies {
        table,
        frequency_column: freq_col,
        damping_column: damping_col,
        frequencies_hz,
        damping_ratios,
        kinds,
        mode_lines,
    })
}

/// The lines of the shapes CSV, in order of lateral position, with where each starts.
struct Shapes {
    table: Table,
    x_column: usize,
    lines: Vec<ImportedLine>,
    /// Each line's lateral position [m] and the CSV line of its first row.
    line_starts: Vec<(f64, usize)>,
}

/// The shapes CSV: `line_y_m`, `x_m`, then one deflection column per mode of `count`; the rows
/// of a line (one y) at strictly ascending x ≥ 0.
fn read_shapes(shapes_csv: &Path, count: usize) -> Result<Shapes, InputError> {
    let table = Table::read(shapes_csv)?;
    let y_col = table.require_column("line_y_m", SHAPES_HEADER)?;
    let x_col = table.require_column("x_m", SHAPES_HEADER)?;
    if (y_col, x_col) != (0, 1) {
        return Err(table.error(1, 0, format!("the header must be {SHAPES_HEADER}")));
    }
    let modes = table.mode_columns(2, count, SHAPES_HEADER)?;
    // Lines keyed by the exact text-parsed y (bit pattern), in order of appearance.
    let mut lines: BTreeMap<u64, (usize, ImportedLine)> = BTreeMap::new();
    for (line, row) in &table.rows {
        let y = table.number(*line, row, y_col, "m")?;
        let x = table.number(*line, row, x_col, "m")?;
        let entry = lines.entry(y.to_bits()).or_insert((
            *line,
            ImportedLine {
                lateral_position: y,
                node_positions: Vec::new(),
                deflection: Vec::new(),
            },
        ));
        if let Some(&previous) = entry.1.node_positions.last() {
            if x <= previous {
                return Err(table.error(*line, x_col, format!("{x} m is not allowed; rows of the line at y = {y} m must have strictly ascending x (previous {previous} m)")));
            }
        } else if x < 0.0 {
            return Err(table.error(
                *line,
                x_col,
                format!(
                    "{x} m is not allowed; x is measured from the first support and must be ≥ 0"
                ),
            ));
        }
        entry.1.node_positions.push(x);
        for &c in &modes {
            entry.1.deflection.push(table.number(*line, row, c, "m")?);
        }
    }
    let line_starts: Vec<(f64, usize)> = lines
        .values()
        .map(|(l, d)| (d.lateral_position, *l))
        .collect();
    let imported_lines: Vec<ImportedLine> = lines.into_values().map(|(_, d)| d).collect();

    Ok(Shapes {
        table,
        x_column: x_col,
        lines: imported_lines,
        line_starts,
    })
}

/// The station moments CSV: `station`, `x_m`, `target` (`section` or `girder_<k>`, k from 1 to
/// `girder_count`), `over_support`, then one moment [N·m] per mode of `count`; the table, the
/// stations and the line of each.
fn read_station_moments(
    path: &Path,
    count: usize,
    girder_count: usize,
) -> Result<(Table, Vec<ImportedStation>, Vec<usize>), InputError> {
    let mut stations = Vec::new();
    let mut station_lines = Vec::new();
    let table = Table::read(path)?;
    let names = ["station", "x_m", "target", "over_support"];
    for (i, name) in names.iter().enumerate() {
        if table.column(name) != Some(i) {
            return Err(table.error(
                1,
                i.min(table.header.len().saturating_sub(1)),
                format!("expected column `{name}` here; the header must be {STATIONS_HEADER}"),
            ));
        }
    }
    let modes = table.mode_columns(4, count, STATIONS_HEADER)?;
    for (line, row) in &table.rows {
        let name = row[0].clone();
        if name.is_empty() {
            return Err(table.error(*line, 0, "empty station name; give each station a name"));
        }
        let position = table.number(*line, row, 1, "m")?;
        let target_text = row.get(2).map(String::as_str).unwrap_or("");
        let target = if target_text == "section" {
            StationTarget::Section
        } else if let Some(k) = target_text
            .strip_prefix("girder_")
            .and_then(|k| k.parse::<usize>().ok())
            .filter(|&k| k >= 1 && k <= girder_count)
        {
            StationTarget::Girder(k - 1)
        } else {
            return Err(table.error(*line, 2, format!("`{target_text}` is not allowed; expected `section` or `girder_<k>` with k from 1 to {} (1 = the line of lowest line_y_m)", girder_count)));
        };
        let over_support = match row.get(3).map(String::as_str).unwrap_or("") {
            "true" => true,
            "false" => false,
            other => {
                return Err(table.error(
                    *line,
                    3,
                    format!("`{other}` is not allowed; expected true or false"),
                ))
            }
        };
        let mut moments = Vec::with_capacity(count);
        for &c in &modes {
            moments.push(table.number(*line, row, c, "N·m")?);
        }
        stations.push(ImportedStation {
            station: Station {
                name,
                position,
                target,
                over_support,
                support: false,
            },
            moments,
        });
        station_lines.push(*line);
    }
    Ok((table, stations, station_lines))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(dir: &Path, name: &str, text: &str) -> std::path::PathBuf {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path
    }

    /// A scratch directory, removed when the test ends.
    fn temp_dir(tag: &str) -> tempfile::TempDir {
        tempfile::Builder::new()
            .prefix(&format!("vbi-modal-import-{tag}-"))
            .tempdir()
            .unwrap()
    }

    #[test]
    fn a_two_girder_import_reads_frequencies_shapes_and_moments() {
        let scratch = temp_dir("ok");
        let dir = scratch.path();
        let f = write(
            dir,
            "f.csv",
            "mode,frequency_hz,damping_ratio,kind\n1,3.5,,\n2,5.0,0.02,torsion\n",
        );
        let s = write(
            dir,
            "s.csv",
            "line_y_m,x_m,mode_1,mode_2\n-1,0,0,0\n-1,5,0.01,-0.02\n-1,10,0,0\n1,0,0,0\n1,5,0.01,0.02\n1,10,0,0\n",
        );
        let m = write(dir, "m.csv", "station,x_m,target,over_support,mode_1,mode_2\nmid,5,section,false,1200,30\nmid_g1,5,girder_1,false,600,-15\n");
        let basis = load_modal_import(&f, &s, Some(&m), 0.05).unwrap();
        assert_eq!(basis.mode_count(), 2);
        assert_eq!(basis.modes[0].damping_ratio, 0.05);
        assert_eq!(basis.modes[1].damping_ratio, 0.02);
        assert_eq!(basis.modes[0].kind, ModeKind::VerticalBending);
        assert_eq!(basis.modes[1].kind, ModeKind::Torsion);
        assert_eq!(basis.deck.lines.len(), 2);
        assert_eq!(basis.stations[1].target, StationTarget::Girder(0));
        assert_eq!(basis.station_moment, vec![1200.0, 30.0, 600.0, -15.0]);
        // Station deflection: mean of the lines at x = 5 m (a node), and girder 1 alone.
        assert!((basis.station_deflection[0] - 0.01).abs() < 1e-15);
        assert!(basis.station_deflection[1].abs() < 1e-15);
        assert!((basis.station_deflection[3] + 0.02).abs() < 1e-15);
    }

    #[test]
    fn a_bad_value_names_file_line_and_column() {
        let scratch = temp_dir("bad");
        let dir = scratch.path();
        let f = write(dir, "f.csv", "mode,frequency_hz\n1,3.5\n2,abc\n");
        let s = write(
            dir,
            "s.csv",
            "line_y_m,x_m,mode_1,mode_2\n0,0,0,0\n0,10,0,0\n",
        );
        let e = load_modal_import(&f, &s, None, 0.05).unwrap_err();
        assert_eq!(e.location, Some((3, 2)));
        assert_eq!(e.field.as_deref(), Some("frequency_hz"));
        let f = write(dir, "f2.csv", "mode,frequency_hz\n1,3.5\n2,3.0\n");
        let e = load_modal_import(&f, &s, None, 0.05).unwrap_err();
        assert_eq!(e.location, Some((3, 2)));
        assert!(e.message.contains("ascending"), "{}", e.message);
        let s = write(dir, "s2.csv", "line_y_m,x_m,mode_1\n0,0,0\n");
        let f = write(dir, "f3.csv", "mode,frequency_hz\n1,3.5\n");
        let s3 = write(
            dir,
            "s3.csv",
            "line_y_m,x_m,mode_1\n0,0,0\n0,5,0.1\n0,4,0\n",
        );
        let e = load_modal_import(&f, &s3, None, 0.05).unwrap_err();
        assert_eq!(e.location, Some((4, 2)));
        let e = load_modal_import(&f, &s, None, 0.05).unwrap_err();
        assert!(e.message.contains("at least 2"), "{}", e.message);
    }
}
