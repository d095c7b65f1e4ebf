//! The mesh of a [`Grillage`]: girder lines on the shared longitudinal grid, transverse slab
//! strips and diaphragms between them, bearings under every girder on every support line, and
//! the barriers' masses on the edge girders.

use super::{
    check_requests, extra_points, longitudinal_grid, nearest_index, parallel, ElementData, FeError,
    Grid, MemberKind, Mesh, MeshElement, MeshOptions,
};
use crate::fe::damage::{girder_factors, holds_vertically, scale_stiffness};
use crate::fe::element::FrameProperties;
use crate::fe::{Direction, StationTarget};
use crate::model::{BearingKind, BridgeModel, Grillage, LateralRestraint, MemberSection};

/// Refuses supports that leave the grillage a rigid-body motion.
fn check_grillage_restraint(grillage: &Grillage) -> Result<(), FeError> {
    let held_lines = (0..grillage.supports.len())
        .filter(|&j| holds_vertically(&grillage.damage, j, true))
        .count();
    if held_lines < 2 {
        return Err(FeError::Mechanism {
            direction: Direction::RotationY,
            explanation: format!(
                "{held_lines} support line holds the deck vertically after the support changes, \
                 and the bearings leave rotation about the support line free; keep at least two"
            ),
        });
    }
    if !grillage.supports.contains(&BearingKind::Pinned) {
        return Err(FeError::Mechanism {
            direction: Direction::TranslationX,
            explanation: "no support line is pinned, so nothing restrains longitudinal \
                          translation; make one support line pinned"
                .into(),
        });
    }
    if grillage.girder_count == 1 && grillage.lateral_restraint == LateralRestraint::PinnedLine {
        return Err(FeError::Mechanism {
            direction: Direction::RotationZ,
            explanation: "a single girder held laterally only at the pinned support turns \
                          freely about the vertical axis; restrain lateral movement at all \
                          supports (lateral_restraint = all_supports)"
                .into(),
        });
    }
    let twist_held = (0..grillage.supports.len()).any(|j| !grillage.bearing(j).torsion_free);
    if grillage.girder_count == 1 && !twist_held {
        return Err(FeError::Mechanism {
            direction: Direction::RotationX,
            explanation: "a single girder on torsionally free bearings at every support twists \
                          freely about its axis; hold torsion (a pair of bearings) on at least \
                          one support line"
                .into(),
        });
    }
    Ok(())
}

/// The frame properties of a member of `section` with the grillage's material.
fn frame(grillage: &Grillage, s: &MemberSection, mass: f64, polar: f64) -> FrameProperties {
    let e = grillage.material.elastic_modulus;
    FrameProperties {
        axial_rigidity: e * s.area,
        flexural_rigidity_y: e * s.second_moment_y,
        flexural_rigidity_z: e * s.second_moment_z,
        torsional_rigidity: grillage.material.shear_modulus() * s.torsion_constant,
        mass_per_length: mass,
        polar_inertia_per_length: polar,
    }
}

/// Number of slab strips in each span: round(L / spacing), at least 2; none on one girder.
fn strip_counts(grillage: &Grillage) -> Vec<usize> {
    grillage
        .span_lengths
        .iter()
        .map(|&l| {
            if grillage.girder_count > 1 {
                ((l / grillage.transverse_member_spacing).round() as usize).max(2)
            } else {
                0
            }
        })
        .collect()
}

/// Positions x of the intermediate diaphragms [m]: L·k/(n + 1) in every span.
fn intermediate_positions(grillage: &Grillage, supports: &[f64]) -> Vec<f64> {
    let Some(d) = grillage.intermediate_diaphragms else {
        return Vec::new();
    };
    if grillage.girder_count < 2 {
        return Vec::new();
    }
    let n = d.per_span;
    (0..grillage.span_lengths.len())
        .flat_map(|s| {
            let (a, l) = (supports[s], grillage.span_lengths[s]);
            (1..=n).map(move |k| a + l * k as f64 / (n + 1) as f64)
        })
        .collect()
}

/// The girder lines' properties: (frame properties, E·I_y, mass per length) of each line.
fn girder_lines(grillage: &Grillage) -> Result<Vec<(FrameProperties, f64, f64)>, FeError> {
    let rho = grillage.material.density;
    (0..grillage.girder_count)
        .map(|i| {
            let member = grillage.girder_section(i)?.member_section();
            let share = grillage.deck_share(i);
            let added = grillage.added_mass_per_length(i);
            let mass = rho * member.area + added;
            // Polar mass moment: ρ(I_y + I_z) of the section plus the pavement spread uniformly
            // over the share width (m_a · b²/12).
            let polar = rho * (member.second_moment_y + member.second_moment_z)
                + added * share * share / 12.0;
            let props = frame(grillage, &member, mass, polar);
            Ok((props, props.flexural_rigidity_y, mass))
        })
        .collect()
}

