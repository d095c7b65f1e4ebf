//! `discretise`: from a [`BridgeModel`] to the sparse FE model, its deck and its stations.
//!
//! Nodes lie on a longitudinal grid shared by all girder lines; the grid contains every support,
//! every mid-span, every transverse-member position and every requested station, so that every
//! station is a node and its moment can be read from element end forces. Each interval between
//! those points is cut into equal elements no longer than the target length.
//!
//! FE nodes are numbered x-major (all girders at one x, then the next x), which keeps the
//! stiffness banded; deck nodes are numbered line-major, as [`DeckGeometry`] requires.

use serde::{Deserialize, Serialize};

use super::damage::{girder_factors, holds_vertically};
use super::element::{
    beam_mass, beam_stiffness, frame_local, horizontal_rotation, to_global, FrameProperties,
};
use super::error::FeError;
use super::{
    DeckNodeDofs, Direction, FeModel, SparseRow, Station, StationFunctional, StationTarget,
};
use crate::deck::{DeckGeometry, DeckLine};
use crate::linalg::SparseMatrix;
use crate::model::{BridgeModel, ContinuousBeam, MemberSection, ModelError, SupportKind};

mod grillage;
mod plan;

pub use plan::{deck_plan, DeckPlan, PlanMember};

/// Most nodes a mesh may have (a guard against absurd element lengths) [-].
pub const MAX_NODE_COUNT: usize = 2_000_000;

/// Most elements in one span [-]. K's condition number grows as (L/h)⁴ for elements of length
/// h in a span L, so a finer mesh loses accuracy to round-off: on a 25 m simply supported beam,
/// 2000 elements carry a round-off error of 2·10⁻⁴ in the static mid-span deflection and 10⁻⁴
/// in ω₁, 4000 elements 10⁻³ and 5·10⁻⁴ (exact at the nodes and 10⁻¹⁴ in ω₁ from the
/// discretisation alone). The lowest eigenvalue, ω₁² ≈ c (h/L)⁴ · mean diag K / mean diag M
/// (c ≈ 3 simply supported, c ≈ 0.4 for a cantilever), also stays above the level
/// `fe::RIGID_BODY_LEVEL` = 10⁻¹⁴ of that ratio at which an eigenvalue is round-off (a
/// mechanism) up to 2000 elements: 2.4·10⁻¹⁴ for a cantilever. Such a mesh resolves modes far
/// beyond any vehicle's reach.
pub const MAX_ELEMENTS_PER_SPAN: usize = 2000;

/// A station the user asks for, in addition to (or instead of) the default ones.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StationRequest {
    /// Name; default `x<position>_g<girder number>` or `x<position>_section`.
    pub name: Option<String>,
    /// Longitudinal position x [m], 0 ≤ x ≤ bridge length.
    pub position: f64,
    /// Girder (deck line index, 0 = rightmost) or the whole section.
    pub target: StationTarget,
}

/// How to mesh a bridge model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshOptions {
    /// Target element length along the girders [m]; default 1.0.
    pub element_length: f64,
    /// If set, each span is cut into this many elements instead (rounded up so that the
    /// mid-span and the transverse members fall on nodes); default none.
    pub elements_per_span: Option<usize>,
    /// Whether to create the default stations (mid-span of every span and every interior
    /// support, for each girder and for the section); default true.
    pub default_stations: bool,
    /// Additional stations; default none.
    pub stations: Vec<StationRequest>,
}

impl Default for MeshOptions {
    fn default() -> Self {
        MeshOptions {
            element_length: 1.0,
            elements_per_span: None,
            default_stations: true,
            stations: Vec::new(),
        }
    }
}

/// The force and moment that one support exerts on the bridge, in global axes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SupportReaction {
    /// Support (line) index, 0 at x = 0.
    pub support: usize,
    /// Girder index (0 for a beam).
    pub girder: usize,
    /// Position (x, y) [m].
    pub position: [f64; 2],
    /// Force (F_x, F_y, F_z) [N] on the bridge; F_z > 0 upwards.
    pub force: [f64; 3],
    /// Moment (M_x, M_y, M_z) [N·m] on the bridge.
    pub moment: [f64; 3],
}

#[derive(Debug, Clone, Copy)]
enum ElementData {
    /// 2D Hermite beam: EI [N·m²], m̄ [kg/m].
    Beam { flexural_rigidity: f64, mass: f64 },
    /// 3D frame member along the horizontal unit direction.
    Frame {
        properties: FrameProperties,
        direction: [f64; 2],
    },
}

/// What a mesh member models.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MemberKind {
    /// An element of a girder (or of the beam).
    Girder,
    /// A transverse strip of deck slab.
    SlabStrip,
    /// A diaphragm (over a support, with its half strips of slab, or inside a span).
    Diaphragm,
}

#[derive(Debug, Clone)]
struct MeshElement {
    kind: MemberKind,
    nodes: [usize; 2],
    length: f64,
    data: ElementData,
}

/// The mesh before reduction to free DOFs.
pub(super) struct Mesh {
    pub(super) dofs_per_node: usize,
    /// Longitudinal grid [m].
    pub(super) xs: Vec<f64>,
    /// Lateral positions of the deck lines (girders) [m], ascending.
    pub(super) line_positions: Vec<f64>,
    /// Longitudinal offset of each line's nodes [m]: a node at grid point ix of line l lies at
    /// x = xs[ix] + line_offsets[l] (non-zero on a skewed grillage only).
    pub(super) line_offsets: Vec<f64>,
    /// Vertical flexural rigidity of each line's intact girder [N·m²].
    pub(super) line_rigidity: Vec<f64>,
    /// Factor on E of each girder element, `[ix * lines + line]` (1 where intact).
    pub(super) girder_factors: Vec<f64>,
    /// Mass per length of each line's girder [kg/m] (its vertical-bending consistent mass).
    pub(super) line_mass: Vec<f64>,
    elements: Vec<MeshElement>,
    /// Per node-DOF: restrained?
    pub(super) restrained: Vec<bool>,
    /// (node-DOF, stiffness) springs to ground.
    springs: Vec<(usize, f64)>,
    /// (node-DOF, node-DOF, stiffness) entries of springs to ground that couple two DOFs: the
    /// bearings of a skewed support line, about axes along and across it.
    coupled_springs: Vec<(usize, usize, f64)>,
    /// (node-DOF, node-DOF, mass) lumped masses (the barriers), added to the consistent mass.
    nodal_masses: Vec<(usize, usize, f64)>,
    /// (support index, line, node) of every support point.
    support_nodes: Vec<(usize, usize, usize)>,
    /// Index into `xs` of each interior support.
    interior_supports: Vec<usize>,
    /// Index into `xs` of each mid-span.
    mid_spans: Vec<usize>,
    /// Grid index of each requested station.
    requested: Vec<usize>,
    total_mass: f64,
}

