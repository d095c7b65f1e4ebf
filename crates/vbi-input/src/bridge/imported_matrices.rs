//! `type = "imported_matrices"`: a bridge given as another FE program's sparse K and M (Matrix
//! Market files), a DOF map (which node and direction each matrix row is), the nodes'
//! coordinates and the deck lines (docs/input-format.md, "Imported FE matrices").
//!
//! The files are in the model's own consistent units (`units`: force and length; mass in
//! force·s²/length) and axes (`vertical_axis`); they are converted here, once, to SI and vbi's
//! axes (x along the bridge from the first support, y to the left, z up). With u_vbi = s·u_file
//! for each DOF (s = ± the length unit for a translation, ± 1 for a rotation, the sign from the
//! axes), energy is kept by K_vbi,ij = K_file,ij · F·L / (s_i s_j), and the same for M.

use std::collections::{HashMap, HashSet};
use std::path::PathBuf;
use std::sync::Arc;

use serde::Deserialize;
use vbi::fe::Direction;
use vbi::linalg::SparseMatrix;
use vbi::model::imported::{asymmetry, SYMMETRY_TOLERANCE};
use vbi::model::{BridgeModel, Damage, ImportedDeckLine, ImportedMatrices};

use crate::bridge_damage::{mode_damping, RawDampingKeys, RawRayleigh};
use crate::csv_table::Table;
use crate::matrix_market;
use crate::source::{
    read_bounded, require_in_range, require_positive, InputError, SourceFile, MAX_DATA_FILE_BYTES,
};
use crate::values::key_range;

/// Most matrix rows an imported model may have: the modal analysis of larger models is refused
/// by its memory estimate anyway; this bounds what reading allocates.
pub const MAX_IMPORTED_DOFS: usize = 2_000_000;

