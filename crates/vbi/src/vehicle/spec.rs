//! A vehicle described as data: moving forces, or rigid bodies, articulations, axles,
//! suspensions and tyres. [`super::assemble`] turns a description into a
//! [`super::VehicleModel`].
//!
//! Coordinates: x along the vehicle, positive forwards (the direction of travel), origin
//! anywhere (conventionally the front axle, so the other axles have negative x); y lateral,
//! positive to the left; z vertical, positive upwards. Pitch is positive nose-up (a point at x
//! ahead of the centre of mass rises by (x − x_cg)·θ); roll is positive left side up (a point at
//! lateral offset y rises by y·φ).

use serde::{Deserialize, Serialize};

use super::VehicleError;

/// A vehicle described as data, with its name and where its parameters come from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VehicleSpec {
    /// Name (preset name or file stem).
    pub name: String,
    /// Source of the parameters, or "representative values" where no source gives them.
    pub source: String,
    /// Forces or multibody model.
    pub description: VehicleDescription,
}

/// What the vehicle is made of.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum VehicleDescription {
    /// Constant moving forces, one per axle (the paper's §2 load); no DOFs.
    MovingForces(Vec<MovingForce>),
    /// A multibody sprung vehicle (paper §3.1, Eq. 19).
    Multibody(MultibodySpec),
}

/// One axle of constant moving forces.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MovingForce {
    /// Longitudinal position x [m], positive forwards (front axle conventionally 0).
    pub longitudinal_position: f64,
    /// Axle load [N], downwards positive.
    pub axle_load: f64,
    /// Wheel track [m]: 0 gives one force on the centreline; > 0 gives two wheel forces of half
    /// the axle load at ±track/2. Default 0.
    pub track: f64,
}

/// Planar (2D, no roll) or spatial (3D) model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Dimension {
    /// 2D: no roll DOFs; one wheel per axle on the centreline; suspension and tyre stiffness
    /// and damping are per axle.
    Planar,
    /// 3D: roll DOFs on every body and axle; two wheels per axle (left and right); suspension
    /// stiffness and damping are per side, tyre stiffness and damping per wheel.
    Spatial,
}

/// A multibody vehicle: rigid bodies carrying axles through suspensions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MultibodySpec {
    /// Planar or spatial.
    pub dimension: Dimension,
    /// Rigid bodies (tractor, semitrailer, ...). An articulated body must follow the body it
    /// hangs from.
    pub bodies: Vec<BodySpec>,
    /// Axles, listed front to back.
    pub axles: Vec<AxleSpec>,
}

/// A rigid body with bounce, pitch and roll DOFs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BodySpec {
    /// Name, for example `tractor`; DOFs are named `<name>_bounce`, `<name>_pitch`, `<name>_roll`.
    pub name: String,
    /// Mass [kg].
    pub mass: f64,
    /// Pitch moment of inertia about the centre of mass [kg·m²]; `None`: no pitch DOF (a body
    /// on a single axle, such as the quarter car).
    pub pitch_inertia: Option<f64>,
    /// Roll moment of inertia about the centre of mass [kg·m²]; used by spatial models only.
    pub roll_inertia: f64,
    /// Longitudinal position of the centre of mass x [m], positive forwards.
    pub longitudinal_position: f64,
    /// Overall width [m], the limit of wheel track and suspension spacing. Presets use 2.5 m.
    pub width: f64,
    /// Fifth-wheel hinge tying this body's bounce to a leading body; `None` for a free body.
    pub articulation: Option<Articulation>,
    /// Height h of the centre of mass above the road [m], in (0, 4]; `None`: not given (no
    /// preset gives one), and braking or acceleration then pitches nothing. With it, a
    /// longitudinal acceleration s̈ of the vehicle loads the body's pitch with the d'Alembert
    /// moment M_θ = m·h·s̈ (nose-up positive: braking, s̈ < 0, pitches the nose down and loads
    /// the front axles). Needs a pitch DOF.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub centre_of_mass_height: Option<f64>,
}

/// A fifth-wheel hinge: the trailing body's bounce follows the leading body at the hinge,
/// z_j + (x_h − x_j)·θ_j = z_i + (x_h − x_i)·θ_i. Pitch and roll stay free.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Articulation {
    /// Index (0-based) of the leading body; it must come before the articulated body.
    pub leading_body: usize,
    /// Longitudinal position of the hinge x_h [m], positive forwards.
    pub longitudinal_position: f64,
}

