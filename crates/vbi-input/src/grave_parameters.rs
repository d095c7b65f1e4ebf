//! BTLS's traffic generator inputs (PyBTLS 1.0.1; spec docs/design/btls-traffic-generator.md
//! §3.1 and §4): a Grave parameter folder (`GVWpdf.csv`, `ASall.csv`, `AW2&3.csv`, `AW4&5.csv`,
//! optional `HeDS.csv`, as under PyBTLS's `py/pybtls/data/GraveParameters/<site>/`) and a lane
//! flow file, read into [`vbi::traffic::generator`]'s types in SI units.
//!
//! The files' layout (BTLS's `VehModelDataGrave.cpp`, `FlowModelData.cpp`, `LaneFlowData.cpp`):
//! comma-separated numbers, trailing commas and blank separator rows allowed (blank rows are
//! skipped, so the blocks are counted in data rows). A distribution is a triple
//! `weight,mean,sd` and a mixture three rows of triples, one row per mode (modes of weight 0
//! are dropped). Units: weights in 100 kg (981 N each: g = 9.81 m/s², PyBTLS's 0.981 kN),
//! spacings in dm, axle loads in % of the gross weight, speeds in dm/s. BTLS is GPL v3: vbi
//! ships none of its parameter files; give a folder of your own or PyBTLS's.

use std::path::{Path, PathBuf};

use vbi::traffic::generator::{
    FlowBlock, GraveParameters, GvwBandLoadShares, HedsFlowRow, HedsTable, LaneFlow, NormalMixture,
    NormalMode, QuadraticCdf, TandemLoadShareTable, AXLE_SHARE_BOUNDS, AXLE_SPACING_BOUNDS,
    GROSS_WEIGHT_BOUNDS, MIN_SPEED,
};
use vbi::traffic::TravelDirection;
use vbi::units::{DM, HUNDRED_KG_WEIGHT};

use crate::source::{read_bounded, InputError, MAX_INPUT_FILE_BYTES};

/// The gross weights' file: per direction 3 rows of 5 triples (speed [dm/s], unused by BTLS,
/// then the GVW [100 kg] of 2, 3, 4, 5 axles).
pub const GVW_FILE: &str = "GVWpdf.csv";
/// The axle spacings' file: per class (2–5 axles) 3 rows of triples, one per spacing [dm].
pub const SPACING_FILE: &str = "ASall.csv";
/// The 2- and 3-axle load shares' file: per class 3 rows of one triple per axle [% of GVW].
pub const SHARE_23_FILE: &str = "AW2&3.csv";
/// The 4- and 5-axle load shares' file: per class 12 rows `mW1,mW2,mWT,sdW1,sdW2,sdWT` [%].
pub const SHARE_45_FILE: &str = "AW4&5.csv";
/// The HeDS headway file (optional): `n`, the 1 s and 1.5 s quadratics, n flow rows.
pub const HEDS_FILE: &str = "HeDS.csv";

/// A Grave parameter folder read: the vehicle model and, when the folder has one, its HeDS
/// headway table.
#[derive(Debug, Clone, PartialEq)]
pub struct GraveFolder {
    /// The vehicle model's parameters, in SI units.
    pub parameters: GraveParameters,
    /// The HeDS table of `HeDS.csv`, if the folder has the file.
    pub heds: Option<HedsTable>,
}

/// One data row of a BTLS CSV file: its 1-based line and its fields with their 1-based columns
/// (trailing empty fields dropped).
struct Row {
    line: usize,
    fields: Vec<(usize, String)>,
}

/// A BTLS CSV file's data rows (blank rows skipped).
struct CsvRows {
    file: String,
    rows: Vec<Row>,
    /// The file's last line (for errors about missing rows).
    last_line: usize,
}

impl CsvRows {
    fn read(path: &Path) -> Result<CsvRows, InputError> {
        let text = read_bounded(path, MAX_INPUT_FILE_BYTES)?;
        Ok(CsvRows::parse(path.display().to_string(), &text))
    }

    fn parse(file: String, text: &str) -> CsvRows {
        let mut rows = Vec::new();
        let mut last_line = 0;
        for (i, line) in text.trim_start_matches('\u{feff}').lines().enumerate() {
            last_line = i + 1;
            let mut fields = Vec::new();
            let mut column = 1;
            for raw in line.split(',') {
                let leading = raw.chars().take_while(|c| c.is_whitespace()).count();
                fields.push((column + leading, raw.trim().to_string()));
                column += raw.chars().count() + 1;
            }
            while fields.last().is_some_and(|(_, f)| f.is_empty()) {
                fields.pop();
            }
            if !fields.is_empty() {
                rows.push(Row {
                    line: i + 1,
                    fields,
                });
            }
        }
        CsvRows {
            file,
            rows,
            last_line,
        }
    }

    fn error(
        &self,
        line: usize,
        column: usize,
        field: &str,
        message: impl Into<String>,
    ) -> InputError {
        InputError {
            file: self.file.clone(),
            location: Some((line, column)),
            field: Some(field.to_string()),
            message: message.into(),
        }
    }