#[derive(Debug, Deserialize)]
struct RawFile {
    bridge: RawBridge,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBridge {
    #[serde(rename = "type")]
    _kind: String,
    stiffness_mtx: String,
    mass_mtx: String,
    dof_map_csv: String,
    nodes_csv: String,
    units: String,
    vertical_axis: Option<String>,
    support_positions_m: Vec<f64>,
    centreline_m: Option<f64>,
    damping_ratio: Option<f64>,
    damping_ratios: Option<Vec<f64>>,
    rayleigh_damping: Option<RawRayleigh>,
    deck_line: Vec<RawDeckLine>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDeckLine {
    nodes: Vec<i64>,
    flexural_rigidity_n_m2: f64,
    mass_per_length_kg_per_m: Option<f64>,
}

/// The unit systems a model's files may be in: name, force unit [N], length unit [m].
pub const UNIT_SYSTEMS: [(&str, f64, f64); 6] = [
    ("N-m", 1.0, 1.0),
    ("kN-m", 1e3, 1.0),
    ("MN-m", 1e6, 1.0),
    ("N-mm", 1.0, 1e-3),
    ("kN-mm", 1e3, 1e-3),
    ("kip-in", 4448.2216152605, 0.0254),
];

/// The six DOF names of a DOF map, in the order of [`Direction::ALL`].
pub const DOF_NAMES: [&str; 6] = ["ux", "uy", "uz", "rx", "ry", "rz"];

/// The model's axes: which file axis is vertical.
#[derive(Debug, Clone, Copy, PartialEq)]
enum VerticalAxis {
    Z,
    Y,
}

impl VerticalAxis {
    /// vbi's direction and sign of a file DOF (index into [`DOF_NAMES`]). With y up the file's
    /// z points to the right (x × y = z), so y_vbi = −z_file and θ_y,vbi = −θ_z,file.
    fn direction(self, dof: usize) -> (Direction, f64) {
        use Direction::*;
        match self {
            VerticalAxis::Z => (Direction::ALL[dof], 1.0),
            VerticalAxis::Y => [
                (TranslationX, 1.0),
                (TranslationZ, 1.0),
                (TranslationY, -1.0),
                (RotationX, 1.0),
                (RotationZ, 1.0),
                (RotationY, -1.0),
            ][dof],
        }
    }

    /// The name of the file's vertical translation DOF.
    fn vertical_dof_name(self) -> &'static str {
        match self {
            VerticalAxis::Z => "uz",
            VerticalAxis::Y => "uy",
        }
    }

    /// The lateral coordinate (vbi's y, before the centreline is taken off) of a file point.
    fn lateral(self, point: [f64; 3]) -> f64 {
        match self {
            VerticalAxis::Z => point[1],
            VerticalAxis::Y => -point[2],
        }
    }
}

/// Reads and converts an `imported_matrices` bridge; every error is located at its key or at
/// the line of the data file it is in.
pub fn load(file: &SourceFile) -> Result<BridgeModel, InputError> {
    let raw: RawFile = file.parse()?;
    let bridge = raw.bridge;
    let (force, length) = units(file, &bridge.units)?;
    let axis = match bridge.vertical_axis.as_deref().unwrap_or("z") {
        "z" => VerticalAxis::Z,
        "y" => VerticalAxis::Y,
        other => {
            return Err(file.error_at(
                "bridge.vertical_axis",
                format!("`{other}` is not allowed; expected `z` or `y`"),
            ))
        }
    };
    let dof_map = read_dof_map(&data_path(file, "dof_map_csv", &bridge.dof_map_csv)?)?;
    let n = dof_map.len();
    let scale: Vec<f64> = dof_map
        .iter()
        .map(|&(_, dof)| {
            let (_, sign) = axis.direction(dof);
            sign * if dof < 3 { length } else { 1.0 }
        })
        .collect();
    let matrix = |key: &str, name: &str| -> Result<SparseMatrix, InputError> {
        let path = data_path(file, key, name)?;
        let text = read_bounded(&path, MAX_DATA_FILE_BYTES)?;
        let triplets = matrix_market::read(&path.display().to_string(), &text, n.max(1))?;
        let at = format!("bridge.{key}");
        if triplets.size != n {
            return Err(file.error_at(
                &at,
                format!(
                    "`{}` is {1} × {1} but the DOF map lists {n} DOFs; expected one matrix row \
                     per DOF of the map",
                    path.display(),
                    triplets.size
                ),
            ));
        }
        let entries: Vec<(usize, usize, f64)> = triplets
            .entries
            .into_iter()
            .map(|(i, j, v)| (i, j, v * force * length / (scale[i] * scale[j])))
            .collect();
        if let Some(&(i, j, v)) = entries.iter().find(|e| !e.2.is_finite()) {
            return Err(file.error_at(
                &at,
                format!(
                    "entry ({}, {}) of `{}` is {v} in SI units; expected values that `units` \
                     converts to finite numbers",
                    i + 1,
                    j + 1,
                    path.display()
                ),
            ));
        }
        let matrix = SparseMatrix::from_triplets(n, &entries);
        if let Some((row, column, relative)) = asymmetry(&matrix) {
            return Err(file.error_at(
                &at,
                format!(
                    "`{}` is not symmetric: entries ({}, {}) and ({}, {}) differ by {relative:.2e} \
                     relative (at most {SYMMETRY_TOLERANCE:e}); expected a stiffness or mass \
                     matrix (a `symmetric` file holds its lower triangle)",
                    path.display(),
                    row + 1,
                    column + 1,
                    column + 1,
                    row + 1
                ),
            ));
        }
        if let Some(row) = matrix.diagonal().iter().position(|&d| d < 0.0) {
            return Err(file.error_at(
                &at,
                format!(
                    "`{}` has a negative diagonal entry in row {} (DOF {} of node {}); a \
                     stiffness or mass matrix has none",
                    path.display(),
                    row + 1,
                    DOF_NAMES[dof_map[row].1],
                    dof_map[row].0
                ),
            ));
        }
        Ok(matrix)
    };
    let stiffness = matrix("stiffness_mtx", &bridge.stiffness_mtx)?;
    let mass = matrix("mass_mtx", &bridge.mass_mtx)?;
    let nodes = read_nodes(&data_path(file, "nodes_csv", &bridge.nodes_csv)?)?;
    let supports = support_positions(file, &bridge.support_positions_m)?;
    let deck_lines = deck_lines(file, &bridge, &dof_map, &nodes, axis, length, &supports)?;
    let damping_ratio = match bridge.damping_ratio {
        None => 0.05,
        Some(z) => {
            let (lowest, largest) = key_range("damping_ratio");
            require_in_range(file, "bridge.damping_ratio", z, lowest, largest, "(ratio)")?
        }
    };
    let keys = RawDampingKeys {
        damping_ratio_given: bridge.damping_ratio.is_some(),
        damping_ratios: bridge.damping_ratios.as_deref(),
        rayleigh_damping: bridge.rayleigh_damping.as_ref(),
    };
    Ok(BridgeModel::ImportedMatrices(ImportedMatrices {
        stiffness: Arc::new(stiffness),
        mass: Arc::new(mass),
        dof_nodes: Arc::new(dof_map.iter().map(|&(node, _)| node).collect()),
        dof_directions: Arc::new(dof_map.iter().map(|&(_, d)| axis.direction(d).0).collect()),
        deck_lines,
        span_lengths: supports.windows(2).map(|w| w[1] - w[0]).collect(),
        damping_ratio,
        mode_damping: mode_damping(file, keys)?,
        damage: Damage::default(),
        source: file.name(),
    }))
}

/// The force and length units of a unit system's name [N, m].
fn units(file: &SourceFile, name: &str) -> Result<(f64, f64), InputError> {
    UNIT_SYSTEMS
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|&(_, force, length)| (force, length))
        .ok_or_else(|| {
            let names: Vec<String> = UNIT_SYSTEMS
                .iter()
                .map(|(n, _, _)| format!("`{n}`"))
                .collect();
            file.error_at(
                "bridge.units",
                format!(
                    "`{name}` is not allowed; expected one of {} (force-length; mass in \
                     force·s²/length)",
                    names.join(", ")
                ),
            )
        })
}

