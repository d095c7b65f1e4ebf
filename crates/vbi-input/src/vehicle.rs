//! The `[vehicle]` input file: a preset with overrides, moving forces, or a full multibody
//! description (docs/input-format.md, section `[vehicle]`).
//!
//! ```toml
//! [vehicle]
//! preset = "three-axle-truck-36t"
//! [[vehicle.axles]]
//! index = 2                              # overrides axle 2 of the preset
//! suspension_stiffness_n_per_m = 1.4e6
//! ```

use std::path::Path;

use serde::Deserialize;
use vbi::units::KN;
use vbi::vehicle::{
    assemble, preset, Articulation, AxleSpec, BodySpec, Dimension, MovingForce, MultibodySpec,
    Suspension, VehicleDescription, VehicleModel, VehicleSpec, MAXIMUM_CENTRE_OF_MASS_HEIGHT,
    PRESET_NAMES,
};

use crate::source::{require_in_range, require_positive, shown, InputError, SourceFile};

/// Widest body allowed [m] (wide special transports; legal limits are 2.5–2.6 m).
const MAXIMUM_WIDTH: f64 = 4.0;
/// Body width when `width_m` is not given [m].
const DEFAULT_WIDTH: f64 = 2.5;

/// Other top-level tables are allowed here: a scenario file inlines `[vehicle]` beside
/// `[scenario]`; `vbi_input::validate` checks the top-level keys of each kind of file.
#[derive(Debug, Deserialize)]
struct Document {
    vehicle: VehicleTable,
}