    /// Exactly `count` data rows, as `layout` describes them; an error at the first missing or
    /// extra row otherwise.
    fn expect_rows(&self, count: usize, layout: &str) -> Result<(), InputError> {
        if self.rows.len() < count {
            let line = self.last_line.max(1);
            return Err(self.error(
                line,
                1,
                "rows",
                format!(
                    "the file ends after {} data rows; {layout} needs {count}",
                    self.rows.len()
                ),
            ));
        }
        if let Some(extra) = self.rows.get(count) {
            return Err(self.error(
                extra.line,
                1,
                "rows",
                format!("a data row beyond the layout's {count}; {layout} has no more"),
            ));
        }
        Ok(())
    }

    /// Field `index` of `row` as a finite number.
    fn number(&self, row: &Row, index: usize, field: &str, unit: &str) -> Result<f64, InputError> {
        let Some((column, text)) = row.fields.get(index) else {
            let column = row
                .fields
                .last()
                .map_or(1, |(c, t)| c + t.chars().count() + 1);
            return Err(self.error(
                row.line,
                column,
                field,
                format!(
                    "the row has {} fields; a number [{unit}] is needed in field {}",
                    row.fields.len(),
                    index + 1
                ),
            ));
        };
        match text.parse::<f64>() {
            Ok(value) if value.is_finite() => Ok(value),
            _ => Err(self.error(
                row.line,
                *column,
                field,
                format!("`{text}` is not allowed; expected a number [{unit}]"),
            )),
        }
    }

    /// The column of field `index` of `row` (past the end for a missing field).
    fn column(&self, row: &Row, index: usize) -> usize {
        row.fields.get(index).map_or(1, |(c, _)| *c)
    }
}

/// How a quantity of a mixture file is read: its name in errors, its unit in the file, the
/// factor to SI and its bounds in SI.
struct Quantity<'a> {
    name: &'a str,
    unit: &'a str,
    to_si: f64,
    bounds: (f64, f64),
}

impl CsvRows {
    /// The mixture of the triple at `triple` over the three mode rows `rows`.
    fn mixture(
        &self,
        rows: &[Row],
        triple: usize,
        quantity: &Quantity,
        label: &str,
    ) -> Result<NormalMixture, InputError> {
        let mut modes = Vec::new();
        for (k, row) in rows.iter().enumerate() {
            let at = |part: &str| format!("{label}.mode{}.{part}", k + 1);
            let first = 3 * triple;
            let weight = self.number(row, first, &at("weight"), "-")?;
            let mean = self.number(row, first + 1, &at("mean"), quantity.unit)?;
            let sd = self.number(row, first + 2, &at("sd"), quantity.unit)?;
            if !(0.0..=1.0).contains(&weight) {
                let message = format!("{weight} is not allowed; expected a weight from 0 to 1");
                return Err(self.error(row.line, self.column(row, first), &at("weight"), message));
            }
            if sd < 0.0 {
                let message = format!(
                    "{sd} is not allowed; expected a standard deviation of 0 or more [{}]",
                    quantity.unit
                );
                return Err(self.error(row.line, self.column(row, first + 2), &at("sd"), message));
            }
            if weight > 0.0 {
                modes.push(NormalMode {
                    weight,
                    mean: mean * quantity.to_si,
                    standard_deviation: sd * quantity.to_si,
                });
            }
        }
        let mixture = NormalMixture {
            modes,
            lower_bound: quantity.bounds.0,
            upper_bound: quantity.bounds.1,
        };
        mixture.check(label).map_err(|e| {
            let row = &rows[0];
            let message = format!(
                "the {} mixture's weights (column {} of the 3 mode rows): {}",
                quantity.name,
                3 * triple + 1,
                e.message
            );
            self.error(row.line, self.column(row, 3 * triple), label, message)
        })?;
        Ok(mixture)
    }
}

