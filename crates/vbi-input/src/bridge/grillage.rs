//! The keys of a `grillage` bridge: girders of any shape (and the edge girders' own), the deck
//! layers, support and intermediate diaphragms, barriers and bearings (docs/input-format.md).

use serde::Deserialize;
use vbi::model::{
    Barriers, Bearing, BearingKind, BoxGirderDimensions, DeckLayers, Diaphragm, GirderShape,
    GivenSection, Grillage, IGirderDimensions, IntermediateDiaphragms, LateralRestraint,
    TBeamDimensions, VoidedSlabDimensions,
};

use crate::bridge::raw::{RawBearing, RawBridge, RawDeck, RawGirder};
use crate::bridge::shared::{
    bridge_damage, damping, damping_keys, forbid, length, material, spans, support_count_check,
};
use crate::bridge_damage::mode_damping;
use crate::source::{require_in_range, InputError, SourceFile};

/// A `supports` entry given as a table: its kind and its own bearing keys.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGrillageSupport {
    kind: String,
    vertical_stiffness_n_per_m: Option<f64>,
    rotational_stiffness_n_m_per_rad: Option<f64>,
    torsion: Option<String>,
}

/// The names of the girder shapes, as `shape` takes them.
const SHAPES: &str = "\"box\", \"t_beam\", \"i_girder\", \"voided_slab\" or \"properties\"";

/// The keys each girder shape takes (besides `shape`).
fn shape_keys(shape: &str) -> &'static [&'static str] {
    match shape {
        "box" => &[
            "height_m",
            "bottom_width_m",
            "web_thickness_m",
            "bottom_slab_thickness_m",
            "web_inclination",
        ],
        "t_beam" => &["height_m", "web_thickness_m"],
        "i_girder" => &[
            "height_m",
            "top_flange_width_m",
            "top_flange_thickness_m",
            "bottom_flange_width_m",
            "bottom_flange_thickness_m",
            "web_thickness_m",
        ],
        "voided_slab" => &["width_m", "depth_m", "void_diameter_m", "void_count"],
        _ => &[
            "area_m2",
            "second_moment_y_m4",
            "second_moment_z_m4",
            "torsion_constant_m4",
            "centroid_height_m",
            "depth_m",
        ],
    }
}

impl RawGirder {
    /// The keys given, by name.
    fn given(&self) -> Vec<&'static str> {
        let numbers = [
            (self.height_m, "height_m"),
            (self.bottom_width_m, "bottom_width_m"),
            (self.web_thickness_m, "web_thickness_m"),
            (self.bottom_slab_thickness_m, "bottom_slab_thickness_m"),
            (self.web_inclination, "web_inclination"),
            (self.top_flange_width_m, "top_flange_width_m"),
            (self.top_flange_thickness_m, "top_flange_thickness_m"),
            (self.bottom_flange_width_m, "bottom_flange_width_m"),
            (self.bottom_flange_thickness_m, "bottom_flange_thickness_m"),
            (self.width_m, "width_m"),
            (self.depth_m, "depth_m"),
            (self.void_diameter_m, "void_diameter_m"),
            (self.area_m2, "area_m2"),
            (self.second_moment_y_m4, "second_moment_y_m4"),
            (self.second_moment_z_m4, "second_moment_z_m4"),
            (self.torsion_constant_m4, "torsion_constant_m4"),
            (self.centroid_height_m, "centroid_height_m"),
        ];
        let mut given: Vec<&'static str> = numbers
            .iter()
            .filter(|(v, _)| v.is_some())
            .map(|&(_, k)| k)
            .collect();
        if self.void_count.is_some() {
            given.push("void_count");
        }
        given
    }
}

