//! A vehicle description written as a `[vehicle]` file, the inverse of [`crate::vehicle::load`]:
//! what `vbi lifetime` writes for each truck of a governing event, so that the event replays
//! with `vbi run`. Every number is written as Rust's shortest representation that reads back
//! to the same f64, so that the file loads to the same description bit for bit (tested).

use std::fmt::Write;

use vbi::units::KN;
use vbi::vehicle::{Dimension, MultibodySpec, VehicleDescription, VehicleSpec};

/// The `[vehicle]` file of `spec`.
pub fn vehicle_toml(spec: &VehicleSpec) -> String {
    let mut text = String::new();
    let _ = writeln!(text, "[vehicle]");
    let _ = writeln!(text, "name = {}", quoted(&spec.name));
    let _ = writeln!(text, "source = {}", quoted(&spec.source));
    match &spec.description {
        VehicleDescription::MovingForces(forces) => {
            for force in forces {
                let _ = writeln!(text, "\n[[vehicle.forces]]");
                let _ = writeln!(text, "position_m = {:?}", force.longitudinal_position);
                let _ = writeln!(text, "load_kn = {:?}", force.axle_load / KN);
                let _ = writeln!(text, "track_m = {:?}", force.track);
            }
        }
        VehicleDescription::Multibody(multibody) => write_multibody(&mut text, multibody),
    }
    text
}

/// The bodies and axles of a multibody description.
fn write_multibody(text: &mut String, multibody: &MultibodySpec) {
    let spatial = multibody.dimension == Dimension::Spatial;
    let dimension = if spatial { "spatial" } else { "planar" };
    let _ = writeln!(text, "dimension = \"{dimension}\"");
    for body in &multibody.bodies {
        let _ = writeln!(text, "\n[[vehicle.bodies]]");
        let _ = writeln!(text, "name = {}", quoted(&body.name));
        let _ = writeln!(text, "mass_kg = {:?}", body.mass);
        if let Some(pitch) = body.pitch_inertia {
            let _ = writeln!(text, "pitch_inertia_kg_m2 = {pitch:?}");
        }
        if spatial {
            let _ = writeln!(text, "roll_inertia_kg_m2 = {:?}", body.roll_inertia);
        }
        let _ = writeln!(text, "position_m = {:?}", body.longitudinal_position);
        let _ = writeln!(text, "width_m = {:?}", body.width);
        if let Some(hinge) = &body.articulation {
            let leading = &multibody.bodies[hinge.leading_body].name;
            let _ = writeln!(text, "articulated_to = {}", quoted(leading));
            let _ = writeln!(text, "hinge_position_m = {:?}", hinge.longitudinal_position);
        }
        if let Some(height) = body.centre_of_mass_height {
            let _ = writeln!(text, "centre_of_mass_height_m = {height:?}");
        }
    }
    for axle in &multibody.axles {
        let _ = writeln!(text, "\n[[vehicle.axles]]");
        let body = &multibody.bodies[axle.body].name;
        let _ = writeln!(text, "body = {}", quoted(body));
        let _ = writeln!(text, "position_m = {:?}", axle.longitudinal_position);
        if let Some(suspension) = &axle.suspension {
            let _ = writeln!(text, "mass_kg = {:?}", suspension.unsprung_mass);
            if spatial {
                let _ = writeln!(text, "roll_inertia_kg_m2 = {:?}", suspension.roll_inertia);
                let _ = writeln!(text, "suspension_spacing_m = {:?}", suspension.spacing);
            }
            let _ = writeln!(
                text,
                "suspension_stiffness_n_per_m = {:?}",
                suspension.stiffness
            );
            let _ = writeln!(
                text,
                "suspension_damping_n_s_per_m = {:?}",
                suspension.damping
            );
        }
        let _ = writeln!(text, "tyre_stiffness_n_per_m = {:?}", axle.tyre_stiffness);
        let _ = writeln!(text, "tyre_damping_n_s_per_m = {:?}", axle.tyre_damping);
        if spatial {
            let _ = writeln!(text, "track_m = {:?}", axle.track);
        }
    }
}

/// A TOML basic string.
pub fn quoted(text: &str) -> String {
    toml::Value::String(text.to_string()).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::SourceFile;

    fn read_back(spec: &VehicleSpec) -> VehicleSpec {
        let text = vehicle_toml(spec);
        let file = SourceFile::from_text("written.toml".into(), text);
        crate::vehicle::load(&file).expect("the written file loads")
    }

    /// Every preset and vehicles built from weigh-in-motion records (rigid, articulated)
    /// written and read back: the same description, bit for bit (the inverse of the reader).
    #[test]
    fn a_written_vehicle_reads_back_to_the_same_description_bit_for_bit() {
        let mut specs = vbi::vehicle::presets();
        let records: [(&[f64], &[f64]); 3] = [
            (&[5.0], &[60e3, 100e3]),
            (&[3.6, 6.0, 1.31, 1.31], &[62e3, 95e3, 78e3, 80e3, 76e3]),
            (&[3.2, 1.35, 6.1, 1.35], &[70e3, 105e3, 104e3, 15e3, 15e3]),
        ];
        for (spacings, loads) in records {
            specs.push(vbi::vehicle::multibody_from_axles(spacings, loads).unwrap());
        }
        for spec in specs {
            assert_eq!(read_back(&spec), spec, "{}", spec.name);
        }
    }
}
