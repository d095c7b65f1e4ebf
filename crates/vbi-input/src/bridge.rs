//! The `[bridge]` input file: a continuous beam, a box-girder grillage, or a modal basis imported
//! from another program's CSV files (docs/input-format.md).
//!
//! Parsing is two-step: the TOML is read into a raw form that rejects unknown keys, then every
//! number is checked against its allowed range and converted once to SI (`modulus_gpa` → Pa).

use std::path::{Path, PathBuf};

use vbi::fe::{discretise, Direction, FeError, MeshOptions};
use vbi::modal::ModalBasis;
use vbi::model::{
    paper_bridge, BeamSection, BoxGirderGeometry, BoxGirderSection, BridgeModel, ContinuousBeam,
    Damage, ModelError, SupportKind,
};
use vbi::units::GPA;

use crate::bridge::raw::{
    RawBeamSection, RawBoxGirder, RawBridge, RawElasticSupport, RawFile, RawImportedFile,
    RawKindFile, RawMaterial,
};
use crate::bridge::shared::{
    bridge_damage, damping, damping_keys, forbid, length, material, spans, support_count_check,
};
use crate::bridge_damage::{mode_damping, ratio_in_range};
use crate::modal_import::read_modal_import;
use crate::source::{require_in_range, require_positive, InputError, SourceFile};

mod grillage;
pub mod imported_matrices;
mod raw;
mod shared;

/// Default modal damping ratio of imported modes without their own [-] (the paper's 0.05).
pub const IMPORTED_DEFAULT_DAMPING_RATIO: f64 = 0.05;

/// The bridge used when no file is given: the paper's 3 × 30 m box-girder bridge.
pub fn built_in_default() -> BridgeModel {
    paper_bridge(3, 30.0)
}

/// Validates a `[bridge]` file: every key, every range, and that the supports hold the model;
/// for an imported basis, its CSV files.
pub fn validate(file: &SourceFile) -> Result<(), InputError> {
    let model = load(file)?;
    if let BridgeModel::ImportedMatrices(_) = model {
        // Imported matrices are planned and factorised as a run would (an indefinite K is an
        // input error): vbi::crossing::check_bridge.
        let spec = vbi::crossing::BridgeSpec::new(model, 1);
        vbi::crossing::check_bridge(&spec).map_err(|error| {
            file.error_at("bridge.stiffness_mtx", vbi::crossing::error_chain(&error))
        })?;
    }
    Ok(())
}

/// Whether the file's `[bridge]` is `type = "imported"`.
fn is_imported(file: &SourceFile) -> Result<bool, InputError> {
    let raw: RawKindFile = file.parse()?;
    Ok(raw.bridge.kind == "imported")
}

/// Reads an imported modal basis: `Some` for a `type = "imported"` bridge (its CSV files read
/// and checked, paths relative to the bridge file), `None` for any other type (read those with
/// [`load`]).
pub fn load_imported(file: &SourceFile) -> Result<Option<ModalBasis>, InputError> {
    if !is_imported(file)? {
        return Ok(None);
    }
    let (data, _) = imported_data(file)?;
    vbi::modal::import::build_imported_basis(&data)
        .map(Some)
        .map_err(|e| file.error_at("bridge", e.to_string()))
}