/// Reads one girder table at `path` (`bridge.girder` or `bridge.edge_girder`).
fn girder_shape(file: &SourceFile, raw: &RawGirder, path: &str) -> Result<GirderShape, InputError> {
    let shape = raw.shape.as_deref().unwrap_or("box");
    if !["box", "t_beam", "i_girder", "voided_slab", "properties"].contains(&shape) {
        return Err(file.error_at(
            &format!("{path}.shape"),
            format!("unknown girder shape `{shape}`; expected {SHAPES}"),
        ));
    }
    let allowed = shape_keys(shape);
    if let Some(key) = raw.given().into_iter().find(|k| !allowed.contains(k)) {
        return Err(file.error_at(
            &format!("{path}.{key}"),
            format!(
                "`{key}` is not a key of a `{shape}` girder; expected {}",
                allowed.join(", ")
            ),
        ));
    }
    let number = |value: Option<f64>, key: &str, low: f64, high: f64, unit: &str| {
        let value = value.ok_or_else(|| {
            file.error_at(
                path,
                format!(
                    "a `{shape}` girder needs `{key}`; its keys: {}",
                    allowed.join(", ")
                ),
            )
        })?;
        require_in_range(file, &format!("{path}.{key}"), value, low, high, unit)
    };
    // Lengths: as `length` allows them.
    let need = |value: Option<f64>, key: &str| number(value, key, 1e-3, 100.0, "m");
    Ok(match shape {
        "box" => GirderShape::Box(BoxGirderDimensions {
            height: need(raw.height_m, "height_m")?,
            bottom_width: need(raw.bottom_width_m, "bottom_width_m")?,
            web_thickness: need(raw.web_thickness_m, "web_thickness_m")?,
            bottom_slab_thickness: need(raw.bottom_slab_thickness_m, "bottom_slab_thickness_m")?,
            web_inclination: require_in_range(
                file,
                &format!("{path}.web_inclination"),
                raw.web_inclination.unwrap_or(0.0),
                0.0,
                2.0,
                "(horizontal per unit rise)",
            )?,
        }),
        "t_beam" => GirderShape::TBeam(TBeamDimensions {
            height: need(raw.height_m, "height_m")?,
            web_thickness: need(raw.web_thickness_m, "web_thickness_m")?,
        }),
        "i_girder" => GirderShape::IGirder(IGirderDimensions {
            height: need(raw.height_m, "height_m")?,
            top_flange_width: need(raw.top_flange_width_m, "top_flange_width_m")?,
            top_flange_thickness: need(raw.top_flange_thickness_m, "top_flange_thickness_m")?,
            bottom_flange_width: need(raw.bottom_flange_width_m, "bottom_flange_width_m")?,
            bottom_flange_thickness: need(
                raw.bottom_flange_thickness_m,
                "bottom_flange_thickness_m",
            )?,
            web_thickness: need(raw.web_thickness_m, "web_thickness_m")?,
        }),
        "voided_slab" => {
            let count = number(
                raw.void_count.map(|n| n as f64),
                "void_count",
                1.0,
                100.0,
                "voids",
            )?;
            if count.fract() != 0.0 {
                return Err(file.error_at(
                    &format!("{path}.void_count"),
                    "expected a whole number of voids",
                ));
            }
            GirderShape::VoidedSlab(VoidedSlabDimensions {
                width: need(raw.width_m, "width_m")?,
                depth: need(raw.depth_m, "depth_m")?,
                void_diameter: need(raw.void_diameter_m, "void_diameter_m")?,
                void_count: count as usize,
            })
        }
        _ => GirderShape::Properties(GivenSection {
            area: number(raw.area_m2, "area_m2", 1e-4, 100.0, "m²")?,
            second_moment_y: number(
                raw.second_moment_y_m4,
                "second_moment_y_m4",
                1e-8,
                1e4,
                "m⁴",
            )?,
            second_moment_z: number(
                raw.second_moment_z_m4,
                "second_moment_z_m4",
                1e-8,
                1e4,
                "m⁴",
            )?,
            torsion_constant: number(
                raw.torsion_constant_m4,
                "torsion_constant_m4",
                1e-8,
                1e4,
                "m⁴",
            )?,
            centroid_height: need(raw.centroid_height_m, "centroid_height_m")?,
            depth: need(raw.depth_m, "depth_m")?,
        }),
    })
}

