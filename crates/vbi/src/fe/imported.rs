//! The FE model of a bridge imported as matrices ([`ImportedMatrices`]): K and M as given, the
//! deck read from the DOF map, and stations at deck nodes, named and placed as on vbi's own
//! models (the middle of every span and every interior support, for each girder and for the
//! section, and the requested ones).
//!
//! A deck node's deflection is its z translation and its slope dw/dx = −θ_y (a rotation about
//! the lateral axis, right-handed with z up, turns a point ahead of the node downwards); a node
//! missing from the DOF map, or missing one of them, is restrained in it. A station stands at
//! the deck node nearest to where it is asked for, on each line it reads.

use std::collections::HashMap;

use crate::deck::{DeckGeometry, DeckLine};
use crate::model::{ImportedDeckLine, ImportedMatrices};

use super::assembly::{default_targets, nearest_index, target_suffix};
use super::element::{beam_mass, beam_stiffness};
use super::{
    DeckNodeDofs, Direction, FeError, FeModel, MeshOptions, SparseRow, Station, StationFunctional,
    StationTarget,
};

/// Where a node's vertical DOFs are among the free DOFs: (z translation, rotation about y).
type NodeDofs = (Option<usize>, Option<usize>);

/// A station and the point it reads: (x [m], the girder or the section).
type StationPoint = (f64, StationTarget);

/// The FE model of imported matrices. Errors: an invalid model (matrices, DOF map and deck
/// lines that do not fit), or a requested station off the deck or on a missing girder.
pub fn discretise_imported(
    model: &ImportedMatrices,
    options: &MeshOptions,
) -> Result<FeModel, FeError> {
    model.validate()?;
    let mut index: HashMap<(u64, Direction), usize> = HashMap::new();
    for (dof, (&node, &direction)) in model
        .dof_nodes
        .iter()
        .zip(model.dof_directions.iter())
        .enumerate()
    {
        index.insert((node, direction), dof);
    }
    let node_dofs = |node: u64| -> NodeDofs {
        (
            index.get(&(node, Direction::TranslationZ)).copied(),
            index.get(&(node, Direction::RotationY)).copied(),
        )
    };
    let mut lines: Vec<&ImportedDeckLine> = model.deck_lines.iter().collect();
    lines.sort_by(|a, b| a.lateral_position.total_cmp(&b.lateral_position));
    let mut deck_lines = Vec::with_capacity(lines.len());
    let mut deck_dofs = Vec::new();
    let mut line_dofs: Vec<Vec<NodeDofs>> = Vec::with_capacity(lines.len());
    for line in &lines {
        deck_lines.push(DeckLine {
            lateral_position: line.lateral_position,
            node_positions: line.node_positions.clone(),
            first_node: deck_dofs.len(),
        });
        let dofs: Vec<NodeDofs> = line.nodes.iter().map(|&node| node_dofs(node)).collect();
        deck_dofs.extend(dofs.iter().map(|&(w, r)| DeckNodeDofs {
            deflection: w.map(|w| vec![(w, 1.0)]).unwrap_or_default(),
            slope: r.map(|r| vec![(r, -1.0)]).unwrap_or_default(),
        }));
        line_dofs.push(dofs);
    }
    let length = model.length();
    let (stations, points) = stations(model, options, &lines)?;
    let functionals = points
        .iter()
        .map(|&(x, target)| {
            let read: Vec<usize> = match target {
                StationTarget::Girder(g) => vec![g],
                StationTarget::Section => (0..lines.len()).collect(),
            };
            let mut sum = StationFunctional::default();
            let share = 1.0 / read.len() as f64;
            for &line in &read {
                let node = nearest_index(&lines[line].node_positions, x);
                sum.add_line(line_functional(lines[line], &line_dofs[line], node), share);
            }
            sum
        })
        .collect();
    Ok(FeModel {
        stiffness: (*model.stiffness).clone(),
        mass: (*model.mass).clone(),
        dof_directions: model.dof_directions.to_vec(),
        deck: DeckGeometry {
            lines: deck_lines,
            length,
        },
        deck_dofs,
        stations,
        station_functionals: functionals,
        damping_ratio: model.damping_ratio,
        mode_damping: model.mode_damping.clone(),
        total_mass: model.vertical_mass(),
        has_station_forces: false,
    })
}