/// The modal data of a `type = "imported"` bridge (its CSV files read and checked), and its
/// span lengths if the file gives them [m].
fn imported_data(
    file: &SourceFile,
) -> Result<(vbi::modal::import::ModalImport, Option<Vec<f64>>), InputError> {
    let raw: RawImportedFile = file.parse()?;
    let bridge = raw.bridge;
    let damping_ratio = match bridge.damping_ratio {
        None => IMPORTED_DEFAULT_DAMPING_RATIO,
        Some(z) => ratio_in_range(file, "bridge.damping_ratio", z)?,
    };
    let csv = |key: &str, name: &str| -> Result<PathBuf, InputError> {
        if name.trim().is_empty() {
            return Err(file.error_at(
                &format!("bridge.{key}"),
                "an empty path is not allowed; expected a CSV file path relative to this file",
            ));
        }
        let path = relative_to(file, name);
        if !path.is_file() {
            return Err(file.error_at(
                &format!("bridge.{key}"),
                format!(
                    "`{}` is not a readable file; expected a CSV file path relative to this file",
                    path.display()
                ),
            ));
        }
        Ok(path)
    };
    let frequencies = csv("frequencies_csv", &bridge.frequencies_csv)?;
    let shapes = csv("shapes_csv", &bridge.shapes_csv)?;
    let moments = match &bridge.station_moments_csv {
        Some(name) => Some(csv("station_moments_csv", name)?),
        None => None,
    };
    let mut data = read_modal_import(&frequencies, &shapes, moments.as_deref(), damping_ratio)?;
    if let Some(value) = &bridge.flexural_rigidity_n_m2 {
        if moments.is_some() {
            return Err(file.error_at(
                "bridge.flexural_rigidity_n_m2",
                "the stations' modal moments come from station_moments_csv or from the shapes' \
                 curvature with flexural_rigidity_n_m2, not both; give one",
            ));
        }
        let rigidity = line_rigidities(file, value, data.lines.len())?;
        let supports = imported_support_positions(file, &data, bridge.span_lengths_m.as_deref())?;
        data.stations = vbi::modal::curvature::curvature_stations(&data, &rigidity, &supports);
    }
    if let Some(name) = &bridge.influence_lines_csv {
        if data.stations.is_empty() {
            return Err(file.error_at(
                "bridge.influence_lines_csv",
                "influence lines are given per station: they need the stations of \
                 station_moments_csv (or of flexural_rigidity_n_m2)",
            ));
        }
        let path = csv("influence_lines_csv", name)?;
        data.influence_lines = crate::influence_csv::read_influence_lines(&path, &data)?;
    }
    Ok((data, bridge.span_lengths_m))
}

/// `flexural_rigidity_n_m2` of an imported basis: one EI for every deck line, or a list of one
/// per line in ascending `line_y_m` [N·m²].
fn line_rigidities(
    file: &SourceFile,
    value: &toml::Value,
    lines: usize,
) -> Result<Vec<f64>, InputError> {
    let key = "bridge.flexural_rigidity_n_m2";
    let number = |path: &str, v: &toml::Value| match v {
        toml::Value::Float(x) => require_positive(file, path, *x, "N·m²"),
        toml::Value::Integer(i) => require_positive(file, path, *i as f64, "N·m²"),
        other => Err(file.error_at(
            path,
            format!("{other} is not allowed; expected a positive number of N·m²"),
        )),
    };
    match value {
        toml::Value::Array(items) => {
            if items.len() != lines {
                return Err(file.error_at(
                    key,
                    format!(
                        "{} values for {lines} deck lines; expected one EI, or one per line in \
                         ascending line_y_m",
                        items.len()
                    ),
                ));
            }
            items
                .iter()
                .enumerate()
                .map(|(i, v)| number(&format!("{key}[{i}]"), v))
                .collect()
        }
        other => Ok(vec![number(key, other)?; lines]),
    }
}

/// The support positions of an imported basis [m]: from its spans if given (each positive,
/// adding up to the deck's length, as a run checks them), else its ends.
fn imported_support_positions(
    file: &SourceFile,
    data: &vbi::modal::import::ModalImport,
    spans: Option<&[f64]>,
) -> Result<Vec<f64>, InputError> {
    let Some(spans) = spans else {
        return Ok(vec![0.0, data.deck_length()]);
    };
    for (i, &length) in spans.iter().enumerate() {
        require_positive(file, &format!("bridge.span_lengths_m[{i}]"), length, "m")?;
    }
    if spans.is_empty() {
        return Err(file.error_at(
            "bridge.span_lengths_m",
            "at least one span length is required",
        ));
    }
    if let Some(message) = data.span_mismatch(spans) {
        return Err(file.error_at("bridge.span_lengths_m", message));
    }
    Ok(vbi::model::support_positions_of(spans))
}

/// A `type = "imported"` bridge as a model that runs: its modes, and its spans (one span of the
/// deck's length unless `span_lengths_m` is given).
fn imported_modes(file: &SourceFile) -> Result<BridgeModel, InputError> {
    let (data, spans) = imported_data(file)?;
    let deck_length = data.deck_length();
    let span_lengths = match spans {
        Some(spans) => {
            for (i, &length) in spans.iter().enumerate() {
                require_positive(file, &format!("bridge.span_lengths_m[{i}]"), length, "m")?;
            }
            spans
        }
        None => vec![deck_length],
    };
    let model = BridgeModel::ImportedModes(vbi::model::ImportedModes {
        data: std::sync::Arc::new(data),
        span_lengths,
        damage: Damage::default(),
        source: file.name(),
    });
    model
        .validate()
        .map_err(|error| file.error_at("bridge.span_lengths_m", error.to_string()))?;
    Ok(model)
}

