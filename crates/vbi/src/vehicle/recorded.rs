//! A planar multibody truck built from a weigh-in-motion record (axle spacings and static axle
//! loads), for the recorded traffic of `vbi lifetime` (docs/lifetime.md).
//!
//! The record gives only where the axles are and what each carries. The masses, springs and
//! dampers are representative values chosen so that the model's static tyre loads equal the
//! recorded axle loads exactly (to round-off), whatever the axle count and grouping:
//!
//! - every suspension deflects by the same δ_s and every tyre by the same δ_t under its static
//!   load (k_s,i = F_i^s / δ_s, k_t,i = F_i / δ_t), so every body sits level;
//! - the centre of mass of every body is placed where the recorded axle loads balance it.
//!
//! With every body level at bounce −(δ_s + δ_t) and every axle at −δ_t, each suspension carries
//! k_s,i δ_s = F_i^s and each tyre k_t,i δ_t = F_i = F_i^s + m_u,i g; the bodies are in
//! equilibrium by the placement of their centres of mass. As the stiffness matrix is positive
//! definite this is the unique static solution, so [`super::assemble`] finds exactly these loads
//! even for tandem and tridem groups on one body (statically indeterminate in general).

use super::spec::{
    Articulation, AxleSpec, BodySpec, Dimension, MultibodySpec, Suspension, VehicleDescription,
    VehicleSpec,
};
use super::VehicleError;
use crate::units::GRAVITY;

/// Smallest axle spacing behind the tractor's first axle that marks a fifth-wheel articulation
/// [m] (4.0 m): representative value; tandem and tridem groups are spaced 1.2–1.5 m and a
/// tractor's steer-to-drive spacing (excluded from the rule) is 3–4 m, while the gap from a
/// tractor's drive group to a semitrailer's axle group is typically 5–8 m.
pub const ARTICULATION_GAP: f64 = 4.0;

/// Distance of the fifth wheel ahead of the centroid of the tractor's axles behind its first
/// one [m] (0.3 m): representative value (fifth wheels sit a little ahead of the drive axles
/// so that they load the steer axle too; the `hs20-44` preset uses the same 0.3 m).
pub const FIFTH_WHEEL_AHEAD: f64 = 0.3;

/// Uncoupled natural frequency of every suspension under its sprung share, f_s [Hz] (2.0 Hz):
/// representative value in the 1.5–4 Hz body-bounce range of heavy vehicles (Cebon 1999,
/// Handbook of Vehicle–Road Interaction, ch. 4). It fixes the static suspension deflection
/// δ_s = g / (2π f_s)² (62 mm).
pub const SUSPENSION_FREQUENCY: f64 = 2.0;

/// Static deflection of every tyre under its recorded load, δ_t [m] (0.025 m): a loaded truck
/// tyre deflects 2–3 cm, about 0.9 MN/m for a 22 kN wheel load (Cebon 1999, ch. 4).
pub const TYRE_STATIC_DEFLECTION: f64 = 0.025;

/// Damping ratio of every suspension under its sprung share, ζ_s [-] (0.10): equivalent viscous
/// damping of steel and air suspensions is 5–20 % (Cebon 1999, ch. 4).
pub const SUSPENSION_DAMPING_RATIO: f64 = 0.10;

/// Tyre damping per unit tyre stiffness, c_t / k_t [s] (0.002 s): vbi's presets use 2 kN·s/m
/// for a 1 MN/m tyre.
pub const TYRE_DAMPING_TIME: f64 = 0.002;

/// Nominal unsprung mass of a steer axle and of a semitrailer axle [kg] (700 kg): Cebon 1999
/// gives 500–1200 kg per heavy-vehicle axle, the lighter end for steer and trailer axles.
pub const STEER_AND_SEMITRAILER_UNSPRUNG_MASS: f64 = 700.0;

/// Nominal unsprung mass of a drive or other tractor or rigid-truck axle [kg] (1000 kg):
/// Cebon 1999 gives 500–1200 kg per heavy-vehicle axle, the heavier end for drive axles.
pub const DRIVE_UNSPRUNG_MASS: f64 = 1000.0;

/// Largest share of an axle's recorded load taken as its unsprung weight [-] (0.3): keeps a
/// sprung share F_i^s = F_i − m_u,i g > 0 on lightly loaded axles; representative value.
pub const MAXIMUM_UNSPRUNG_SHARE: f64 = 0.3;

