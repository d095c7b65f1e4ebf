//! Built-in vehicles. Each states the source of its parameters, or "representative values"
//! where no public source gives them (the paper's Fig. 8 truck and the field-test truck have no
//! published parameters).

use super::spec::{
    Articulation, AxleSpec, BodySpec, Dimension, MovingForce, MultibodySpec, Suspension,
    VehicleDescription, VehicleSpec,
};
use crate::units::GRAVITY;

/// Names of the built-in vehicles, in the order `vbi vehicle list` shows them.
pub const PRESET_NAMES: [&str; 8] = [
    "moving-force",
    "moving-forces-hs20",
    "sprung-mass",
    "quarter-car",
    "two-axle-truck-vbi2d",
    "three-axle-truck-36t",
    "tractor-semitrailer-5axle",
    "hs20-44",
];

/// The built-in vehicle of that name, or `None`.
pub fn preset(name: &str) -> Option<VehicleSpec> {
    let spec = match name {
        "moving-force" => moving_force(),
        "moving-forces-hs20" => moving_forces_hs20(),
        "sprung-mass" => sprung_mass(),
        "quarter-car" => quarter_car(),
        "two-axle-truck-vbi2d" => two_axle_truck_vbi2d(),
        "three-axle-truck-36t" => three_axle_truck_36t(),
        "tractor-semitrailer-5axle" => tractor_semitrailer_5axle(),
        "hs20-44" => hs20_44(),
        _ => return None,
    };
    Some(spec)
}

/// All built-in vehicles, in the order of [`PRESET_NAMES`].
pub fn presets() -> Vec<VehicleSpec> {
    PRESET_NAMES.iter().filter_map(|n| preset(n)).collect()
}

/// One kip [N] (1000 lbf = 4448.2216 N), for the AASHTO loads.
const KIP: f64 = 4_448.221_615_260_5;
/// One foot [m].
const FOOT: f64 = 0.3048;
/// Overall width used by the presets [m] (the 2.5 m legal limit of most codes).
const WIDTH: f64 = 2.5;

/// Mass of the VBI-2D sprung mass [kg] (docs/verification.md §9).
const VBI2D_SPRUNG_MASS: f64 = 5750.0;

fn moving_force() -> VehicleSpec {
    VehicleSpec {
        name: "moving-force".into(),
        source: "one constant force P = 5750 kg × 9.81 m/s² = 56.41 kN, the weight of the VBI-2D \
                 sprung mass (docs/verification.md §9), for the Frýba moving-force case"
            .into(),
        description: VehicleDescription::MovingForces(vec![MovingForce {
            longitudinal_position: 0.0,
            axle_load: VBI2D_SPRUNG_MASS * GRAVITY,
            track: 0.0,
        }]),
    }
}

fn moving_forces_hs20() -> VehicleSpec {
    VehicleSpec {
        name: "moving-forces-hs20".into(),
        source:
            "AASHTO Standard Specifications HS20-44 design truck as constant forces: axle loads \
                 8, 32, 32 kip (35.6, 142.3, 142.3 kN), axle spacings 14 ft (4.27 m, the \
                 minimum of the variable rear spacing), wheel spacing 6 ft (1.83 m)"
                .into(),
        description: VehicleDescription::MovingForces(
            [(0.0, 8.0), (-14.0, 32.0), (-28.0, 32.0)]
                .into_iter()
                .map(|(x_ft, load_kip)| MovingForce {
                    longitudinal_position: x_ft * FOOT,
                    axle_load: load_kip * KIP,
                    track: 6.0 * FOOT,
                })
                .collect(),
        ),
    }
}

fn sprung_mass() -> VehicleSpec {
    VehicleSpec {
        name: "sprung-mass".into(),
        source: "VBI-2D verification vehicle (DanielCanteroNTNU/VBI-2D, \
                 V01_Analytical_Verification_Examples.m; docs/verification.md §9): \
                 m = 5750 kg on k = 1.595e6 N/m, c = 0; 1 DOF"
            .into(),
        description: VehicleDescription::Multibody(MultibodySpec {
            dimension: Dimension::Planar,
            bodies: vec![BodySpec {
                name: "body".into(),
                mass: VBI2D_SPRUNG_MASS,
                pitch_inertia: None,
                roll_inertia: 0.0,
                longitudinal_position: 0.0,
                width: WIDTH,
                articulation: None,
                centre_of_mass_height: None,
            }],
            axles: vec![AxleSpec {
                body: 0,
                longitudinal_position: 0.0,
                suspension: None,
                tyre_stiffness: 1.595e6,
                tyre_damping: 0.0,
                track: 0.0,
            }],
        }),
    }
}

