//! Assembly of M, C, K (paper Eq. 19) by Lagrange's equations through a kinematic
//! transformation, and of the static wheel loads from static equilibrium.
//!
//! Physical coordinates u hold, for every body, its bounce z, pitch θ and roll φ at the centre
//! of mass, and for every axle its bounce and roll: the kinetic energy is ½ u̇ᵀ m u̇ with m
//! diagonal. The independent (generalised) coordinates q omit the bounce of articulated bodies
//! and the DOFs a model does not have; u = T q. Each spring or damper e stretches by
//! δ_e = b_eᵀ u, so its potential energy is ½ k_e (b_eᵀ T q)². Lagrange's equations give
//!
//! M = Tᵀ m T,  K = Σ_e k_e (Tᵀ b_e)(b_eᵀ T) = Tᵀ k T,  C = Σ_e c_e (Tᵀ b_e)(b_eᵀ T).
//!
//! The static displacement under gravity solves K q_s = Tᵀ f_g with f_g = −g·m on every bounce;
//! each tyre's static load is k_t times its compression. q is then measured from q_s, so the
//! dynamic equations carry no gravity term.

use nalgebra::{DMatrix, DVector};

use super::spec::{Dimension, MovingForce, MultibodySpec, VehicleDescription, VehicleSpec};
use super::{ContactKind, TyreContact, VehicleError, VehicleModel};
use crate::units::GRAVITY;

/// Assembles a vehicle description into the model the solver integrates.
///
/// Multibody vehicles: M, C, K by the kinematic transformation above (Eq. 19), DOFs measured
/// from static equilibrium, one [`TyreContact`] per wheel (left before right, front to back)
/// whose `coupling` gives the wheel's vertical displacement (axle bounce ± half track × axle
/// roll), and static wheel loads from K q_s = Tᵀ f_g (statically indeterminate vehicles
/// included). Moving forces: no DOFs, one force contact per wheel.
pub fn assemble(spec: &VehicleSpec) -> Result<VehicleModel, VehicleError> {
    spec.validate()?;
    match &spec.description {
        VehicleDescription::MovingForces(forces) => Ok(assemble_forces(&spec.name, forces)),
        VehicleDescription::Multibody(body) => assemble_multibody(&spec.name, body),
    }
}

fn assemble_forces(name: &str, forces: &[MovingForce]) -> VehicleModel {
    let front = forces
        .iter()
        .map(|f| f.longitudinal_position)
        .fold(f64::NEG_INFINITY, f64::max);
    let mut order: Vec<&MovingForce> = forces.iter().collect();
    order.sort_by(|a, b| b.longitudinal_position.total_cmp(&a.longitudinal_position));
    let mut contacts = Vec::new();
    for f in order {
        let offset = f.longitudinal_position - front;
        if f.track > 0.0 {
            for side in [1.0, -1.0] {
                contacts.push(TyreContact {
                    longitudinal_offset: offset,
                    lateral_offset: side * f.track / 2.0,
                    static_load: f.axle_load / 2.0,
                    kind: ContactKind::Force,
                });
            }
        } else {
            contacts.push(TyreContact {
                longitudinal_offset: offset,
                lateral_offset: 0.0,
                static_load: f.axle_load,
                kind: ContactKind::Force,
            });
        }
    }
    VehicleModel {
        name: name.to_string(),
        dof_names: Vec::new(),
        mass_matrix: DMatrix::zeros(0, 0),
        damping_matrix: DMatrix::zeros(0, 0),
        stiffness_matrix: DMatrix::zeros(0, 0),
        contacts,
        pitch_load_per_acceleration: Vec::new(),
    }
}

/// Physical coordinate layout: body b has z, θ, φ at 3b, 3b+1, 3b+2; axle a has z, φ at
/// 3·bodies + 2a and 3·bodies + 2a + 1.
struct Layout {
    bodies: usize,
}

impl Layout {
    fn body_bounce(&self, b: usize) -> usize {
        3 * b
    }
    fn body_pitch(&self, b: usize) -> usize {
        3 * b + 1
    }
    fn body_roll(&self, b: usize) -> usize {
        3 * b + 2
    }
    fn axle_bounce(&self, a: usize) -> usize {
        3 * self.bodies + 2 * a
    }
    fn axle_roll(&self, a: usize) -> usize {
        3 * self.bodies + 2 * a + 1
    }
}

