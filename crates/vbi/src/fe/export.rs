//! vbi's own FE model written out as another program would give it ([`ImportedMatrices`]):
//! K and M over the free DOFs, the node and direction of each, the nodes' coordinates and the
//! deck lines. What `vbi modes --export-matrices` writes, and the round trip that checks the
//! import: read back, the same frequencies, statics and crossings.
//!
//! Nodes are tagged 1, 2, … in vbi's own numbering (x-major, then line). A rotation DOF is the
//! right-handed rotation about its axis: a beam's slope DOF dw/dx is written as
//! θ_y = −dw/dx (its rows and columns change sign), as a 3D frame program has it.

use std::sync::Arc;

use crate::linalg::SparseMatrix;
use crate::model::{BridgeModel, ImportedDeckLine, ImportedMatrices, ModelError};

use super::assembly::build_mesh;
use super::{discretise, Direction, FeError, MeshOptions};

/// An FE model as matrices, with the coordinates of its nodes [m] by tag.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportedMatrices {
    /// The model as an imported one would be.
    pub model: ImportedMatrices,
    /// (tag, [x, y, z]) of every node, x from the first support, y from the centreline [m].
    pub node_coordinates: Vec<(u64, [f64; 3])>,
}

/// Writes vbi's own model of `model` (meshed with `options`) as matrices. Errors: those of
/// [`discretise`]; a model with stiffness losses (its girders' EI is not one value per line,
/// which the imported moment rows need); a skewed grillage (an imported model's deck lines
/// share their support positions).
pub fn export_matrices(
    model: &BridgeModel,
    options: &MeshOptions,
) -> Result<ExportedMatrices, FeError> {
    if matches!(model, BridgeModel::Grillage(g) if g.is_skewed()) {
        return Err(FeError::Model(ModelError::ImportedMatrices {
            message: "a skewed grillage cannot be exported yet: an imported model's deck lines \
                      share one set of support positions"
                .into(),
        }));
    }
    if !model.damage().stiffness_losses.is_empty() {
        return Err(FeError::Model(ModelError::ImportedMatrices {
            message: "a model with stiffness losses cannot be exported: its girders' EI is not \
                      one value per deck line"
                .into(),
        }));
    }
    let fe = discretise(model, options)?;
    let mesh = build_mesh(model, options)?;
    let dpn = mesh.dofs_per_node;
    let free_dofs: Vec<usize> = (0..mesh.restrained.len())
        .filter(|&dof| !mesh.restrained[dof])
        .collect();
    // A beam's slope DOF is dw/dx = −θ_y.
    let sign: Vec<f64> = free_dofs
        .iter()
        .map(|&dof| if dpn == 2 && dof % 2 == 1 { -1.0 } else { 1.0 })
        .collect();
    let signed = |matrix: &SparseMatrix| -> SparseMatrix {
        let mut out = matrix.clone();
        for column in 0..out.size {
            for k in out.column_pointers[column]..out.column_pointers[column + 1] {
                out.values[k] *= sign[out.row_indices[k]] * sign[column];
            }
        }
        out
    };
    let lines = mesh.line_positions.len();
    let tag = |ix: usize, line: usize| (mesh.node(ix, line) + 1) as u64;
    let deck_lines = (0..lines)
        .map(|line| ImportedDeckLine {
            lateral_position: mesh.line_positions[line],
            nodes: (0..mesh.xs.len()).map(|ix| tag(ix, line)).collect(),
            node_positions: mesh.xs.clone(),
            flexural_rigidity: mesh.line_rigidity[line],
            mass_per_length: mesh.line_mass[line],
        })
        .collect();
    let node_coordinates = (0..mesh.xs.len())
        .flat_map(|ix| (0..lines).map(move |line| (ix, line)))
        .map(|(ix, line)| (tag(ix, line), [mesh.xs[ix], mesh.line_positions[line], 0.0]))
        .collect();
    let dof_directions: Vec<Direction> = free_dofs.iter().map(|&d| mesh.direction(d)).collect();
    Ok(ExportedMatrices {
        model: ImportedMatrices {
            stiffness: Arc::new(signed(&fe.stiffness)),
            mass: Arc::new(signed(&fe.mass)),
            dof_nodes: Arc::new(free_dofs.iter().map(|&d| (d / dpn + 1) as u64).collect()),
            dof_directions: Arc::new(dof_directions),
            deck_lines,
            span_lengths: model.span_lengths().to_vec(),
            damping_ratio: model.damping_ratio(),
            mode_damping: model.mode_damping().cloned(),
            damage: Default::default(),
            source: "vbi's own FE model".into(),
        },
        node_coordinates,
    })
}