impl Mesh {
    pub(super) fn node(&self, ix: usize, line: usize) -> usize {
        ix * self.line_positions.len() + line
    }

    /// Whether the grillage is skewed (its lines' nodes are offset along x).
    pub(super) fn is_skewed(&self) -> bool {
        self.line_offsets.iter().any(|&o| o != 0.0)
    }

    /// The deck position x of grid point `ix` on `line` [m].
    pub(super) fn node_x(&self, ix: usize, line: usize) -> f64 {
        self.xs[ix] + self.line_offsets[line]
    }

    /// The deck position x of a station at grid point `ix` reading `target` [m]: its girder's
    /// node, or the grid point itself for the whole section (square decks only).
    fn station_x(&self, ix: usize, target: StationTarget) -> f64 {
        match target {
            StationTarget::Girder(g) if g < self.line_offsets.len() => self.node_x(ix, g),
            _ => self.xs[ix],
        }
    }

    /// Node-DOF index of the vertical translation and of the vertical-plane rotation, and the
    /// sign s with dw/dx = s · rotation.
    fn vertical_dofs(&self, node: usize) -> (usize, usize, f64) {
        let base = node * self.dofs_per_node;
        if self.dofs_per_node == 2 {
            (base, base + 1, 1.0)
        } else {
            (base + 2, base + 4, -1.0)
        }
    }

    pub(super) fn direction(&self, dof: usize) -> Direction {
        if self.dofs_per_node == 2 {
            [Direction::TranslationZ, Direction::RotationY][dof % 2]
        } else {
            Direction::ALL[dof % 6]
        }
    }

    /// Global element matrices and their node-DOF indices.
    fn element_matrices(&self, e: &MeshElement) -> (Vec<usize>, Vec<f64>, Vec<f64>) {
        let dpn = self.dofs_per_node;
        let dofs: Vec<usize> = e
            .nodes
            .iter()
            .flat_map(|&n| (0..dpn).map(move |d| n * dpn + d))
            .collect();
        match e.data {
            ElementData::Beam {
                flexural_rigidity,
                mass,
            } => {
                let k = beam_stiffness(flexural_rigidity, e.length);
                let m = beam_mass(mass, e.length);
                (
                    dofs,
                    k.iter().flatten().copied().collect(),
                    m.iter().flatten().copied().collect(),
                )
            }
            ElementData::Frame {
                properties,
                direction,
            } => {
                let (k, m) = frame_local(&properties, e.length);
                let rotation = horizontal_rotation(direction);
                let (k, m) = if direction == [1.0, 0.0] {
                    (k, m)
                } else {
                    (to_global(&k, &rotation), to_global(&m, &rotation))
                };
                (
                    dofs,
                    k.iter().flatten().copied().collect(),
                    m.iter().flatten().copied().collect(),
                )
            }
        }
    }
}

/// The longitudinal grid, the grid index of each support and of each extra point.
struct Grid {
    xs: Vec<f64>,
    support_index: Vec<usize>,
    extra_index: Vec<usize>,
}

/// Longitudinal grid: supports, mid-spans, transverse members and requested stations are nodes;
/// every interval between them is cut into equal elements no longer than the target.
fn longitudinal_grid(
    support_positions: &[f64],
    options: &MeshOptions,
    strip_counts: &[usize],
    extra_points: &[f64],
) -> Result<Grid, FeError> {
    if let Some(n) = options.elements_per_span {
        if n == 0 {
            return Err(FeError::ElementsPerSpan {
                elements_per_span: n,
            });
        }
    } else if !(options.element_length.is_finite() && options.element_length > 0.0) {
        return Err(FeError::ElementLength {
            element_length: options.element_length,
        });
    }
    let span_count = support_positions.len() - 1;
    let target = |span: usize| {
        let length = support_positions[span + 1] - support_positions[span];
        match options.elements_per_span {
            Some(n) => length / n as f64,
            None => options.element_length,
        }
    };
    let estimate: f64 = (0..span_count)
        .map(|s| (support_positions[s + 1] - support_positions[s]) / target(s) + 3.0)
        .sum::<f64>()
        + strip_counts.iter().sum::<usize>() as f64
        + extra_points.len() as f64;
    if estimate > MAX_NODE_COUNT as f64 {
        return Err(FeError::TooManyNodes {
            node_count: estimate.min(usize::MAX as f64) as usize,
            limit: MAX_NODE_COUNT,
        });
    }
    let mut xs = vec![support_positions[0]];
    let mut support_index = vec![0];
    for s in 0..span_count {
        let (a, b) = (support_positions[s], support_positions[s + 1]);
        let length = b - a;
        let mut points: Vec<f64> = vec![a + length / 2.0];
        let strips = strip_counts.get(s).copied().unwrap_or(0);
        for k in 1..strips {
            points.push(a + length * k as f64 / strips as f64);
        }
        points.extend(extra_points.iter().copied().filter(|&x| x > a && x < b));
        points.push(b);
        points.sort_by(f64::total_cmp);
        let tolerance = 1e-9 * length;
        let mut previous = a;
        for &p in &points {
            if p - previous <= tolerance {
                continue;
            }
            let p = if (b - p) <= tolerance { b } else { p };
            let count = ((p - previous) / target(s) - 1e-9).ceil().max(1.0) as usize;
            for i in 1..count {
                xs.push(previous + (p - previous) * i as f64 / count as f64);
            }
            xs.push(p);
            previous = p;
        }
        if *xs.last().unwrap_or(&a) != b {
            xs.push(b);
        }
        support_index.push(xs.len() - 1);
        let elements = support_index[s + 1] - support_index[s];
        if elements > MAX_ELEMENTS_PER_SPAN {
            return Err(FeError::TooFine {
                elements,
                span_length: length,
                limit: MAX_ELEMENTS_PER_SPAN,
            });
        }
    }
    let extra_index = extra_points
        .iter()
        .map(|&x| nearest_index(&xs, x))
        .collect();
    Ok(Grid {
        xs,
        support_index,
        extra_index,
    })
}

