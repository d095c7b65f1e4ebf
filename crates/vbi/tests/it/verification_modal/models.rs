//! Small FE models built directly from element matrices, for the modal and static
//! verification tests and the modal benchmark (independent of the `fe` assembly).
//!
//! Conventions: z up, x along the bridge, y lateral. A beam element's local DOFs are
//! [w₁, s₁, w₂, s₂] with s = dw/d(local axis); each local DOF reads one global DOF with a sign.

#![allow(dead_code)]

use vbi::deck::{DeckGeometry, DeckLine};
use vbi::fe::{DeckNodeDofs, Direction, FeModel, SparseRow, StationFunctional};
use vbi::linalg::SparseMatrix;
use vbi::modal::{Station, StationTarget};

/// Hermite beam stiffness (EI/h³ ·[12, 6h, −12, 6h; …]) over [w₁, s₁, w₂, s₂].
pub fn beam_stiffness(ei: f64, h: f64) -> [[f64; 4]; 4] {
    let c = ei / h.powi(3);
    [
        [12.0 * c, 6.0 * h * c, -12.0 * c, 6.0 * h * c],
        [6.0 * h * c, 4.0 * h * h * c, -6.0 * h * c, 2.0 * h * h * c],
        [-12.0 * c, -6.0 * h * c, 12.0 * c, -6.0 * h * c],
        [6.0 * h * c, 2.0 * h * h * c, -6.0 * h * c, 4.0 * h * h * c],
    ]
}

/// Consistent beam mass (m̄h/420 ·[156, 22h, 54, −13h; …]).
pub fn beam_mass(mass_per_length: f64, h: f64) -> [[f64; 4]; 4] {
    let c = mass_per_length * h / 420.0;
    [
        [156.0 * c, 22.0 * h * c, 54.0 * c, -13.0 * h * c],
        [
            22.0 * h * c,
            4.0 * h * h * c,
            13.0 * h * c,
            -3.0 * h * h * c,
        ],
        [54.0 * c, 13.0 * h * c, 156.0 * c, -22.0 * h * c],
        [
            -13.0 * h * c,
            -3.0 * h * h * c,
            -22.0 * h * c,
            4.0 * h * h * c,
        ],
    ]
}

/// Global DOF numbering with restraints: `None` for a restrained DOF.
pub struct Numbering {
    pub free: Vec<Option<usize>>,
    pub directions: Vec<Direction>,
}

impl Numbering {
    pub fn new(all_directions: &[Direction], restrained: &[bool]) -> Self {
        let mut free = Vec::new();
        let mut directions = Vec::new();
        for (d, &r) in all_directions.iter().zip(restrained) {
            if r {
                free.push(None);
            } else {
                free.push(Some(directions.len()));
                directions.push(*d);
            }
        }
        Numbering { free, directions }
    }
    pub fn count(&self) -> usize {
        self.directions.len()
    }
}

/// Adds a local matrix whose local DOF a reads global DOF `map[a].0` with sign `map[a].1`.
pub fn scatter<const N: usize>(
    triplets: &mut Vec<(usize, usize, f64)>,
    numbering: &Numbering,
    map: [(usize, f64); N],
    local: &[[f64; N]; N],
) {
    for a in 0..N {
        let Some(ga) = numbering.free[map[a].0] else {
            continue;
        };
        for b in 0..N {
            let Some(gb) = numbering.free[map[b].0] else {
                continue;
            };
            triplets.push((ga, gb, map[a].1 * map[b].1 * local[a][b]));
        }
    }
}

/// A row Σ sign·coef·u over a local-to-global map (restrained DOFs dropped).
pub fn local_row<const N: usize>(
    numbering: &Numbering,
    map: [(usize, f64); N],
    coefficients: [f64; N],
) -> SparseRow {
    (0..N)
        .filter_map(|a| numbering.free[map[a].0].map(|g| (g, map[a].1 * coefficients[a])))
        .filter(|&(_, c)| c != 0.0)
        .collect()
}

/// Support of a beam test model.
#[derive(Clone, Copy, PartialEq, Debug)]
pub enum BeamSupport {
    /// w = 0 and u = 0.
    Pinned,
    /// w = 0 only.
    Roller,
}