/// Reads a Grave parameter folder (see the module's description). The file names are matched
/// exactly, else regardless of case (PyBTLS's Angers folder spells `ASALL.csv`).
pub fn load_grave_folder(folder: &Path) -> Result<GraveFolder, InputError> {
    if !folder.is_dir() {
        return Err(InputError {
            file: folder.display().to_string(),
            location: None,
            field: None,
            message: format!(
                "not a folder: a Grave parameter folder holds {GVW_FILE}, {SPACING_FILE}, {SHARE_23_FILE}, {SHARE_45_FILE} (and optionally {HEDS_FILE})"
            ),
        });
    }
    let required = |name: &str| {
        find_file(folder, name).ok_or_else(|| InputError {
            file: folder.join(name).display().to_string(),
            location: None,
            field: None,
            message: format!("the Grave parameter folder has no {name}; it needs {GVW_FILE}, {SPACING_FILE}, {SHARE_23_FILE} and {SHARE_45_FILE}"),
        })
    };
    let gross_weight = read_gross_weights(&CsvRows::read(&required(GVW_FILE)?)?)?;
    let axle_spacings = read_spacings(&CsvRows::read(&required(SPACING_FILE)?)?)?;
    let (two, three) = read_shares_23(&CsvRows::read(&required(SHARE_23_FILE)?)?)?;
    let (four, five) = read_shares_45(&CsvRows::read(&required(SHARE_45_FILE)?)?)?;
    let heds = match find_file(folder, HEDS_FILE) {
        Some(path) => Some(read_heds(&CsvRows::read(&path)?)?),
        None => None,
    };
    let parameters = GraveParameters {
        gross_weight,
        axle_spacings,
        two_axle_load_shares: two,
        three_axle_load_shares: three,
        four_axle_load_shares: four,
        five_axle_load_shares: five,
    };
    parameters.check().map_err(|e| InputError {
        file: folder.display().to_string(),
        location: None,
        field: Some(e.field),
        message: e.message,
    })?;
    Ok(GraveFolder { parameters, heds })
}

/// `folder/name`, or the folder's file whose name matches `name` regardless of case.
fn find_file(folder: &Path, name: &str) -> Option<PathBuf> {
    let exact = folder.join(name);
    if exact.is_file() {
        return Some(exact);
    }
    std::fs::read_dir(folder)
        .ok()?
        .filter_map(Result::ok)
        .find(|entry| {
            entry
                .file_name()
                .to_string_lossy()
                .eq_ignore_ascii_case(name)
                && entry.path().is_file()
        })
        .map(|entry| entry.path())
}

/// `GVWpdf.csv`: 3 rows for direction 1, then 3 for direction 2; triple 0 the speed (unused),
/// triples 1–4 the GVW of 2–5 axles [100 kg].
fn read_gross_weights(csv: &CsvRows) -> Result<[[NormalMixture; 4]; 2], InputError> {
    csv.expect_rows(
        6,
        "GVWpdf.csv's layout (3 mode rows per direction, 2 directions)",
    )?;
    let quantity = Quantity {
        name: "gross weight",
        unit: "100 kg",
        to_si: HUNDRED_KG_WEIGHT,
        bounds: GROSS_WEIGHT_BOUNDS,
    };
    let direction = |d: usize| -> Result<[NormalMixture; 4], InputError> {
        let rows = &csv.rows[3 * d..3 * d + 3];
        for row in rows {
            for i in 0..3 {
                csv.number(row, i, &format!("direction{}.speed", d + 1), "dm/s")?;
            }
        }
        let class = |c: usize| {
            let label = format!("direction{}.gvw_{}_axles", d + 1, c + 2);
            csv.mixture(rows, c + 1, &quantity, &label)
        };
        Ok([class(0)?, class(1)?, class(2)?, class(3)?])
    };
    Ok([direction(0)?, direction(1)?])
}

/// `ASall.csv`: per class (2–5 axles) 3 mode rows of one triple per spacing [dm].
fn read_spacings(csv: &CsvRows) -> Result<[Vec<NormalMixture>; 4], InputError> {
    csv.expect_rows(
        12,
        "ASall.csv's layout (3 mode rows for each of 2, 3, 4, 5 axles)",
    )?;
    let quantity = Quantity {
        name: "axle spacing",
        unit: "dm",
        to_si: DM,
        bounds: AXLE_SPACING_BOUNDS,
    };
    let class = |c: usize| {
        let rows = &csv.rows[3 * c..3 * c + 3];
        (0..c + 1)
            .map(|j| {
                let label = format!("axles_{}.spacing{}", c + 2, j + 1);
                csv.mixture(rows, j, &quantity, &label)
            })
            .collect::<Result<Vec<_>, _>>()
    };
    Ok([class(0)?, class(1)?, class(2)?, class(3)?])
}

/// `AW2&3.csv`: 3 mode rows of 2 triples (2 axles), then 3 of 3 triples (3 axles) [% of GVW].
fn read_shares_23(csv: &CsvRows) -> Result<(Vec<NormalMixture>, Vec<NormalMixture>), InputError> {
    csv.expect_rows(
        6,
        "AW2&3.csv's layout (3 mode rows for 2 axles, then 3 for 3 axles)",
    )?;
    let quantity = Quantity {
        name: "axle-load share",
        unit: "%",
        to_si: 0.01,
        bounds: AXLE_SHARE_BOUNDS,
    };
    let class = |c: usize| {
        let rows = &csv.rows[3 * c..3 * c + 3];
        (0..c + 2)
            .map(|j| {
                csv.mixture(
                    rows,
                    j,
                    &quantity,
                    &format!("axles_{}.axle{}", c + 2, j + 1),
                )
            })
            .collect::<Result<Vec<_>, _>>()
    };
    Ok((class(0)?, class(1)?))
}