/// Sums two sections acting side by side (parallel members): A, I and J add.
fn parallel(a: MemberSection, b: MemberSection) -> MemberSection {
    MemberSection {
        area: a.area + b.area,
        second_moment_y: a.second_moment_y + b.second_moment_y,
        second_moment_z: a.second_moment_z + b.second_moment_z,
        torsion_constant: a.torsion_constant + b.torsion_constant,
    }
}

fn check_beam_restraint(beam: &ContinuousBeam) -> Result<(), FeError> {
    let vertical = beam
        .supports
        .iter()
        .enumerate()
        .filter(|&(j, s)| {
            let intact = match s {
                SupportKind::Elastic {
                    vertical_stiffness, ..
                } => *vertical_stiffness > 0.0,
                _ => true,
            };
            holds_vertically(&beam.damage, j, intact)
        })
        .count();
    let rotational = beam.supports.iter().any(|s| match s {
        SupportKind::Fixed => true,
        SupportKind::Elastic {
            rotational_stiffness,
            ..
        } => *rotational_stiffness > 0.0,
        _ => false,
    });
    if vertical == 0 {
        return Err(FeError::Mechanism {
            direction: Direction::TranslationZ,
            explanation: "no support restrains vertical translation: every support is elastic \
                          with zero vertical stiffness or removed"
                .into(),
        });
    }
    if vertical == 1 && !rotational {
        return Err(FeError::Mechanism {
            direction: Direction::RotationY,
            explanation: "only one support restrains deflection and none restrains rotation, so \
                          the beam turns freely about it; add a support or make one fixed"
                .into(),
        });
    }
    Ok(())
}

/// The extra grid points: the requested stations first, then the ends of the damage regions.
fn extra_points(model: &BridgeModel, options: &MeshOptions) -> Vec<f64> {
    let mut points: Vec<f64> = options.stations.iter().map(|s| s.position).collect();
    points.extend(model.damage().region_ends(model.length()));
    points
}

fn check_requests(
    options: &MeshOptions,
    length: f64,
    line_count: usize,
    is_beam: bool,
) -> Result<(), FeError> {
    for (i, request) in options.stations.iter().enumerate() {
        let name = request_name(request, i);
        if !(request.position.is_finite() && (0.0..=length).contains(&request.position)) {
            return Err(FeError::StationOffDeck {
                name,
                position: request.position,
                length,
            });
        }
        if let StationTarget::Girder(g) = request.target {
            if g >= line_count && !(is_beam && g == 0) {
                return Err(FeError::NoSuchGirder {
                    name,
                    girder: g,
                    girder_count: line_count,
                });
            }
        }
    }
    Ok(())
}

/// The targets of the default stations: each girder and the section, or the section alone on
/// a deck of one line.
pub(super) fn default_targets(lines: usize, single_line: bool) -> Vec<StationTarget> {
    if single_line {
        vec![StationTarget::Section]
    } else {
        (0..lines)
            .map(StationTarget::Girder)
            .chain([StationTarget::Section])
            .collect()
    }
}

/// The suffix of a default station's name: `g<girder number>` or `section`.
pub(super) fn target_suffix(target: StationTarget) -> String {
    match target {
        StationTarget::Girder(g) => format!("g{}", g + 1),
        StationTarget::Section => "section".to_string(),
    }
}

pub(super) fn request_name(request: &StationRequest, _index: usize) -> String {
    request.name_or_default()
}

impl StationRequest {
    /// The station's name: the one given, or `x<position>_g<girder number>` or
    /// `x<position>_section`.
    pub fn name_or_default(&self) -> String {
        match (&self.name, self.target) {
            (Some(name), _) => name.clone(),
            (None, StationTarget::Girder(g)) => format!("x{}_g{}", self.position, g + 1),
            (None, StationTarget::Section) => format!("x{}_section", self.position),
        }
    }
}

