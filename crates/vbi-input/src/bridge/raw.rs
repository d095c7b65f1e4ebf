//! The `[bridge]` table as written, every type's keys (`continuous_beam`, `grillage`,
//! `imported`), before any check; read by the loaders of each type.

use serde::Deserialize;

use crate::bridge_damage::{RawRayleigh, RawStiffnessLoss, RawSupportChange};

/// Other top-level tables are allowed here: a scenario file inlines `[bridge]` beside
/// `[scenario]`; `vbi_input::validate` checks the top-level keys of each kind of file.
#[derive(Debug, Deserialize)]
pub(crate) struct RawFile {
    pub(crate) bridge: RawBridge,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawBridge {
    #[serde(rename = "type")]
    pub(crate) kind: String,
    pub(crate) span_lengths_m: Vec<f64>,
    pub(crate) damping_ratio: Option<f64>,
    pub(crate) damping_ratios: Option<Vec<f64>>,
    pub(crate) rayleigh_damping: Option<RawRayleigh>,
    pub(crate) supports: Option<Vec<toml::Value>>,
    #[serde(default)]
    pub(crate) stiffness_loss: Vec<RawStiffnessLoss>,
    #[serde(default)]
    pub(crate) support_change: Vec<RawSupportChange>,
    // Beam only.
    pub(crate) added_mass_kg_per_m: Option<f64>,
    pub(crate) section: Option<RawBeamSection>,
    // Both (beam: only with a box-girder section).
    pub(crate) material: Option<RawMaterial>,
    // Grillage only.
    pub(crate) lateral_restraint: Option<String>,
    pub(crate) skew_angle_deg: Option<f64>,
    pub(crate) deck_width_m: Option<f64>,
    pub(crate) girder_count: Option<i64>,
    pub(crate) girder_spacing_m: Option<f64>,
    pub(crate) transverse_member_spacing_m: Option<f64>,
    pub(crate) girder: Option<RawGirder>,
    pub(crate) edge_girder: Option<RawGirder>,
    pub(crate) deck: Option<RawDeck>,
    pub(crate) diaphragm: Option<RawDiaphragm>,
    pub(crate) intermediate_diaphragms: Option<RawIntermediateDiaphragms>,
    pub(crate) barriers: Option<RawBarriers>,
    pub(crate) bearings: Option<RawBearing>,
}

/// Only the `type` key, to tell an imported basis from an FE model before the full parse.
#[derive(Debug, Deserialize)]
pub(crate) struct RawKindFile {
    pub(crate) bridge: RawKind,
}

#[derive(Debug, Deserialize)]
pub(crate) struct RawKind {
    #[serde(rename = "type")]
    pub(crate) kind: String,
}

#[derive(Debug, Deserialize)]
pub(crate) struct RawImportedFile {
    pub(crate) bridge: RawImported,
}

/// `type = "imported"`: a modal basis from CSV files (paths relative to the bridge file).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawImported {
    #[serde(rename = "type")]
    pub(crate) _kind: String,
    pub(crate) frequencies_csv: String,
    pub(crate) shapes_csv: String,
    pub(crate) station_moments_csv: Option<String>,
    pub(crate) influence_lines_csv: Option<String>,
    pub(crate) flexural_rigidity_n_m2: Option<toml::Value>,
    pub(crate) damping_ratio: Option<f64>,
    pub(crate) span_lengths_m: Option<Vec<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawBeamSection {
    pub(crate) flexural_rigidity_n_m2: Option<f64>,
    pub(crate) modulus_gpa: Option<f64>,
    pub(crate) second_moment_of_area_m4: Option<f64>,
    pub(crate) mass_per_length_kg_per_m: Option<f64>,
    pub(crate) box_girder: Option<RawBoxGirder>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawBoxGirder {
    pub(crate) height_m: f64,
    pub(crate) top_flange_width_m: f64,
    pub(crate) bottom_width_m: f64,
    pub(crate) top_slab_thickness_m: f64,
    pub(crate) web_thickness_m: f64,
    pub(crate) bottom_slab_thickness_m: f64,
    pub(crate) web_inclination: Option<f64>,
    pub(crate) overlay_thickness_m: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMaterial {
    pub(crate) modulus_gpa: Option<f64>,
    pub(crate) density_kg_per_m3: Option<f64>,
    pub(crate) poisson_ratio: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawElasticSupport {
    pub(crate) kind: String,
    pub(crate) vertical_stiffness_n_per_m: Option<f64>,
    pub(crate) rotational_stiffness_n_m_per_rad: Option<f64>,
}

/// `[bridge.girder]` and `[bridge.edge_girder]`: `shape` and the keys of that shape.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawGirder {
    pub(crate) shape: Option<String>,
    pub(crate) height_m: Option<f64>,
    pub(crate) bottom_width_m: Option<f64>,
    pub(crate) web_thickness_m: Option<f64>,
    pub(crate) bottom_slab_thickness_m: Option<f64>,
    pub(crate) web_inclination: Option<f64>,
    pub(crate) top_flange_width_m: Option<f64>,
    pub(crate) top_flange_thickness_m: Option<f64>,
    pub(crate) bottom_flange_width_m: Option<f64>,
    pub(crate) bottom_flange_thickness_m: Option<f64>,
    pub(crate) width_m: Option<f64>,
    pub(crate) depth_m: Option<f64>,
    pub(crate) void_diameter_m: Option<f64>,
    pub(crate) void_count: Option<i64>,
    pub(crate) area_m2: Option<f64>,
    pub(crate) second_moment_y_m4: Option<f64>,
    pub(crate) second_moment_z_m4: Option<f64>,
    pub(crate) torsion_constant_m4: Option<f64>,
    pub(crate) centroid_height_m: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawDeck {
    pub(crate) slab_thickness_m: Option<f64>,
    pub(crate) structural_overlay_thickness_m: Option<f64>,
    pub(crate) pavement_concrete_thickness_m: Option<f64>,
    pub(crate) asphalt_thickness_m: Option<f64>,
    pub(crate) asphalt_density_kg_per_m3: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawDiaphragm {
    pub(crate) width_m: Option<f64>,
    pub(crate) depth_m: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawIntermediateDiaphragms {
    pub(crate) per_span: i64,
    pub(crate) width_m: Option<f64>,
    pub(crate) depth_m: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawBarriers {
    pub(crate) mass_per_length_kg_per_m: f64,
    pub(crate) edge_distance_m: Option<f64>,
}

/// `[bridge.bearings]`, or the bearing keys of one `supports` entry given as a table.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawBearing {
    pub(crate) vertical_stiffness_n_per_m: Option<f64>,
    pub(crate) rotational_stiffness_n_m_per_rad: Option<f64>,
    pub(crate) torsion: Option<String>,
}
