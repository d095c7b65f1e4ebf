//! The exact static response from the full stiffness K (not from truncated modes): influence
//! lines by Maxwell–Betti reciprocity, and the response to any set of point loads on the deck.
//!
//! A station reads its response r = cᵀu through a functional c (a row of
//! [`StationFunctional`](super::StationFunctional)). A unit downward force at a deck point
//! whose deflection reads w = dᵀu does the work −w, so its generalised load is f = −d and the
//! response is r = −cᵀK⁻¹d. By Maxwell–Betti reciprocity (K symmetric) this is −dᵀz with
//! K z = c: one solve per functional gives the response to a unit load anywhere on the deck.
//! The influence line at a deck node is −(deflection row)·z, and its slope along the line is
//! −(slope row)·z; between nodes the deck's Hermite interpolation reproduces exactly the
//! response to a load inside an element, since that load's consistent nodal forces are the same
//! Hermite shape functions.

use thiserror::Error;

use crate::deck::{DeckField, DeckStencil};
use crate::linalg::{CholeskyFactor, LinalgError};

use super::influence::InfluenceLines;
use super::{
    diagnose_mechanism, factor_is_singular, validate_fe_model, FeModel, ModalError, SparseRow,
};

/// Errors of the static solve.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum StaticError {
    /// K is singular or indefinite: the model is a mechanism (the free direction is named).
    #[error("no static solution: {0}")]
    Mechanism(ModalError),
    /// The model's parts do not fit together.
    #[error("inconsistent FE model: {message}")]
    InvalidModel {
        /// What is inconsistent.
        message: String,
    },
    /// A load with a non-finite position or force.
    #[error("load {index}: position ({x}, {y}) m and force {force} N must be finite")]
    NonFiniteLoad {
        /// 0-based index of the load.
        index: usize,
        /// Longitudinal position [m].
        x: f64,
        /// Lateral position [m].
        y: f64,
        /// Force [N].
        force: f64,
    },
    /// The sparse solver failed otherwise.
    #[error(transparent)]
    Linalg(#[from] LinalgError),
    /// The influence lines of every station would not fit in memory.
    #[error(
        "the influence lines of {stations} stations on a model of {degrees_of_freedom} degrees \
         of freedom would need about {:.1} GiB, over the limit of {:.1} GiB; use fewer stations, \
         fewer spans or a coarser mesh (a longer element_length_m)",
        *needed_bytes as f64 / (1u64 << 30) as f64,
        *limit_bytes as f64 / (1u64 << 30) as f64
    )]
    TooLarge {
        /// Stations of the model.
        stations: usize,
        /// Size of the model.
        degrees_of_freedom: usize,
        /// The estimate [bytes].
        needed_bytes: u64,
        /// [`MAX_INFLUENCE_BYTES`].
        limit_bytes: u64,
    },
}

/// Largest memory of the influence lines (the solutions of every station's rows, n values each,
/// and their deck fields): 2 GiB. Both grow with the stations times the model, so with the
/// square of a beam's span count: a 500-span beam asked for 4 GB.
pub const MAX_INFLUENCE_BYTES: u64 = 2 << 30;

/// A point load on the deck.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLoad {
    /// Longitudinal position x [m] from the first support.
    pub x: f64,
    /// Lateral position y [m] from the deck centreline, positive to the left.
    pub y: f64,
    /// Downward force [N] (a wheel's weight is positive).
    pub force: f64,
}

/// The static response at every station.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticResponse {
    /// Deflection at each station [m], positive upwards.
    pub deflection: Vec<f64>,
    /// Sagging bending moment at each station [N·m]: for each load, the element-end moment on
    /// the side away from the load (`moment_left` for a load at x ≥ the station, `moment_right`
    /// for a load left of it), exact like the influence lines.
    pub moment: Vec<f64>,
    /// The force quantity at each station [N] ([`super::Station::quantities`]): the support
    /// reaction K_cf u − f_c (the loads' shares on the bearings' nodes included), or the shear
    /// force from the element on the side away from each load.
    pub force: Vec<f64>,
}

/// The factorised stiffness of a model, for any number of static solves.
#[derive(Debug, Clone)]
pub struct StaticSolver<'a> {
    model: &'a FeModel,
    factor: CholeskyFactor,
}