pub(super) fn build_mesh(model: &BridgeModel, options: &MeshOptions) -> Result<Mesh, FeError> {
    model.validate()?;
    let supports = model.support_positions();
    let length = model.length();
    match model {
        // [`discretise`] gives imported matrices to `discretise_imported`: they have no mesh.
        BridgeModel::ImportedMatrices(_) => Err(FeError::Model(ModelError::ImportedMatrices {
            message: "imported matrices are not meshed".into(),
        })),
        BridgeModel::ImportedModes(_) => Err(FeError::Model(ModelError::ImportedMatrices {
            message: "an imported modal basis has no FE model".into(),
        })),
        BridgeModel::ContinuousBeam(beam) => {
            check_beam_restraint(beam)?;
            check_requests(options, length, 1, true)?;
            let extra = extra_points(model, options);
            let Grid {
                xs,
                support_index,
                extra_index: mut requested,
            } = longitudinal_grid(&supports, options, &[], &extra)?;
            requested.truncate(options.stations.len());
            let girder_factors = girder_factors(&beam.damage, &xs, 1)?;
            let node_count = xs.len();
            let mass = beam.section.mass_per_length + beam.added_mass_per_length;
            let elements: Vec<MeshElement> = (0..node_count - 1)
                .map(|i| MeshElement {
                    kind: MemberKind::Girder,
                    nodes: [i, i + 1],
                    length: xs[i + 1] - xs[i],
                    data: ElementData::Beam {
                        flexural_rigidity: girder_factors[i] * beam.section.flexural_rigidity,
                        mass,
                    },
                })
                .collect();
            let mut restrained = vec![false; 2 * node_count];
            let mut springs = Vec::new();
            let mut support_nodes = Vec::new();
            for (j, (support, &ix)) in beam.supports.iter().zip(&support_index).enumerate() {
                support_nodes.push((j, 0, ix));
                match *support {
                    SupportKind::Pinned | SupportKind::Roller => restrained[2 * ix] = true,
                    SupportKind::Fixed => {
                        restrained[2 * ix] = true;
                        restrained[2 * ix + 1] = true;
                    }
                    SupportKind::Elastic {
                        vertical_stiffness,
                        rotational_stiffness,
                    } => {
                        if vertical_stiffness > 0.0 {
                            springs.push((2 * ix, vertical_stiffness));
                        }
                        if rotational_stiffness > 0.0 {
                            springs.push((2 * ix + 1, rotational_stiffness));
                        }
                    }
                }
                if let Some(stiffness) = beam.damage.support_stiffness(j) {
                    restrained[2 * ix] = false;
                    springs.retain(|&(dof, _)| dof != 2 * ix);
                    if stiffness > 0.0 {
                        springs.push((2 * ix, stiffness));
                    }
                }
            }
            let span_count = supports.len() - 1;
            let mid_spans = (0..span_count)
                .map(|s| nearest_index(&xs, (supports[s] + supports[s + 1]) / 2.0))
                .collect();
            Ok(Mesh {
                dofs_per_node: 2,
                total_mass: mass * length,
                xs,
                line_positions: vec![0.0],
                line_offsets: vec![0.0],
                line_rigidity: vec![beam.section.flexural_rigidity],
                girder_factors,
                line_mass: vec![mass],
                elements,
                restrained,
                springs,
                coupled_springs: Vec::new(),
                nodal_masses: Vec::new(),
                support_nodes,
                interior_supports: support_index[1..span_count].to_vec(),
                mid_spans,
                requested,
            })
        }
        BridgeModel::Grillage(grillage) => grillage::grillage_mesh(model, grillage, options),
    }
}

/// Index of the grid point nearest to x (the grid is ascending).
pub(super) fn nearest_index(xs: &[f64], x: f64) -> usize {
    match xs.partition_point(|&p| p < x) {
        0 => 0,
        i if i >= xs.len() => xs.len() - 1,
        i if (x - xs[i - 1]).abs() <= (xs[i] - x).abs() => i - 1,
        i => i,
    }
}

/// Discretises a bridge model (the paper §3–§4.1).
///
/// - Beam: 2 DOF per node (w, φ = dw/dx), Hermite elements with consistent mass
///   m̄h/420·[…]; supports remove restrained DOFs, elastic supports add springs.
/// - Grillage: 3D frame elements, 6 DOF per node, consistent mass including the polar inertia
///   ρ(I_y + I_z) (plus the pavement's); girders, slab strips (massless: the slab's mass is in
///   the girders) and diaphragms; bearings restrain w and θx at every girder on every support,
///   u and v on the pinned line (v on all lines with [`LateralRestraint::AllSupports`](crate::model::LateralRestraint::AllSupports)).
///
/// K and M are assembled sparse from triplets over the free DOFs, in O(number of elements).
/// Stations read deflection from the vertical DOF and the sagging moment from the end forces
/// k_e·u_e of the girder elements either side of the station.
///
/// Errors: an invalid model, bad mesh options, a station off the deck or on a missing girder,
/// or supports that leave a rigid-body motion free ([`FeError::Mechanism`] names it).
pub fn discretise(model: &BridgeModel, options: &MeshOptions) -> Result<FeModel, FeError> {
    if let BridgeModel::ImportedMatrices(imported) = model {
        return super::discretise_imported(imported, options);
    }
    let mesh = build_mesh(model, options)?;
    let (free, dof_directions) = number_free_dofs(&mesh);
    let (stiffness, mass) = assemble_stiffness_and_mass(&mesh, &free, dof_directions.len());
    let (deck, deck_dofs) = deck_geometry_and_dofs(model, &mesh, &free);
    let (stations, station_points) = place_stations(model, &mesh, options);
    let lines = mesh.line_positions.len();
    let station_functionals: Vec<StationFunctional> = station_points
        .iter()
        .map(|&(ix, target)| match target {
            StationTarget::Girder(g) => girder_line_functional(&mesh, &free, ix, g),
            StationTarget::Section => {
                let mut sum = StationFunctional::default();
                for line in 0..lines {
                    sum.add_line(
                        girder_line_functional(&mesh, &free, ix, line),
                        1.0 / lines as f64,
                    );
                }
                sum
            }
        })
        .collect();
    let stations = mark_support_stations(&mesh, stations, &station_points);

    Ok(FeModel {
        stiffness,
        mass,
        dof_directions,
        deck,
        deck_dofs,
        stations,
        station_functionals,
        damping_ratio: model.damping_ratio(),
        mode_damping: model.mode_damping().cloned(),
        total_mass: mesh.total_mass,
        has_station_forces: true,
    })
}

/// The free-DOF numbering, x-major: for every mesh DOF its free index (`usize::MAX` where
/// restrained), and the direction of every free DOF in order.
fn number_free_dofs(mesh: &Mesh) -> (Vec<usize>, Vec<Direction>) {
    let mut free = vec![usize::MAX; mesh.restrained.len()];
    let mut dof_directions = Vec::new();
    for (dof, &fixed) in mesh.restrained.iter().enumerate() {
        if !fixed {
            free[dof] = dof_directions.len();
            dof_directions.push(mesh.direction(dof));
        }
    }
    (free, dof_directions)
}