/// An axle: wheels on the road, hung from a body through a suspension (or fixed to it).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AxleSpec {
    /// Index (0-based) of the body carrying the axle.
    pub body: usize,
    /// Longitudinal position x [m], positive forwards.
    pub longitudinal_position: f64,
    /// The unsprung mass and its suspension; `None`: the tyre is attached to the body directly
    /// (the single sprung mass of VBI-2D).
    pub suspension: Option<Suspension>,
    /// Tyre stiffness k_t [N/m], per wheel (spatial) or per axle (planar).
    pub tyre_stiffness: f64,
    /// Tyre damping c_t [N·s/m], per wheel (spatial) or per axle (planar). Default 0.
    pub tyre_damping: f64,
    /// Wheel track [m], the lateral distance between the left and right wheel (centres of the
    /// dual tyres); spatial models only.
    pub track: f64,
}

/// An unsprung axle mass (bounce and roll DOFs) and the springs and dampers above it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Suspension {
    /// Unsprung mass of the axle with its wheels [kg].
    pub unsprung_mass: f64,
    /// Roll moment of inertia of the axle [kg·m²]; spatial models only.
    pub roll_inertia: f64,
    /// Suspension stiffness k_s [N/m], per side (spatial) or per axle (planar).
    pub stiffness: f64,
    /// Suspension damping c_s [N·s/m], per side (spatial) or per axle (planar). Default 0.
    pub damping: f64,
    /// Lateral distance between the left and right suspension springs [m]; spatial only.
    pub spacing: f64,
}

impl VehicleSpec {
    /// Total mass [kg]: bodies and unsprung masses, or the axle loads divided by g.
    pub fn total_mass(&self) -> f64 {
        match &self.description {
            VehicleDescription::MovingForces(forces) => {
                forces.iter().map(|f| f.axle_load).sum::<f64>() / crate::units::GRAVITY
            }
            VehicleDescription::Multibody(spec) => {
                spec.bodies.iter().map(|b| b.mass).sum::<f64>()
                    + spec
                        .axles
                        .iter()
                        .filter_map(|a| a.suspension.as_ref())
                        .map(|s| s.unsprung_mass)
                        .sum::<f64>()
            }
        }
    }

    /// Checks every number and reference; [`super::assemble`] calls it first.
    pub fn validate(&self) -> Result<(), VehicleError> {
        match &self.description {
            VehicleDescription::MovingForces(forces) => validate_forces(forces),
            VehicleDescription::Multibody(spec) => spec.validate(),
        }
    }
}

fn positive(quantity: impl FnOnce() -> String, value: f64) -> Result<(), VehicleError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(VehicleError::NotPositive {
            quantity: quantity(),
            value,
        })
    }
}

fn non_negative(quantity: impl FnOnce() -> String, value: f64) -> Result<(), VehicleError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(VehicleError::Negative {
            quantity: quantity(),
            value,
        })
    }
}

fn finite(quantity: impl FnOnce() -> String, value: f64) -> Result<(), VehicleError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(VehicleError::NotFinite {
            quantity: quantity(),
            value,
        })
    }
}

fn validate_forces(forces: &[MovingForce]) -> Result<(), VehicleError> {
    if forces.is_empty() {
        return Err(VehicleError::Empty { what: "forces" });
    }
    for (i, f) in forces.iter().enumerate() {
        let n = i + 1;
        finite(|| format!("force {n} position"), f.longitudinal_position)?;
        positive(|| format!("force {n} axle load"), f.axle_load)?;
        non_negative(|| format!("force {n} track"), f.track)?;
    }
    Ok(())
}