impl<'a> StaticSolver<'a> {
    /// Factorises K once (sparse Cholesky). A singular K (a failed factorisation, or one whose
    /// inverse iteration finds ω² ≈ 0) is reported as a mechanism naming its free direction.
    pub fn new(model: &'a FeModel) -> Result<Self, StaticError> {
        validate_fe_model(model).map_err(|e| StaticError::InvalidModel {
            message: e.to_string(),
        })?;
        let factor = match CholeskyFactor::new(&model.stiffness) {
            Ok(factor) if factor_is_singular(model, &factor) => {
                return Err(StaticError::Mechanism(diagnose_mechanism(model)))
            }
            Ok(factor) => factor,
            Err(LinalgError::NotPositiveDefinite { .. }) => {
                return Err(StaticError::Mechanism(diagnose_mechanism(model)))
            }
            Err(e) => return Err(e.into()),
        };
        Ok(Self { model, factor })
    }

    /// Solves K z = c for each row c, all at once; returns the solutions column-major.
    fn solve_rows(&self, rows: &[&SparseRow]) -> Result<Vec<f64>, StaticError> {
        let n = self.model.dof_count();
        let mut rhs = vec![0.0; n * rows.len()];
        for (j, row) in rows.iter().enumerate() {
            for &(dof, c) in row.iter() {
                rhs[j * n + dof] += c;
            }
        }
        self.factor.solve_many_in_place(&mut rhs, rows.len())?;
        Ok(rhs)
    }

    /// Influence lines of every station for a unit downward load: deflection, the moment from
    /// the element left and right of the station, and the force quantity (the shear force from
    /// either side, or the support reaction). One factorisation, 5 solves per station (4 at a
    /// support; 3 for a model without station forces, whose force lines are left empty).
    ///
    /// A reaction's field adds the load's direct share: a unit load's restrained component
    /// f_c = −N_c does not reach K u = f, and r_c = K_cf u_f − f_c, so the field gains the value 1
    /// (slope 0) at each deck node on the station's bearings; the deck's Hermite interpolation
    /// then adds N_c(x) for a load in an element next to the support.
    pub fn influence_lines(&self) -> Result<InfluenceLines, StaticError> {
        let model = self.model;
        let n = model.dof_count();
        let mut rows: Vec<&SparseRow> = Vec::new();
        // For each station, the indices into `rows` of its fields: deflection, moment left and
        // right, force left and right.
        let mut indices: Vec<[usize; 5]> = Vec::new();
        for (station, f) in model.stations.iter().zip(&model.station_functionals) {
            let first = rows.len();
            rows.extend([&f.deflection, &f.moment_left, &f.moment_right]);
            if !model.has_station_forces {
                indices.push([first, first + 1, first + 2, first, first]);
            } else if station.support {
                rows.push(&f.reaction);
                indices.push([first, first + 1, first + 2, first + 3, first + 3]);
            } else {
                rows.extend([&f.shear_left, &f.shear_right]);
                indices.push([first, first + 1, first + 2, first + 3, first + 4]);
            }
        }
        let needed = 8 * rows.len() as u64 * (n + 2 * model.deck_dofs.len()) as u64;
        if needed > MAX_INFLUENCE_BYTES {
            return Err(StaticError::TooLarge {
                stations: model.stations.len(),
                degrees_of_freedom: n,
                needed_bytes: needed,
                limit_bytes: MAX_INFLUENCE_BYTES,
            });
        }
        let z = self.solve_rows(&rows)?;
        let field = |j: usize| -> DeckField {
            let zj = &z[j * n..(j + 1) * n];
            let read =
                |row: &SparseRow| -> f64 { -row.iter().map(|&(d, c)| c * zj[d]).sum::<f64>() };
            DeckField {
                deflection: model
                    .deck_dofs
                    .iter()
                    .map(|d| read(&d.deflection))
                    .collect(),
                slope: model.deck_dofs.iter().map(|d| read(&d.slope)).collect(),
            }
        };
        let force_field = |s: usize, j: usize| -> DeckField {
            let mut f = field(j);
            if model.stations[s].support {
                for &node in &model.station_functionals[s].reaction_nodes {
                    f.deflection[node] += 1.0;
                }
            }
            f
        };
        let fields = |part: usize| -> Vec<DeckField> {
            indices
                .iter()
                .enumerate()
                .map(|(s, ix)| match part {
                    0..=2 => field(ix[part]),
                    _ => force_field(s, ix[part]),
                })
                .collect()
        };
        Ok(InfluenceLines {
            deck: model.deck.clone(),
            stations: model.stations.clone(),
            deflection: fields(0),
            moment_left: fields(1),
            moment_right: fields(2),
            force_left: if model.has_station_forces {
                fields(3)
            } else {
                Vec::new()
            },
            force_right: if model.has_station_forces {
                fields(4)
            } else {
                Vec::new()
            },
        })
    }