fn quarter_car() -> VehicleSpec {
    VehicleSpec {
        name: "quarter-car".into(),
        source: "representative values for one corner of a heavy truck: sprung 3000 kg, unsprung \
                 350 kg, suspension 4.0e5 N/m and 1.0e4 N·s/m, tyre 1.75e6 N/m; 2 DOF"
            .into(),
        description: VehicleDescription::Multibody(MultibodySpec {
            dimension: Dimension::Planar,
            bodies: vec![BodySpec {
                name: "body".into(),
                mass: 3000.0,
                pitch_inertia: None,
                roll_inertia: 0.0,
                longitudinal_position: 0.0,
                width: WIDTH,
                articulation: None,
                centre_of_mass_height: None,
            }],
            axles: vec![AxleSpec {
                body: 0,
                longitudinal_position: 0.0,
                suspension: Some(Suspension {
                    unsprung_mass: 350.0,
                    roll_inertia: 0.0,
                    stiffness: 4.0e5,
                    damping: 1.0e4,
                    spacing: 0.0,
                }),
                tyre_stiffness: 1.75e6,
                tyre_damping: 0.0,
                track: 0.0,
            }],
        }),
    }
}

fn two_axle_truck_vbi2d() -> VehicleSpec {
    let axle = |x: f64| AxleSpec {
        body: 0,
        longitudinal_position: x,
        suspension: Some(Suspension {
            unsprung_mass: 900.0,
            roll_inertia: 0.0,
            stiffness: 6.0e6,
            damping: 1.0e4,
            spacing: 0.0,
        }),
        tyre_stiffness: 1.75e6,
        tyre_damping: 0.0,
        track: 0.0,
    };
    VehicleSpec {
        name: "two-axle-truck-vbi2d".into(),
        source: "VBI-2D E01_Example.m two-axle rigid truck (DanielCanteroNTNU/VBI-2D; \
                 docs/verification.md §9): body 10500 kg, pitch inertia 5.0e4 kg·m², axles \
                 at ±2.5 m, suspension 6e6 N/m and 1e4 N·s/m per axle, axle 900 kg, tyre \
                 1.75e6 N/m, no tyre damping; 4 DOF"
            .into(),
        description: VehicleDescription::Multibody(MultibodySpec {
            dimension: Dimension::Planar,
            bodies: vec![BodySpec {
                name: "body".into(),
                mass: 10500.0,
                pitch_inertia: Some(5.0e4),
                roll_inertia: 0.0,
                longitudinal_position: -2.5,
                width: WIDTH,
                articulation: None,
                centre_of_mass_height: None,
            }],
            axles: vec![axle(0.0), axle(-5.0)],
        }),
    }
}

/// A spatial axle with a suspension.
fn spatial_axle(
    body: usize,
    x: f64,
    unsprung_mass: f64,
    roll_inertia: f64,
    suspension_stiffness: f64,
    suspension_damping: f64,
    tyre_stiffness: f64,
    track: f64,
) -> AxleSpec {
    AxleSpec {
        body,
        longitudinal_position: x,
        suspension: Some(Suspension {
            unsprung_mass,
            roll_inertia,
            stiffness: suspension_stiffness,
            damping: suspension_damping,
            spacing: 1.0,
        }),
        tyre_stiffness,
        tyre_damping: 2.0e3,
        track,
    }
}

fn body(name: &str, mass: f64, pitch: f64, roll: f64, x: f64) -> BodySpec {
    BodySpec {
        name: name.into(),
        mass,
        pitch_inertia: Some(pitch),
        roll_inertia: roll,
        longitudinal_position: x,
        width: WIDTH,
        articulation: None,
        centre_of_mass_height: None,
    }
}

fn three_axle_truck_36t() -> VehicleSpec {
    VehicleSpec {
        name: "three-axle-truck-36t".into(),
        source: "representative values: the paper's field test used a 36 t three-axle truck \
                 (§5) without publishing its parameters. A 6×4 rigid truck: axles at 0, −3.8, \
                 −5.15 m; body 32 900 kg, unsprung 700 + 2 × 1200 kg; suspension 0.9e6 / 1.65e6 \
                 N/m per side, tyres 1.0e6 / 2.0e6 N/m per wheel (dual rear); centre of mass \
                 placed for about 8 t on the front axle and 14 t on each rear axle; 9 DOF"
            .into(),
        description: VehicleDescription::Multibody(MultibodySpec {
            dimension: Dimension::Spatial,
            bodies: vec![body("truck", 32_900.0, 1.6e5, 3.0e4, -3.48)],
            axles: vec![
                spatial_axle(0, 0.0, 700.0, 450.0, 0.9e6, 1.0e4, 1.0e6, 2.0),
                spatial_axle(0, -3.8, 1200.0, 900.0, 1.65e6, 1.5e4, 2.0e6, 1.85),
                spatial_axle(0, -5.15, 1200.0, 900.0, 1.65e6, 1.5e4, 2.0e6, 1.85),
            ],
        }),
    }
}