/// The `[vehicle]` table as written.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VehicleTable {
    name: Option<String>,
    source: Option<String>,
    preset: Option<String>,
    dimension: Option<String>,
    #[serde(default)]
    bodies: Vec<BodyTable>,
    #[serde(default)]
    axles: Vec<AxleTable>,
    #[serde(default)]
    forces: Vec<ForceTable>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct BodyTable {
    name: Option<String>,
    mass_kg: Option<f64>,
    pitch_inertia_kg_m2: Option<f64>,
    roll_inertia_kg_m2: Option<f64>,
    position_m: Option<f64>,
    width_m: Option<f64>,
    articulated_to: Option<String>,
    hinge_position_m: Option<f64>,
    centre_of_mass_height_m: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct AxleTable {
    index: Option<i64>,
    body: Option<String>,
    position_m: Option<f64>,
    mass_kg: Option<f64>,
    roll_inertia_kg_m2: Option<f64>,
    suspension_stiffness_n_per_m: Option<f64>,
    suspension_damping_n_s_per_m: Option<f64>,
    suspension_spacing_m: Option<f64>,
    tyre_stiffness_n_per_m: Option<f64>,
    tyre_damping_n_s_per_m: Option<f64>,
    track_m: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct ForceTable {
    index: Option<i64>,
    position_m: Option<f64>,
    load_kn: Option<f64>,
    track_m: Option<f64>,
}

/// Validates a `[vehicle]` file (it must also assemble).
pub fn validate(file: &SourceFile) -> Result<(), InputError> {
    load_model(file).map(|_| ())
}

/// Reads the vehicle description of a `[vehicle]` file, checked field by field and assembled
/// once to be sure it is statically stable.
pub fn load(file: &SourceFile) -> Result<VehicleSpec, InputError> {
    let document: Document = file.parse()?;
    let stem = file
        .path
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_else(|| "vehicle".into());
    let spec = build(file, &document.vehicle, "vehicle", &stem)?;
    assemble_checked(file, "vehicle", &spec)?;
    Ok(spec)
}

/// Reads and assembles a `[vehicle]` file.
pub fn load_model(file: &SourceFile) -> Result<VehicleModel, InputError> {
    let spec = load(file)?;
    assemble_checked(file, "vehicle", &spec)
}

/// A vehicle named on the command line or in another file: a path to a `[vehicle]` file (an
/// existing file, or anything ending in `.toml`), otherwise a preset name.
pub fn resolve(reference: &str) -> Result<VehicleSpec, InputError> {
    let path = Path::new(reference);
    if path.is_file() || reference.ends_with(".toml") {
        let file = SourceFile::read(path)?;
        crate::kind::expect_kind(&file, "vehicle", "vbi vehicle show")?;
        return load(&file);
    }
    preset(reference).ok_or_else(|| {
        InputError::command_line(
            "vehicle",
            format!(
                "`{reference}` is neither a file nor a preset; expected a [vehicle] TOML file or \
                 one of: {}",
                PRESET_NAMES.join(", ")
            ),
        )
    })
}

/// Assembles, turning a library error into an input error at `path`.
pub fn assemble_checked(
    file: &SourceFile,
    path: &str,
    spec: &VehicleSpec,
) -> Result<VehicleModel, InputError> {
    assemble(spec).map_err(|e| file.error_at(path, e.to_string()))
}

/// Builds the description from a `[vehicle]` table found at `path` (dotted) in `file`; `name`
/// is the default name.
pub fn build(
    file: &SourceFile,
    table: &VehicleTable,
    path: &str,
    name: &str,
) -> Result<VehicleSpec, InputError> {
    let mut spec = match &table.preset {
        Some(preset_name) => {
            let mut spec = preset(preset_name).ok_or_else(|| {
                file.error_at(
                    &format!("{path}.preset"),
                    format!(
                        "unknown preset `{preset_name}`; expected one of: {}",
                        PRESET_NAMES.join(", ")
                    ),
                )
            })?;
            if table.dimension.is_some() {
                return Err(file.error_at(
                    &format!("{path}.dimension"),
                    "a preset has its own dimension; remove `dimension` or the preset",
                ));
            }
            spec.name = table.name.clone().unwrap_or(spec.name);
            if let Some(source) = &table.source {
                spec.source = source.clone();
            }
            apply_overrides(file, table, path, &mut spec)?;
            spec
        }
        None => VehicleSpec {
            name: table.name.clone().unwrap_or_else(|| name.to_string()),
            source: table
                .source
                .clone()
                .unwrap_or_else(|| "user input".to_string()),
            description: describe(file, table, path)?,
        },
    };
    if spec.name.trim().is_empty() {
        spec.name = name.to_string();
    }
    Ok(spec)
}

/// A full description without a preset.
fn describe(
    file: &SourceFile,
    table: &VehicleTable,
    path: &str,
) -> Result<VehicleDescription, InputError> {
    if !table.forces.is_empty() {
        if !table.bodies.is_empty() || !table.axles.is_empty() {
            return Err(file.error_at(
                &format!("{path}.forces"),
                "give either `forces` (moving forces) or `bodies` and `axles` (a sprung vehicle), \
                 not both",
            ));
        }
        let mut forces = Vec::new();
        for (i, f) in table.forces.iter().enumerate() {
            let p = format!("{path}.forces[{i}]");
            if f.index.is_some() {
                return Err(file.error_at(
                    &format!("{p}.index"),
                    "`index` selects an entry of a preset to override; without `preset` list \
                     every force instead",
                ));
            }
            let mut force = MovingForce {
                longitudinal_position: 0.0,
                axle_load: 0.0,
                track: 0.0,
            };
            force.longitudinal_position = required(file, &p, "position_m", f.position_m)?;
            force.axle_load = required(file, &p, "load_kn", f.load_kn)? * KN;
            apply_force(file, &p, f, &mut force)?;
            forces.push(force);
        }
        return Ok(VehicleDescription::MovingForces(forces));
    }
    let dimension = match table.dimension.as_deref() {
        None | Some("spatial") | Some("3d") => Dimension::Spatial,
        Some("planar") | Some("2d") => Dimension::Planar,
        Some(other) => {
            return Err(file.error_at(
                &format!("{path}.dimension"),
                format!("`{other}` is not allowed; expected `spatial` (3D) or `planar` (2D)"),
            ))
        }
    };
    if table.bodies.is_empty() {
        return Err(file.error_at(
            &format!("{path}.bodies"),
            "is required: at least one [[vehicle.bodies]] (or a `preset`, or [[vehicle.forces]])",
        ));
    }
    if table.axles.is_empty() {
        return Err(file.error_at(
            &format!("{path}.axles"),
            "is required: at least one [[vehicle.axles]]",
        ));
    }
    let mut spec = MultibodySpec {
        dimension,
        bodies: Vec::new(),
        axles: Vec::new(),
    };
    for (i, b) in table.bodies.iter().enumerate() {
        let p = format!("{path}.bodies[{i}]");
        if b.name.is_none() {
            return Err(file.error_at(
                &format!("{p}.name"),
                "is required (for example \"tractor\")",
            ));
        }
        let mut body = BodySpec {
            name: String::new(),
            mass: required(file, &p, "mass_kg", b.mass_kg)?,
            pitch_inertia: None,
            roll_inertia: 0.0,
            longitudinal_position: required(file, &p, "position_m", b.position_m)?,
            width: DEFAULT_WIDTH,
            articulation: None,
            centre_of_mass_height: None,
        };
        if dimension == Dimension::Spatial {
            body.roll_inertia = required(file, &p, "roll_inertia_kg_m2", b.roll_inertia_kg_m2)?;
        }
        spec.bodies.push(body);
    }
    for (i, b) in table.bodies.iter().enumerate() {
        let p = format!("{path}.bodies[{i}]");
        apply_body(file, &p, b, &mut spec, i)?;
    }
    for (i, a) in table.axles.iter().enumerate() {
        let p = format!("{path}.axles[{i}]");
        if a.index.is_some() {
            return Err(file.error_at(
                &format!("{p}.index"),
                "`index` selects an axle of a preset to override; without `preset` list every \
                 axle instead, front to back",
            ));
        }
        let spatial = dimension == Dimension::Spatial;
        let mut axle = AxleSpec {
            body: 0,
            longitudinal_position: required(file, &p, "position_m", a.position_m)?,
            suspension: None,
            tyre_stiffness: required(file, &p, "tyre_stiffness_n_per_m", a.tyre_stiffness_n_per_m)?,
            tyre_damping: 0.0,
            track: if spatial {
                required(file, &p, "track_m", a.track_m)?
            } else {
                0.0
            },
        };
        if a.mass_kg.is_some() {
            axle.suspension = Some(Suspension {
                unsprung_mass: 0.0,
                roll_inertia: if spatial {
                    required(file, &p, "roll_inertia_kg_m2", a.roll_inertia_kg_m2)?
                } else {
                    0.0
                },
                stiffness: required(
                    file,
                    &p,
                    "suspension_stiffness_n_per_m",
                    a.suspension_stiffness_n_per_m,
                )?,
                damping: 0.0,
                spacing: if spatial {
                    required(file, &p, "suspension_spacing_m", a.suspension_spacing_m)?
                } else {
                    0.0
                },
            });
        }
        spec.axles.push(axle);
        apply_axle(file, &p, a, &mut spec, i)?;
    }
    check_axle_order(file, path, &spec)?;
    Ok(VehicleDescription::Multibody(spec))
}

/// Overrides given entries of a preset.
fn apply_overrides(
    file: &SourceFile,
    table: &VehicleTable,
    path: &str,
    spec: &mut VehicleSpec,
) -> Result<(), InputError> {
    match &mut spec.description {
        VehicleDescription::MovingForces(forces) => {
            if let Some(p) = [("bodies", table.bodies.len()), ("axles", table.axles.len())]
                .iter()
                .find(|(_, n)| *n > 0)
            {
                return Err(file.error_at(
                    &format!("{path}.{}", p.0),
                    "this preset is made of moving forces; override [[vehicle.forces]] instead",
                ));
            }
            for (i, f) in table.forces.iter().enumerate() {
                let p = format!("{path}.forces[{i}]");
                let k = override_index(file, &p, f.index, forces.len(), "force")?;
                if let Some(x) = f.position_m {
                    forces[k].longitudinal_position = x;
                }
                if let Some(load) = f.load_kn {
                    forces[k].axle_load = load * KN;
                }
                apply_force(file, &p, f, &mut forces[k])?;
            }
        }
        VehicleDescription::Multibody(multibody) => {
            if !table.forces.is_empty() {
                return Err(file.error_at(
                    &format!("{path}.forces"),
                    "this preset is a sprung vehicle; override [[vehicle.bodies]] or \
                     [[vehicle.axles]] instead",
                ));
            }
            for (i, b) in table.bodies.iter().enumerate() {
                let p = format!("{path}.bodies[{i}]");
                let names: Vec<&str> = multibody.bodies.iter().map(|b| b.name.as_str()).collect();
                let Some(name) = &b.name else {
                    return Err(file.error_at(
                        &format!("{p}.name"),
                        format!(
                            "is required: the name of the preset body to override, one of: {}",
                            names.join(", ")
                        ),
                    ));
                };
                let Some(k) = names.iter().position(|n| n == name) else {
                    return Err(file.error_at(
                        &format!("{p}.name"),
                        format!(
                            "the preset has no body `{name}`; expected one of: {}",
                            names.join(", ")
                        ),
                    ));
                };
                if let Some(mass) = b.mass_kg {
                    multibody.bodies[k].mass = mass;
                }
                if let Some(x) = b.position_m {
                    multibody.bodies[k].longitudinal_position = x;
                }
                if let Some(roll) = b.roll_inertia_kg_m2 {
                    multibody.bodies[k].roll_inertia = roll;
                }
                apply_body(file, &p, b, multibody, k)?;
            }
            for (i, a) in table.axles.iter().enumerate() {
                let p = format!("{path}.axles[{i}]");
                let k = override_index(file, &p, a.index, multibody.axles.len(), "axle")?;
                let axle = &mut multibody.axles[k];
                if let Some(x) = a.position_m {
                    axle.longitudinal_position = x;
                }
                if let Some(k_t) = a.tyre_stiffness_n_per_m {
                    axle.tyre_stiffness = k_t;
                }
                if let Some(track) = a.track_m {
                    axle.track = track;
                }
                if let Some(s) = &mut axle.suspension {
                    if let Some(roll) = a.roll_inertia_kg_m2 {
                        s.roll_inertia = roll;
                    }
                    if let Some(k_s) = a.suspension_stiffness_n_per_m {
                        s.stiffness = k_s;
                    }
                    if let Some(spacing) = a.suspension_spacing_m {
                        s.spacing = spacing;
                    }
                } else if let Some((key, _)) = [
                    ("mass_kg", a.mass_kg),
                    ("roll_inertia_kg_m2", a.roll_inertia_kg_m2),
                    (
                        "suspension_stiffness_n_per_m",
                        a.suspension_stiffness_n_per_m,
                    ),
                    (
                        "suspension_damping_n_s_per_m",
                        a.suspension_damping_n_s_per_m,
                    ),
                    ("suspension_spacing_m", a.suspension_spacing_m),
                ]
                .into_iter()
                .find(|(_, v)| v.is_some())
                {
                    return Err(file.error_at(
                        &format!("{p}.{key}"),
                        "this preset axle has no suspension (its tyre is fixed to the body)",
                    ));
                }
                apply_axle(file, &p, a, multibody, k)?;
            }
            check_axle_order(file, path, multibody)?;
            // Fields that were not overridden come from the preset and are valid; the ones
            // that were are checked above. Re-check the preset-relative limits (track within
            // the possibly overridden width) for every axle.
            for k in 0..multibody.axles.len() {
                check_widths(file, &format!("{path}.axles[{k}]"), multibody, k)?;
            }
        }
    }
    Ok(())
}

/// The 0-based entry that an override's 1-based `index` selects.
fn override_index(
    file: &SourceFile,
    path: &str,
    index: Option<i64>,
    count: usize,
    what: &str,
) -> Result<usize, InputError> {
    match index {
        Some(i) if i >= 1 && (i as usize) <= count => Ok(i as usize - 1),
        Some(i) => Err(file.error_at(
            &format!("{path}.index"),
            format!(
                "{i} is not allowed; expected a number from 1 to {count} (the {what}s of the \
                 preset, front to back)"
            ),
        )),
        None => Err(file.error_at(
            &format!("{path}.index"),
            format!("is required: the {what} of the preset to override, from 1 to {count}"),
        )),
    }
}

fn required(
    file: &SourceFile,
    path: &str,
    key: &str,
    value: Option<f64>,
) -> Result<f64, InputError> {
    value.ok_or_else(|| file.error_at(&format!("{path}.{key}"), "is required"))
}

/// Checks (and stores) the optional force fields.
fn apply_force(
    file: &SourceFile,
    path: &str,
    table: &ForceTable,
    force: &mut MovingForce,
) -> Result<(), InputError> {
    if let Some(track) = table.track_m {
        force.track = track;
    }
    finite(
        file,
        &format!("{path}.position_m"),
        force.longitudinal_position,
    )?;
    require_positive(file, &format!("{path}.load_kn"), force.axle_load / KN, "kN")?;
    require_in_range(
        file,
        &format!("{path}.track_m"),
        force.track,
        0.0,
        MAXIMUM_WIDTH,
        "m",
    )?;
    Ok(())
}

/// Stores and checks the fields of body `k` given by `table`.
fn apply_body(
    file: &SourceFile,
    path: &str,
    table: &BodyTable,
    spec: &mut MultibodySpec,
    k: usize,
) -> Result<(), InputError> {
    let spatial = spec.dimension == Dimension::Spatial;
    if let Some(name) = &table.name {
        let reserved = name
            .strip_prefix("axle")
            .is_some_and(|r| !r.is_empty() && r.chars().all(|c| c.is_ascii_digit()));
        if name.trim().is_empty() || reserved {
            return Err(file.error_at(
                &format!("{path}.name"),
                format!("`{name}` is not allowed; expected a non-empty name not of the form `axle<number>`"),
            ));
        }
        if spec.bodies[..k].iter().any(|b| &b.name == name) {
            return Err(file.error_at(
                &format!("{path}.name"),
                format!("`{name}` is already the name of another body; names must differ"),
            ));
        }
        spec.bodies[k].name = name.clone();
    }
    if let Some(pitch) = table.pitch_inertia_kg_m2 {
        spec.bodies[k].pitch_inertia = Some(pitch);
    }
    if let Some(width) = table.width_m {
        spec.bodies[k].width = width;
    }
    if let Some(height) = table.centre_of_mass_height_m {
        spec.bodies[k].centre_of_mass_height = Some(height);
    }
    let body = &spec.bodies[k];
    require_positive(file, &format!("{path}.mass_kg"), body.mass, "kg")?;
    if let Some(pitch) = body.pitch_inertia {
        require_positive(file, &format!("{path}.pitch_inertia_kg_m2"), pitch, "kg·m²")?;
    }
    if spatial {
        require_positive(
            file,
            &format!("{path}.roll_inertia_kg_m2"),
            body.roll_inertia,
            "kg·m²",
        )?;
    }
    finite(
        file,
        &format!("{path}.position_m"),
        body.longitudinal_position,
    )?;
    require_in_range(
        file,
        &format!("{path}.width_m"),
        body.width,
        f64::MIN_POSITIVE,
        MAXIMUM_WIDTH,
        "m",
    )?;
    check_height(file, path, &spec.bodies[k])?;
    match (&table.articulated_to, table.hinge_position_m) {
        (Some(leader), hinge) => {
            let earlier: Vec<&str> = spec.bodies[..k].iter().map(|b| b.name.as_str()).collect();
            let Some(leading_body) = earlier.iter().position(|n| n == leader) else {
                return Err(file.error_at(
                    &format!("{path}.articulated_to"),
                    if earlier.is_empty() {
                        format!("the first body cannot be articulated (`{leader}` must be listed before it)")
                    } else {
                        format!(
                            "`{leader}` is not a body listed before this one; expected one of: {}",
                            earlier.join(", ")
                        )
                    },
                ));
            };
            let hinge = hinge.ok_or_else(|| {
                file.error_at(
                    &format!("{path}.hinge_position_m"),
                    "is required with `articulated_to`",
                )
            })?;
            finite(file, &format!("{path}.hinge_position_m"), hinge)?;
            if spec.bodies[k].pitch_inertia.is_none() {
                return Err(file.error_at(
                    &format!("{path}.pitch_inertia_kg_m2"),
                    "is required for an articulated body (its pitch is its free DOF)",
                ));
            }
            spec.bodies[k].articulation = Some(Articulation {
                leading_body,
                longitudinal_position: hinge,
            });
        }
        (None, Some(_)) => {
            return Err(file.error_at(
                &format!("{path}.hinge_position_m"),
                "is allowed only with `articulated_to` (the leading body's name)",
            ))
        }
        (None, None) => {}
    }
    Ok(())
}

/// A centre-of-mass height in (0, 4] m above the road, on a body with a pitch inertia.
fn check_height(file: &SourceFile, path: &str, body: &BodySpec) -> Result<(), InputError> {
    let Some(height) = body.centre_of_mass_height else {
        return Ok(());
    };
    let at = format!("{path}.centre_of_mass_height_m");
    if !(height.is_finite() && height > 0.0 && height <= MAXIMUM_CENTRE_OF_MASS_HEIGHT) {
        return Err(file.error_at(
            &at,
            format!(
                "{} is not allowed; expected more than 0 and at most \
                 {MAXIMUM_CENTRE_OF_MASS_HEIGHT} m (the height of the centre of mass above the \
                 road)",
                shown(height)
            ),
        ));
    }
    if body.pitch_inertia.is_none() {
        return Err(file.error_at(
            &at,
            "needs the body's pitch DOF: give `pitch_inertia_kg_m2` (the braking moment acts on \
             the pitch), or remove the height",
        ));
    }
    Ok(())
}

/// Stores and checks the fields of axle `k` given by `table`.
fn apply_axle(
    file: &SourceFile,
    path: &str,
    table: &AxleTable,
    spec: &mut MultibodySpec,
    k: usize,
) -> Result<(), InputError> {
    let spatial = spec.dimension == Dimension::Spatial;
    if let Some(body) = &table.body {
        let names: Vec<&str> = spec.bodies.iter().map(|b| b.name.as_str()).collect();
        spec.axles[k].body = names.iter().position(|n| n == body).ok_or_else(|| {
            file.error_at(
                &format!("{path}.body"),
                format!("no body `{body}`; expected one of: {}", names.join(", ")),
            )
        })?;
    }
    if let Some(c_t) = table.tyre_damping_n_s_per_m {
        spec.axles[k].tyre_damping = c_t;
    }
    let axle = &mut spec.axles[k];
    if let Some(s) = &mut axle.suspension {
        if let Some(mass) = table.mass_kg {
            s.unsprung_mass = mass;
        }
        if let Some(c_s) = table.suspension_damping_n_s_per_m {
            s.damping = c_s;
        }
    } else if let Some((key, _)) = [
        ("roll_inertia_kg_m2", table.roll_inertia_kg_m2),
        (
            "suspension_stiffness_n_per_m",
            table.suspension_stiffness_n_per_m,
        ),
        (
            "suspension_damping_n_s_per_m",
            table.suspension_damping_n_s_per_m,
        ),
        ("suspension_spacing_m", table.suspension_spacing_m),
    ]
    .into_iter()
    .find(|(_, v)| v.is_some())
    {
        return Err(file.error_at(
            &format!("{path}.{key}"),
            "a suspension needs the axle's unsprung mass: give `mass_kg`, or remove the \
             suspension keys for a tyre fixed to the body",
        ));
    }
    let axle = &spec.axles[k];
    finite(
        file,
        &format!("{path}.position_m"),
        axle.longitudinal_position,
    )?;
    require_positive(
        file,
        &format!("{path}.tyre_stiffness_n_per_m"),
        axle.tyre_stiffness,
        "N/m",
    )?;
    non_negative(
        file,
        &format!("{path}.tyre_damping_n_s_per_m"),
        axle.tyre_damping,
        "N·s/m",
    )?;
    if let Some(s) = &axle.suspension {
        require_positive(file, &format!("{path}.mass_kg"), s.unsprung_mass, "kg")?;
        require_positive(
            file,
            &format!("{path}.suspension_stiffness_n_per_m"),
            s.stiffness,
            "N/m",
        )?;
        non_negative(
            file,
            &format!("{path}.suspension_damping_n_s_per_m"),
            s.damping,
            "N·s/m",
        )?;
        if spatial {
            require_positive(
                file,
                &format!("{path}.roll_inertia_kg_m2"),
                s.roll_inertia,
                "kg·m²",
            )?;
        }
    }
    check_widths(file, path, spec, k)
}

/// Wheel track and suspension spacing within the width of the axle's body (spatial models).
fn check_widths(
    file: &SourceFile,
    path: &str,
    spec: &MultibodySpec,
    k: usize,
) -> Result<(), InputError> {
    if spec.dimension != Dimension::Spatial {
        return Ok(());
    }
    let axle = &spec.axles[k];
    let body = &spec.bodies[axle.body];
    let within = |key: &str, value: f64| -> Result<(), InputError> {
        if value.is_finite() && value > 0.0 && value <= body.width {
            Ok(())
        } else {
            Err(file.error_at(
                &format!("{path}.{key}"),
                format!(
                    "{} is not allowed; expected more than 0 and at most {} m, the width of \
                     body `{}` (`width_m`)",
                    shown(value),
                    body.width,
                    body.name
                ),
            ))
        }
    };
    within("track_m", axle.track)?;
    if let Some(s) = &axle.suspension {
        within("suspension_spacing_m", s.spacing)?;
    }
    Ok(())
}

fn check_axle_order(file: &SourceFile, path: &str, spec: &MultibodySpec) -> Result<(), InputError> {
    for k in 1..spec.axles.len() {
        let (previous, current) = (
            spec.axles[k - 1].longitudinal_position,
            spec.axles[k].longitudinal_position,
        );
        if current >= previous {
            return Err(file.error_at(
                &format!("{path}.axles[{k}].position_m"),
                format!(
                    "{} is not allowed; axles are listed front to back (x positive \
                     forwards), so axle {} must be behind axle {k} at {} m",
                    shown(current),
                    k + 1,
                    shown(previous)
                ),
            ));
        }
    }
    Ok(())
}

fn finite(file: &SourceFile, path: &str, value: f64) -> Result<f64, InputError> {
    require_in_range(file, path, value, f64::NEG_INFINITY, f64::INFINITY, "m")
}

fn non_negative(file: &SourceFile, path: &str, value: f64, unit: &str) -> Result<f64, InputError> {
    require_in_range(file, path, value, 0.0, f64::INFINITY, unit)
}
