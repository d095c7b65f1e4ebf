//! `vbi modes --export-matrices DIR`: vbi's own FE model of a bridge written as another program
//! would give it, in the files that an `imported_matrices` bridge reads (docs/input-format.md,
//! "Imported FE matrices"): stiffness.mtx, mass.mtx (Matrix Market, SI), dofs.csv, nodes.csv
//! and bridge.toml. Read back, it gives the same modes, statics and crossings to round-off.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::Result;
use vbi::fe::ExportedMatrices;
use vbi::linalg::SparseMatrix;
use vbi::model::{Direction, ModeDamping};
use vbi_input::imported_matrices::DOF_NAMES;
use vbi_input::matrix_market::write_symmetric;

use crate::output::{create_output_dir, write_atomic, write_csv};

/// Writes the five files into `dir` (created if needed); `source` names the bridge in comments.
pub fn write(dir: &Path, exported: &ExportedMatrices, source: &str) -> Result<()> {
    create_output_dir(dir)?;
    let model = &exported.model;
    let matrix = |m: &SparseMatrix, what: &str| {
        write_symmetric(
            m.size,
            &m.column_pointers,
            &m.row_indices,
            &m.values,
            &format!(
                "{what} of {source}, written by vbi {}",
                env!("CARGO_PKG_VERSION")
            ),
        )
    };
    write_atomic(
        &dir.join("stiffness.mtx"),
        matrix(&model.stiffness, "stiffness [N/m, N, N·m]").as_bytes(),
    )?;
    write_atomic(
        &dir.join("mass.mtx"),
        matrix(&model.mass, "mass [kg, kg·m, kg·m²]").as_bytes(),
    )?;
    let dof_rows: Vec<Vec<String>> = model
        .dof_nodes
        .iter()
        .zip(model.dof_directions.iter())
        .enumerate()
        .map(|(i, (node, &direction))| {
            let index = Direction::ALL.iter().position(|&d| d == direction);
            vec![
                (i + 1).to_string(),
                node.to_string(),
                DOF_NAMES[index.unwrap_or(0)].to_string(),
            ]
        })
        .collect();
    write_csv(
        &dir.join("dofs.csv"),
        &["equation", "node", "dof"],
        &dof_rows,
    )?;
    let node_rows: Vec<Vec<String>> = exported
        .node_coordinates
        .iter()
        .map(|(tag, p)| {
            let mut row = vec![tag.to_string()];
            row.extend(p.iter().map(|v| format!("{v:?}")));
            row
        })
        .collect();
    write_csv(&dir.join("nodes.csv"), &["node", "x", "y", "z"], &node_rows)?;
    write_atomic(
        &dir.join("bridge.toml"),
        bridge_toml(exported, source).as_bytes(),
    )
}

/// The `[bridge]` file of the export; every number in Rust's round-trip form.
fn bridge_toml(exported: &ExportedMatrices, source: &str) -> String {
    let model = &exported.model;
    let supports = vbi::model::support_positions_of(&model.span_lengths);
    let list = |values: &[f64]| {
        values
            .iter()
            .map(|v| format!("{v:?}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut text = format!(
        "# vbi's own FE model of {source}, written by `vbi modes --export-matrices` (vbi {}).\n\
         # Read back as an imported model it gives the same modes, statics and crossings.\n\
         \n\
         [bridge]\n\
         type = \"imported_matrices\"\n\
         stiffness_mtx = \"stiffness.mtx\"\n\
         mass_mtx = \"mass.mtx\"\n\
         dof_map_csv = \"dofs.csv\"\n\
         nodes_csv = \"nodes.csv\"\n\
         units = \"N-m\"\n\
         vertical_axis = \"z\"\n\
         support_positions_m = [{}]\n\
         centreline_m = 0.0\n",
        env!("CARGO_PKG_VERSION"),
        list(&supports),
    );
    // The damping law as the bridge gives it (the keys exclude each other).
    let _ = match &model.mode_damping {
        None => writeln!(text, "damping_ratio = {:?}", model.damping_ratio),
        Some(ModeDamping::PerMode { ratios }) => {
            writeln!(text, "damping_ratios = [{}]", list(ratios))
        }
        Some(ModeDamping::Rayleigh(r)) => writeln!(
            text,
            "rayleigh_damping = {{ ratio_1 = {:?}, frequency_1_hz = {:?}, ratio_2 = {:?}, \
             frequency_2_hz = {:?} }}",
            r.first_ratio, r.first_frequency, r.second_ratio, r.second_frequency
        ),
    };
    for line in &model.deck_lines {
        let nodes: Vec<String> = line.nodes.iter().map(|n| n.to_string()).collect();
        let _ = write!(
            text,
            "\n[[bridge.deck_line]]   # y = {:?} m\nnodes = [{}]\nflexural_rigidity_n_m2 = {:?}\n\
             mass_per_length_kg_per_m = {:?}\n",
            line.lateral_position,
            nodes.join(", "),
            line.flexural_rigidity,
            line.mass_per_length,
        );
    }
    text
}