/// One bearing: the keys given over `base` (the `[bridge.bearings]` table or the default).
fn bearing(
    file: &SourceFile,
    raw: &RawBearing,
    path: &str,
    base: Bearing,
) -> Result<Bearing, InputError> {
    let mut bearing = base;
    if let Some(k) = raw.vertical_stiffness_n_per_m {
        bearing.vertical_stiffness = Some(require_in_range(
            file,
            &format!("{path}.vertical_stiffness_n_per_m"),
            k,
            1.0,
            1e15,
            "N/m",
        )?);
    }
    if let Some(k) = raw.rotational_stiffness_n_m_per_rad {
        bearing.rotational_stiffness = require_in_range(
            file,
            &format!("{path}.rotational_stiffness_n_m_per_rad"),
            k,
            0.0,
            1e15,
            "N·m/rad",
        )?;
    }
    match raw.torsion.as_deref() {
        None => {}
        Some("held") => bearing.torsion_free = false,
        Some("free") => bearing.torsion_free = true,
        Some(other) => {
            return Err(file.error_at(
                &format!("{path}.torsion"),
                format!("unknown torsion restraint `{other}`; expected \"held\" or \"free\""),
            ))
        }
    }
    Ok(bearing)
}

/// The support lines' kinds and bearings: `supports` entries are "pinned", "roller" or a table
/// `{ kind, vertical_stiffness_n_per_m, rotational_stiffness_n_m_per_rad, torsion }` over the
/// `[bridge.bearings]` of every line.
fn supports(
    file: &SourceFile,
    bridge: &RawBridge,
    span_count: usize,
) -> Result<(Vec<BearingKind>, Vec<Bearing>), InputError> {
    let base = match &bridge.bearings {
        Some(raw) => bearing(file, raw, "bridge.bearings", Bearing::default())?,
        None => Bearing::default(),
    };
    let Some(items) = &bridge.supports else {
        let mut kinds = vec![BearingKind::Roller; span_count + 1];
        kinds[0] = BearingKind::Pinned;
        return Ok((kinds, vec![base; span_count + 1]));
    };
    support_count_check(file, items.len(), span_count)?;
    let allowed = "expected \"pinned\", \"roller\" or a table { kind = \"pinned\" or \"roller\", \
                   vertical_stiffness_n_per_m, rotational_stiffness_n_m_per_rad, torsion }";
    let kind = |path: &str, name: &str| match name {
        "pinned" => Ok(BearingKind::Pinned),
        "roller" => Ok(BearingKind::Roller),
        other => Err(file.error_at(path, format!("unknown support `{other}`; {allowed}"))),
    };
    let mut kinds = Vec::with_capacity(items.len());
    let mut bearings = Vec::with_capacity(items.len());
    for (i, value) in items.iter().enumerate() {
        let path = format!("bridge.supports[{i}]");
        match value {
            toml::Value::String(name) => {
                kinds.push(kind(&path, name)?);
                bearings.push(base);
            }
            toml::Value::Table(table) => {
                let raw: RawGrillageSupport =
                    table.clone().try_into().map_err(|e: toml::de::Error| {
                        file.error_at(&path, format!("{}; {allowed}", e.message().trim()))
                    })?;
                kinds.push(kind(&format!("{path}.kind"), &raw.kind)?);
                let own = RawBearing {
                    vertical_stiffness_n_per_m: raw.vertical_stiffness_n_per_m,
                    rotational_stiffness_n_m_per_rad: raw.rotational_stiffness_n_m_per_rad,
                    torsion: raw.torsion,
                };
                bearings.push(bearing(file, &own, &path, base)?);
            }
            other => return Err(file.error_at(&path, format!("{other} is not allowed; {allowed}"))),
        }
    }
    Ok((kinds, bearings))
}

