//! Vehicle models: moving forces up to 3D multibody trucks, assembled as M, C, K (paper Eq. 19).
//!
//! A vehicle is described as data ([`VehicleSpec`]): rigid bodies, an optional fifth-wheel
//! articulation, axles with suspensions and tyres. [`assemble`] turns it into the
//! [`VehicleModel`] the coupled solver integrates: M, C and K by Lagrange's equations through a
//! kinematic transformation (K = Tᵀ k T), the static wheel loads from static equilibrium, and one
//! [`TyreContact`] per wheel. [`preset`] gives the built-in vehicles, [`natural_modes`] their
//! natural frequencies with the dominant motion of each.

mod assemble;
mod modes;
mod presets;
mod recorded;
mod spec;

pub use assemble::assemble;
pub use modes::{natural_frequencies, natural_modes, MotionKind, VehicleMode};
pub use presets::{preset, presets, PRESET_NAMES};
pub use recorded::{
    multibody_from_axles, ARTICULATION_GAP, DRIVE_UNSPRUNG_MASS, FIFTH_WHEEL_AHEAD,
    MAXIMUM_UNSPRUNG_SHARE, STEER_AND_SEMITRAILER_UNSPRUNG_MASS, SUSPENSION_DAMPING_RATIO,
    SUSPENSION_FREQUENCY, TYRE_DAMPING_TIME, TYRE_STATIC_DEFLECTION,
};
pub use spec::{
    Articulation, AxleSpec, BodySpec, Dimension, MovingForce, MultibodySpec, Suspension,
    VehicleDescription, VehicleSpec, MAXIMUM_CENTRE_OF_MASS_HEIGHT,
};

use nalgebra::DMatrix;

/// Why a vehicle description cannot be assembled. Each variant carries the offending numbers.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VehicleError {
    /// A mass, inertia, stiffness, length or load that must be positive is not.
    #[error("{quantity} is {value}; it must be a positive finite number")]
    NotPositive {
        /// What the number is, for example `axle 3 tyre stiffness`.
        quantity: String,
        /// The offending value.
        value: f64,
    },
    /// A damping coefficient or offset that must be zero or positive is not.
    #[error("{quantity} is {value}; it must be zero or a positive finite number")]
    Negative {
        /// What the number is.
        quantity: String,
        /// The offending value.
        value: f64,
    },
    /// A length above its physical limit.
    #[error("{quantity} is {value} m; it must be at most {limit} m")]
    TooHigh {
        /// What the number is.
        quantity: String,
        /// The offending value [m].
        value: f64,
        /// The largest value allowed [m].
        limit: f64,
    },
    /// A centre-of-mass height on a body without a pitch DOF, which could not carry the moment.
    #[error("body `{body}` has a centre-of-mass height but no pitch inertia: the pitch moment of braking and acceleration acts on the body's pitch, so give its pitch inertia or remove the height")]
    HeightWithoutPitch {
        /// The body's name.
        body: String,
    },
    /// A position that must be finite is not.
    #[error("{quantity} is {value}; it must be a finite number")]
    NotFinite {
        /// What the number is.
        quantity: String,
        /// The offending value.
        value: f64,
    },
    /// The wheel track or the suspension spacing of an axle is wider than its body.
    #[error("axle {axle}: {what} {value} m is wider than the {width} m width of body `{body}`")]
    WiderThanBody {
        /// Axle number, 1-based, front to back.
        axle: usize,
        /// `wheel track` or `suspension spacing`.
        what: &'static str,
        /// The offending lateral distance [m].
        value: f64,
        /// The body's width [m].
        width: f64,
        /// The body's name.
        body: String,
    },
    /// An axle or an articulation names a body that does not exist (or a later body).
    #[error("{what} refers to body {body}, but only bodies 1 to {allowed} are allowed there")]
    UnknownBody {
        /// Which reference, for example `axle 2` or `articulation of body 2`.
        what: String,
        /// The body number given, 1-based.
        body: usize,
        /// The highest body number allowed there.
        allowed: usize,
    },
    /// Axles must be listed front to back, each behind the previous one.
    #[error("axle {axle} at {position} m is not behind axle {previous_axle} at {previous_position} m; list axles front to back")]
    AxlesOutOfOrder {
        /// Axle number, 1-based.
        axle: usize,
        /// Its longitudinal position [m].
        position: f64,
        /// The previous axle's number.
        previous_axle: usize,
        /// Its longitudinal position [m].
        previous_position: f64,
    },
    /// An articulated body has no pitch degree of freedom.
    #[error("body `{body}` is articulated, so it needs a pitch inertia (its pitch is what remains free)")]
    ArticulatedWithoutPitch {
        /// The body's name.
        body: String,
    },
    /// A vehicle with nothing touching the road.
    #[error("the vehicle has no {what}")]
    Empty {
        /// `axles`, `bodies` or `forces`.
        what: &'static str,
    },
    /// Two bodies share a name, or a body name clashes with the axle DOF names.
    #[error("body name `{name}` is not allowed: {reason}")]
    BadBodyName {
        /// The name.
        name: String,
        /// Why.
        reason: &'static str,
    },
    /// K is singular or indefinite: some motion is not held by any spring (a mechanism).
    #[error("the vehicle is not statically stable: its stiffness matrix is not positive definite (a degree of freedom, such as the pitch of a body on one axle, is held by no spring; check axle positions and articulations)")]
    Unstable,
    /// M is not positive definite.
    #[error("the mass matrix is not positive definite")]
    MassNotPositiveDefinite,
}