/// A path given in `file`, relative to the directory of `file` unless absolute.
fn relative_to(file: &SourceFile, name: &str) -> PathBuf {
    let given = Path::new(name);
    if given.is_absolute() {
        return given.to_path_buf();
    }
    file.path
        .parent()
        .map_or_else(|| given.to_path_buf(), |dir| dir.join(given))
}

/// Reads a `[bridge]` file into a validated bridge model: vbi's own (a continuous beam, a
/// grillage), another program's matrices (`imported_matrices`) or its modes (`imported`, a
/// model that runs on the modal flexibility; [`load_imported`] reads the same file as a basis).
pub fn load(file: &SourceFile) -> Result<BridgeModel, InputError> {
    if is_imported(file)? {
        return imported_modes(file);
    }
    let kind: RawKindFile = file.parse()?;
    let model = if kind.bridge.kind == "imported_matrices" {
        imported_matrices::load(file)?
    } else {
        native(file)?
    };
    if let Err(error) = model.validate() {
        return Err(model_error(file, error));
    }
    match discretise(&model, &MeshOptions::default()) {
        Ok(_) => Ok(model),
        Err(FeError::Mechanism {
            direction,
            explanation,
        }) => Err(file.error_at(
            if model.damage().support_changes.is_empty() {
                "bridge.supports"
            } else {
                "bridge.support_change"
            },
            format!(
                "the supports do not hold the bridge: it is free in {} ({explanation})",
                direction_name(direction)
            ),
        )),
        Err(FeError::Model(error)) => Err(model_error(file, error)),
        Err(FeError::DamageRegionTooShort { index, .. }) => Err(file.error_at(
            &format!("bridge.stiffness_loss[{index}]"),
            "the region is too short to hold a mesh element; expected a longer region",
        )),
        Err(error) => Err(file.error_at("bridge", error.to_string())),
    }
}

/// A `continuous_beam` or `grillage` bridge, as given (checked by [`load`]).
fn native(file: &SourceFile) -> Result<BridgeModel, InputError> {
    let raw: RawFile = file.parse()?;
    let bridge = raw.bridge;
    let model = match bridge.kind.as_str() {
        "continuous_beam" => BridgeModel::ContinuousBeam(beam(file, &bridge)?),
        "grillage" => BridgeModel::Grillage(grillage::grillage(file, &bridge)?),
        other => {
            return Err(file.error_at(
                "bridge.type",
                format!(
                    "unknown bridge type `{other}`; expected `continuous_beam`, `grillage`, \
                     `imported_matrices` or `imported`"
                ),
            ))
        }
    };
    Ok(model)
}

/// A free direction in words, as error messages name it.
pub fn direction_name(direction: Direction) -> &'static str {
    match direction {
        Direction::TranslationX => "longitudinal translation (x)",
        Direction::TranslationY => "lateral translation (y)",
        Direction::TranslationZ => "vertical translation (z)",
        Direction::RotationX => "rotation about the bridge axis (x, torsion)",
        Direction::RotationY => "rotation about the lateral axis (y, in the vertical plane)",
        Direction::RotationZ => "rotation about the vertical axis (z)",
    }
}

/// Points a model error that the key-by-key checks could not catch at the key that causes it.
fn model_error(file: &SourceFile, error: ModelError) -> InputError {
    let path = match &error {
        ModelError::DeckTooNarrow { .. } => "bridge.girder_spacing_m",
        ModelError::FlangeNarrowerThanBox { .. } => "bridge.girder_spacing_m",
        ModelError::GirderShape { .. } => "bridge.girder",
        ModelError::SkewAngle { .. } => "bridge.skew_angle_deg",
        ModelError::BarrierEdge { .. } => "bridge.barriers.edge_distance_m",
        ModelError::BearingCount { .. } => "bridge.bearings",
        ModelError::SlabsTooThick { .. } => "bridge.girder.height_m",
        ModelError::WebsTooThick { .. } => "bridge.girder.web_thickness_m",
        ModelError::SupportCount { .. } => "bridge.supports",
        _ => "bridge",
    };
    file.error_at(path, error.to_string())
}