/// Transverse members (kind, grid index, section, mass per length, polar inertia): slab
/// strips inside the spans, diaphragms with the adjacent half strips of slab on the support
/// lines, and the intermediate diaphragms (beside any strip at their position).
fn transverse_members(
    grillage: &Grillage,
    xs: &[f64],
    supports: &[f64],
    support_index: &[usize],
    strips: &[usize],
) -> Vec<(MemberKind, usize, MemberSection, f64, f64)> {
    let mut transverse = Vec::new();
    if grillage.girder_count < 2 {
        return transverse;
    }
    let rho = grillage.material.density;
    let deck = &grillage.deck;
    // A strip along a skewed support line is as wide, normal to itself, as its tributary
    // length along the girders times cos θ.
    let cos = grillage.skew_angle.cos();
    let strip = |width: f64| grillage.girder.transverse_strip(width * cos, deck);
    for s in 0..grillage.span_lengths.len() {
        let width = grillage.span_lengths[s] / strips[s] as f64;
        for k in 1..strips[s] {
            let x = supports[s] + grillage.span_lengths[s] * k as f64 / strips[s] as f64;
            let ix = nearest_index(xs, x);
            transverse.push((MemberKind::SlabStrip, ix, strip(width), 0.0, 0.0));
        }
    }
    let diaphragm_member = |d: &crate::model::Diaphragm| {
        let section = MemberSection::rectangle(d.width, d.depth);
        let mass = rho * section.area;
        let polar = rho * (section.second_moment_y + section.second_moment_z);
        (section, mass, polar)
    };
    let (support_diaphragm, mass, polar) = diaphragm_member(&grillage.diaphragm);
    for (j, &ix) in support_index.iter().enumerate() {
        let half = |s: Option<usize>| {
            s.and_then(|s| {
                grillage
                    .span_lengths
                    .get(s)
                    .map(|l| l / strips[s] as f64 / 2.0)
            })
            .unwrap_or(0.0)
        };
        let slab_width = half(j.checked_sub(1)) + half(Some(j));
        let section = parallel(support_diaphragm, strip(slab_width));
        transverse.push((MemberKind::Diaphragm, ix, section, mass, polar));
    }
    if let Some(d) = &grillage.intermediate_diaphragms {
        let (section, mass, polar) = diaphragm_member(&d.section);
        for x in intermediate_positions(grillage, supports) {
            let ix = nearest_index(xs, x);
            transverse.push((MemberKind::Diaphragm, ix, section, mass, polar));
        }
    }
    transverse
}

/// How much stiffer than a girder's end (4EI/L over its shortest span) the torsional restraint
/// of a bearing pair on a skewed support line is made [-]: the constraint then holds to about
/// 1e-6 of the rotation, while K's condition number grows by no more than this factor.
pub(super) const SKEW_BEARING_PENALTY: f64 = 1e6;

/// The bearings' restraints and springs at the support nodes.
#[derive(Default)]
struct BearingRestraints {
    restrained: Vec<bool>,
    springs: Vec<(usize, f64)>,
    coupled_springs: Vec<(usize, usize, f64)>,
    support_nodes: Vec<(usize, usize, usize)>,
}

/// Adds a rotational spring k about the horizontal unit axis (a_x, a_y) at the node whose
/// rotation DOFs θx, θy are `base + 3`, `base + 4`: the block k a aᵀ.
fn rotational_spring(springs: &mut Vec<(usize, usize, f64)>, base: usize, axis: [f64; 2], k: f64) {
    let dofs = [base + 3, base + 4];
    for (i, &ai) in axis.iter().enumerate() {
        for (j, &aj) in axis.iter().enumerate() {
            if ai * aj != 0.0 {
                springs.push((dofs[i], dofs[j], k * ai * aj));
            }
        }
    }
}