/// `AW4&5.csv`: 12 rows for 4 axles, then 12 for 5; row k the GVW band
/// [25 + 50 (k − 1), 25 + 50 k) kN, row 0 (below 25 kN, which no truck reaches) read and unused.
fn read_shares_45(
    csv: &CsvRows,
) -> Result<(TandemLoadShareTable, TandemLoadShareTable), InputError> {
    csv.expect_rows(
        24,
        "AW4&5.csv's layout (12 band rows for 4 axles, then 12 for 5)",
    )?;
    let class = |c: usize| -> Result<TandemLoadShareTable, InputError> {
        let mut bands = Vec::new();
        for (k, row) in csv.rows[12 * c..12 * c + 12].iter().enumerate() {
            let mut values = [0.0; 6];
            for (i, value) in values.iter_mut().enumerate() {
                let field = format!(
                    "axles_{}.band{k}.{}",
                    c + 4,
                    ["mW1", "mW2", "mWT", "sdW1", "sdW2", "sdWT"][i]
                );
                *value = csv.number(row, i, &field, "%")?;
                if *value < 0.0 {
                    let message = format!(
                        "{value} is not allowed; expected a share or deviation of 0 or more [%]"
                    );
                    return Err(csv.error(row.line, csv.column(row, i), &field, message));
                }
            }
            if k > 0 {
                bands.push(GvwBandLoadShares {
                    mean: [values[0] / 100.0, values[1] / 100.0, values[2] / 100.0],
                    standard_deviation: [values[3] / 100.0, values[4] / 100.0, values[5] / 100.0],
                });
            }
        }
        if !bands.iter().any(GvwBandLoadShares::has_data) {
            let row = &csv.rows[12 * c];
            let message =
                "every band of the class is zero; at least one band needs a share above 0";
            return Err(csv.error(row.line, 1, &format!("axles_{}", c + 4), message));
        }
        Ok(TandemLoadShareTable {
            bands,
            share_lower_bound: AXLE_SHARE_BOUNDS.0,
            share_upper_bound: AXLE_SHARE_BOUNDS.1,
        })
    };
    Ok((class(0)?, class(1)?))
}

/// `HeDS.csv`: `n` in field 1 of row 1; `_,a,b,c` of the quadratic below 1 s and of the one
/// from 1 s to 1.5 s; then n rows `Q_upper,a,b,c` (veh/h; t in s).
fn read_heds(csv: &CsvRows) -> Result<HedsTable, InputError> {
    let Some(first) = csv.rows.first() else {
        return Err(csv.error(
            1,
            1,
            "n",
            "the file is empty; expected `n` (the number of flow rows) on its first row",
        ));
    };
    let n = csv.number(first, 0, "n", "flow rows")?;
    if !(n >= 1.0 && n.fract() == 0.0 && n <= 10_000.0) {
        return Err(csv.error(
            first.line,
            csv.column(first, 0),
            "n",
            format!("{n} is not allowed; expected a whole number of flow rows from 1"),
        ));
    }
    let n = n as usize;
    csv.expect_rows(
        3 + n,
        &format!("HeDS.csv's layout (`n`, the 1 s and 1.5 s rows, then n = {n} flow rows)"),
    )?;
    let quadratic = |row: &Row, name: &str| -> Result<QuadraticCdf, InputError> {
        let coefficient = |i: usize, unit: &str| {
            csv.number(row, i, &format!("{name}.{}", ["", "a", "b", "c"][i]), unit)
        };
        Ok(QuadraticCdf {
            a: coefficient(1, "1/s²")?,
            b: coefficient(2, "1/s")?,
            c: coefficient(3, "-")?,
        })
    };
    let mut table = HedsTable {
        below_one_second: quadratic(&csv.rows[1], "below_1s")?,
        one_to_one_and_a_half_seconds: quadratic(&csv.rows[2], "1s_to_1.5s")?,
        by_flow: Vec::with_capacity(n),
    };
    for (i, row) in csv.rows[3..].iter().enumerate() {
        let name = format!("flow_row{}", i + 1);
        table.by_flow.push(HedsFlowRow {
            flow_upper: csv.number(row, 0, &format!("{name}.q_upper"), "veh/h")?,
            cdf: quadratic(row, &name)?,
        });
        table
            .check_flow_row(i)
            .map_err(|message| csv.error(row.line, 1, &name, message))?;
    }
    Ok(table)
}

/// The direction of BTLS's direction number (1 or 2).
fn direction_of(number: f64) -> Option<TravelDirection> {
    match number {
        1.0 => Some(TravelDirection::Forward),
        2.0 => Some(TravelDirection::Backward),
        _ => None,
    }
}

/// The block rows' fields, for errors.
const BLOCK_ROW_LAYOUT: &str = "block, truck flow [veh/h], speed mean [dm/s], speed sd [dm/s], \
    car %, % 2-axle, % 3-axle, % 4-axle, % 5-axle";

/// A block row's class percentages must sum to 100 within this (BTLS's tolerance,
/// `LaneFlowComposition.cpp`); they are then scaled to sum to 1.
const CLASS_PERCENT_TOLERANCE: f64 = 0.01;