/// The global stiffness K and consistent mass M over the `size` free DOFs, assembled sparse
/// from triplets: K = Σ_e k_e + springs (grounded and coupled), M = Σ_e m_e + nodal masses,
/// restrained DOFs dropped.
fn assemble_stiffness_and_mass(
    mesh: &Mesh,
    free: &[usize],
    size: usize,
) -> (SparseMatrix, SparseMatrix) {
    let dpn = mesh.dofs_per_node;
    let per_element = (2 * dpn) * (2 * dpn);
    let mut k_triplets = Vec::with_capacity(mesh.elements.len() * per_element + 16);
    let mut m_triplets = Vec::with_capacity(mesh.elements.len() * per_element);
    for element in &mesh.elements {
        let (dofs, k, m) = mesh.element_matrices(element);
        let n = dofs.len();
        for (i, &di) in dofs.iter().enumerate() {
            let fi = free[di];
            if fi == usize::MAX {
                continue;
            }
            for (j, &dj) in dofs.iter().enumerate() {
                let fj = free[dj];
                if fj == usize::MAX {
                    continue;
                }
                if k[i * n + j] != 0.0 {
                    k_triplets.push((fi, fj, k[i * n + j]));
                }
                if m[i * n + j] != 0.0 {
                    m_triplets.push((fi, fj, m[i * n + j]));
                }
            }
        }
    }
    for &(dof, stiffness) in &mesh.springs {
        k_triplets.push((free[dof], free[dof], stiffness));
    }
    for &(i, j, stiffness) in &mesh.coupled_springs {
        if free[i] != usize::MAX && free[j] != usize::MAX {
            k_triplets.push((free[i], free[j], stiffness));
        }
    }
    for &(i, j, value) in &mesh.nodal_masses {
        if free[i] != usize::MAX && free[j] != usize::MAX {
            m_triplets.push((free[i], free[j], value));
        }
    }
    let stiffness = SparseMatrix::from_triplets(size, &k_triplets);
    drop(k_triplets);
    let mass = SparseMatrix::from_triplets(size, &m_triplets);
    drop(m_triplets);
    (stiffness, mass)
}

/// The row over the free DOFs that reads `coefficient` × u(`dof`): empty when `dof` is
/// restrained.
fn free_dof_row(free: &[usize], dof: usize, coefficient: f64) -> SparseRow {
    if free[dof] == usize::MAX {
        Vec::new()
    } else {
        vec![(free[dof], coefficient)]
    }
}

/// The deck geometry (one line per girder, line-major node numbering) and, per deck node, the
/// rows reading its deflection w and slope dw/dx from the free DOFs.
fn deck_geometry_and_dofs(
    model: &BridgeModel,
    mesh: &Mesh,
    free: &[usize],
) -> (DeckGeometry, Vec<DeckNodeDofs>) {
    let nx = mesh.xs.len();
    let lines = mesh.line_positions.len();
    let deck = DeckGeometry {
        lines: mesh
            .line_positions
            .iter()
            .enumerate()
            .map(|(line, &y)| DeckLine {
                lateral_position: y,
                node_positions: (0..nx).map(|ix| mesh.node_x(ix, line)).collect(),
                first_node: line * nx,
            })
            .collect(),
        length: model.deck_length(),
    };
    let mut deck_dofs = Vec::with_capacity(lines * nx);
    for line in 0..lines {
        for ix in 0..nx {
            let (w, r, sign) = mesh.vertical_dofs(mesh.node(ix, line));
            deck_dofs.push(DeckNodeDofs {
                deflection: free_dof_row(free, w, 1.0),
                slope: free_dof_row(free, r, sign),
            });
        }
    }
    (deck, deck_dofs)
}

/// The stations (the default ones at every mid-span and interior support when asked for, then
/// the requested ones) and the grid point and target each reads. Every station's `support` is
/// false here; [`mark_support_stations`] sets it.
fn place_stations(
    model: &BridgeModel,
    mesh: &Mesh,
    options: &MeshOptions,
) -> (Vec<Station>, Vec<(usize, StationTarget)>) {
    let lines = mesh.line_positions.len();
    let is_beam = mesh.dofs_per_node == 2;
    let mut stations = Vec::new();
    let mut station_points: Vec<(usize, StationTarget)> = Vec::new();
    let mut targets = default_targets(lines, is_beam);
    if mesh.is_skewed() {
        // A skewed deck has no section at one x through every girder's station: each girder
        // is read at its own mid-span and supports.
        targets.retain(|t| *t != StationTarget::Section);
    }
    let suffix = target_suffix;
    let length = model.length();
    let over_support = |x: f64| {
        mesh.interior_supports
            .iter()
            .any(|&ix| (mesh.xs[ix] - x).abs() <= 1e-9 * length)
    };
    if options.default_stations {
        for (s, &ix) in mesh.mid_spans.iter().enumerate() {
            for &t in &targets {
                stations.push(Station {
                    name: format!("span{}_mid_{}", s + 1, suffix(t)),
                    position: mesh.station_x(ix, t),
                    target: t,
                    over_support: false,
                    support: false,
                });
                station_points.push((ix, t));
            }
        }
        for (j, &ix) in mesh.interior_supports.iter().enumerate() {
            for &t in &targets {
                stations.push(Station {
                    name: format!("support{}_{}", j + 2, suffix(t)),
                    position: mesh.station_x(ix, t),
                    target: t,
                    over_support: true,
                    support: false,
                });
                station_points.push((ix, t));
            }
        }
    }
    for (i, (request, &ix)) in options.stations.iter().zip(&mesh.requested).enumerate() {
        let target = match request.target {
            StationTarget::Girder(_) if is_beam => StationTarget::Section,
            t => t,
        };
        stations.push(Station {
            name: request_name(request, i),
            position: mesh.station_x(ix, target),
            target,
            over_support: over_support(mesh.xs[ix]),
            support: false,
        });
        station_points.push((ix, target));
    }
    (stations, station_points)
}

/// The stations with `support` set where any girder line the station reads is held vertically
/// at its grid point.
fn mark_support_stations(
    mesh: &Mesh,
    stations: Vec<Station>,
    station_points: &[(usize, StationTarget)],
) -> Vec<Station> {
    let lines = mesh.line_positions.len();
    stations
        .into_iter()
        .zip(station_points)
        .map(|(station, &(ix, target))| {
            let lines_read: Vec<usize> = match target {
                StationTarget::Girder(g) => vec![g],
                StationTarget::Section => (0..lines).collect(),
            };
            let support = lines_read
                .iter()
                .any(|&line| is_vertical_support(mesh, mesh.node(ix, line)));
            Station { support, ..station }
        })
        .collect()
}