/// Overall body width [m] (2.5 m, as the presets: the legal limit of most codes).
const WIDTH: f64 = 2.5;

/// Tractor sprung weight as a multiple of its steer axle's sprung share, at most [-] (1.2):
/// representative value (a loaded tractor unit weighs 7–9 t with 6–7 t on its steer axle).
const TRACTOR_WEIGHT_PER_STEER_LOAD: f64 = 1.2;

/// Tractor sprung weight as a share of the sprung load on the tractor's axles, at most [-] (0.6):
/// representative value, so that the fifth wheel carries at least 40 % of it.
const TRACTOR_WEIGHT_SHARE: f64 = 0.6;

/// Radius of gyration in pitch per metre of a body's support extent [-] (0.3): representative
/// value (ρ ≈ 0.3 L for a uniform-ish body of length L, 1/√12 = 0.29 for a uniform bar).
const GYRATION_PER_LENGTH: f64 = 0.3;

/// Body length beyond its supports, front and rear overhang together [m] (2 m): representative.
const OVERHANG: f64 = 2.0;

/// One loaded axle of the record with its representative unsprung mass.
#[derive(Debug, Clone, Copy)]
struct RecordedAxle {
    /// Longitudinal position x_i [m], front axle at 0.
    position: f64,
    /// Recorded static load F_i [N].
    load: f64,
    /// Unsprung mass m_u,i [kg].
    unsprung_mass: f64,
}

impl RecordedAxle {
    /// m_u,i = min(nominal, 0.3 F_i / g).
    fn new(position: f64, load: f64, nominal_unsprung_mass: f64) -> Self {
        let unsprung_mass = nominal_unsprung_mass.min(MAXIMUM_UNSPRUNG_SHARE * load / GRAVITY);
        RecordedAxle {
            position,
            load,
            unsprung_mass,
        }
    }

    /// Sprung share F_i^s = F_i − m_u,i g [N], > 0.
    fn sprung_load(&self) -> f64 {
        self.load - self.unsprung_mass * GRAVITY
    }
}