fn beam(file: &SourceFile, bridge: &RawBridge) -> Result<ContinuousBeam, InputError> {
    let t = "continuous_beam";
    forbid(
        file,
        bridge.lateral_restraint.is_some(),
        "lateral_restraint",
        t,
    )?;
    forbid(file, bridge.deck_width_m.is_some(), "deck_width_m", t)?;
    forbid(file, bridge.girder_count.is_some(), "girder_count", t)?;
    forbid(
        file,
        bridge.girder_spacing_m.is_some(),
        "girder_spacing_m",
        t,
    )?;
    forbid(
        file,
        bridge.transverse_member_spacing_m.is_some(),
        "transverse_member_spacing_m",
        t,
    )?;
    forbid(file, bridge.girder.is_some(), "girder", t)?;
    forbid(file, bridge.deck.is_some(), "deck", t)?;
    forbid(file, bridge.diaphragm.is_some(), "diaphragm", t)?;
    for (present, key) in [
        (bridge.edge_girder.is_some(), "edge_girder"),
        (bridge.skew_angle_deg.is_some(), "skew_angle_deg"),
        (
            bridge.intermediate_diaphragms.is_some(),
            "intermediate_diaphragms",
        ),
        (bridge.barriers.is_some(), "barriers"),
        (bridge.bearings.is_some(), "bearings"),
    ] {
        forbid(file, present, key, t)?;
    }
    let span_lengths = spans(file, bridge)?;
    let supports = match &bridge.supports {
        None => vec![SupportKind::Pinned; span_lengths.len() + 1],
        Some(items) => {
            support_count_check(file, items.len(), span_lengths.len())?;
            items
                .iter()
                .enumerate()
                .map(|(i, v)| beam_support(file, i, v))
                .collect::<Result<_, _>>()?
        }
    };
    let Some(section) = &bridge.section else {
        return Err(file.error_at(
            "bridge.section",
            "a continuous beam needs a [bridge.section] table",
        ));
    };
    let material_given = bridge.material.is_some();
    let section = beam_section(file, section, bridge.material.as_ref(), material_given)?;
    let added_mass_per_length = match bridge.added_mass_kg_per_m {
        None => 0.0,
        Some(m) => require_in_range(file, "bridge.added_mass_kg_per_m", m, 0.0, 1e6, "kg/m")?,
    };
    let damage = bridge_damage(file, bridge, &span_lengths, 1)?;
    Ok(ContinuousBeam {
        damage,
        span_lengths,
        supports,
        section,
        added_mass_per_length,
        damping_ratio: damping(file, bridge, 0.0)?,
        mode_damping: mode_damping(file, damping_keys(bridge))?,
    })
}

fn beam_support(
    file: &SourceFile,
    i: usize,
    value: &toml::Value,
) -> Result<SupportKind, InputError> {
    let path = format!("bridge.supports[{i}]");
    let allowed = "expected \"pinned\", \"roller\", \"fixed\" or a table { kind = \"elastic\", \
                   vertical_stiffness_n_per_m = …, rotational_stiffness_n_m_per_rad = … }";
    match value {
        toml::Value::String(s) => match s.as_str() {
            "pinned" => Ok(SupportKind::Pinned),
            "roller" => Ok(SupportKind::Roller),
            "fixed" => Ok(SupportKind::Fixed),
            other => Err(file.error_at(&path, format!("unknown support `{other}`; {allowed}"))),
        },
        toml::Value::Table(table) => {
            let raw: RawElasticSupport =
                table.clone().try_into().map_err(|e: toml::de::Error| {
                    file.error_at(&path, format!("{}; {allowed}", e.message().trim()))
                })?;
            if raw.kind != "elastic" {
                return Err(file.error_at(
                    &format!("{path}.kind"),
                    format!("unknown support kind `{}`; {allowed}", raw.kind),
                ));
            }
            let vertical = require_in_range(
                file,
                &format!("{path}.vertical_stiffness_n_per_m"),
                raw.vertical_stiffness_n_per_m.unwrap_or(0.0),
                0.0,
                f64::INFINITY,
                "N/m",
            )?;
            let rotational = require_in_range(
                file,
                &format!("{path}.rotational_stiffness_n_m_per_rad"),
                raw.rotational_stiffness_n_m_per_rad.unwrap_or(0.0),
                0.0,
                f64::INFINITY,
                "N·m/rad",
            )?;
            Ok(SupportKind::Elastic {
                vertical_stiffness: vertical,
                rotational_stiffness: rotational,
            })
        }
        _ => Err(file.error_at(&path, allowed)),
    }
}