/// `[bridge.deck]` over the paper's layers.
fn deck_layers(file: &SourceFile, raw: Option<&RawDeck>) -> Result<DeckLayers, InputError> {
    let mut deck = DeckLayers::default();
    let Some(raw) = raw else {
        return Ok(deck);
    };
    let d = "bridge.deck";
    if let Some(v) = raw.slab_thickness_m {
        deck.slab_thickness = length(file, &format!("{d}.slab_thickness_m"), v)?;
    }
    for (value, key, target) in [
        (
            raw.structural_overlay_thickness_m,
            "structural_overlay_thickness_m",
            &mut deck.structural_overlay_thickness,
        ),
        (
            raw.pavement_concrete_thickness_m,
            "pavement_concrete_thickness_m",
            &mut deck.pavement_concrete_thickness,
        ),
        (
            raw.asphalt_thickness_m,
            "asphalt_thickness_m",
            &mut deck.asphalt_thickness,
        ),
    ] {
        if let Some(v) = value {
            *target = require_in_range(file, &format!("{d}.{key}"), v, 0.0, 2.0, "m")?;
        }
    }
    if let Some(v) = raw.asphalt_density_kg_per_m3 {
        deck.asphalt_density = require_in_range(
            file,
            &format!("{d}.asphalt_density_kg_per_m3"),
            v,
            0.0,
            5000.0,
            "kg/m³",
        )?;
    }
    Ok(deck)
}

/// A diaphragm's `width_m` and `depth_m` at `path` over `base`.
fn diaphragm(
    file: &SourceFile,
    path: &str,
    width: Option<f64>,
    depth: Option<f64>,
    base: Diaphragm,
) -> Result<Diaphragm, InputError> {
    let mut d = base;
    if let Some(v) = width {
        d.width = length(file, &format!("{path}.width_m"), v)?;
    }
    if let Some(v) = depth {
        d.depth = length(file, &format!("{path}.depth_m"), v)?;
    }
    Ok(d)
}

/// The intermediate diaphragms and the barriers.
fn additions(
    file: &SourceFile,
    bridge: &RawBridge,
    support_diaphragm: Diaphragm,
) -> Result<(Option<IntermediateDiaphragms>, Option<Barriers>), InputError> {
    let intermediate = match &bridge.intermediate_diaphragms {
        None => None,
        Some(raw) => {
            let p = "bridge.intermediate_diaphragms";
            if !(1..=50).contains(&raw.per_span) {
                return Err(file.error_at(
                    &format!("{p}.per_span"),
                    format!(
                        "{} is not allowed; expected from 1 to 50 per span",
                        raw.per_span
                    ),
                ));
            }
            Some(IntermediateDiaphragms {
                per_span: raw.per_span as usize,
                section: diaphragm(file, p, raw.width_m, raw.depth_m, support_diaphragm)?,
            })
        }
    };
    let barriers = match &bridge.barriers {
        None => None,
        Some(raw) => {
            let p = "bridge.barriers";
            Some(Barriers {
                mass_per_length: require_in_range(
                    file,
                    &format!("{p}.mass_per_length_kg_per_m"),
                    raw.mass_per_length_kg_per_m,
                    0.0,
                    1e5,
                    "kg/m",
                )?,
                edge_distance: require_in_range(
                    file,
                    &format!("{p}.edge_distance_m"),
                    raw.edge_distance_m.unwrap_or(0.25),
                    0.0,
                    50.0,
                    "m",
                )?,
            })
        }
    };
    Ok((intermediate, barriers))
}

/// Checks each girder table's section with its deck share, at its own key.
fn check_sections(file: &SourceFile, grillage: &Grillage) -> Result<(), InputError> {
    for i in 0..grillage.girder_count {
        if let Err(error) = grillage.girder_section(i) {
            let path = if grillage.edge_girder.is_some() && grillage.is_edge_girder(i) {
                "bridge.edge_girder"
            } else {
                "bridge.girder"
            };
            return Err(file.error_at(path, format!("girder {}: {error}", i + 1)));
        }
    }
    if let Some(b) = &grillage.barriers {
        if b.edge_distance >= grillage.deck_width / 2.0 {
            return Err(file.error_at(
                "bridge.barriers.edge_distance_m",
                format!(
                    "{} m is not less than half the {} m deck width",
                    b.edge_distance, grillage.deck_width
                ),
            ));
        }
    }
    Ok(())
}