/// The rows (stiffness, consistent mass) of end force `row_index` of the girder element of
/// `line` from grid index a to a + 1, times `factor`: f_i = factor · Σ_j k_ij h_j (and m_ij),
/// with the Hermite variables h_j = s_j · u(dof_j) (s_j the slope sign of a rotation).
fn girder_end_force_rows(
    mesh: &Mesh,
    free: &[usize],
    line: usize,
    a: usize,
    row_index: usize,
    factor: f64,
) -> (SparseRow, SparseRow) {
    let lines = mesh.line_positions.len();
    let h = mesh.xs[a + 1] - mesh.xs[a];
    let rigidity = mesh.line_rigidity[line] * mesh.girder_factors[a * lines + line];
    let k = beam_stiffness(rigidity, h);
    let m = beam_mass(mesh.line_mass[line], h);
    let (w1, r1, s) = mesh.vertical_dofs(mesh.node(a, line));
    let (w2, r2, _) = mesh.vertical_dofs(mesh.node(a + 1, line));
    let mut stiffness_row = SparseRow::new();
    let mut mass_row = SparseRow::new();
    for (j, (dof, sign)) in [(w1, 1.0), (r1, s), (w2, 1.0), (r2, s)]
        .into_iter()
        .enumerate()
    {
        if free[dof] != usize::MAX {
            stiffness_row.push((free[dof], factor * k[row_index][j] * sign));
            mass_row.push((free[dof], factor * m[row_index][j] * sign));
        }
    }
    (stiffness_row, mass_row)
}

/// One end force of girder `line` at grid index `ix` read from either side: the rows of the
/// element left of the station (its row `left_row`, times `left_factor`) and of the one right
/// of it (`right_row`, `right_factor`). At a deck end the missing side reads the node's
/// equilibrium, `end_side` (None where the node is held: then both sides read the one element
/// there, exact for loads outside it).
fn end_force_rows_either_side(
    mesh: &Mesh,
    free: &[usize],
    ix: usize,
    line: usize,
    (left_row, left_factor): (usize, f64),
    (right_row, right_factor): (usize, f64),
    end_side: Option<(SparseRow, SparseRow)>,
) -> ((SparseRow, SparseRow), (SparseRow, SparseRow)) {
    let nx = mesh.xs.len();
    let left =
        (ix > 0).then(|| girder_end_force_rows(mesh, free, line, ix - 1, left_row, left_factor));
    let right =
        (ix + 1 < nx).then(|| girder_end_force_rows(mesh, free, line, ix, right_row, right_factor));
    match (left, right, end_side) {
        (Some(l), Some(r), _) => (l, r),
        (Some(l), None, Some(end)) => (l, end),
        (None, Some(r), Some(end)) => (end, r),
        (Some(l), None, None) => (l.clone(), l),
        (None, Some(r), None) => (r.clone(), r),
        (None, None, _) => Default::default(),
    }
}

/// The rows of a girder's end force at node-DOF `dof` of a deck end from the equilibrium of
/// the node, when that DOF is free (no restraint, no spring): the other members' end forces,
/// Σ f(others) times `sign` at the start and −`sign` at the far end. None away from the ends
/// or where the DOF is held.
fn free_end_equilibrium_rows(
    mesh: &Mesh,
    free: &[usize],
    ix: usize,
    line: usize,
    dof: usize,
    sign: f64,
) -> Option<(SparseRow, SparseRow)> {
    let at_start = ix == 0;
    let held = mesh.restrained[dof]
        || mesh.springs.iter().any(|&(d, _)| d == dof)
        || mesh.coupled_springs.iter().any(|&(i, _, _)| i == dof);
    let at_end = at_start || ix + 1 == mesh.xs.len();
    let sign = if at_start { sign } else { -sign };
    (at_end && !held).then(|| other_members_rows(mesh, free, ix, line, dof, sign))
}

/// The functionals of one girder line at grid index ix: its deflection, the sagging moment and
/// the shear from the elements either side, with their consistent-mass parts, and the support
/// reaction.
///
/// Virtual work of a Hermite element [0, h] with M = EI w'' and V = dM/dx: the force conjugate
/// to w'(h) is +M(h), to w(h) is −V(h), to w'(0) is −M(0), to w(0) is +V(0). Left element:
/// M = f_φ2, V = −f_w2; right element: M = −f_φ1, V = +f_w1.
///
/// At a deck end whose rotation is free (no restraint, no spring), the node's equilibrium
/// f_φ(girder) + Σ f_φ(other members) = 0 gives the girder's end moment exactly from the
/// members that meet it there (slab strips, diaphragms: never loaded by a wheel, so k_e u_e is
/// exact for them): M(0) = Σ f_φ(others), M(L) = −Σ f_φ(others); zero on a beam. Likewise the
/// shear at an end without a vertical support, V(0) = −Σ f_w(others), V(L) = +Σ f_w(others).
fn girder_line_functional(
    mesh: &Mesh,
    free: &[usize],
    ix: usize,
    line: usize,
) -> StationFunctional {
    let (w, _, _) = mesh.vertical_dofs(mesh.node(ix, line));
    let node = mesh.node(ix, line);
    let (w_dof, r_dof, slope_sign) = mesh.vertical_dofs(node);
    let ((moment_left, moment_left_mass), (moment_right, moment_right_mass)) =
        end_force_rows_either_side(
            mesh,
            free,
            ix,
            line,
            (3, 1.0),
            (1, -1.0),
            free_end_equilibrium_rows(mesh, free, ix, line, r_dof, slope_sign),
        );
    let ((shear_left, shear_left_mass), (shear_right, shear_right_mass)) =
        end_force_rows_either_side(
            mesh,
            free,
            ix,
            line,
            (2, -1.0),
            (0, 1.0),
            free_end_equilibrium_rows(mesh, free, ix, line, w_dof, -1.0),
        );
    let (reaction, reaction_mass, reaction_nodes) = support_rows(mesh, free, ix, line);
    StationFunctional {
        deflection: free_dof_row(free, w, 1.0),
        moment_left,
        moment_right,
        moment_left_mass,
        moment_right_mass,
        shear_left,
        shear_right,
        shear_left_mass,
        shear_right_mass,
        reaction,
        reaction_mass,
        reaction_nodes,
    }
}