/// A data file named at `bridge.<key>`, relative to the bridge file.
fn data_path(file: &SourceFile, key: &str, name: &str) -> Result<PathBuf, InputError> {
    let path = crate::source::relative(file, name);
    if name.trim().is_empty() || !path.is_file() {
        return Err(file.error_at(
            &format!("bridge.{key}"),
            format!(
                "`{}` is not a readable file; expected a path relative to this file",
                path.display()
            ),
        ));
    }
    Ok(path)
}

const DOF_MAP_HEADER: &str = "`equation,node,dof`";

/// The DOF map: for each matrix row (equation 1…N, each once), its node tag and DOF index.
fn read_dof_map(path: &std::path::Path) -> Result<Vec<(u64, usize)>, InputError> {
    let table = Table::read(path)?;
    let equation = table.require_column("equation", DOF_MAP_HEADER)?;
    let node = table.require_column("node", DOF_MAP_HEADER)?;
    let dof = table.require_column("dof", DOF_MAP_HEADER)?;
    let count = table.rows.len();
    if count > MAX_IMPORTED_DOFS {
        return Err(table.error(1, 0, format!("{count} DOFs; at most {MAX_IMPORTED_DOFS}")));
    }
    let mut map: Vec<Option<(u64, usize)>> = vec![None; count];
    let mut seen = HashSet::new();
    for (line, row) in &table.rows {
        let cell = |c: usize| row.get(c).map(String::as_str).unwrap_or("");
        let e = cell(equation)
            .parse::<usize>()
            .ok()
            .filter(|e| (1..=count).contains(e))
            .ok_or_else(|| {
                table.error(
                    *line,
                    equation,
                    format!(
                        "`{}` is not allowed; expected a matrix row from 1 to {count} (one line \
                         per row)",
                        cell(equation)
                    ),
                )
            })?;
        let tag = node_tag(&table, *line, node, cell(node))?;
        let d = DOF_NAMES
            .iter()
            .position(|&n| n == cell(dof))
            .ok_or_else(|| {
                table.error(
                    *line,
                    dof,
                    format!(
                        "`{}` is not allowed; expected one of {}",
                        cell(dof),
                        DOF_NAMES.join(", ")
                    ),
                )
            })?;
        if map[e - 1].is_some() {
            return Err(table.error(*line, equation, format!("equation {e} is listed twice")));
        }
        if !seen.insert((tag, d)) {
            return Err(table.error(
                *line,
                dof,
                format!("node {tag} has `{}` twice", DOF_NAMES[d]),
            ));
        }
        map[e - 1] = Some((tag, d));
    }
    // Every equation is there: count rows, each in 1..=count, none twice.
    Ok(map.into_iter().flatten().collect())
}