fn tractor_semitrailer_5axle() -> VehicleSpec {
    let mut trailer = body("semitrailer", 31_800.0, 4.5e5, 3.5e4, -7.76);
    trailer.articulation = Some(Articulation {
        leading_body: 0,
        longitudinal_position: -3.7,
    });
    VehicleSpec {
        name: "tractor-semitrailer-5axle".into(),
        source: "representative values for the paper's five-axle 3D tractor–semitrailer (§4.1, \
                 Fig. 8; 15 DOF: tractor bounce, pitch, roll; semitrailer pitch, roll; 5 axles × \
                 bounce, roll), whose parameters the paper does not publish. A 3-axle tractor \
                 (axles 0, −3.3, −4.65 m, fifth wheel −3.7 m) and a 2-axle semitrailer (axles \
                 −11.0, −12.35 m), 43 t, about 7 t on the steer axle and 9 t on each other axle"
            .into(),
        description: VehicleDescription::Multibody(MultibodySpec {
            dimension: Dimension::Spatial,
            bodies: vec![body("tractor", 6_300.0, 2.0e4, 6.0e3, -0.68), trailer],
            axles: vec![
                spatial_axle(0, 0.0, 700.0, 500.0, 1.0e6, 1.0e4, 1.0e6, 2.0),
                spatial_axle(0, -3.3, 1200.0, 900.0, 0.9e6, 1.0e4, 2.0e6, 1.85),
                spatial_axle(0, -4.65, 1200.0, 900.0, 0.9e6, 1.0e4, 2.0e6, 1.85),
                spatial_axle(1, -11.0, 900.0, 700.0, 0.95e6, 1.0e4, 2.0e6, 1.85),
                spatial_axle(1, -12.35, 900.0, 700.0, 0.95e6, 1.0e4, 2.0e6, 1.85),
            ],
        }),
    }
}

/// HS20-44 axle loads [N]: 8, 32, 32 kip.
pub(crate) const HS20_AXLE_LOADS: [f64; 3] = [8.0 * KIP, 32.0 * KIP, 32.0 * KIP];

fn hs20_44() -> VehicleSpec {
    // Geometry (AASHTO): axles 14 ft apart (the minimum rear spacing), wheels 6 ft apart.
    let x = [0.0, -14.0 * FOOT, -28.0 * FOOT];
    let hinge = x[1] + 0.3;
    let unsprung = [600.0, 1100.0, 1100.0];
    let trailer_mass = 24_000.0;
    // Body loads on each axle [kg] so that the axle loads are the AASHTO ones.
    let body_load: Vec<f64> = (0..3)
        .map(|i| HS20_AXLE_LOADS[i] / GRAVITY - unsprung[i])
        .collect();
    // The vehicle is statically determinate: the semitrailer rests on the hinge and axle 3,
    // the tractor on axles 1 and 2 and the hinge load.
    let hinge_load = trailer_mass - body_load[2];
    let trailer_x = hinge - body_load[2] * (hinge - x[2]) / trailer_mass;
    let tractor_mass = body_load[0] + body_load[1] - hinge_load;
    let tractor_x =
        x[1] + (body_load[0] * (x[0] - x[1]) - hinge_load * (hinge - x[1])) / tractor_mass;
    let track = 6.0 * FOOT;
    let mut trailer = body("semitrailer", trailer_mass, 3.0e5, 2.5e4, trailer_x);
    trailer.articulation = Some(Articulation {
        leading_body: 0,
        longitudinal_position: hinge,
    });
    VehicleSpec {
        name: "hs20-44".into(),
        source: "AASHTO HS20-44 tractor–semitrailer as a 3D model with 11 DOF (the model type of \
                 Wang & Huang 1992): geometry and static axle loads from AASHTO (8, 32, 32 kip; \
                 14 ft axle spacing; 6 ft wheel spacing), with the centres of mass placed to give \
                 exactly those loads; masses, inertias, springs and dampers are representative \
                 values"
            .into(),
        description: VehicleDescription::Multibody(MultibodySpec {
            dimension: Dimension::Spatial,
            bodies: vec![
                body("tractor", tractor_mass, 1.6e4, 5.0e3, tractor_x),
                trailer,
            ],
            axles: vec![
                spatial_axle(0, x[0], unsprung[0], 400.0, 0.33e6, 5.0e3, 0.875e6, track),
                spatial_axle(0, x[1], unsprung[1], 900.0, 1.5e6, 1.5e4, 2.0e6, track),
                spatial_axle(1, x[2], unsprung[2], 900.0, 1.5e6, 1.5e4, 2.0e6, track),
            ],
        }),
    }
}