/// A spring and damper in parallel: its stretch is `b · u`.
struct Element {
    stretch: Vec<(usize, f64)>,
    stiffness: f64,
    damping: f64,
}

/// A wheel: its axle (index), lateral offset [m] and vertical displacement as b · u.
struct Wheel {
    axle: usize,
    lateral_offset: f64,
    displacement: Vec<(usize, f64)>,
}

/// Assembles a multibody vehicle (see [`assemble`]): M = Tᵀ m T, K = Σ_e k_e (Tᵀ b_e)(b_eᵀ T),
/// C likewise, symmetrised; the static wheel loads from K q_s = Tᵀ f_g.
fn assemble_multibody(name: &str, spec: &MultibodySpec) -> Result<VehicleModel, VehicleError> {
    let spatial = spec.dimension == Dimension::Spatial;
    let layout = Layout {
        bodies: spec.bodies.len(),
    };
    let physical_count = 3 * spec.bodies.len() + 2 * spec.axles.len();
    let independent = generalised_coordinates(spec, &layout, spatial);
    let t = kinematic_transformation(spec, &layout, &independent, physical_count);
    let physical_mass = physical_mass(spec, &layout, spatial, physical_count);
    let (elements, wheels) = springs_dampers_and_wheels(spec, &layout, spatial);
    let (stiffness, damping) = stiffness_and_damping(&t, &elements);
    let mass = t.transpose() * DMatrix::from_diagonal(&physical_mass) * &t;
    // Exact symmetry (the products above are symmetric up to round-off).
    let symmetrise = |a: DMatrix<f64>| (&a + a.transpose()) * 0.5;
    let (mass, stiffness, damping) = (symmetrise(mass), symmetrise(stiffness), symmetrise(damping));

    // M positive definite and no zero-frequency mode (a mechanism such as the pitch of a body
    // on one axle, which Cholesky alone can miss through round-off).
    super::modes::generalised_eigen(&mass, &stiffness)?;
    let factor = stiffness.clone().cholesky().ok_or(VehicleError::Unstable)?;

    // Static equilibrium K q_s = Tᵀ f_g (gravity downwards on every bounce coordinate).
    let gravity = gravity_load(spec, &layout, physical_count);
    let static_displacement = factor.solve(&(t.transpose() * gravity));
    if static_displacement.iter().any(|v| !v.is_finite()) {
        return Err(VehicleError::Unstable);
    }

    let contacts = tyre_contacts(spec, &t, wheels, &static_displacement);
    let pitch_load_per_acceleration = pitch_load_per_acceleration(spec, &layout, &t);
    Ok(VehicleModel {
        name: name.to_string(),
        dof_names: independent.into_iter().map(|(_, n)| n).collect(),
        mass_matrix: mass,
        damping_matrix: damping,
        stiffness_matrix: stiffness,
        contacts,
        pitch_load_per_acceleration,
    })
}

/// The generalised coordinates q, as (physical coordinate, name): every body's bounce unless
/// it is articulated, its pitch when it has a pitch inertia and its roll in a spatial model,
/// then the bounce (and roll) of every axle with a suspension.
fn generalised_coordinates(
    spec: &MultibodySpec,
    layout: &Layout,
    spatial: bool,
) -> Vec<(usize, String)> {
    let mut independent: Vec<(usize, String)> = Vec::new();
    for (b, body) in spec.bodies.iter().enumerate() {
        if body.articulation.is_none() {
            independent.push((layout.body_bounce(b), format!("{}_bounce", body.name)));
        }
        if body.pitch_inertia.is_some() {
            independent.push((layout.body_pitch(b), format!("{}_pitch", body.name)));
        }
        if spatial {
            independent.push((layout.body_roll(b), format!("{}_roll", body.name)));
        }
    }
    for (a, axle) in spec.axles.iter().enumerate() {
        if axle.suspension.is_some() {
            independent.push((layout.axle_bounce(a), format!("axle{}_bounce", a + 1)));
            if spatial {
                independent.push((layout.axle_roll(a), format!("axle{}_roll", a + 1)));
            }
        }
    }
    independent
}