fn node_tag(table: &Table, line: usize, column: usize, text: &str) -> Result<u64, InputError> {
    text.parse::<u64>().map_err(|_| {
        table.error(
            line,
            column,
            format!("`{text}` is not allowed; expected a node tag (a whole number ≥ 0)"),
        )
    })
}

/// Node coordinates in the file's length unit: `node,x,y[,z]`.
fn read_nodes(path: &std::path::Path) -> Result<HashMap<u64, [f64; 3]>, InputError> {
    let table = Table::read(path)?;
    let allowed = "`node,x,y,z` (z may be left out for a plane model)";
    let node = table.require_column("node", allowed)?;
    let columns = [
        table.require_column("x", allowed)?,
        table.require_column("y", allowed)?,
    ];
    let z = table.column("z");
    let mut nodes = HashMap::with_capacity(table.rows.len());
    for (line, row) in &table.rows {
        let tag = node_tag(&table, *line, node, row.get(node).map_or("", |s| s))?;
        let x = table.number(*line, row, columns[0], "length unit")?;
        let y = table.number(*line, row, columns[1], "length unit")?;
        let z = match z {
            Some(c) => table.number(*line, row, c, "length unit")?,
            None => 0.0,
        };
        if nodes.insert(tag, [x, y, z]).is_some() {
            return Err(table.error(*line, node, format!("node {tag} is listed twice")));
        }
    }
    Ok(nodes)
}

/// The supports' x in the model's frame [m], strictly ascending, at least two.
fn support_positions(file: &SourceFile, given: &[f64]) -> Result<Vec<f64>, InputError> {
    let key = "bridge.support_positions_m";
    if given.len() < 2 {
        return Err(file.error_at(
            key,
            "expected the x of every support line, at least two, in ascending order [m]",
        ));
    }
    for (i, pair) in given.windows(2).enumerate() {
        if !(pair[0].is_finite() && pair[1].is_finite() && pair[1] > pair[0]) {
            return Err(file.error_at(
                &format!("{key}[{}]", i + 1),
                format!(
                    "{} after {} is not allowed; expected strictly ascending finite positions [m]",
                    pair[1], pair[0]
                ),
            ));
        }
    }
    Ok(given.to_vec())
}

