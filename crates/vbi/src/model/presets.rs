//! The paper's nine prototype bridges (§4.1, Table 1): precast continuous box-girder bridges of
//! 2, 3 or 4 spans of 20, 30 or 40 m, girder heights 1.2, 1.8 and 2.0 m.
//!
//! The paper prints the span lengths, the girder heights, the deck layers, the material and the
//! deck width of the field bridges (8.5 m), but not the full cross-section. The remaining
//! dimensions are assumptions, chosen as representative of the standard precast small box
//! girders of the Chinese general bridge atlas (which the paper cites for its field bridges):
//! - 3 girders at 2.9 m spacing on the 8.5 m deck, so that each carries about 2.8–2.9 m of deck
//!   (the atlas: 2.4 m inner and 2.85 m edge precast flanges plus wet joints);
//! - bottom width 1.0 m, webs inclined outwards 1:4 (0.25 horizontal per unit rise);
//! - webs and bottom slab 0.18 m thick for 20 and 30 m spans, 0.20 m for 40 m (mid-span values;
//!   the thickening near the supports is ignored);
//! - diaphragms 0.4 m thick and as deep as the girder over every support;
//! - slab strips every 2 m (about L/10 to L/20, finer than the L/4–L/8 of grillage practice).

use super::{
    BearingKind, BoxGirderDimensions, BridgeModel, DeckLayers, Diaphragm, GirderShape, Grillage,
    LateralRestraint, Material,
};

/// Girder height of the paper's bridges by span length [m]: 1.2 m up to 25 m spans, 1.8 m up
/// to 35 m, 2.0 m beyond (the paper: 20 m → 1.2, 30 m → 1.8, 40 m → 2.0).
pub fn paper_girder_height(span_length: f64) -> f64 {
    if span_length <= 25.0 {
        1.2
    } else if span_length <= 35.0 {
        1.8
    } else {
        2.0
    }
}

/// The assumed precast box of the paper's bridges for a span length [m] (see the module doc).
pub fn paper_girder_geometry(span_length: f64) -> BoxGirderDimensions {
    let thick = if span_length > 35.0 { 0.20 } else { 0.18 };
    BoxGirderDimensions {
        height: paper_girder_height(span_length),
        bottom_width: 1.0,
        web_thickness: thick,
        bottom_slab_thickness: thick,
        web_inclination: 0.25,
    }
}

/// The paper's bridge of `span_count` equal spans of `span_length` [m]: a grillage of three
/// composite box girders on an 8.5 m deck, the first support line pinned and the others roller
/// (free longitudinally, held laterally: see [`LateralRestraint`]),
/// E = 34.5 GPa, ρ = 2500 kg/m³, ζ = 0.05. `span_count` 0 is taken as 1. The paper's nine are
/// `paper_bridge(n, l)` for n in {2, 3, 4} and l in {20, 30, 40}.
pub fn paper_bridge(span_count: usize, span_length: f64) -> BridgeModel {
    let span_count = span_count.max(1);
    let girder = paper_girder_geometry(span_length);
    let mut supports = vec![BearingKind::Roller; span_count + 1];
    supports[0] = BearingKind::Pinned;
    BridgeModel::Grillage(Grillage {
        span_lengths: vec![span_length; span_count],
        supports,
        lateral_restraint: LateralRestraint::AllSupports,
        skew_angle: 0.0,
        deck_width: 8.5,
        girder_count: 3,
        girder_spacing: 2.9,
        girder: GirderShape::Box(girder),
        edge_girder: None,
        barriers: None,
        deck: DeckLayers::default(),
        diaphragm: Diaphragm {
            width: 0.4,
            depth: girder.height,
        },
        intermediate_diaphragms: None,
        bearings: Vec::new(),
        transverse_member_spacing: 2.0,
        material: Material::default(),
        damping_ratio: 0.05,
        mode_damping: None,
        damage: Default::default(),
    })
}

/// Span counts that a `paper-NxL` preset name accepts.
pub const PRESET_SPAN_COUNTS: std::ops::RangeInclusive<usize> = 1..=20;
/// Span lengths that a `paper-NxL` preset name accepts [m].
pub const PRESET_SPAN_LENGTHS: std::ops::RangeInclusive<f64> = 1.0..=500.0;
/// The bridge preset `paper-NxL` ([`paper_bridge`] of N spans of L metres), or None when the
/// name is not one. The one parser of bridge preset names: scenarios and studies both use it.
pub fn bridge_preset(name: &str) -> Option<(usize, f64)> {
    let rest = name.strip_prefix("paper-")?;
    let (spans, length) = rest.split_once('x')?;
    let spans: usize = spans.parse().ok()?;
    let length: f64 = length.parse().ok()?;
    (PRESET_SPAN_COUNTS.contains(&spans) && PRESET_SPAN_LENGTHS.contains(&length))
        .then_some((spans, length))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bridge_preset_names_are_parsed_within_their_ranges() {
        assert_eq!(bridge_preset("paper-3x30"), Some((3, 30.0)));
        assert_eq!(bridge_preset("paper-5x25"), Some((5, 25.0)));
        assert_eq!(bridge_preset("paper-1x12.5"), Some((1, 12.5)));
        for bad in [
            "paper-0x30",
            "paper-21x30",
            "paper-3x0.5",
            "paper-3x501",
            "paper-3",
            "box-3x30",
        ] {
            assert_eq!(bridge_preset(bad), None, "{bad}");
        }
    }

    #[test]
    fn the_nine_paper_bridges_are_valid_with_the_paper_girder_heights() {
        for (span_length, height) in [(20.0, 1.2), (30.0, 1.8), (40.0, 2.0)] {
            for span_count in 2..=4 {
                let model = paper_bridge(span_count, span_length);
                assert!(model.validate().is_ok(), "{span_count}x{span_length}");
                let BridgeModel::Grillage(g) = &model else {
                    panic!("grillage")
                };
                let GirderShape::Box(girder) = g.girder else {
                    panic!("box girders")
                };
                assert_eq!(girder.height, height);
                assert_eq!(g.span_lengths.len(), span_count);
            }
        }
    }
}