/// The kinematic transformation u = T q (physical_count × generalised): a unit entry for every
/// independent coordinate, and the bounce of an articulated body j from its leading body i
/// through the hinge at x_h, z_j = z_i + (x_h − x_i) θ_i − (x_h − x_j) θ_j.
fn kinematic_transformation(
    spec: &MultibodySpec,
    layout: &Layout,
    independent: &[(usize, String)],
    physical_count: usize,
) -> DMatrix<f64> {
    let mut t = DMatrix::<f64>::zeros(physical_count, independent.len());
    for (j, (u, _)) in independent.iter().enumerate() {
        t[(*u, j)] = 1.0;
    }
    // Articulated bounce, body by body (a leading body always comes first, so its rows are
    // complete).
    for (j, body) in spec.bodies.iter().enumerate() {
        if let Some(hinge) = &body.articulation {
            let i = hinge.leading_body;
            let lead = &spec.bodies[i];
            let arm_lead = hinge.longitudinal_position - lead.longitudinal_position;
            let arm_own = hinge.longitudinal_position - body.longitudinal_position;
            let row = t.row(layout.body_bounce(i)) + t.row(layout.body_pitch(i)) * arm_lead
                - t.row(layout.body_pitch(j)) * arm_own;
            t.set_row(layout.body_bounce(j), &row);
        }
    }
    t
}

/// The diagonal physical mass m: body mass on its bounce, pitch inertia on its pitch, roll
/// inertia on its roll (spatial only); unsprung mass and roll inertia on each suspended axle.
fn physical_mass(
    spec: &MultibodySpec,
    layout: &Layout,
    spatial: bool,
    physical_count: usize,
) -> DVector<f64> {
    let mut physical_mass = DVector::<f64>::zeros(physical_count);
    for (b, body) in spec.bodies.iter().enumerate() {
        physical_mass[layout.body_bounce(b)] = body.mass;
        physical_mass[layout.body_pitch(b)] = body.pitch_inertia.unwrap_or(0.0);
        physical_mass[layout.body_roll(b)] = if spatial { body.roll_inertia } else { 0.0 };
    }
    for (a, axle) in spec.axles.iter().enumerate() {
        if let Some(s) = &axle.suspension {
            physical_mass[layout.axle_bounce(a)] = s.unsprung_mass;
            physical_mass[layout.axle_roll(a)] = if spatial { s.roll_inertia } else { 0.0 };
        }
    }
    physical_mass
}

/// The springs and dampers (suspension between the axle and the body point above it at the
/// spring's lateral offset, then the tyre) and the wheels, axle by axle, left (+1) before
/// right (−1); planar models have one "side" 0. A wheel's vertical displacement is its axle's
/// bounce ± half track × axle roll, or the body point's without a suspension.
fn springs_dampers_and_wheels(
    spec: &MultibodySpec,
    layout: &Layout,
    spatial: bool,
) -> (Vec<Element>, Vec<Wheel>) {
    let sides: &[f64] = if spatial { &[1.0, -1.0] } else { &[0.0] };
    let mut elements = Vec::new();
    let mut wheels: Vec<Wheel> = Vec::new();
    for (a, axle) in spec.axles.iter().enumerate() {
        let b = axle.body;
        let body = &spec.bodies[b];
        let arm = axle.longitudinal_position - body.longitudinal_position;
        // Vertical displacement of the body point above the axle at lateral offset y.
        let body_point = |y: f64| -> Vec<(usize, f64)> {
            let mut point = vec![(layout.body_bounce(b), 1.0), (layout.body_pitch(b), arm)];
            if spatial {
                point.push((layout.body_roll(b), y));
            }
            point
        };
        for &side in sides {
            let wheel_y = side * axle.track / 2.0;
            let wheel = match &axle.suspension {
                Some(s) => {
                    let spring_y = side * s.spacing / 2.0;
                    let mut stretch = vec![(layout.axle_bounce(a), 1.0)];
                    if spatial {
                        stretch.push((layout.axle_roll(a), spring_y));
                    }
                    stretch.extend(body_point(spring_y).into_iter().map(|(i, c)| (i, -c)));
                    elements.push(Element {
                        stretch,
                        stiffness: s.stiffness,
                        damping: s.damping,
                    });
                    let mut wheel = vec![(layout.axle_bounce(a), 1.0)];
                    if spatial {
                        wheel.push((layout.axle_roll(a), wheel_y));
                    }
                    wheel
                }
                None => body_point(wheel_y),
            };
            // The tyre stretches by the wheel displacement on a flat rigid road.
            elements.push(Element {
                stretch: wheel.clone(),
                stiffness: axle.tyre_stiffness,
                damping: axle.tyre_damping,
            });
            wheels.push(Wheel {
                axle: a,
                lateral_offset: wheel_y,
                displacement: wheel,
            });
        }
    }
    (elements, wheels)
}