/// A planar multibody truck from a weigh-in-motion record whose static tyre loads equal the
/// recorded axle loads exactly (to round-off).
///
/// `axle_spacings` [m], front to back, one fewer than `axle_loads` [N], front first. The front
/// axle is at x = 0 and axle i at x_i = −(sum of the spacings before it). Axles with zero load
/// carry nothing and are left out of the model; the rules below apply to the loaded axles.
///
/// **Articulation**: with three or more axles, if the largest spacing behind the second axle
/// (the first such if several are equal) is at least [`ARTICULATION_GAP`], the truck is a
/// tractor (the axles ahead of that gap) and a semitrailer (the axles behind it), hinged at the
/// fifth wheel x_h, [`FIFTH_WHEEL_AHEAD`] ahead of the mean position of the tractor's axles
/// behind its first. Otherwise one rigid body (`truck`) carries every axle; a single axle gives
/// a body without a pitch DOF.
///
/// **Axles**: unsprung mass m_u,i = min(nominal, 0.3 F_i / g) with the nominal
/// [`STEER_AND_SEMITRAILER_UNSPRUNG_MASS`] or [`DRIVE_UNSPRUNG_MASS`]; sprung share
/// F_i^s = F_i − m_u,i g; suspension k_s,i = F_i^s / δ_s, δ_s = g / (2π f_s)² with f_s =
/// [`SUSPENSION_FREQUENCY`], c_s,i = 2 ζ_s √(k_s,i F_i^s / g) with ζ_s =
/// [`SUSPENSION_DAMPING_RATIO`]; tyre k_t,i = F_i / δ_t with δ_t = [`TYRE_STATIC_DEFLECTION`],
/// c_t,i = [`TYRE_DAMPING_TIME`] · k_t,i.
///
/// **Bodies** (centres of mass from static equilibrium, every body level):
/// - rigid: m g = Σ F_i^s, x_cg = Σ F_i^s x_i / Σ F_i^s;
/// - tractor: sprung weight W_1 = max(F_1^s, min(1.2 F_1^s, 0.6 S_T)), S_T = Σ_tractor F_i^s;
///   hinge load H = S_T − W_1 ≥ 0; vertical equilibrium W_1 + H = S_T, moments
///   W_1 x_1 + H x_h = Σ_tractor F_i^s x_i, so x_1 = (Σ_tractor F_i^s x_i − H x_h) / W_1;
/// - semitrailer: vertical equilibrium m_t g = H + Σ_trailer F_j^s, moments about the hinge
///   m_t g (x_t − x_h) = Σ_trailer F_j^s (x_j − x_h), so
///   x_t = x_h + Σ_trailer F_j^s (x_j − x_h) / (m_t g).
///
/// Pitch inertia m ρ² with the representative radius of gyration ρ = 0.3 (L + 2 m), L the
/// extent of the body's supports (its axles, and the fifth wheel for an articulated vehicle).
///
/// Errors: no axle loads or all zero ([`VehicleError::Empty`]); a spacing count other than
/// loads − 1 (the missing or surplus axle's number as [`VehicleError::NotFinite`]); a spacing
/// not positive and finite ([`VehicleError::NotPositive`]); a load negative or not finite
/// ([`VehicleError::Negative`]).
pub fn multibody_from_axles(
    axle_spacings: &[f64],
    axle_loads: &[f64],
) -> Result<VehicleSpec, VehicleError> {
    validate_record(axle_spacings, axle_loads)?;
    let loaded: Vec<(f64, f64)> = axle_positions(axle_spacings)
        .into_iter()
        .zip(axle_loads.iter().copied())
        .filter(|&(_, load)| load > 0.0)
        .collect();
    if loaded.is_empty() {
        return Err(VehicleError::Empty {
            what: "loaded axles",
        });
    }
    let first_semitrailer_axle = first_semitrailer_axle(&loaded);
    let axles: Vec<RecordedAxle> = loaded
        .iter()
        .enumerate()
        .map(|(i, &(position, load))| {
            let steer_or_semitrailer = i == 0 || first_semitrailer_axle.is_some_and(|s| i >= s);
            let nominal = if steer_or_semitrailer {
                STEER_AND_SEMITRAILER_UNSPRUNG_MASS
            } else {
                DRIVE_UNSPRUNG_MASS
            };
            RecordedAxle::new(position, load, nominal)
        })
        .collect();
    let (bodies, kind) = match first_semitrailer_axle {
        Some(split) => (tractor_and_semitrailer(&axles, split), "articulated"),
        None => (vec![rigid_truck(&axles)], "rigid"),
    };
    let axle_specs = axles
        .iter()
        .enumerate()
        .map(|(i, axle)| {
            let body = usize::from(first_semitrailer_axle.is_some_and(|s| i >= s));
            axle_spec(body, axle)
        })
        .collect();
    Ok(VehicleSpec {
        name: format!("recorded-{}-axle-{kind}", axles.len()),
        source: "built from a weigh-in-motion record's axle spacings and static axle loads \
                 (zero-load axles left out) with representative masses, springs and dampers: \
                 2 Hz suspensions with 10 % damping, 25 mm static tyre deflection, 700/1000 kg \
                 unsprung axles, centres of mass placed for exactly the recorded axle loads \
                 (docs/lifetime.md)"
            .into(),
        description: VehicleDescription::Multibody(MultibodySpec {
            dimension: Dimension::Planar,
            bodies,
            axles: axle_specs,
        }),
    })
}

/// Checks the record: at least one load, one fewer spacing than loads, spacings positive and
/// finite, loads zero or positive and finite.
fn validate_record(axle_spacings: &[f64], axle_loads: &[f64]) -> Result<(), VehicleError> {
    if axle_loads.is_empty() {
        return Err(VehicleError::Empty { what: "axles" });
    }
    let needed = axle_loads.len() - 1;
    if axle_spacings.len() != needed {
        // The first axle without a position (too few spacings) or without a load (too many).
        let (axle, what) = if axle_spacings.len() < needed {
            (axle_spacings.len() + 2, "position")
        } else {
            (axle_loads.len() + 1, "load")
        };
        return Err(VehicleError::NotFinite {
            quantity: format!(
                "axle {axle} {what} ({} axle spacings for {} axle loads; give one fewer \
                 spacing than loads)",
                axle_spacings.len(),
                axle_loads.len()
            ),
            value: f64::NAN,
        });
    }
    for (i, &spacing) in axle_spacings.iter().enumerate() {
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(VehicleError::NotPositive {
                quantity: format!("spacing between axles {} and {}", i + 1, i + 2),
                value: spacing,
            });
        }
    }
    for (i, &load) in axle_loads.iter().enumerate() {
        if !(load.is_finite() && load >= 0.0) {
            return Err(VehicleError::Negative {
                quantity: format!("axle {} load", i + 1),
                value: load,
            });
        }
    }
    Ok(())
}