/// Restraints and springs of the bearings, and the support points (support, line, node).
///
/// Each girder's bearing holds w (or is a vertical spring) and, unless torsion is free, the
/// rotation about the horizontal axis normal to its support line, leaving rotation about the
/// support line free (or a spring). On a square deck that axis is the girder's, so θx is
/// restrained exactly; on a skewed line (axis n = (cos θ, −sin θ), support line a = (sin θ,
/// cos θ)) the pair is a stiff spring k n nᵀ, [`SKEW_BEARING_PENALTY`] × 4EI/L, and a
/// rotational stiffness k_r a aᵀ.
/// `line_rigidity`: E·I_y of each girder line [N·m²].
fn bearings(
    grillage: &Grillage,
    support_index: &[usize],
    node_count: usize,
    line_rigidity: &[f64],
) -> BearingRestraints {
    let lines = grillage.girder_count;
    let mut out = BearingRestraints {
        restrained: vec![false; 6 * node_count],
        ..BearingRestraints::default()
    };
    let (sin, cos) = grillage.skew_angle.sin_cos();
    let skewed = grillage.is_skewed();
    let shortest = grillage
        .span_lengths
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    for (j, (&kind, &ix)) in grillage.supports.iter().zip(support_index).enumerate() {
        let bearing = grillage.bearing(j);
        let change = grillage.damage.support_stiffness(j);
        for line in 0..lines {
            let n = ix * lines + line;
            let base = 6 * n;
            out.support_nodes.push((j, line, n));
            // Vertical: rigid, a spring, or as the support change makes it.
            match (change, bearing.vertical_stiffness) {
                (Some(k), _) | (None, Some(k)) if k > 0.0 => out.springs.push((base + 2, k)),
                (Some(_), _) => {}
                (None, _) => out.restrained[base + 2] = true,
            }
            // Torsion: held by the bearing pair unless free or the support is removed.
            let removed = matches!(change, Some(k) if k <= 0.0);
            if !bearing.torsion_free && !removed {
                if skewed {
                    let k = SKEW_BEARING_PENALTY * 4.0 * line_rigidity[line] / shortest;
                    rotational_spring(&mut out.coupled_springs, base, [cos, -sin], k);
                } else {
                    out.restrained[base + 3] = true;
                }
            }
            // A removed support transmits no moment either.
            if bearing.rotational_stiffness > 0.0 && !removed {
                if skewed {
                    let k = bearing.rotational_stiffness;
                    rotational_spring(&mut out.coupled_springs, base, [sin, cos], k);
                } else {
                    out.springs.push((base + 4, bearing.rotational_stiffness));
                }
            }
            if kind == BearingKind::Pinned {
                out.restrained[base] = true;
            }
            if kind == BearingKind::Pinned
                || grillage.lateral_restraint == LateralRestraint::AllSupports
            {
                out.restrained[base + 1] = true;
            }
        }
    }
    out
}

/// The barriers' masses lumped at the edge girders' nodes as (node-DOF, node-DOF, mass)
/// entries, and their total [kg]. A barrier of m per length at lateral offset e from its
/// girder moves with v, with w + e·θx (the rotation θx about the girder's axis lifts a point
/// at +e by e·θx) and with u − e·θz (a yaw θz moves it back by e·θz), so a node of tributary
/// length h carries m h in v and the kinetic-energy blocks m h [1, e; e, e²] in (w, θx) and
/// m h [1, −e; −e, e²] in (u, θz): positive semi-definite, exact for every rigid motion of a
/// point mass at the barrier's position in the deck's plane.
fn barrier_masses(grillage: &Grillage, xs: &[f64]) -> (Vec<(usize, usize, f64)>, f64) {
    let lines = grillage.girder_count;
    let mut entries = Vec::new();
    let mut total = 0.0;
    for (line, mass_per_length, e) in grillage.barrier_loads() {
        for ix in 0..xs.len() {
            let left = if ix > 0 { xs[ix] - xs[ix - 1] } else { 0.0 };
            let right = if ix + 1 < xs.len() {
                xs[ix + 1] - xs[ix]
            } else {
                0.0
            };
            let m = mass_per_length * (left + right) / 2.0;
            total += m;
            let base = 6 * (ix * lines + line);
            entries.push((base + 1, base + 1, m));
            for (translation, rotation, offset) in [(base + 2, base + 3, e), (base, base + 5, -e)] {
                entries.push((translation, translation, m));
                entries.push((translation, rotation, m * offset));
                entries.push((rotation, translation, m * offset));
                entries.push((rotation, rotation, m * offset * offset));
            }
        }
    }
    (entries, total)
}