/// A continuous 2D Euler–Bernoulli beam: spans of given lengths, `elements_per_span` each,
/// uniform EI [N·m²] and m̄ [kg/m], supports at span ends. DOFs per node: w (TranslationZ),
/// s = dw/dx (RotationY, with the slope sign of this test model), and, if `axial`, u
/// (TranslationX) with EA [N] and consistent axial mass. Stations: mid-span of each span and
/// each interior support (girder 0).
pub fn continuous_beam(
    spans: &[f64],
    elements_per_span: usize,
    flexural_rigidity: f64,
    mass_per_length: f64,
    supports: &[BeamSupport],
    axial: Option<f64>,
) -> FeModel {
    assert_eq!(supports.len(), spans.len() + 1);
    let mut xs = vec![0.0];
    let mut support_nodes = vec![0];
    for &l in spans {
        let x0 = *xs.last().unwrap();
        for e in 1..=elements_per_span {
            xs.push(x0 + l * e as f64 / elements_per_span as f64);
        }
        support_nodes.push(xs.len() - 1);
    }
    let nodes = xs.len();
    let per = if axial.is_some() { 3 } else { 2 };
    let mut dirs = Vec::new();
    let mut restrained = Vec::new();
    for node in 0..nodes {
        let support = support_nodes
            .iter()
            .position(|&s| s == node)
            .map(|i| supports[i]);
        dirs.push(Direction::TranslationZ);
        restrained.push(support.is_some());
        dirs.push(Direction::RotationY);
        restrained.push(false);
        if axial.is_some() {
            dirs.push(Direction::TranslationX);
            restrained.push(support == Some(BeamSupport::Pinned));
        }
    }
    let numbering = Numbering::new(&dirs, &restrained);
    let mut kt = Vec::new();
    let mut mt = Vec::new();
    let mut total_mass = 0.0;
    for e in 0..nodes - 1 {
        let h = xs[e + 1] - xs[e];
        let map = [
            (per * e, 1.0),
            (per * e + 1, 1.0),
            (per * (e + 1), 1.0),
            (per * (e + 1) + 1, 1.0),
        ];
        scatter(
            &mut kt,
            &numbering,
            map,
            &beam_stiffness(flexural_rigidity, h),
        );
        scatter(&mut mt, &numbering, map, &beam_mass(mass_per_length, h));
        if let Some(ea) = axial {
            let map = [(per * e + 2, 1.0), (per * (e + 1) + 2, 1.0)];
            let k = ea / h;
            let m = mass_per_length * h / 6.0;
            scatter(&mut kt, &numbering, map, &[[k, -k], [-k, k]]);
            scatter(&mut mt, &numbering, map, &[[2.0 * m, m], [m, 2.0 * m]]);
        }
        total_mass += mass_per_length * h;
    }
    let n = numbering.count();
    let deck = DeckGeometry {
        lines: vec![DeckLine {
            lateral_position: 0.0,
            node_positions: xs.clone(),
            first_node: 0,
        }],
        length: *xs.last().unwrap(),
    };
    let deck_dofs = (0..nodes)
        .map(|node| DeckNodeDofs {
            deflection: numbering.free[per * node]
                .map(|g| vec![(g, 1.0)])
                .unwrap_or_default(),
            slope: numbering.free[per * node + 1]
                .map(|g| vec![(g, 1.0)])
                .unwrap_or_default(),
        })
        .collect();
    // Stations at mid-spans and interior supports.
    let mut stations = Vec::new();
    let mut functionals = Vec::new();
    let element_map = |e: usize| {
        [
            (per * e, 1.0),
            (per * e + 1, 1.0),
            (per * (e + 1), 1.0),
            (per * (e + 1) + 1, 1.0),
        ]
    };
    let mut add_station = |name: String, node: usize, over_support: bool| {
        let k_left = beam_stiffness(flexural_rigidity, xs[node] - xs[node - 1]);
        let k_right = beam_stiffness(flexural_rigidity, xs[node + 1] - xs[node]);
        // Sagging moment EI w'' = +(row s₂ of k_e u_e) at an element's right end and
        // −(row s₁) at its left end.
        stations.push(Station {
            name,
            position: xs[node],
            target: StationTarget::Girder(0),
            over_support,
            support: false,
        });
        functionals.push(StationFunctional {
            deflection: numbering.free[per * node]
                .map(|g| vec![(g, 1.0)])
                .unwrap_or_default(),
            moment_left: local_row(&numbering, element_map(node - 1), k_left[3]),
            moment_right: local_row(&numbering, element_map(node), k_right[1].map(|v| -v)),
            ..StationFunctional::default()
        });
    };
    for (i, _) in spans.iter().enumerate() {
        let mid = support_nodes[i] + elements_per_span / 2;
        add_station(format!("span{}_mid", i + 1), mid, false);
        if i + 1 < spans.len() {
            add_station(format!("support{}", i + 2), support_nodes[i + 1], true);
        }
    }
    FeModel {
        stiffness: SparseMatrix::from_triplets(n, &kt),
        mass: SparseMatrix::from_triplets(n, &mt),
        dof_directions: numbering.directions,
        deck,
        deck_dofs,
        stations,
        station_functionals: functionals,
        damping_ratio: 0.05,
        mode_damping: None,
        total_mass,
        has_station_forces: true,
    }
}