/// The rows (stiffness, consistent mass) of the end forces at node-DOF `dof` of grid point
/// (`ix`, `line`) of every member meeting there other than the girder elements of `line`,
/// summed and scaled by `scale`.
fn other_members_rows(
    mesh: &Mesh,
    free: &[usize],
    ix: usize,
    line: usize,
    dof: usize,
    scale: f64,
) -> (SparseRow, SparseRow) {
    let node = mesh.node(ix, line);
    let girder_neighbours = [ix.checked_sub(1), Some(ix + 1)]
        .map(|j| j.filter(|&j| j < mesh.xs.len()).map(|j| mesh.node(j, line)));
    node_dof_rows(mesh, free, node, dof, scale, |element| {
        let other = element.nodes[0] + element.nodes[1] - node;
        !girder_neighbours.contains(&Some(other))
    })
}

/// The rows (stiffness, consistent mass) over the free DOFs of the end forces at node-DOF `dof`
/// of every element at `node` that `include` accepts, and of the node's lumped masses, summed
/// and scaled by `scale`.
fn node_dof_rows(
    mesh: &Mesh,
    free: &[usize],
    node: usize,
    dof: usize,
    scale: f64,
    include: impl Fn(&MeshElement) -> bool,
) -> (SparseRow, SparseRow) {
    let mut stiffness_row = SparseRow::new();
    let mut mass_row = SparseRow::new();
    let at_node = |e: &&MeshElement| e.nodes.contains(&node) && include(e);
    for element in mesh.elements.iter().filter(at_node) {
        let (dofs, k, m) = mesh.element_matrices(element);
        let n = dofs.len();
        let Some(i) = dofs.iter().position(|&d| d == dof) else {
            continue;
        };
        for (j, &column) in dofs.iter().enumerate() {
            if free[column] == usize::MAX {
                continue;
            }
            if k[i * n + j] != 0.0 {
                stiffness_row.push((free[column], scale * k[i * n + j]));
            }
            if m[i * n + j] != 0.0 {
                mass_row.push((free[column], scale * m[i * n + j]));
            }
        }
    }
    // The node's lumped masses (the barriers) act at the node like another member.
    for &(row, column, value) in &mesh.nodal_masses {
        if row == dof && free[column] != usize::MAX {
            mass_row.push((free[column], scale * value));
        }
    }
    (stiffness_row, mass_row)
}

/// Whether a support bears node `node` vertically: its vertical DOF restrained, or held by a
/// spring (an elastic or changed support).
fn is_vertical_support(mesh: &Mesh, node: usize) -> bool {
    let (w, _, _) = mesh.vertical_dofs(node);
    mesh.restrained[w] || mesh.springs.iter().any(|&(dof, _)| dof == w)
}

/// The reaction rows of the support under girder line `line` at grid index `ix` (all empty
/// where there is none): (stiffness row, consistent-mass row, deck nodes whose load share goes
/// straight into the bearing).
///
/// At a restrained vertical DOF c, K u + M ü = f + r gives the reaction r_c = K_cf u_f +
/// M_cf ü_f − f_c: the rows K_cf and M_cf of every element that holds c (girders, slab strips,
/// diaphragms), over the free DOFs. A downward unit load's restrained component is
/// f_c = −N_c (the Hermite shape function of c), so the deck node at c is listed: its share
/// of a load enters the reaction directly. At a spring k the reaction is −k·w (upward when
/// the deck moves down).
fn support_rows(
    mesh: &Mesh,
    free: &[usize],
    ix: usize,
    line: usize,
) -> (SparseRow, SparseRow, Vec<usize>) {
    let node = mesh.node(ix, line);
    let (w, _, _) = mesh.vertical_dofs(node);
    let (mut stiffness_row, mass_row, nodes) = if mesh.restrained[w] {
        let (k, m) = node_dof_rows(mesh, free, node, w, 1.0, |_| true);
        (k, m, vec![line * mesh.xs.len() + ix])
    } else {
        Default::default()
    };
    for &(dof, stiffness) in mesh.springs.iter().filter(|&&(dof, _)| dof == w) {
        stiffness_row.push((free[dof], -stiffness));
    }
    (stiffness_row, mass_row, nodes)
}