/// Reads BTLS's lane flow file (`LaneFlowData.cpp:29-80`; the BTLS manual's "Lane Flow Data
/// File"): an optional header `nBlocks,blockSize` (told by a second field above 900 s; default
/// 24 blocks of 3600 s), then for each lane a line `lane,dir` followed by nBlocks rows
/// `block, truckFlow [veh/h], speedMean [dm/s], speedSd [dm/s], car%, %2ax, %3ax, %4ax, %5ax`.
///
/// Lanes are numbered 1, 2, … in the file's order (BTLS's global lane number), direction-1
/// lanes first; each becomes a lane numbered within its direction as BTLS numbers a truck's
/// lane (`Vehicle.cpp:705`): the global number in direction 1, n − global + 1 in direction 2 (n
/// lanes in all). The block field is not read (BTLS does not read it either); the car
/// percentage, from 0 to below 100, is checked and dropped (vbi generates trucks only, and the
/// flow is the trucks'); the class percentages, summing to 100 within 0.01, become fractions
/// summing to 1.
pub fn load_lane_flow(path: &Path) -> Result<Vec<LaneFlow>, InputError> {
    let csv = CsvRows::read(path)?;
    let Some(first) = csv.rows.first() else {
        return Err(csv.error(
            1,
            1,
            "lane",
            "the lane flow file is empty; expected a `lane,dir` line and its block rows",
        ));
    };
    let header = first.fields.len() == 2
        && first.fields[1]
            .1
            .parse::<f64>()
            .is_ok_and(|size| size > 900.0);
    let (block_count, block_seconds) = if header {
        let count = csv.number(first, 0, "nBlocks", "blocks")?;
        if !(count >= 1.0 && count.fract() == 0.0 && count <= 100_000.0) {
            let message =
                format!("{count} is not allowed; expected a whole number of blocks from 1");
            return Err(csv.error(first.line, csv.column(first, 0), "nBlocks", message));
        }
        (count as usize, csv.number(first, 1, "blockSize", "s")?)
    } else {
        (
            vbi::traffic::generator::DEFAULT_BLOCK_COUNT,
            vbi::traffic::generator::DEFAULT_BLOCK_SECONDS,
        )
    };
    let mut rows = csv.rows[usize::from(header)..].iter();
    let mut lanes: Vec<(usize, LaneFlow)> = Vec::new();
    while let Some(row) = rows.next() {
        let global = lanes.len() + 1;
        let direction = read_lane_line(&csv, row, global, lanes.last().map(|(_, l)| l.direction))?;
        let mut blocks = Vec::with_capacity(block_count);
        for i in 0..block_count {
            let Some(block_row) = rows.next() else {
                let message = format!("lane {global} has {i} block rows; each lane needs {block_count} ({BLOCK_ROW_LAYOUT})");
                return Err(csv.error(csv.last_line.max(1), 1, "block", message));
            };
            blocks.push(read_block_row(&csv, block_row)?);
        }
        let lane = LaneFlow {
            direction,
            lane: global,
            block_seconds,
            blocks,
        };
        lanes.push((row.line, lane));
    }
    let count = lanes.len();
    let mut flows = Vec::with_capacity(count);
    for (line, mut lane) in lanes {
        if lane.direction == TravelDirection::Backward {
            lane.lane = count - lane.lane + 1;
        }
        lane.check("lane")
            .map_err(|e| csv.error(line, 1, &e.field, e.message))?;
        flows.push(lane);
    }
    Ok(flows)
}

/// A lane's `lane,dir` line: the lane must be the next global number, the direction 1 or 2,
/// and no direction-1 lane may follow a direction-2 one.
fn read_lane_line(
    csv: &CsvRows,
    row: &Row,
    global: usize,
    previous: Option<TravelDirection>,
) -> Result<TravelDirection, InputError> {
    if row.fields.len() != 2 {
        let message = format!(
            "expected a lane's `lane,dir` line (2 fields), got {} fields; each lane's line is followed by its block rows ({BLOCK_ROW_LAYOUT})",
            row.fields.len()
        );
        return Err(csv.error(row.line, 1, "lane", message));
    }
    let lane = csv.number(row, 0, "lane", "lane number")?;
    if lane != global as f64 {
        let message = format!("lane {lane} is not allowed here; expected lane {global}: lanes are numbered 1, 2, … in the file's order");
        return Err(csv.error(row.line, csv.column(row, 0), "lane", message));
    }
    let number = csv.number(row, 1, "dir", "direction")?;
    let Some(direction) = direction_of(number) else {
        let message = format!("{number} is not allowed; expected the direction 1 or 2");
        return Err(csv.error(row.line, csv.column(row, 1), "dir", message));
    };
    if previous == Some(TravelDirection::Backward) && direction == TravelDirection::Forward {
        let message = "a direction-1 lane after a direction-2 lane is not allowed; list the direction-1 lanes first (BTLS's order)";
        return Err(csv.error(row.line, csv.column(row, 1), "dir", message));
    }
    Ok(direction)
}