/// A plane grillage (plate-like grid of beams) in the x–y plane: `girders` longitudinal lines at
/// `girder_spacing` [m], each of `span` [m] cut into `elements` elements, and a transverse
/// member at every node. DOFs per node: w (TranslationZ), θx (RotationX), θy (RotationY), with
/// dw/dx = −θy and dw/dy = θx. Girders: EI, GJ, m̄, polar mass inertia; cross-members weaker.
/// Each girder is simply supported at both ends (w = 0). Stations: mid-span of each girder.
pub fn plate_grid(girders: usize, girder_spacing: f64, span: f64, elements: usize) -> FeModel {
    let nodes_per_line = elements + 1;
    let node = |g: usize, i: usize| g * nodes_per_line + i;
    let total_nodes = girders * nodes_per_line;
    let mut dirs = Vec::new();
    let mut restrained = Vec::new();
    for _g in 0..girders {
        for i in 0..nodes_per_line {
            let end = i == 0 || i == elements;
            dirs.extend([
                Direction::TranslationZ,
                Direction::RotationX,
                Direction::RotationY,
            ]);
            restrained.extend([end, false, false]);
        }
    }
    let numbering = Numbering::new(&dirs, &restrained);
    // Girder: precast box with its slab share; cross-members: slab strips.
    let (girder_ei, girder_gj, girder_m, girder_ip) = (2.0e10, 1.5e10, 3000.0, 800.0);
    let (cross_ei, cross_gj, cross_m, cross_ip) = (4.0e8, 3.0e8, 200.0, 20.0);
    let h = span / elements as f64;
    let mut kt = Vec::new();
    let mut mt = Vec::new();
    let mut total_mass = 0.0;
    // w, θx, θy of a node.
    let w = |n: usize| 3 * n;
    let tx = |n: usize| 3 * n + 1;
    let ty = |n: usize| 3 * n + 2;
    let mut add_member =
        |a: usize, b: usize, along_x: bool, length: f64, ei: f64, gj: f64, m: f64, ip: f64| {
            // Bending: slope along x is −θy, along y is +θx. Torsion: about x is θx, about y is θy.
            let (slope_a, slope_b, sign, tor_a, tor_b) = if along_x {
                (ty(a), ty(b), -1.0, tx(a), tx(b))
            } else {
                (tx(a), tx(b), 1.0, ty(a), ty(b))
            };
            let map = [(w(a), 1.0), (slope_a, sign), (w(b), 1.0), (slope_b, sign)];
            scatter(&mut kt, &numbering, map, &beam_stiffness(ei, length));
            scatter(&mut mt, &numbering, map, &beam_mass(m, length));
            let map = [(tor_a, 1.0), (tor_b, 1.0)];
            let k = gj / length;
            let mi = ip * length / 6.0;
            scatter(&mut kt, &numbering, map, &[[k, -k], [-k, k]]);
            scatter(&mut mt, &numbering, map, &[[2.0 * mi, mi], [mi, 2.0 * mi]]);
            total_mass += m * length;
        };
    for g in 0..girders {
        for i in 0..elements {
            add_member(
                node(g, i),
                node(g, i + 1),
                true,
                h,
                girder_ei,
                girder_gj,
                girder_m,
                girder_ip,
            );
        }
    }
    for g in 0..girders.saturating_sub(1) {
        for i in 0..nodes_per_line {
            add_member(
                node(g, i),
                node(g + 1, i),
                false,
                girder_spacing,
                cross_ei,
                cross_gj,
                cross_m,
                cross_ip,
            );
        }
    }
    let n = numbering.count();
    let xs: Vec<f64> = (0..nodes_per_line).map(|i| i as f64 * h).collect();
    let width = girder_spacing * (girders as f64 - 1.0);
    let deck = DeckGeometry {
        lines: (0..girders)
            .map(|g| DeckLine {
                lateral_position: -0.5 * width + g as f64 * girder_spacing,
                node_positions: xs.clone(),
                first_node: g * nodes_per_line,
            })
            .collect(),
        length: span,
    };
    let deck_dofs = (0..total_nodes)
        .map(|nd| DeckNodeDofs {
            deflection: numbering.free[w(nd)]
                .map(|g| vec![(g, 1.0)])
                .unwrap_or_default(),
            slope: numbering.free[ty(nd)]
                .map(|g| vec![(g, -1.0)])
                .unwrap_or_default(),
        })
        .collect();
    let mut stations = Vec::new();
    let mut functionals = Vec::new();
    let k_e = beam_stiffness(girder_ei, h);
    let mid = elements / 2;
    for g in 0..girders {
        let nd = node(g, mid);
        let map = |a: usize, b: usize| [(w(a), 1.0), (ty(a), -1.0), (w(b), 1.0), (ty(b), -1.0)];
        stations.push(Station {
            name: format!("mid_g{}", g + 1),
            position: xs[mid],
            target: StationTarget::Girder(g),
            over_support: false,
            support: false,
        });
        functionals.push(StationFunctional {
            deflection: numbering.free[w(nd)]
                .map(|d| vec![(d, 1.0)])
                .unwrap_or_default(),
            moment_left: local_row(&numbering, map(node(g, mid - 1), nd), k_e[3]),
            moment_right: local_row(&numbering, map(nd, node(g, mid + 1)), k_e[1].map(|v| -v)),
            ..StationFunctional::default()
        });
    }
    FeModel {
        stiffness: SparseMatrix::from_triplets(n, &kt),
        mass: SparseMatrix::from_triplets(n, &mt),
        dof_directions: numbering.directions,
        deck,
        deck_dofs,
        stations,
        station_functionals: functionals,
        damping_ratio: 0.05,
        mode_damping: None,
        total_mass,
        has_station_forces: true,
    }
}