/// The forces and moments that the supports exert on the bridge under the free displacements
/// `displacements` of `discretise(model, options)` (same model and options), from the element
/// end forces k_e·u_e at the restrained DOFs and the spring forces −k·u of elastic supports.
/// Under static loads they balance the applied loads.
pub fn support_reactions(
    model: &BridgeModel,
    options: &MeshOptions,
    displacements: &[f64],
) -> Result<Vec<SupportReaction>, FeError> {
    let mesh = build_mesh(model, options)?;
    let dpn = mesh.dofs_per_node;
    let mut free = vec![usize::MAX; mesh.restrained.len()];
    let mut count = 0;
    for (dof, &fixed) in mesh.restrained.iter().enumerate() {
        if !fixed {
            free[dof] = count;
            count += 1;
        }
    }
    if displacements.len() != count {
        return Err(FeError::DisplacementCount {
            expected: count,
            got: displacements.len(),
        });
    }
    let u = |dof: usize| {
        if free[dof] == usize::MAX {
            0.0
        } else {
            displacements[free[dof]]
        }
    };
    let mut internal = vec![0.0; mesh.restrained.len()];
    for element in &mesh.elements {
        let (dofs, k, _) = mesh.element_matrices(element);
        let n = dofs.len();
        for i in 0..n {
            internal[dofs[i]] += (0..n).map(|j| k[i * n + j] * u(dofs[j])).sum::<f64>();
        }
    }
    let mut reaction = vec![0.0; mesh.restrained.len()];
    for (dof, &fixed) in mesh.restrained.iter().enumerate() {
        if fixed {
            reaction[dof] = internal[dof];
        }
    }
    for &(dof, stiffness) in &mesh.springs {
        reaction[dof] -= stiffness * u(dof);
    }
    for &(i, j, stiffness) in &mesh.coupled_springs {
        reaction[i] -= stiffness * u(j);
    }
    Ok(mesh
        .support_nodes
        .iter()
        .map(|&(support, line, node)| {
            let base = node * dpn;
            let (force, moment) = if dpn == 2 {
                // Beam: the rotation DOF is φ = dw/dx = −θy, so M_y = −R_φ.
                ([0.0, 0.0, reaction[base]], [0.0, -reaction[base + 1], 0.0])
            } else {
                (
                    [reaction[base], reaction[base + 1], reaction[base + 2]],
                    [reaction[base + 3], reaction[base + 4], reaction[base + 5]],
                )
            };
            SupportReaction {
                support,
                girder: line,
                position: [
                    mesh.node_x(node / mesh.line_positions.len(), line),
                    mesh.line_positions[line],
                ],
                force,
                moment,
            }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{paper_bridge, BeamSection};

    #[test]
    fn the_grid_holds_supports_mid_spans_and_extra_points_with_elements_no_longer_than_asked() {
        let supports = [0.0, 20.0, 45.0];
        let options = MeshOptions {
            element_length: 1.5,
            ..MeshOptions::default()
        };
        let grid = longitudinal_grid(&supports, &options, &[4, 5], &[7.77, 45.0]).unwrap();
        let xs = &grid.xs;
        for x in [0.0, 10.0, 20.0, 32.5, 45.0, 7.77, 5.0, 15.0, 40.0] {
            assert!(xs.iter().any(|&p| (p - x).abs() < 1e-9), "{x} missing");
        }
        assert!(xs
            .windows(2)
            .all(|w| w[1] > w[0] && w[1] - w[0] <= 1.5 + 1e-9));
        assert_eq!(
            grid.support_index
                .iter()
                .map(|&i| xs[i])
                .collect::<Vec<_>>(),
            supports
        );
        assert_eq!(xs[grid.extra_index[1]], 45.0);
    }

    #[test]
    fn absurd_mesh_options_are_rejected_before_allocating() {
        let model = paper_bridge(2, 20.0);
        let tiny = MeshOptions {
            element_length: 1e-6,
            ..MeshOptions::default()
        };
        assert!(matches!(
            discretise(&model, &tiny),
            Err(FeError::TooManyNodes { .. })
        ));
        // 20 m / 0.009 m: about 2223 elements in a span (the split at the mid-span and the
        // transverse members adds a few), more than double precision resolves.
        let fine = MeshOptions {
            element_length: 0.009,
            ..MeshOptions::default()
        };
        match discretise(&model, &fine) {
            Err(FeError::TooFine {
                elements, limit, ..
            }) => assert!(limit == MAX_ELEMENTS_PER_SPAN && (2223..2240).contains(&elements)),
            other => panic!("expected a mesh too fine, got {other:?}"),
        }
        let zero = MeshOptions {
            element_length: 0.0,
            ..MeshOptions::default()
        };
        assert!(matches!(
            discretise(&model, &zero),
            Err(FeError::ElementLength { .. })
        ));
        let none = MeshOptions {
            elements_per_span: Some(0),
            ..MeshOptions::default()
        };
        assert!(matches!(
            discretise(&model, &none),
            Err(FeError::ElementsPerSpan { .. })
        ));
    }

    #[test]
    fn a_beam_deck_is_one_line_at_the_centreline_with_slope_rows_on_the_rotation() {
        let beam = ContinuousBeam::pinned(
            vec![10.0, 12.0],
            BeamSection {
                flexural_rigidity: 1e9,
                mass_per_length: 1000.0,
            },
        );
        let fe = discretise(&BridgeModel::ContinuousBeam(beam), &MeshOptions::default()).unwrap();
        assert_eq!(fe.deck.lines.len(), 1);
        assert_eq!(fe.deck.lines[0].lateral_position, 0.0);
        assert_eq!(fe.deck.length, 22.0);
        // Supported nodes have no deflection row; every node has a slope row with coefficient 1.
        assert!(fe.deck_dofs[0].deflection.is_empty());
        assert!(fe
            .deck_dofs
            .iter()
            .all(|d| d.slope.len() == 1 && d.slope[0].1 == 1.0));
        // 3 supports restrain w: 2 DOF per node minus 3.
        assert_eq!(fe.dof_count(), 2 * fe.deck.node_count() - 3);
        assert!((fe.total_mass - 22_000.0).abs() < 1e-9);
        let names: Vec<&str> = fe.stations.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(
            names,
            ["span1_mid_section", "span2_mid_section", "support2_section"]
        );
    }

    #[test]
    fn the_unconstrained_consistent_mass_carries_the_total_mass_in_every_direction() {
        // Reference: a consistent mass matrix reproduces the member mass under a rigid
        // translation, 1_dᵀ M 1_d = Σ m̄h, in x, y and z alike (members along x and along y).
        let model = paper_bridge(2, 20.0);
        let mesh = build_mesh(&model, &MeshOptions::default()).unwrap();
        for direction in 0..3 {
            let mut sum = 0.0;
            for element in &mesh.elements {
                let (dofs, _, m) = mesh.element_matrices(element);
                let n = dofs.len();
                for i in 0..n {
                    for j in 0..n {
                        if dofs[i] % 6 == direction && dofs[j] % 6 == direction {
                            sum += m[i * n + j];
                        }
                    }
                }
            }
            // Sums of ~1e4 terms of size ~1e3 kg: round-off ~1e-12 relative.
            assert!(
                (sum - mesh.total_mass).abs() < 1e-10 * mesh.total_mass,
                "direction {direction}: {sum} vs {}",
                mesh.total_mass
            );
        }
    }
}