/// The mesh of a grillage (the paper §4.1, Fig. 7, with the additions of [`Grillage`]).
pub(super) fn grillage_mesh(
    model: &BridgeModel,
    grillage: &Grillage,
    options: &MeshOptions,
) -> Result<Mesh, FeError> {
    check_grillage_restraint(grillage)?;
    let supports = model.support_positions();
    let lines = grillage.girder_count;
    check_requests(options, model.length(), lines, false)?;
    if grillage.is_skewed() {
        if let Some(request) = options
            .stations
            .iter()
            .find(|r| r.target == StationTarget::Section)
        {
            return Err(FeError::SkewedSection {
                name: request.name_or_default(),
            });
        }
    }
    let strips = strip_counts(grillage);
    let mut extra = extra_points(model, options);
    extra.extend(intermediate_positions(grillage, &supports));
    let Grid {
        xs,
        support_index,
        extra_index: mut requested,
    } = longitudinal_grid(&supports, options, &strips, &extra)?;
    requested.truncate(options.stations.len());
    let girder_factors = girder_factors(&grillage.damage, &xs, lines)?;
    let positions = grillage.girder_positions();
    let offsets = grillage.line_offsets();
    let girders = girder_lines(grillage)?;
    let node = |ix: usize, line: usize| ix * lines + line;
    let mut elements = Vec::with_capacity(xs.len() * lines * 2);
    let mut total_mass = 0.0;
    for ix in 0..xs.len() - 1 {
        let h = xs[ix + 1] - xs[ix];
        for (line, (props, _, _)) in girders.iter().enumerate() {
            total_mass += props.mass_per_length * h;
            elements.push(MeshElement {
                kind: MemberKind::Girder,
                nodes: [node(ix, line), node(ix + 1, line)],
                length: h,
                data: ElementData::Frame {
                    properties: scale_stiffness(*props, girder_factors[ix * lines + line]),
                    direction: [1.0, 0.0],
                },
            });
        }
    }
    for (kind, ix, section, mass, polar) in
        transverse_members(grillage, &xs, &supports, &support_index, &strips)
    {
        let props = frame(grillage, &section, mass, polar);
        for line in 0..lines - 1 {
            // Along the support lines' skew: (Δx, Δy) from one girder's node to the next.
            let (dx, dy) = (
                offsets[line + 1] - offsets[line],
                positions[line + 1] - positions[line],
            );
            let h = dx.hypot(dy);
            total_mass += mass * h;
            elements.push(MeshElement {
                kind,
                nodes: [node(ix, line), node(ix, line + 1)],
                length: h,
                data: ElementData::Frame {
                    properties: props,
                    direction: [dx / h, dy / h],
                },
            });
        }
    }
    let line_rigidity: Vec<f64> = girders.iter().map(|g| g.1).collect();
    let BearingRestraints {
        restrained,
        springs,
        coupled_springs,
        support_nodes,
    } = bearings(grillage, &support_index, xs.len() * lines, &line_rigidity);
    let (nodal_masses, barrier_mass) = barrier_masses(grillage, &xs);
    total_mass += barrier_mass;
    let span_count = supports.len() - 1;
    let mid_spans = (0..span_count)
        .map(|s| nearest_index(&xs, (supports[s] + supports[s + 1]) / 2.0))
        .collect();
    Ok(Mesh {
        dofs_per_node: 6,
        xs,
        line_positions: positions,
        line_offsets: offsets,
        line_rigidity,
        girder_factors,
        line_mass: girders.iter().map(|g| g.2).collect(),
        elements,
        restrained,
        springs,
        coupled_springs,
        nodal_masses,
        support_nodes,
        interior_supports: support_index[1..span_count].to_vec(),
        mid_spans,
        requested,
        total_mass,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_skewed_bearing_pair_resists_rotation_across_its_line_and_none_along_it() {
        // Reference: the pair lies along the support line a = (sin θ, cos θ); a rotation about
        // a lifts neither bearing (zero energy), one about n = (cos θ, −sin θ) is resisted with
        // the full k. A wrong sign inside n would give both rotations energy k sin²2θ-like.
        let theta: f64 = 30f64.to_radians();
        let (sin, cos) = theta.sin_cos();
        let mut springs = Vec::new();
        rotational_spring(&mut springs, 0, [cos, -sin], 2.0);
        let energy = |rotation: [f64; 2]| -> f64 {
            springs
                .iter()
                .map(|&(i, j, k)| k * rotation[i - 3] * rotation[j - 3])
                .sum()
        };
        assert!(energy([sin, cos]).abs() < 1e-15);
        assert!((energy([cos, -sin]) - 2.0).abs() < 1e-15);
    }
}