/// How a tyre meets the road.
#[derive(Debug, Clone, PartialEq)]
pub enum ContactKind {
    /// A constant moving force: the contact has no stiffness and no DOF (the paper's §2 load).
    Force,
    /// A tyre spring and damper under a wheel whose vertical displacement is a combination of
    /// vehicle DOFs.
    Tyre {
        /// Tyre stiffness k_t [N/m].
        stiffness: f64,
        /// Tyre damping c_t [N·s/m].
        damping: f64,
        /// Wheel vertical displacement [m] = Σ coefficient · Z[dof] (upwards positive).
        coupling: Vec<(usize, f64)>,
    },
}

/// One tyre contact (one wheel, or one axle of a 2D model).
#[derive(Debug, Clone, PartialEq)]
pub struct TyreContact {
    /// Position along the direction of travel relative to the front axle [m]; ≤ 0.
    pub longitudinal_offset: f64,
    /// Lateral position from the vehicle centreline [m], positive to the left.
    pub lateral_offset: f64,
    /// Static load on the road at equilibrium [N], downwards positive.
    pub static_load: f64,
    /// Force-only or tyre.
    pub kind: ContactKind,
}

/// A vehicle as the solver needs it. DOFs Z are measured from static equilibrium on a flat rigid
/// road, upwards positive; so gravity is already balanced by the static tyre loads.
#[derive(Debug, Clone, PartialEq)]
pub struct VehicleModel {
    /// Name (preset name or file stem).
    pub name: String,
    /// One name per DOF, for example `tractor_bounce`, `axle3_roll`.
    pub dof_names: Vec<String>,
    /// Mass matrix M_v [kg, kg·m²].
    pub mass_matrix: DMatrix<f64>,
    /// Damping matrix C_v [N·s/m, ...].
    pub damping_matrix: DMatrix<f64>,
    /// Stiffness matrix K_v, suspension and tyres on a rigid road [N/m, ...].
    pub stiffness_matrix: DMatrix<f64>,
    /// Tyre contacts, front to back.
    pub contacts: Vec<TyreContact>,
    /// The generalised load per unit longitudinal acceleration s̈ of the vehicle, as (DOF,
    /// coefficient) [kg·m on a pitch DOF, N·m per m/s²]: f_Z += s̈ Σ coefficient·e_DOF, the
    /// d'Alembert pitch moments m_b·h_b·s̈ of the bodies with a centre-of-mass height h_b
    /// (nose-up positive, Tᵀ of the physical moments). Empty when no body has a height.
    pub pitch_load_per_acceleration: Vec<(usize, f64)>,
}

impl VehicleModel {
    /// Number of vehicle DOFs.
    pub fn dof_count(&self) -> usize {
        self.dof_names.len()
    }

    /// Number of axles: the distinct longitudinal offsets of the contacts (tyres of one axle
    /// share one offset, to within a millimetre).
    pub fn axle_count(&self) -> usize {
        let mut offsets: Vec<f64> = self
            .contacts
            .iter()
            .map(|c| c.longitudinal_offset)
            .collect();
        offsets.sort_by(f64::total_cmp);
        offsets.dedup_by(|a, b| (*a - *b).abs() < 1e-3);
        offsets.len()
    }

    /// The lateral spread of the wheels, max − min lateral offset of the contacts [m]: the
    /// spacing of the two wheel tracks (0 for a vehicle on one track, a 2D model).
    pub fn track_spacing(&self) -> f64 {
        let offsets = self.contacts.iter().map(|c| c.lateral_offset);
        let high = offsets.clone().fold(f64::NEG_INFINITY, f64::max);
        let low = offsets.fold(f64::INFINITY, f64::min);
        if high >= low {
            high - low
        } else {
            0.0
        }
    }

    /// Total weight carried by the contacts [N].
    pub fn total_static_load(&self) -> f64 {
        self.contacts.iter().map(|c| c.static_load).sum()
    }

    /// How far the last contact trails the front one, max(0, −min offset) [m] (offsets are
    /// from the front axle, negative behind it).
    pub fn trailing_length(&self) -> f64 {
        self.contacts
            .iter()
            .map(|c| -c.longitudinal_offset)
            .fold(0.0, f64::max)
    }
}
