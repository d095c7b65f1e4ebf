//! The keys of a `grillage` bridge read through [`vbi_input::bridge::load`]: girders of each
//! shape, the deck, diaphragms, barriers and bearings in SI, and their refusals.

use vbi::model::BridgeModel;

use vbi_input::bridge::load;
use vbi_input::source::SourceFile;

const HEAD: &str = "[bridge]\ntype = \"grillage\"\nspan_lengths_m = [20.0]\n\
                    deck_width_m = 9.0\ngirder_count = 4\ngirder_spacing_m = 2.2\n";
const T_BEAM: &str = "[bridge.girder]\nshape = \"t_beam\"\nheight_m = 1.4\n\
                      web_thickness_m = 0.4\n";

fn load_text(text: &str) -> Result<vbi::model::Grillage, vbi_input::source::InputError> {
    match load(&SourceFile::from_text("b.toml".into(), text.into()))? {
        BridgeModel::Grillage(g) => Ok(g),
        other => panic!("a grillage, got {other:?}"),
    }
}

#[test]
fn a_t_beam_deck_with_barriers_diaphragms_and_bearings_is_read_in_si() {
    let text = format!(
        "{HEAD}supports = [\"pinned\", {{ kind = \"roller\", torsion = \"free\" }}]\n\
         {T_BEAM}[bridge.intermediate_diaphragms]\nper_span = 2\n\
         [bridge.barriers]\nmass_per_length_kg_per_m = 600.0\n\
         [bridge.bearings]\nvertical_stiffness_n_per_m = 1.5e9\n"
    );
    let g = load_text(&text).unwrap();
    assert!(matches!(g.girder, vbi::model::GirderShape::TBeam(t) if t.height == 1.4));
    assert_eq!(g.intermediate_diaphragms.unwrap().per_span, 2);
    assert_eq!(g.barriers.unwrap().edge_distance, 0.25);
    assert_eq!(g.bearings.len(), 2);
    assert_eq!(g.bearings[0].vertical_stiffness, Some(1.5e9));
    assert!(!g.bearings[0].torsion_free && g.bearings[1].torsion_free);
    assert_eq!(g.bearings[1].vertical_stiffness, Some(1.5e9));
}

#[test]
fn girder_keys_are_checked_against_their_shape_at_their_key() {
    let cases = [
        (T_BEAM.replace("t_beam", "tee"), "bridge.girder.shape", "unknown girder shape"),
        (
            format!("{T_BEAM}bottom_width_m = 1.0\n"),
            "bridge.girder.bottom_width_m",
            "not a key of a `t_beam` girder",
        ),
        (
            T_BEAM.replace("web_thickness_m = 0.4\n", ""),
            "bridge.girder",
            "needs `web_thickness_m`",
        ),
        (
            "[bridge.girder]\nshape = \"voided_slab\"\nwidth_m = 2.5\ndepth_m = 0.6\n\
             void_diameter_m = 0.3\nvoid_count = 2\n"
                .to_string(),
            "bridge.girder",
            "wider than its",
        ),
        (
            format!("{T_BEAM}[bridge.barriers]\nmass_per_length_kg_per_m = 500.0\nedge_distance_m = 4.5\n"),
            "bridge.barriers.edge_distance_m",
            "half the 9 m deck width",
        ),
        (
            format!("{T_BEAM}[bridge.bearings]\ntorsion = \"loose\"\n"),
            "bridge.bearings.torsion",
            "expected \"held\" or \"free\"",
        ),
        (
            format!("{T_BEAM}[bridge.edge_girder]\nshape = \"t_beam\"\nheight_m = 0.1\nweb_thickness_m = 0.5\n"),
            "bridge.edge_girder",
            "leaves no web",
        ),
    ];
    for (girder, field, message) in cases {
        let error = load_text(&format!("{HEAD}{girder}")).unwrap_err();
        assert_eq!(error.field.as_deref(), Some(field), "{error}");
        assert!(error.message.contains(message), "{}", error.message);
    }
}