fn box_geometry(file: &SourceFile, raw: &RawBoxGirder) -> Result<BoxGirderGeometry, InputError> {
    let p = "bridge.section.box_girder";
    Ok(BoxGirderGeometry {
        height: length(file, &format!("{p}.height_m"), raw.height_m)?,
        top_flange_width: length(
            file,
            &format!("{p}.top_flange_width_m"),
            raw.top_flange_width_m,
        )?,
        bottom_width: length(file, &format!("{p}.bottom_width_m"), raw.bottom_width_m)?,
        top_slab_thickness: length(
            file,
            &format!("{p}.top_slab_thickness_m"),
            raw.top_slab_thickness_m,
        )?,
        web_thickness: length(file, &format!("{p}.web_thickness_m"), raw.web_thickness_m)?,
        bottom_slab_thickness: length(
            file,
            &format!("{p}.bottom_slab_thickness_m"),
            raw.bottom_slab_thickness_m,
        )?,
        web_inclination: require_in_range(
            file,
            &format!("{p}.web_inclination"),
            raw.web_inclination.unwrap_or(0.0),
            0.0,
            2.0,
            "(horizontal per unit rise)",
        )?,
        overlay_thickness: require_in_range(
            file,
            &format!("{p}.overlay_thickness_m"),
            raw.overlay_thickness_m.unwrap_or(0.0),
            0.0,
            1.0,
            "m",
        )?,
    })
}