/// An imported model written back as it was read (in SI and vbi's axes); its nodes file holds
/// the deck nodes, the only ones whose coordinates the import keeps. Errors: a bridge that is
/// not imported matrices.
pub fn export_imported(model: &BridgeModel) -> Result<ExportedMatrices, FeError> {
    let BridgeModel::ImportedMatrices(imported) = model else {
        return Err(FeError::Model(ModelError::ImportedMatrices {
            message: "not an imported model".into(),
        }));
    };
    let mut node_coordinates: Vec<(u64, [f64; 3])> = imported
        .deck_lines
        .iter()
        .flat_map(|line| {
            line.nodes
                .iter()
                .zip(&line.node_positions)
                .map(|(&tag, &x)| (tag, [x, line.lateral_position, 0.0]))
        })
        .collect();
    node_coordinates.sort_by_key(|&(tag, _)| tag);
    node_coordinates.dedup_by_key(|&mut (tag, _)| tag);
    Ok(ExportedMatrices {
        model: imported.clone(),
        node_coordinates,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::{Quantity, StationTarget};
    use crate::modal::{solve_modes, ModalOptions};
    use crate::model::{paper_bridge, BeamSection, ContinuousBeam};

    fn round_trip(model: &BridgeModel, modes: usize) {
        let options = MeshOptions::default();
        let own = discretise(model, &options).unwrap();
        let exported = export_matrices(model, &options).unwrap();
        let imported =
            discretise(&BridgeModel::ImportedMatrices(exported.model), &options).unwrap();
        assert_eq!(own.stiffness.size, imported.stiffness.size);
        let modal = ModalOptions {
            mode_count: modes,
            ..ModalOptions::default()
        };
        let a = solve_modes(&own, &modal).unwrap();
        let b = solve_modes(&imported, &modal).unwrap();
        for (m, n) in a.modes.iter().zip(&b.modes) {
            let relative =
                (m.circular_frequency - n.circular_frequency).abs() / m.circular_frequency;
            assert!(
                relative < 1e-12,
                "ω {} against {}",
                m.circular_frequency,
                n.circular_frequency
            );
        }
        // The stations are the same, at the same places, with the same deflection and moment
        // (each mode up to its sign).
        assert_eq!(a.stations.len(), b.stations.len());
        for (s, (p, q)) in a.stations.iter().zip(&b.stations).enumerate() {
            assert_eq!(
                (&p.name, p.position, p.target),
                (&q.name, q.position, q.target)
            );
            for quantity in [Quantity::Deflection, Quantity::BendingMoment] {
                let (x, y) = (a.station_values(s, quantity), b.station_values(s, quantity));
                let scale = x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                for (k, (u, v)) in x.iter().zip(y).enumerate() {
                    let sign = a
                        .deck_deflection
                        .iter()
                        .zip(&b.deck_deflection)
                        .skip(k)
                        .step_by(a.mode_count())
                        .map(|(p, q)| p * q)
                        .sum::<f64>()
                        .signum();
                    assert!(
                        (u - sign * v).abs() <= 1e-8 * scale,
                        "{} {quantity:?} mode {k}: {u} against {v}",
                        p.name
                    );
                }
            }
        }
        assert!(matches!(
            b.stations[0].target,
            StationTarget::Girder(_) | StationTarget::Section
        ));
    }

    #[test]
    fn a_two_span_beam_exported_and_imported_has_the_same_modes_and_stations() {
        let beam = ContinuousBeam::pinned(
            vec![20.0, 25.0],
            BeamSection {
                flexural_rigidity: 2.0e10,
                mass_per_length: 1.0e4,
            },
        );
        round_trip(&BridgeModel::ContinuousBeam(beam), 8);
    }

    #[test]
    fn the_paper_grillage_exported_and_imported_has_the_same_modes_and_stations() {
        round_trip(&paper_bridge(2, 20.0), 12);
    }
}