/// x_1 = 0, x_i = −(sum of the spacings before axle i) [m].
fn axle_positions(axle_spacings: &[f64]) -> Vec<f64> {
    std::iter::once(0.0)
        .chain(axle_spacings.iter().scan(0.0, |behind, spacing| {
            *behind += spacing;
            Some(-*behind)
        }))
        .collect()
}

/// Index of the first semitrailer axle among the loaded axles (position, load), or `None` for
/// a rigid truck: the axle behind the largest gap after the second axle (the first of equal
/// largest), when there are three or more axles and that gap is at least [`ARTICULATION_GAP`].
fn first_semitrailer_axle(loaded: &[(f64, f64)]) -> Option<usize> {
    if loaded.len() < 3 {
        return None;
    }
    let (gap_index, gap) = (1..loaded.len() - 1)
        .map(|i| (i, loaded[i].0 - loaded[i + 1].0))
        .fold((0, f64::NEG_INFINITY), |best, candidate| {
            if candidate.1 > best.1 {
                candidate
            } else {
                best
            }
        });
    (gap >= ARTICULATION_GAP).then_some(gap_index + 1)
}

/// One rigid body carrying every axle: m g = Σ F_i^s, x_cg = Σ F_i^s x_i / Σ F_i^s; no pitch
/// DOF on a single axle.
fn rigid_truck(axles: &[RecordedAxle]) -> BodySpec {
    let sprung: f64 = axles.iter().map(RecordedAxle::sprung_load).sum();
    let moment: f64 = axles.iter().map(|a| a.sprung_load() * a.position).sum();
    let mass = sprung / GRAVITY;
    let positions: Vec<f64> = axles.iter().map(|a| a.position).collect();
    let pitch_inertia = (axles.len() > 1).then(|| pitch_inertia(mass, &positions));
    body("truck", mass, pitch_inertia, moment / sprung, None)
}

/// A tractor (axles before `split`) and a semitrailer (axles from `split`) hinged at the fifth
/// wheel, with the masses and centres of mass of [`multibody_from_axles`].
fn tractor_and_semitrailer(axles: &[RecordedAxle], split: usize) -> Vec<BodySpec> {
    let (tractor_axles, trailer_axles) = axles.split_at(split);
    let behind_steer = &tractor_axles[1..];
    let hinge = behind_steer.iter().map(|a| a.position).sum::<f64>() / behind_steer.len() as f64
        + FIFTH_WHEEL_AHEAD;

    let steer_sprung = tractor_axles[0].sprung_load();
    let tractor_sprung: f64 = tractor_axles.iter().map(RecordedAxle::sprung_load).sum();
    let tractor_weight = steer_sprung.max(
        (TRACTOR_WEIGHT_PER_STEER_LOAD * steer_sprung).min(TRACTOR_WEIGHT_SHARE * tractor_sprung),
    );
    let hinge_load = tractor_sprung - tractor_weight;
    let tractor_moment: f64 = tractor_axles
        .iter()
        .map(|a| a.sprung_load() * a.position)
        .sum();
    let tractor_position = (tractor_moment - hinge_load * hinge) / tractor_weight;

    let trailer_sprung: f64 = trailer_axles.iter().map(RecordedAxle::sprung_load).sum();
    let trailer_weight = hinge_load + trailer_sprung;
    let trailer_moment_about_hinge: f64 = trailer_axles
        .iter()
        .map(|a| a.sprung_load() * (a.position - hinge))
        .sum();
    let trailer_position = hinge + trailer_moment_about_hinge / trailer_weight;

    let supports = |group: &[RecordedAxle]| -> Vec<f64> {
        group
            .iter()
            .map(|a| a.position)
            .chain(std::iter::once(hinge))
            .collect()
    };
    let tractor_mass = tractor_weight / GRAVITY;
    let trailer_mass = trailer_weight / GRAVITY;
    vec![
        body(
            "tractor",
            tractor_mass,
            Some(pitch_inertia(tractor_mass, &supports(tractor_axles))),
            tractor_position,
            None,
        ),
        body(
            "semitrailer",
            trailer_mass,
            Some(pitch_inertia(trailer_mass, &supports(trailer_axles))),
            trailer_position,
            Some(Articulation {
                leading_body: 0,
                longitudinal_position: hinge,
            }),
        ),
    ]
}