fn beam_section(
    file: &SourceFile,
    raw: &RawBeamSection,
    raw_material: Option<&RawMaterial>,
    material_given: bool,
) -> Result<BeamSection, InputError> {
    let p = "bridge.section";
    if let Some(box_girder) = &raw.box_girder {
        for (present, key) in [
            (
                raw.flexural_rigidity_n_m2.is_some(),
                "flexural_rigidity_n_m2",
            ),
            (raw.modulus_gpa.is_some(), "modulus_gpa"),
            (
                raw.second_moment_of_area_m4.is_some(),
                "second_moment_of_area_m4",
            ),
            (
                raw.mass_per_length_kg_per_m.is_some(),
                "mass_per_length_kg_per_m",
            ),
        ] {
            if present {
                return Err(file.error_at(
                    &format!("{p}.{key}"),
                    "give either a box_girder (with [bridge.material]) or the section numbers, not both",
                ));
            }
        }
        let geometry = box_geometry(file, box_girder)?;
        let section = BoxGirderSection::new(geometry)
            .map_err(|e| file.error_at(&format!("{p}.box_girder"), e.to_string()))?;
        let material = material(file, raw_material)?;
        return Ok(BeamSection::from_box_girder(&section, &material));
    }
    if material_given {
        return Err(file.error_at(
            "bridge.material",
            "[bridge.material] is used only with a box_girder section; give the modulus in [bridge.section]",
        ));
    }
    let flexural_rigidity = match (
        raw.flexural_rigidity_n_m2,
        raw.modulus_gpa,
        raw.second_moment_of_area_m4,
    ) {
        (Some(ei), None, None) => {
            require_positive(file, &format!("{p}.flexural_rigidity_n_m2"), ei, "N·m²")?
        }
        (None, Some(e), Some(i)) => {
            let e = require_in_range(file, &format!("{p}.modulus_gpa"), e, 0.1, 1000.0, "GPa")?;
            let i = require_positive(file, &format!("{p}.second_moment_of_area_m4"), i, "m⁴")?;
            e * GPA * i
        }
        (Some(_), _, _) => {
            return Err(file.error_at(
                &format!("{p}.flexural_rigidity_n_m2"),
                "give either flexural_rigidity_n_m2 or modulus_gpa with second_moment_of_area_m4, not both",
            ))
        }
        _ => {
            return Err(file.error_at(
                p,
                "the section needs flexural_rigidity_n_m2, or modulus_gpa and second_moment_of_area_m4, or a box_girder table",
            ))
        }
    };
    let Some(mass) = raw.mass_per_length_kg_per_m else {
        return Err(file.error_at(
            &format!("{p}.mass_per_length_kg_per_m"),
            "mass_per_length_kg_per_m is required (a positive number of kg/m)",
        ));
    };
    Ok(BeamSection {
        flexural_rigidity,
        mass_per_length: require_positive(
            file,
            &format!("{p}.mass_per_length_kg_per_m"),
            mass,
            "kg/m",
        )?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(text: &str) -> SourceFile {
        SourceFile::from_text("b.toml".into(), text.into())
    }

    const BEAM: &str = "[bridge]\ntype = \"continuous_beam\"\nspan_lengths_m = [25.0]\n\
                        [bridge.section]\nmodulus_gpa = 35.0\nsecond_moment_of_area_m4 = 1.3901\n\
                        mass_per_length_kg_per_m = 18358.0\n";

    #[test]
    fn a_beam_file_converts_the_modulus_from_gpa() {
        let BridgeModel::ContinuousBeam(beam) = load(&file(BEAM)).unwrap() else {
            panic!("beam")
        };
        assert!((beam.section.flexural_rigidity - 3.5e10 * 1.3901).abs() < 1e-3);
        assert_eq!(beam.supports, vec![SupportKind::Pinned; 2]);
    }

    #[test]
    fn a_negative_span_is_reported_at_its_array_element() {
        let text = BEAM.replace("[25.0]", "[25.0, -3.0]");
        let e = load(&file(&text)).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("bridge.span_lengths_m[1]"));
        assert_eq!(e.location.map(|l| l.0), Some(3));
        assert!(e.message.contains("from 0.5 to 1000 m"), "{}", e.message);
    }

    #[test]
    fn an_elastic_support_table_is_read_and_a_single_support_is_a_mechanism() {
        let text = BEAM.replace(
            "[bridge.section]",
            "supports = [\"fixed\", { kind = \"elastic\", vertical_stiffness_n_per_m = 1e8 }]\n[bridge.section]",
        );
        let BridgeModel::ContinuousBeam(beam) = load(&file(&text)).unwrap() else {
            panic!("beam")
        };
        assert!(
            matches!(beam.supports[1], SupportKind::Elastic { vertical_stiffness, .. } if vertical_stiffness == 1e8)
        );
        let text = BEAM.replace(
            "[bridge.section]",
            "supports = [\"pinned\", { kind = \"elastic\" }]\n[bridge.section]",
        );
        let e = load(&file(&text)).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("bridge.supports"));
        assert!(e.message.contains("turns freely"), "{}", e.message);
    }

    #[test]
    fn grillage_keys_in_a_beam_file_are_rejected() {
        let text = BEAM.replace("[bridge.section]", "girder_count = 3\n[bridge.section]");
        let e = load(&file(&text)).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("bridge.girder_count"));
    }

    #[test]
    fn an_imported_bridge_is_read_as_a_basis_and_as_a_model_of_its_modes() {
        assert_eq!(load_imported(&file(BEAM)).unwrap(), None);
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/bridges/imported/two-span-imported.toml");
        let imported = SourceFile::read(&root).unwrap();
        let basis = load_imported(&imported)
            .unwrap()
            .expect("an imported basis");
        assert_eq!(basis.mode_count(), 10);
        assert_eq!(basis.stations.len(), 3);
        // damping_ratio = 0.0 in the file, for modes without their own.
        assert!(basis.modes.iter().all(|m| m.damping_ratio == 0.0));
        // As a model that runs: one span of the deck's length (40 m), as no span_lengths_m is
        // given.
        let BridgeModel::ImportedModes(model) = load(&imported).unwrap() else {
            panic!("imported modes")
        };
        assert_eq!(model.span_lengths, vec![40.0]);
        validate(&imported).unwrap();
    }

    #[test]
    fn the_built_in_default_is_the_paper_3x30_bridge() {
        assert_eq!(built_in_default(), paper_bridge(3, 30.0));
    }

    #[test]
    fn the_paper_example_files_are_the_library_presets() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/bridges");
        for span_count in 2..=4 {
            for span_length in [20, 30, 40] {
                let path = root.join(format!("paper-{span_count}x{span_length}.toml"));
                let model = load(&SourceFile::read(&path).unwrap()).unwrap();
                assert_eq!(
                    model,
                    paper_bridge(span_count, span_length as f64),
                    "{}",
                    path.display()
                );
            }
        }
    }
}