/// The stations (default and requested) and the point (x, target) each one reads; a station's
/// position is the deck node it stands at (on the lowest line it reads).
fn stations(
    model: &ImportedMatrices,
    options: &MeshOptions,
    lines: &[&ImportedDeckLine],
) -> Result<(Vec<Station>, Vec<StationPoint>), FeError> {
    let length = model.length();
    let single = lines.len() == 1;
    let supports = crate::model::support_positions_of(&model.span_lengths);
    let interior = &supports[1..supports.len() - 1];
    let tolerance = 1e-6 * length;
    let snap = |x: f64, target: StationTarget| -> f64 {
        let line = match target {
            StationTarget::Girder(g) => lines[g],
            StationTarget::Section => lines[0],
        };
        line.node_positions[nearest_index(&line.node_positions, x)]
    };
    let targets = default_targets(lines.len(), single);
    let suffix = target_suffix;
    let mut stations = Vec::new();
    let mut points = Vec::new();
    let mut add = |name: String, x: f64, target: StationTarget| {
        let position = snap(x, target);
        stations.push(Station {
            name,
            position,
            target,
            over_support: interior.iter().any(|&s| (s - position).abs() <= tolerance),
            support: false,
        });
        points.push((position, target));
    };
    if options.default_stations {
        for (s, pair) in supports.windows(2).enumerate() {
            for &t in &targets {
                let name = format!("span{}_mid_{}", s + 1, suffix(t));
                add(name, 0.5 * (pair[0] + pair[1]), t);
            }
        }
        for (j, &x) in interior.iter().enumerate() {
            for &t in &targets {
                add(format!("support{}_{}", j + 2, suffix(t)), x, t);
            }
        }
    }
    for (i, request) in options.stations.iter().enumerate() {
        let name = super::assembly::request_name(request, i);
        if !(request.position.is_finite() && (0.0..=length).contains(&request.position)) {
            return Err(FeError::StationOffDeck {
                name,
                position: request.position,
                length,
            });
        }
        let target = match request.target {
            StationTarget::Girder(_) if single => StationTarget::Section,
            StationTarget::Girder(g) if g >= lines.len() => {
                return Err(FeError::NoSuchGirder {
                    name,
                    girder: g,
                    girder_count: lines.len(),
                })
            }
            t => t,
        };
        add(name, request.position, target);
    }
    Ok((stations, points))
}

/// The deflection and the moment rows of one line at its node `node`: the end moments of the
/// Hermite elements either side ([`beam_stiffness`], [`beam_mass`] with the line's EI and m̄),
/// in the variables (w₁, w₁′, w₂, w₂′) with w′ = −θ_y. Left element: M = f_φ2; right element:
/// M = −f_φ1 (as for vbi's own girders). At a deck end the one element there reads both sides
/// (exact for loads outside it).
fn line_functional(line: &ImportedDeckLine, dofs: &[NodeDofs], node: usize) -> StationFunctional {
    let end_moment = |a: usize, row: usize, factor: f64| -> (SparseRow, SparseRow) {
        let h = line.node_positions[a + 1] - line.node_positions[a];
        let k = beam_stiffness(line.flexural_rigidity, h);
        let m = beam_mass(line.mass_per_length, h);
        let (w1, r1) = dofs[a];
        let (w2, r2) = dofs[a + 1];
        let mut stiffness_row = SparseRow::new();
        let mut mass_row = SparseRow::new();
        for (j, (dof, sign)) in [(w1, 1.0), (r1, -1.0), (w2, 1.0), (r2, -1.0)]
            .into_iter()
            .enumerate()
        {
            if let Some(dof) = dof {
                stiffness_row.push((dof, factor * k[row][j] * sign));
                if m[row][j] != 0.0 {
                    mass_row.push((dof, factor * m[row][j] * sign));
                }
            }
        }
        (stiffness_row, mass_row)
    };
    let left = (node > 0).then(|| end_moment(node - 1, 3, 1.0));
    let right = (node + 1 < dofs.len()).then(|| end_moment(node, 1, -1.0));
    let ((moment_left, moment_left_mass), (moment_right, moment_right_mass)) = match (left, right) {
        (Some(l), Some(r)) => (l, r),
        (Some(l), None) => (l.clone(), l),
        (None, Some(r)) => (r.clone(), r),
        (None, None) => Default::default(),
    };
    StationFunctional {
        deflection: dofs[node].0.map(|w| vec![(w, 1.0)]).unwrap_or_default(),
        moment_left,
        moment_right,
        moment_left_mass,
        moment_right_mass,
        ..StationFunctional::default()
    }
}