/// m ρ² with the representative radius of gyration ρ = 0.3 (L + 2 m), L the extent of the
/// body's supports at `support_positions` [kg·m²].
fn pitch_inertia(mass: f64, support_positions: &[f64]) -> f64 {
    let front = support_positions
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    let rear = support_positions
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    let radius_of_gyration = GYRATION_PER_LENGTH * (front - rear + OVERHANG);
    mass * radius_of_gyration * radius_of_gyration
}

/// A planar body: no roll inertia, no centre-of-mass height, width [`WIDTH`].
fn body(
    name: &str,
    mass: f64,
    pitch_inertia: Option<f64>,
    longitudinal_position: f64,
    articulation: Option<Articulation>,
) -> BodySpec {
    BodySpec {
        name: name.into(),
        mass,
        pitch_inertia,
        roll_inertia: 0.0,
        longitudinal_position,
        width: WIDTH,
        articulation,
        centre_of_mass_height: None,
    }
}

/// A planar axle with uniform static deflections: k_s = F^s / δ_s, c_s = 2 ζ_s √(k_s F^s / g),
/// k_t = F / δ_t, c_t = [`TYRE_DAMPING_TIME`] · k_t.
fn axle_spec(body: usize, axle: &RecordedAxle) -> AxleSpec {
    let suspension_deflection =
        GRAVITY / (2.0 * std::f64::consts::PI * SUSPENSION_FREQUENCY).powi(2);
    let sprung = axle.sprung_load();
    let suspension_stiffness = sprung / suspension_deflection;
    let suspension_damping =
        2.0 * SUSPENSION_DAMPING_RATIO * (suspension_stiffness * sprung / GRAVITY).sqrt();
    let tyre_stiffness = axle.load / TYRE_STATIC_DEFLECTION;
    AxleSpec {
        body,
        longitudinal_position: axle.position,
        suspension: Some(Suspension {
            unsprung_mass: axle.unsprung_mass,
            roll_inertia: 0.0,
            stiffness: suspension_stiffness,
            damping: suspension_damping,
            spacing: 0.0,
        }),
        tyre_stiffness,
        tyre_damping: TYRE_DAMPING_TIME * tyre_stiffness,
        track: 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vehicle::{assemble, natural_frequencies};

    const KILONEWTON: f64 = 1.0e3;

    /// A record: axle spacings [m], axle loads [N], expected body count in the model.
    struct Layout {
        spacings: Vec<f64>,
        loads: Vec<f64>,
        bodies: usize,
    }

    fn layout(spacings: &[f64], loads_kn: &[f64], bodies: usize) -> Layout {
        Layout {
            spacings: spacings.to_vec(),
            loads: loads_kn.iter().map(|l| l * KILONEWTON).collect(),
            bodies,
        }
    }

    /// Layouts from 1 to 6 axles, rigid and articulated, with a light empty trailer axle
    /// (15 kN) and zero-load (lifted) axles.
    fn layouts() -> Vec<Layout> {
        vec![
            layout(&[], &[50.0], 1),
            layout(&[5.0], &[60.0, 100.0], 1),
            layout(&[3.8, 1.35], &[70.0, 95.0, 95.0], 1),
            layout(&[3.6, 7.0], &[60.0, 100.0, 15.0], 2),
            layout(&[1.9, 3.4, 1.35], &[60.0, 60.0, 90.0, 90.0], 1),
            layout(&[3.6, 5.5, 1.3], &[65.0, 100.0, 80.0, 0.0], 2),
            layout(&[3.6, 6.0, 1.31, 1.31], &[70.0, 110.0, 75.0, 75.0, 75.0], 2),
            layout(&[3.3, 1.35, 6.3, 1.35], &[62.0, 90.0, 90.0, 15.0, 15.0], 2),
            layout(
                &[3.4, 1.35, 5.8, 1.31, 1.31],
                &[70.0, 95.0, 95.0, 0.0, 80.0, 80.0],
                2,
            ),
        ]
    }

    fn relative_difference(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    /// Equilibrium invariant (uniform static deflection, centres of mass from the equilibrium
    /// equations of `multibody_from_axles`): every static tyre load from `assemble` equals the
    /// recorded axle load, and their sum the gross weight.
    #[test]
    fn static_tyre_loads_equal_recorded_axle_loads_by_static_equilibrium() {
        for record in layouts() {
            let spec = multibody_from_axles(&record.spacings, &record.loads).unwrap();
            let VehicleDescription::Multibody(multibody) = &spec.description else {
                panic!("{}: not a multibody vehicle", spec.name);
            };
            assert_eq!(multibody.bodies.len(), record.bodies, "{}", spec.name);
            let model = assemble(&spec).unwrap();
            let recorded: Vec<f64> = record.loads.iter().copied().filter(|l| *l > 0.0).collect();
            assert_eq!(model.contacts.len(), recorded.len(), "{}", spec.name);
            for (contact, load) in model.contacts.iter().zip(&recorded) {
                assert!(
                    relative_difference(contact.static_load, *load) < 1e-9,
                    "{}: static load {} N for recorded {load} N",
                    spec.name,
                    contact.static_load
                );
            }
            let gross: f64 = record.loads.iter().sum();
            assert!(relative_difference(model.total_static_load(), gross) < 1e-9);
        }
    }

    /// Mass conservation: the description validates and its total mass weighs the gross weight.
    #[test]
    fn total_mass_weighs_the_recorded_gross_weight() {
        for record in layouts() {
            let spec = multibody_from_axles(&record.spacings, &record.loads).unwrap();
            spec.validate().unwrap();
            let gross: f64 = record.loads.iter().sum();
            assert!(
                relative_difference(spec.total_mass() * GRAVITY, gross) < 1e-12,
                "{}",
                spec.name
            );
        }
    }

    /// Natural frequencies of a 40 t five-axle tractor–semitrailer in the published ranges:
    /// body bounce and pitch 1–4 Hz, axle hop 8–20 Hz (Cebon 1999, ch. 4; OBrien et al. 2010).
    #[test]
    fn natural_frequencies_of_a_40_tonne_five_axle_truck_lie_in_the_published_ranges_cebon_1999() {
        let tonnes = [7.0, 11.0, 7.0, 7.5, 7.5];
        let loads: Vec<f64> = tonnes.iter().map(|t| t * 1.0e3 * GRAVITY).collect();
        let spec = multibody_from_axles(&[3.6, 6.0, 1.31, 1.31], &loads).unwrap();
        let model = assemble(&spec).unwrap();
        let frequencies = natural_frequencies(&model).unwrap();
        let lowest = frequencies.first().unwrap().0;
        let highest = frequencies.last().unwrap().0;
        assert!((1.0..=4.0).contains(&lowest), "lowest {lowest} Hz");
        assert!((8.0..=20.0).contains(&highest), "highest {highest} Hz");
    }

    #[test]
    fn invalid_records_are_errors() {
        let loads = [60.0e3, 100.0e3, 100.0e3];
        assert!(matches!(
            multibody_from_axles(&[3.8], &loads),
            Err(VehicleError::NotFinite { .. })
        ));
        assert!(matches!(
            multibody_from_axles(&[3.8, 1.3, 1.3], &loads),
            Err(VehicleError::NotFinite { .. })
        ));
        assert!(matches!(
            multibody_from_axles(&[3.8, 1.3], &[60.0e3, -1.0, 100.0e3]),
            Err(VehicleError::Negative { .. })
        ));
        assert!(matches!(
            multibody_from_axles(&[3.8, 1.3], &[60.0e3, f64::NAN, 100.0e3]),
            Err(VehicleError::Negative { .. })
        ));
        assert!(matches!(
            multibody_from_axles(&[3.8, 0.0], &loads),
            Err(VehicleError::NotPositive { .. })
        ));
        assert!(matches!(
            multibody_from_axles(&[f64::INFINITY, 1.3], &loads),
            Err(VehicleError::NotPositive { .. })
        ));
        assert!(matches!(
            multibody_from_axles(&[3.8, 1.3], &[0.0, 0.0, 0.0]),
            Err(VehicleError::Empty { .. })
        ));
        assert!(matches!(
            multibody_from_axles(&[], &[]),
            Err(VehicleError::Empty { .. })
        ));
    }
}