/// The row Tᵀ b of a stretch b · u in the generalised coordinates: Σ_(u, c) c · T_u.
fn generalised_row(t: &DMatrix<f64>, stretch: &[(usize, f64)]) -> DVector<f64> {
    let mut row = DVector::<f64>::zeros(t.ncols());
    for &(u, c) in stretch {
        row += t.row(u).transpose() * c;
    }
    row
}

/// K = Σ_e k_e (Tᵀ b_e)(b_eᵀ T) and C = Σ_e c_e (Tᵀ b_e)(b_eᵀ T), element by element (not yet
/// symmetrised).
fn stiffness_and_damping(t: &DMatrix<f64>, elements: &[Element]) -> (DMatrix<f64>, DMatrix<f64>) {
    let dof_count = t.ncols();
    let mut stiffness = DMatrix::<f64>::zeros(dof_count, dof_count);
    let mut damping = DMatrix::<f64>::zeros(dof_count, dof_count);
    for e in elements {
        let row = generalised_row(t, &e.stretch);
        let outer = &row * row.transpose();
        stiffness += &outer * e.stiffness;
        damping += &outer * e.damping;
    }
    (stiffness, damping)
}

/// The physical gravity load f_g: −g · mass on the bounce of every body and suspended axle.
fn gravity_load(spec: &MultibodySpec, layout: &Layout, physical_count: usize) -> DVector<f64> {
    let mut gravity = DVector::<f64>::zeros(physical_count);
    for (b, body) in spec.bodies.iter().enumerate() {
        gravity[layout.body_bounce(b)] = -GRAVITY * body.mass;
    }
    for (a, axle) in spec.axles.iter().enumerate() {
        if let Some(s) = &axle.suspension {
            gravity[layout.axle_bounce(a)] = -GRAVITY * s.unsprung_mass;
        }
    }
    gravity
}

/// One tyre contact per wheel: offsets from the front axle, the coupling Tᵀ b of its vertical
/// displacement (non-zero entries), and the static load −k_t (bᵀ T q_s), k_t times the tyre's
/// compression under gravity.
fn tyre_contacts(
    spec: &MultibodySpec,
    t: &DMatrix<f64>,
    wheels: Vec<Wheel>,
    static_displacement: &DVector<f64>,
) -> Vec<TyreContact> {
    let front = spec.axles[0].longitudinal_position;
    wheels
        .into_iter()
        .map(|wheel| {
            let axle = &spec.axles[wheel.axle];
            let (k_t, c_t) = (axle.tyre_stiffness, axle.tyre_damping);
            let row = generalised_row(t, &wheel.displacement);
            let coupling: Vec<(usize, f64)> = row
                .iter()
                .enumerate()
                .filter(|(_, c)| **c != 0.0)
                .map(|(i, c)| (i, *c))
                .collect();
            let displacement = row.dot(static_displacement);
            TyreContact {
                longitudinal_offset: axle.longitudinal_position - front,
                lateral_offset: wheel.lateral_offset,
                static_load: -k_t * displacement,
                kind: ContactKind::Tyre {
                    stiffness: k_t,
                    damping: c_t,
                    coupling,
                },
            }
        })
        .collect()
}

/// The generalised pitch load per unit longitudinal acceleration, Tᵀ e with e_θ(b) = m_b h_b on
/// the physical pitch of every body with a centre-of-mass height h_b [kg·m]: the d'Alembert
/// force −m_b s̈ at height h_b above the road, balanced by the tyres' longitudinal forces at the
/// road, is the couple M_θ = m_b h_b s̈ (nose-up positive). Its non-zero entries as (DOF,
/// coefficient); empty without heights.
fn pitch_load_per_acceleration(
    spec: &MultibodySpec,
    layout: &Layout,
    t: &DMatrix<f64>,
) -> Vec<(usize, f64)> {
    let mut load = DVector::<f64>::zeros(t.ncols());
    for (b, body) in spec.bodies.iter().enumerate() {
        if let Some(height) = body.centre_of_mass_height {
            load += t.row(layout.body_pitch(b)).transpose() * (body.mass * height);
        }
    }
    load.iter()
        .enumerate()
        .filter(|(_, c)| **c != 0.0)
        .map(|(i, c)| (i, *c))
        .collect()
}