/// The deck lines in vbi's frame: x from the first support, y from the centreline.
fn deck_lines(
    file: &SourceFile,
    bridge: &RawBridge,
    dof_map: &[(u64, usize)],
    nodes: &HashMap<u64, [f64; 3]>,
    axis: VerticalAxis,
    length_unit: f64,
    supports: &[f64],
) -> Result<Vec<ImportedDeckLine>, InputError> {
    if bridge.deck_line.is_empty() {
        return Err(file.error_at(
            "bridge",
            "no [[bridge.deck_line]]; expected one per girder (a beam has one), each with its \
             `nodes` along the bridge",
        ));
    }
    let mapped: HashSet<(u64, Direction)> = dof_map
        .iter()
        .map(|&(node, dof)| (node, axis.direction(dof).0))
        .collect();
    let origin = supports[0];
    let bridge_length = supports[supports.len() - 1] - origin;
    let tolerance = 1e-6 * bridge_length;
    let mut lines = Vec::with_capacity(bridge.deck_line.len());
    for (i, line) in bridge.deck_line.iter().enumerate() {
        let key = format!("bridge.deck_line[{i}]");
        let mut tags = Vec::with_capacity(line.nodes.len());
        let mut xs = Vec::with_capacity(line.nodes.len());
        let mut lateral = Vec::with_capacity(line.nodes.len());
        for (k, &tag) in line.nodes.iter().enumerate() {
            let node_key = format!("{key}.nodes[{k}]");
            let Some(point) = u64::try_from(tag).ok().and_then(|t| nodes.get(&t)) else {
                return Err(file.error_at(
                    &node_key,
                    format!(
                        "node {tag} is not in the nodes file; expected a node tag listed there"
                    ),
                ));
            };
            let tag = tag as u64;
            // A deck node reads its deflection and slope from its vertical translation and its
            // rotation about the lateral axis; one missing is restrained, which only a node
            // over a support may be.
            let x = point[0] * length_unit - origin;
            let missing: Vec<&str> = [
                (Direction::TranslationZ, "vertical translation"),
                (Direction::RotationY, "rotation about the lateral axis"),
            ]
            .into_iter()
            .filter(|(direction, _)| !mapped.contains(&(tag, *direction)))
            .map(|(_, name)| name)
            .collect();
            let over_support = supports
                .iter()
                .any(|&s| (s - origin - x).abs() <= tolerance);
            if !missing.is_empty() && !over_support {
                return Err(file.error_at(
                    &node_key,
                    format!(
                        "node {tag} (x = {x} m from the first support) has no {} in the DOF map \
                         and is not over a support; expected a deck node of frame elements with \
                         both (check `vertical_axis`: the vertical DOF is `{}`)",
                        missing.join(" and no "),
                        axis.vertical_dof_name()
                    ),
                ));
            }
            tags.push(tag);
            xs.push(point[0] * length_unit - origin);
            lateral.push(axis.lateral(*point) * length_unit);
        }
        if lateral
            .iter()
            .any(|&y| (y - lateral[0]).abs() > tolerance.max(1e-6))
        {
            return Err(file.error_at(
                &format!("{key}.nodes"),
                "the nodes are not on one line parallel to the x axis; expected a girder line",
            ));
        }
        if let Some(k) = xs.windows(2).position(|w| w[1] <= w[0]) {
            return Err(file.error_at(
                &format!("{key}.nodes[{}]", k + 1),
                format!(
                    "node {} at x = {} m does not follow node {} at x = {} m; expected the \
                     line's nodes by strictly ascending x",
                    tags[k + 1],
                    xs[k + 1],
                    tags[k],
                    xs[k]
                ),
            ));
        }
        // The end nodes stand on the end supports: round-off in the coordinates is taken off.
        let last = xs.len().saturating_sub(1);
        if xs.len() < 2
            || (xs[0].abs() > tolerance)
            || ((xs[last] - bridge_length).abs() > tolerance)
        {
            return Err(file.error_at(
                &format!("{key}.nodes"),
                format!(
                    "the line runs from x = {} m to {} m from the first support, in `{}`; \
                     expected at least two nodes, the first over the first support and the last \
                     over the last (0 and {bridge_length} m): check `units` and \
                     `support_positions_m`",
                    xs.first().copied().unwrap_or(f64::NAN),
                    xs.last().copied().unwrap_or(f64::NAN),
                    bridge.units
                ),
            ));
        }
        xs[0] = 0.0;
        xs[last] = bridge_length;
        lines.push(ImportedDeckLine {
            lateral_position: lateral[0],
            nodes: tags,
            node_positions: xs,
            flexural_rigidity: require_positive(
                file,
                &format!("{key}.flexural_rigidity_n_m2"),
                line.flexural_rigidity_n_m2,
                "N·m²",
            )?,
            mass_per_length: match line.mass_per_length_kg_per_m {
                None => 0.0,
                Some(m) => require_in_range(
                    file,
                    &format!("{key}.mass_per_length_kg_per_m"),
                    m,
                    0.0,
                    1e7,
                    "kg/m",
                )?,
            },
        });
    }
    centre_lines(file, bridge, axis, &mut lines)?;
    Ok(lines)
}

/// The lines' lateral positions measured from the deck centreline (`centreline_m` in the
/// model's axes, default midway between the outer lines) [m]; two lines at one position are
/// refused.
fn centre_lines(
    file: &SourceFile,
    bridge: &RawBridge,
    axis: VerticalAxis,
    lines: &mut [ImportedDeckLine],
) -> Result<(), InputError> {
    let centreline = match bridge.centreline_m {
        Some(c) => match axis {
            VerticalAxis::Z => c,
            VerticalAxis::Y => -c,
        },
        None => {
            let (low, high) = lines.iter().fold((f64::MAX, f64::MIN), |(l, h), line| {
                (l.min(line.lateral_position), h.max(line.lateral_position))
            });
            0.5 * (low + high)
        }
    };
    for line in lines.iter_mut() {
        line.lateral_position -= centreline;
    }
    for (i, line) in lines.iter().enumerate() {
        if let Some(j) = lines[..i]
            .iter()
            .position(|other| (other.lateral_position - line.lateral_position).abs() <= 1e-6)
        {
            return Err(file.error_at(
                &format!("bridge.deck_line[{i}].nodes"),
                format!(
                    "the line lies at the lateral position of deck_line[{j}] (y = {} m); \
                     expected one line per girder",
                    line.lateral_position
                ),
            ));
        }
    }
    Ok(())
}
