//! The plan of a mesh (members, bearings and counts), as `vbi modes` prints it and draws it.

use serde::Serialize;

use super::{build_mesh, FeError, MemberKind, Mesh, MeshOptions};
use crate::model::BridgeModel;

/// One member of the plan, from `start` to `end` (x, y) [m].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanMember {
    /// What it models.
    pub kind: MemberKind,
    /// Start (x, y) [m].
    pub start: [f64; 2],
    /// End (x, y) [m].
    pub end: [f64; 2],
}

/// The plan of a meshed bridge: its members (each girder line as one member from end to end),
/// its bearings and the mesh's counts.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DeckPlan {
    /// Girder lines, slab strips and diaphragms.
    pub members: Vec<PlanMember>,
    /// Position (x, y) of every bearing [m].
    pub bearings: Vec<[f64; 2]>,
    /// Nodes of the mesh [-].
    pub node_count: usize,
    /// Girder elements [-].
    pub girder_element_count: usize,
    /// Transverse elements (slab strips and diaphragms) [-].
    pub transverse_element_count: usize,
    /// Longest girder element [m].
    pub longest_girder_element: f64,
    /// Total mass of the model (members, pavement, barriers) [kg].
    pub total_mass: f64,
}

/// The (x, y) of a node of the mesh [m].
fn node_position(mesh: &Mesh, node: usize) -> [f64; 2] {
    let lines = mesh.line_positions.len();
    [
        mesh.node_x(node / lines, node % lines),
        mesh.line_positions[node % lines],
    ]
}

/// The plan of `model` meshed with `options` (not for imported matrices or modes: they have no
/// mesh).
pub fn deck_plan(model: &BridgeModel, options: &MeshOptions) -> Result<DeckPlan, FeError> {
    let mesh = build_mesh(model, options)?;
    let last = mesh.xs.len() - 1;
    let mut members: Vec<PlanMember> = mesh
        .line_positions
        .iter()
        .enumerate()
        .map(|(line, &y)| PlanMember {
            kind: MemberKind::Girder,
            start: [mesh.node_x(0, line), y],
            end: [mesh.node_x(last, line), y],
        })
        .collect();
    let mut girder_element_count = 0;
    let mut longest_girder_element: f64 = 0.0;
    for element in &mesh.elements {
        if element.kind == MemberKind::Girder {
            girder_element_count += 1;
            longest_girder_element = longest_girder_element.max(element.length);
        } else {
            members.push(PlanMember {
                kind: element.kind,
                start: node_position(&mesh, element.nodes[0]),
                end: node_position(&mesh, element.nodes[1]),
            });
        }
    }
    let bearings = mesh
        .support_nodes
        .iter()
        .map(|&(_, _, node)| node_position(&mesh, node))
        .collect();
    Ok(DeckPlan {
        transverse_element_count: mesh.elements.len() - girder_element_count,
        members,
        bearings,
        node_count: mesh.xs.len() * mesh.line_positions.len(),
        girder_element_count,
        longest_girder_element,
        total_mass: mesh.total_mass,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::paper_bridge;

    #[test]
    fn the_paper_plan_has_its_girders_diaphragms_and_a_bearing_under_every_girder() {
        // The paper's 2 × 20 m bridge: 3 girder lines, 3 support diaphragms spanning 2 gaps
        // each, 10 strips per span minus one at each end inside a span, 3 × 3 bearings.
        let plan = deck_plan(&paper_bridge(2, 20.0), &MeshOptions::default()).unwrap();
        let count = |kind| plan.members.iter().filter(|m| m.kind == kind).count();
        assert_eq!(count(MemberKind::Girder), 3);
        assert_eq!(count(MemberKind::Diaphragm), 3 * 2);
        assert_eq!(count(MemberKind::SlabStrip), 2 * 9 * 2);
        assert_eq!(plan.bearings.len(), 9);
        assert!(plan.longest_girder_element <= MeshOptions::default().element_length + 1e-12);
    }
}