/// A `grillage` bridge.
pub(super) fn grillage(file: &SourceFile, bridge: &RawBridge) -> Result<Grillage, InputError> {
    let t = "grillage";
    forbid(
        file,
        bridge.added_mass_kg_per_m.is_some(),
        "added_mass_kg_per_m",
        t,
    )?;
    forbid(file, bridge.section.is_some(), "section", t)?;
    let span_lengths = spans(file, bridge)?;
    let (supports, bearings) = supports(file, bridge, span_lengths.len())?;
    let lateral_restraint = match bridge.lateral_restraint.as_deref() {
        None | Some("all_supports") => LateralRestraint::AllSupports,
        Some("pinned_line") => LateralRestraint::PinnedLine,
        Some(other) => {
            return Err(file.error_at(
                "bridge.lateral_restraint",
                format!("unknown value `{other}`; expected \"all_supports\" or \"pinned_line\""),
            ))
        }
    };
    let limit = vbi::model::MAX_SKEW_ANGLE.to_degrees();
    let skew_angle = require_in_range(
        file,
        "bridge.skew_angle_deg",
        bridge.skew_angle_deg.unwrap_or(0.0),
        -limit,
        limit,
        "degrees",
    )?
    .to_radians();
    let required = |value: Option<f64>, key: &str| {
        value.ok_or_else(|| {
            file.error_at(
                &format!("bridge.{key}"),
                format!("`{key}` is required for a grillage"),
            )
        })
    };
    let deck_width = require_in_range(
        file,
        "bridge.deck_width_m",
        required(bridge.deck_width_m, "deck_width_m")?,
        0.5,
        100.0,
        "m",
    )?;
    let Some(girder_count) = bridge.girder_count else {
        return Err(file.error_at(
            "bridge.girder_count",
            "`girder_count` is required for a grillage",
        ));
    };
    if !(1..=50).contains(&girder_count) {
        return Err(file.error_at(
            "bridge.girder_count",
            format!("{girder_count} is not allowed; expected from 1 to 50 girders"),
        ));
    }
    let girder_spacing = length(
        file,
        "bridge.girder_spacing_m",
        required(bridge.girder_spacing_m, "girder_spacing_m")?,
    )?;
    let transverse_member_spacing = require_in_range(
        file,
        "bridge.transverse_member_spacing_m",
        bridge.transverse_member_spacing_m.unwrap_or(2.0),
        0.1,
        100.0,
        "m",
    )?;
    let Some(raw_girder) = &bridge.girder else {
        return Err(file.error_at("bridge.girder", "a grillage needs a [bridge.girder] table"));
    };
    let girder = girder_shape(file, raw_girder, "bridge.girder")?;
    let edge_girder = match &bridge.edge_girder {
        Some(raw) => Some(girder_shape(file, raw, "bridge.edge_girder")?),
        None => None,
    };
    let deck = deck_layers(file, bridge.deck.as_ref())?;
    let default_diaphragm = Diaphragm {
        width: 0.4,
        depth: girder.depth_to_slab_top(&deck),
    };
    let support_diaphragm = match &bridge.diaphragm {
        Some(raw) => diaphragm(
            file,
            "bridge.diaphragm",
            raw.width_m,
            raw.depth_m,
            default_diaphragm,
        )?,
        None => default_diaphragm,
    };
    let (intermediate_diaphragms, barriers) = additions(file, bridge, support_diaphragm)?;
    let damage = bridge_damage(file, bridge, &span_lengths, girder_count as usize)?;
    let grillage = Grillage {
        damage,
        span_lengths,
        supports,
        lateral_restraint,
        skew_angle,
        deck_width,
        girder_count: girder_count as usize,
        girder_spacing,
        girder,
        edge_girder,
        barriers,
        deck,
        diaphragm: support_diaphragm,
        intermediate_diaphragms,
        // All default bearings are written as none, as the paper's presets have them.
        bearings: if bearings.iter().all(|b| *b == Bearing::default()) {
            Vec::new()
        } else {
            bearings
        },
        transverse_member_spacing,
        material: material(file, bridge.material.as_ref())?,
        damping_ratio: damping(file, bridge, 0.05)?,
        mode_damping: mode_damping(file, damping_keys(bridge))?,
    };
    if grillage.deck_width >= (grillage.girder_count as f64 - 1.0) * grillage.girder_spacing {
        check_sections(file, &grillage)?;
    }
    Ok(grillage)
}