impl MultibodySpec {
    /// Checks masses, stiffnesses, widths, references and the axle order.
    pub fn validate(&self) -> Result<(), VehicleError> {
        let spatial = self.dimension == Dimension::Spatial;
        if self.bodies.is_empty() {
            return Err(VehicleError::Empty { what: "bodies" });
        }
        if self.axles.is_empty() {
            return Err(VehicleError::Empty { what: "axles" });
        }
        for (i, body) in self.bodies.iter().enumerate() {
            let name = &body.name;
            if name.is_empty() || is_axle_name(name) {
                return Err(VehicleError::BadBodyName {
                    name: name.clone(),
                    reason: "a body name must not be empty nor of the form `axle<number>` (kept for axle DOFs)",
                });
            }
            if self.bodies[..i].iter().any(|b| &b.name == name) {
                return Err(VehicleError::BadBodyName {
                    name: name.clone(),
                    reason: "two bodies have this name",
                });
            }
            positive(|| format!("body `{name}` mass"), body.mass)?;
            if let Some(inertia) = body.pitch_inertia {
                positive(|| format!("body `{name}` pitch inertia"), inertia)?;
            }
            if spatial {
                positive(|| format!("body `{name}` roll inertia"), body.roll_inertia)?;
            }
            finite(
                || format!("body `{name}` position"),
                body.longitudinal_position,
            )?;
            positive(|| format!("body `{name}` width"), body.width)?;
            validate_height(body)?;
            if let Some(hinge) = &body.articulation {
                if hinge.leading_body >= i {
                    return Err(VehicleError::UnknownBody {
                        what: format!("the articulation of body `{name}`"),
                        body: hinge.leading_body + 1,
                        allowed: i,
                    });
                }
                if body.pitch_inertia.is_none() {
                    return Err(VehicleError::ArticulatedWithoutPitch { body: name.clone() });
                }
                finite(
                    || format!("body `{name}` hinge position"),
                    hinge.longitudinal_position,
                )?;
            }
        }
        for (i, axle) in self.axles.iter().enumerate() {
            let n = i + 1;
            let Some(body) = self.bodies.get(axle.body) else {
                return Err(VehicleError::UnknownBody {
                    what: format!("axle {n}"),
                    body: axle.body + 1,
                    allowed: self.bodies.len(),
                });
            };
            finite(|| format!("axle {n} position"), axle.longitudinal_position)?;
            if i > 0 {
                let previous = self.axles[i - 1].longitudinal_position;
                if axle.longitudinal_position >= previous {
                    return Err(VehicleError::AxlesOutOfOrder {
                        axle: n,
                        position: axle.longitudinal_position,
                        previous_axle: i,
                        previous_position: previous,
                    });
                }
            }
            positive(|| format!("axle {n} tyre stiffness"), axle.tyre_stiffness)?;
            non_negative(|| format!("axle {n} tyre damping"), axle.tyre_damping)?;
            if spatial {
                positive(|| format!("axle {n} wheel track"), axle.track)?;
                if axle.track > body.width {
                    return Err(VehicleError::WiderThanBody {
                        axle: n,
                        what: "wheel track",
                        value: axle.track,
                        width: body.width,
                        body: body.name.clone(),
                    });
                }
            }
            if let Some(s) = &axle.suspension {
                positive(|| format!("axle {n} unsprung mass"), s.unsprung_mass)?;
                positive(|| format!("axle {n} suspension stiffness"), s.stiffness)?;
                non_negative(|| format!("axle {n} suspension damping"), s.damping)?;
                if spatial {
                    positive(|| format!("axle {n} roll inertia"), s.roll_inertia)?;
                    positive(|| format!("axle {n} suspension spacing"), s.spacing)?;
                    if s.spacing > body.width {
                        return Err(VehicleError::WiderThanBody {
                            axle: n,
                            what: "suspension spacing",
                            value: s.spacing,
                            width: body.width,
                            body: body.name.clone(),
                        });
                    }
                }
            }
        }
        Ok(())
    }
}

/// Highest centre of mass allowed [m] (a body taller than the 4 m height limit of most roads).
pub const MAXIMUM_CENTRE_OF_MASS_HEIGHT: f64 = 4.0;

/// A centre-of-mass height in (0, 4] m, on a body with a pitch DOF (the moment acts on it).
fn validate_height(body: &BodySpec) -> Result<(), VehicleError> {
    let Some(height) = body.centre_of_mass_height else {
        return Ok(());
    };
    let name = &body.name;
    positive(|| format!("body `{name}` centre-of-mass height"), height)?;
    if height > MAXIMUM_CENTRE_OF_MASS_HEIGHT {
        return Err(VehicleError::TooHigh {
            quantity: format!("body `{name}` centre-of-mass height"),
            value: height,
            limit: MAXIMUM_CENTRE_OF_MASS_HEIGHT,
        });
    }
    if body.pitch_inertia.is_none() {
        return Err(VehicleError::HeightWithoutPitch { body: name.clone() });
    }
    Ok(())
}

/// Whether a name has the form `axle<digits>` (reserved for axle DOF names).
pub(super) fn is_axle_name(name: &str) -> bool {
    name.strip_prefix("axle")
        .is_some_and(|rest| !rest.is_empty() && rest.chars().all(|c| c.is_ascii_digit()))
}