/// One block row, in SI units.
fn read_block_row(csv: &CsvRows, row: &Row) -> Result<FlowBlock, InputError> {
    if row.fields.len() != 9 {
        let message = format!(
            "expected a block row of 9 fields ({BLOCK_ROW_LAYOUT}), got {}",
            row.fields.len()
        );
        return Err(csv.error(row.line, 1, "block", message));
    }
    let mut values = [0.0; 9];
    let names = [
        "block",
        "truckFlow",
        "speedMean",
        "speedSd",
        "car%",
        "%2ax",
        "%3ax",
        "%4ax",
        "%5ax",
    ];
    let units = ["-", "veh/h", "dm/s", "dm/s", "%", "%", "%", "%", "%"];
    for (i, value) in values.iter_mut().enumerate() {
        *value = csv.number(row, i, names[i], units[i])?;
    }
    let refuse = |i: usize, allowed: &str| {
        let message = format!("{} is not allowed; expected {allowed}", values[i]);
        Err(csv.error(row.line, csv.column(row, i), names[i], message))
    };
    if values[1] <= 0.0 {
        return refuse(1, "a positive truck flow [veh/h]");
    }
    if values[2] * DM < MIN_SPEED {
        return refuse(
            2,
            &format!("a mean speed of at least {} dm/s", MIN_SPEED / DM),
        );
    }
    if values[3] < 0.0 {
        return refuse(3, "a speed deviation of 0 or more [dm/s]");
    }
    if !(0.0..100.0).contains(&values[4]) {
        return refuse(4, "a car percentage from 0 to below 100");
    }
    if let Some(i) = (5..9).find(|&i| values[i] < 0.0) {
        return refuse(i, "a class percentage of 0 or more");
    }
    let total: f64 = values[5..].iter().sum();
    if (total - 100.0).abs() > CLASS_PERCENT_TOLERANCE {
        let message = format!(
            "the class percentages sum to {total}; expected 100 (within {CLASS_PERCENT_TOLERANCE})"
        );
        return Err(csv.error(row.line, csv.column(row, 5), "%2ax", message));
    }
    Ok(FlowBlock {
        truck_flow: values[1],
        speed_mean: values[2] * DM,
        speed_standard_deviation: values[3] * DM,
        class_fractions: [
            values[5] / total,
            values[6] / total,
            values[7] / total,
            values[8] / total,
        ],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use vbi::traffic::generator::{HeadwayModel, TrafficGenerator};

    fn fixture(name: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/files/data/grave")
            .join(name)
    }

    fn close(actual: f64, expected: f64) -> bool {
        (actual - expected).abs() <= 1e-12 * expected.abs().max(1.0)
    }

    fn modes(mixture: &NormalMixture) -> Vec<(f64, f64, f64)> {
        mixture
            .modes
            .iter()
            .map(|m| (m.weight, m.mean, m.standard_deviation))
            .collect()
    }

    fn assert_modes(mixture: &NormalMixture, expected: &[(f64, f64, f64)]) {
        let actual = modes(mixture);
        assert_eq!(actual.len(), expected.len(), "{actual:?}");
        for (a, e) in actual.iter().zip(expected) {
            assert!(
                close(a.0, e.0) && close(a.1, e.1) && close(a.2, e.2),
                "{actual:?} != {expected:?}"
            );
        }
    }

    /// Spec §3.1 and §4: the made-up site folder loads to its numbers in SI units: gross
    /// weights 100 kg → 981 N by direction (modes of weight 0 dropped), spacings dm → m, shares
    /// % → fractions with BTLS's bounds, the 4-/5-axle tables without their unused row 0, and
    /// the HeDS table; and a generator runs on them.
    #[test]
    fn the_fixture_folder_loads_to_the_expected_numbers_in_si_units() {
        let folder = load_grave_folder(&fixture("site")).unwrap();
        let p = &folder.parameters;
        let w = HUNDRED_KG_WEIGHT;
        assert_modes(
            &p.gross_weight[0][0],
            &[(0.3, 60.0 * w, 10.0 * w), (0.7, 120.0 * w, 30.0 * w)],
        );
        assert_modes(
            &p.gross_weight[1][0],
            &[
                (0.25, 55.0 * w, 8.0 * w),
                (0.55, 125.0 * w, 35.0 * w),
                (0.2, 200.0 * w, 20.0 * w),
            ],
        );
        assert_modes(
            &p.gross_weight[1][3],
            &[(0.2, 310.0 * w, 50.0 * w), (0.8, 440.0 * w, 55.0 * w)],
        );
        assert_eq!(
            (
                p.gross_weight[0][2].lower_bound,
                p.gross_weight[0][2].upper_bound
            ),
            (34_335.0, 981_000.0)
        );
        assert_eq!(p.axle_spacings.each_ref().map(|s| s.len()), [1, 2, 3, 4]);
        assert_modes(&p.axle_spacings[2][1], &[(0.2, 4.5, 0.8), (0.8, 6.0, 0.5)]);
        assert_modes(&p.axle_spacings[3][3], &[(1.0, 1.25, 0.15)]);
        assert_eq!(p.axle_spacings[0][0].lower_bound, 0.05);
        assert_modes(
            &p.two_axle_load_shares[1],
            &[(0.4, 0.65, 0.03), (0.6, 0.70, 0.04)],
        );
        assert_modes(
            &p.three_axle_load_shares[2],
            &[(0.7, 0.40, 0.03), (0.3, 0.30, 0.03)],
        );
        assert_eq!(p.two_axle_load_shares[0].lower_bound, 0.15);
        let four = &p.four_axle_load_shares;
        assert_eq!(four.bands.len(), 11);
        assert!(
            close(four.bands[0].mean[0], 0.29) && close(four.bands[0].standard_deviation[2], 0.05)
        );
        assert!(!four.bands[9].has_data() && four.bands[8].has_data());
        assert!(close(p.five_axle_load_shares.bands[10].mean[2], 0.55));
        let heds = folder.heds.as_ref().unwrap();
        assert_eq!(
            heds.by_flow
                .iter()
                .map(|r| r.flow_upper)
                .collect::<Vec<_>>(),
            [80.0, 100.0, 150.0]
        );
        assert!((heds.cdf(4.0, 100.0) - 0.15).abs() < 1e-12);
        let lanes = load_lane_flow(&fixture("lane-flow.csv")).unwrap();
        let trucks: Vec<_> = TrafficGenerator::new(
            folder.parameters,
            lanes,
            HeadwayModel::Heds(heds.clone()),
            1,
            1,
            40.0,
        )
        .unwrap()
        .collect();
        assert!(trucks.len() > 1000 && trucks.iter().all(|t| t.check().is_ok()));
    }

    /// Spec §4 (`LaneFlowData.cpp:29-80`, `Vehicle.cpp:705`): without a header, 24 blocks of
    /// 3600 s; with `2,43200`, 2 blocks of 12 h; lanes numbered within their direction
    /// (direction 2: n − global + 1); speeds dm/s → m/s; class % → fractions.
    #[test]
    fn the_lane_flow_file_loads_with_btls_lane_numbers_and_si_units() {
        let lanes = load_lane_flow(&fixture("lane-flow.csv")).unwrap();
        let ids: Vec<_> = lanes.iter().map(|l| (l.direction, l.lane)).collect();
        assert_eq!(
            ids,
            [
                (TravelDirection::Forward, 1),
                (TravelDirection::Backward, 1)
            ]
        );
        assert!(lanes
            .iter()
            .all(|l| l.blocks.len() == 24 && l.block_seconds == 3600.0));
        let block = &lanes[0].blocks[0];
        assert_eq!(block.truck_flow, 20.0);
        assert!(close(block.speed_mean, 25.0) && close(block.speed_standard_deviation, 1.2));
        let expected = [0.2, 0.05, 0.3, 0.45];
        assert!(block
            .class_fractions
            .iter()
            .zip(expected)
            .all(|(a, e)| close(*a, e)));
        assert!(
            close(lanes[1].blocks[6].truck_flow, 60.0)
                && close(lanes[1].blocks[12].truck_flow, 100.0)
        );
        let lanes = load_lane_flow(&fixture("lane-flow-blocks.csv")).unwrap();
        let ids: Vec<_> = lanes.iter().map(|l| (l.direction, l.lane)).collect();
        let (f, b) = (TravelDirection::Forward, TravelDirection::Backward);
        assert_eq!(ids, [(f, 1), (b, 2), (b, 1)]);
        assert!(lanes
            .iter()
            .all(|l| l.blocks.len() == 2 && l.block_seconds == 43_200.0));
        assert_eq!(lanes[2].blocks[1].truck_flow, 60.0);
    }

    /// A copy of the fixture folder with `name` replaced by `text`.
    fn folder_with(name: &str, text: &str) -> tempfile::TempDir {
        let dir = tempfile::Builder::new()
            .prefix("vbi-grave-")
            .tempdir()
            .unwrap();
        for file in [
            GVW_FILE,
            SPACING_FILE,
            SHARE_23_FILE,
            SHARE_45_FILE,
            HEDS_FILE,
        ] {
            std::fs::copy(fixture("site").join(file), dir.path().join(file)).unwrap();
        }
        std::fs::write(dir.path().join(name), text).unwrap();
        dir
    }

    fn folder_error(name: &str, text: &str) -> InputError {
        let dir = folder_with(name, text);
        load_grave_folder(dir.path()).unwrap_err()
    }

    fn fixture_text(name: &str) -> String {
        std::fs::read_to_string(fixture("site").join(name)).unwrap()
    }

    /// Bad parameter files are refused at their line and column, naming the field and what is
    /// allowed: text for a number, weights that do not sum to 1, a missing row, a negative
    /// share, falling HeDS flows, a missing file; other names' case is accepted.
    #[test]
    fn bad_parameter_files_give_located_errors() {
        let gvw = fixture_text(GVW_FILE).replacen("0.700,120.0", "0.700,abc", 1);
        let e = folder_error(GVW_FILE, &gvw);
        assert_eq!(
            (e.location, e.field.as_deref()),
            (Some((2, 21)), Some("direction1.gvw_2_axles.mode2.mean"))
        );
        assert!(
            e.message
                .contains("`abc` is not allowed; expected a number [100 kg]"),
            "{e}"
        );
        let gvw = fixture_text(GVW_FILE).replacen("0.700,120.0", "0.600,120.0", 1);
        let e = folder_error(GVW_FILE, &gvw);
        assert_eq!(
            (e.location, e.field.as_deref()),
            (Some((1, 18)), Some("direction1.gvw_2_axles"))
        );
        assert!(e.message.contains("must sum to 1"), "{e}");
        let spacings = fixture_text(SPACING_FILE);
        let spacings: Vec<&str> = spacings.lines().take(14).collect();
        let e = folder_error(SPACING_FILE, &spacings.join("\n"));
        assert_eq!(e.location, Some((14, 1)));
        assert!(e.message.contains("ends after 11 data rows"), "{e}");
        let shares = fixture_text(SHARE_45_FILE).replacen("28.0,35.0", "28.0,-35.0", 1);
        let e = folder_error(SHARE_45_FILE, &shares);
        assert_eq!(
            (e.location, e.field.as_deref()),
            (Some((3, 6)), Some("axles_4.band2.mW2"))
        );
        let heds = fixture_text(HEDS_FILE).replacen("100,", "70,", 1);
        let e = folder_error(HEDS_FILE, &heds);
        assert_eq!(
            (e.location, e.field.as_deref()),
            (Some((5, 1)), Some("flow_row2"))
        );
        assert!(e.message.contains("rise from row to row"), "{e}");
        let dir = folder_with("asall.csv", &fixture_text(SPACING_FILE));
        std::fs::remove_file(dir.path().join(SPACING_FILE)).unwrap();
        assert!(
            load_grave_folder(dir.path()).is_ok(),
            "a name in another case"
        );
        std::fs::remove_file(dir.path().join(HEDS_FILE)).unwrap();
        assert_eq!(load_grave_folder(dir.path()).unwrap().heds, None);
        std::fs::remove_file(dir.path().join(SHARE_23_FILE)).unwrap();
        let e = load_grave_folder(dir.path()).unwrap_err();
        assert!(
            e.to_string()
                .contains("AW2&3.csv: the Grave parameter folder has no AW2&3.csv"),
            "{e}"
        );
    }

    fn lane_flow_error(text: &str) -> InputError {
        let dir = tempfile::Builder::new()
            .prefix("vbi-lane-flow-")
            .tempdir()
            .unwrap();
        let path = dir.path().join("lanes.csv");
        std::fs::write(&path, text).unwrap();
        load_lane_flow(&path).unwrap_err()
    }

    /// Bad lane flow files are refused at their line and column: class percentages off 100, a
    /// direction 3, lanes out of order, a direction-1 lane after a direction-2 one, missing
    /// block rows, a row of the wrong length, a zero flow.
    #[test]
    fn bad_lane_flow_files_give_located_errors() {
        let good = "2,7200\n1,1\n0,50,240,10,0,25,25,25,25\n1,20,220,15,50,10,20,30,40\n";
        let cases = [
            (
                good.replace("10,20,30,40", "10,20,30,39"),
                (4, 16),
                "%2ax",
                "sum to 99",
            ),
            (
                good.replace("1,1\n", "1,3\n"),
                (2, 3),
                "dir",
                "the direction 1 or 2",
            ),
            (
                good.replace("1,1\n", "2,1\n"),
                (2, 1),
                "lane",
                "expected lane 1",
            ),
            (
                format!("{good}2,2\n0,5,240,10,0,25,25,25,25\n1,5,240,10,0,25,25,25,25\n3,1\n"),
                (8, 3),
                "dir",
                "direction-1 lanes first",
            ),
            (
                good.replace("1,20,220,15,50,10,20,30,40\n", ""),
                (3, 1),
                "block",
                "lane 1 has 1 block rows",
            ),
            (
                good.replace("25,25,25,25", "25,25,50"),
                (3, 1),
                "block",
                "9 fields",
            ),
            (
                good.replace("0,50,", "0,0,"),
                (3, 3),
                "truckFlow",
                "a positive truck flow",
            ),
            (
                good.replace("240,", "5,"),
                (3, 6),
                "speedMean",
                "at least 10 dm/s",
            ),
        ];
        for (text, location, field, message) in cases {
            let e = lane_flow_error(&text);
            assert_eq!(
                (e.location, e.field.as_deref()),
                (Some(location), Some(field)),
                "{e}"
            );
            assert!(e.message.contains(message), "{e}");
        }
    }
}