    /// The generalised load vector of a downward force P at (x, y): f = −P Σ_terms (weights of
    /// the deck stencil applied to the nodes' deflection and slope rows). Zero off the deck.
    fn load_vector(&self, stencil: &DeckStencil, force: f64, out: &mut [f64]) {
        for t in stencil.terms() {
            let rows = &self.model.deck_dofs[t.node];
            for &(dof, c) in &rows.deflection {
                out[dof] -= force * t.value_from_deflection * c;
            }
            for &(dof, c) in &rows.slope {
                out[dof] -= force * t.value_from_slope * c;
            }
        }
    }

    /// Deflection and moment at every station under a set of downward point loads, from K u = f
    /// (one solve per load, all with the same factor). Equal to Σ force · influence line.
    pub fn response(&self, loads: &[PointLoad]) -> Result<StaticResponse, StaticError> {
        let model = self.model;
        let n = model.dof_count();
        for (index, load) in loads.iter().enumerate() {
            if !(load.x.is_finite() && load.y.is_finite() && load.force.is_finite()) {
                return Err(StaticError::NonFiniteLoad {
                    index,
                    x: load.x,
                    y: load.y,
                    force: load.force,
                });
            }
        }
        let mut u = vec![0.0; n * loads.len()];
        let stencils: Vec<DeckStencil> = loads
            .iter()
            .map(|load| model.deck.stencil(load.x, load.y))
            .collect();
        for (j, (load, stencil)) in loads.iter().zip(&stencils).enumerate() {
            self.load_vector(stencil, load.force, &mut u[j * n..(j + 1) * n]);
        }
        self.factor.solve_many_in_place(&mut u, loads.len())?;
        let stations = model.stations.len();
        let mut deflection = vec![0.0; stations];
        let mut moment = vec![0.0; stations];
        let mut force = vec![0.0; stations];
        let read =
            |row: &SparseRow, uj: &[f64]| -> f64 { row.iter().map(|&(d, c)| c * uj[d]).sum() };
        for (j, (load, stencil)) in loads.iter().zip(&stencils).enumerate() {
            let uj = &u[j * n..(j + 1) * n];
            for s in 0..stations {
                let f = &model.station_functionals[s];
                let station = &model.stations[s];
                deflection[s] += read(&f.deflection, uj);
                let left_element = station.reads_left_element(load.x);
                moment[s] += if left_element {
                    read(&f.moment_left, uj)
                } else {
                    read(&f.moment_right, uj)
                };
                force[s] += if station.support {
                    // r_c = K_cf u − f_c, with f_c = −P·(the load's weight on the node).
                    let direct: f64 = stencil
                        .terms()
                        .iter()
                        .filter(|t| f.reaction_nodes.contains(&t.node))
                        .map(|t| t.value_from_deflection)
                        .sum();
                    read(&f.reaction, uj) + load.force * direct
                } else if left_element {
                    read(&f.shear_left, uj)
                } else {
                    read(&f.shear_right, uj)
                };
            }
        }
        Ok(StaticResponse {
            deflection,
            moment,
            force,
        })
    }
}

/// Influence lines of every station of the model (see the module documentation); one
/// factorisation of K for all the solves.
pub fn influence_lines(model: &FeModel) -> Result<InfluenceLines, StaticError> {
    StaticSolver::new(model)?.influence_lines()
}

/// Deflection and moment at every station under downward point loads `(x [m], y [m], force [N])`
/// on the deck; consistent with [`influence_lines`].
pub fn static_response(
    model: &FeModel,
    loads: &[(f64, f64, f64)],
) -> Result<StaticResponse, StaticError> {
    let loads: Vec<PointLoad> = loads
        .iter()
        .map(|&(x, y, force)| PointLoad { x, y, force })
        .collect();
    StaticSolver::new(model)?.response(&loads)
}
