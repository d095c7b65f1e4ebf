//! The girders of a grillage: their shapes (the paper's precast box, a T-beam, a precast
//! I-girder or a voided slab unit under the deck slab, or section properties given directly)
//! and the composite section each gives with its share of the deck.
//!
//! Axes: y lateral, z up from the soffit. A, the centroid and the second moments are exact for
//! the outlines (rectangles, the box's polygon, circular voids). The torsion constants follow
//! grillage practice (Hambly, *Bridge Deck Behaviour*, §3.8 and §5): the deck slab over a girder
//! contributes b t³/6, half the plate's b t³/3, because the transverse slab strips carry the
//! other half; a thin rectangle b × t gives β b t³ with β = (1 − 0.63 t/b)/3; a closed cell
//! gives Bredt's 4A_m²/∮ds/t.

use serde::{Deserialize, Serialize};

use super::section::{polygon_integrals, BoxGirderGeometry, BoxGirderSection};
use super::{BoxGirderDimensions, DeckLayers, MemberSection, ModelError};

/// A T-beam: a rectangular web (stem) under the deck slab, whose flange is the girder's share of
/// the slab.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TBeamDimensions {
    /// Height from the soffit to the top of the deck slab [m].
    pub height: f64,
    /// Web (stem) thickness [m].
    pub web_thickness: f64,
}

/// A precast I-girder with the deck slab cast on its top flange (no haunch).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct IGirderDimensions {
    /// Depth of the precast girder, soffit to the top of its top flange (the slab excluded) [m].
    pub height: f64,
    /// Top flange width [m].
    pub top_flange_width: f64,
    /// Top flange thickness [m].
    pub top_flange_thickness: f64,
    /// Bottom flange width [m].
    pub bottom_flange_width: f64,
    /// Bottom flange thickness [m].
    pub bottom_flange_thickness: f64,
    /// Web thickness [m].
    pub web_thickness: f64,
}

/// A precast voided slab unit with circular voids along the bridge, under the deck slab
/// (topping) and overlay.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct VoidedSlabDimensions {
    /// Width of the unit [m]; at most the girder's deck share.
    pub width: f64,
    /// Depth of the unit (the topping excluded) [m].
    pub depth: f64,
    /// Diameter of the voids [m]; less than the depth.
    pub void_diameter: f64,
    /// Number of voids, equally spaced across the unit, at mid-depth.
    pub void_count: usize,
}

/// Section properties given directly: the composite girder with its share of the deck slab.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GivenSection {
    /// Area A [m²].
    pub area: f64,
    /// Second moment about the horizontal centroidal axis I_y [m⁴] (vertical bending).
    pub second_moment_y: f64,
    /// Second moment about the vertical centroidal axis I_z [m⁴] (lateral bending).
    pub second_moment_z: f64,
    /// Saint-Venant torsion constant J [m⁴].
    pub torsion_constant: f64,
    /// Height of the centroid above the soffit [m].
    pub centroid_height: f64,
    /// Overall depth, soffit to the top of the slab [m] (the default diaphragm depth).
    pub depth: f64,
}

/// The shape of a grillage girder.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "shape")]
pub enum GirderShape {
    /// The paper's precast box, its top flange the girder's share of the deck slab.
    Box(BoxGirderDimensions),
    /// A T-beam, its flange the girder's share of the deck slab.
    TBeam(TBeamDimensions),
    /// A precast I-girder under its share of the deck slab.
    IGirder(IGirderDimensions),
    /// A voided slab unit under its share of the deck slab (topping).
    VoidedSlab(VoidedSlabDimensions),
    /// Composite section properties given directly (the deck slab included).
    Properties(GivenSection),
}

/// The composite section of one girder with its deck share, as the grillage uses it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GirderSection {
    /// Area A [m²] (structural overlay included).
    pub area: f64,
    /// Second moment about the horizontal centroidal axis I_y [m⁴] (vertical bending).
    pub second_moment_y: f64,
    /// Second moment about the vertical centroidal axis I_z [m⁴] (lateral bending).
    pub second_moment_z: f64,
    /// Saint-Venant torsion constant J [m⁴].
    pub torsion_constant: f64,
    /// Height of the centroid above the soffit [m].
    pub centroid_height: f64,
    /// Overall depth, soffit to the top of the structural overlay [m].
    pub depth: f64,
}

impl GirderSection {
    /// The section as a frame member.
    pub fn member_section(&self) -> MemberSection {
        MemberSection {
            area: self.area,
            second_moment_y: self.second_moment_y,
            second_moment_z: self.second_moment_z,
            torsion_constant: self.torsion_constant,
        }
    }
}

impl From<BoxGirderSection> for GirderSection {
    fn from(s: BoxGirderSection) -> Self {
        GirderSection {
            area: s.area(),
            second_moment_y: s.second_moment_y(),
            second_moment_z: s.second_moment_z(),
            torsion_constant: s.torsion_constant(),
            centroid_height: s.centroid_height(),
            depth: s.geometry().height + s.geometry().overlay_thickness,
        }
    }
}

/// Area integrals (A, ∫y dA, ∫z dA, ∫y² dA, ∫z² dA) of a section built from parts.
#[derive(Debug, Default)]
struct Integrals([f64; 5]);

impl Integrals {
    /// Adds (sign 1) or removes (sign −1) the rectangle from y0 to y1 and z0 to z1.
    fn rectangle(&mut self, sign: f64, (y0, y1): (f64, f64), (z0, z1): (f64, f64)) {
        let p = polygon_integrals(&[(y0, z0), (y1, z0), (y1, z1), (y0, z1)]);
        for k in 0..5 {
            self.0[k] += sign * p[k];
        }
    }

    /// Removes a circle of radius r centred at (y, z): A = πr², I about its centre πr⁴/4.
    fn remove_circle(&mut self, r: f64, y: f64, z: f64) {
        let a = std::f64::consts::PI * r * r;
        let own = a * r * r / 4.0;
        self.0[0] -= a;
        self.0[1] -= a * y;
        self.0[2] -= a * z;
        self.0[3] -= own + a * y * y;
        self.0[4] -= own + a * z * z;
    }

    /// A, the centroid height and the centroidal I_y, I_z.
    fn section(&self, torsion_constant: f64, depth: f64) -> GirderSection {
        let [a, sy, sz, syy, szz] = self.0;
        let (yc, zc) = (sy / a, sz / a);
        GirderSection {
            area: a,
            second_moment_y: szz - a * zc * zc,
            second_moment_z: syy - a * yc * yc,
            torsion_constant,
            centroid_height: zc,
            depth,
        }
    }
}

/// β b t³ of a solid rectangle b × t (either order), β = (1 − 0.63 c/a)/3 with c the shorter
/// side and a the longer (within 4 % of the series solution).
fn rectangle_torsion(b: f64, t: f64) -> f64 {
    MemberSection::rectangle(b, t).torsion_constant
}

/// Requires each (name, value) to be positive and finite.
fn positive(values: &[(&'static str, f64)]) -> Result<(), ModelError> {
    for &(quantity, value) in values {
        super::require_positive(quantity, value)?;
    }
    Ok(())
}

/// A geometric inconsistency of a girder shape.
fn misfit(message: String) -> ModelError {
    ModelError::GirderShape { message }
}

impl GirderShape {
    /// The composite section of a girder of this shape with `deck_share` [m] of the deck.
    pub fn section(&self, deck_share: f64, deck: &DeckLayers) -> Result<GirderSection, ModelError> {
        let slab = deck.slab_thickness;
        let overlay = deck.structural_overlay_thickness;
        match *self {
            GirderShape::Box(g) => BoxGirderSection::new(BoxGirderGeometry {
                height: g.height,
                top_flange_width: deck_share,
                bottom_width: g.bottom_width,
                top_slab_thickness: slab,
                web_thickness: g.web_thickness,
                bottom_slab_thickness: g.bottom_slab_thickness,
                web_inclination: g.web_inclination,
                overlay_thickness: overlay,
            })
            .map(GirderSection::from),
            GirderShape::TBeam(t) => t_beam(t, deck_share, slab, overlay),
            GirderShape::IGirder(i) => i_girder(i, deck_share, slab, overlay),
            GirderShape::VoidedSlab(v) => voided_slab(v, deck_share, slab, overlay),
            GirderShape::Properties(p) => {
                positive(&[
                    ("girder area", p.area),
                    ("girder second moment I_y", p.second_moment_y),
                    ("girder second moment I_z", p.second_moment_z),
                    ("girder torsion constant", p.torsion_constant),
                    ("girder depth", p.depth),
                ])?;
                if !(p.centroid_height.is_finite()
                    && p.centroid_height > 0.0
                    && p.centroid_height < p.depth)
                {
                    return Err(misfit(format!(
                        "the centroid height {} m is not inside the girder's depth {} m",
                        p.centroid_height, p.depth
                    )));
                }
                Ok(GirderSection {
                    area: p.area,
                    second_moment_y: p.second_moment_y,
                    second_moment_z: p.second_moment_z,
                    torsion_constant: p.torsion_constant,
                    centroid_height: p.centroid_height,
                    depth: p.depth,
                })
            }
        }
    }

    /// Depth from the soffit to the top of the deck slab [m], the overlay excluded: the default
    /// depth of the diaphragms. Given properties: their depth.
    pub fn depth_to_slab_top(&self, deck: &DeckLayers) -> f64 {
        match *self {
            GirderShape::Box(g) => g.height,
            GirderShape::TBeam(t) => t.height,
            GirderShape::IGirder(i) => i.height + deck.slab_thickness,
            GirderShape::VoidedSlab(v) => v.depth + deck.slab_thickness,
            GirderShape::Properties(p) => p.depth,
        }
    }

    /// The section of a transverse slab strip `width` [m] wide (along the bridge) over girders
    /// of this shape: the deck slab and overlay, [`MemberSection::slab_strip`]; over voided slab
    /// units, the unit's depth acts transversely too ([`voided_transverse_strip`]).
    pub fn transverse_strip(&self, width: f64, deck: &DeckLayers) -> MemberSection {
        let thickness = deck.slab_thickness + deck.structural_overlay_thickness;
        match *self {
            GirderShape::VoidedSlab(v) => voided_transverse_strip(&v, width, thickness),
            _ => MemberSection::slab_strip(width, thickness),
        }
    }
}

/// T-beam: web b_w × (h − t_s) under a flange (deck share × slab) and the overlay. J: the web
/// rectangle β b t³ plus the slab and overlay b t³/6 (Hambly).
fn t_beam(
    t: TBeamDimensions,
    share: f64,
    slab: f64,
    overlay: f64,
) -> Result<GirderSection, ModelError> {
    positive(&[
        ("T-beam height", t.height),
        ("T-beam web thickness", t.web_thickness),
    ])?;
    let web_height = t.height - slab;
    if web_height <= 0.0 {
        return Err(misfit(format!(
            "the T-beam's height {} m leaves no web under the {slab} m slab",
            t.height
        )));
    }
    if t.web_thickness > share {
        return Err(misfit(format!(
            "the T-beam's web ({} m) is wider than its {share} m share of the deck",
            t.web_thickness
        )));
    }
    let (hw, hs) = (t.web_thickness / 2.0, share / 2.0);
    let mut sum = Integrals::default();
    sum.rectangle(1.0, (-hw, hw), (0.0, web_height));
    sum.rectangle(1.0, (-hs, hs), (web_height, t.height + overlay));
    let torsion =
        rectangle_torsion(t.web_thickness, web_height) + share * (slab + overlay).powi(3) / 6.0;
    Ok(sum.section(torsion, t.height + overlay))
}

/// I-girder: bottom flange, web and top flange, the slab (deck share) on top, then the overlay.
/// J: β b t³ of the three precast rectangles plus the slab and overlay b t³/6 (Hambly).
fn i_girder(
    i: IGirderDimensions,
    share: f64,
    slab: f64,
    overlay: f64,
) -> Result<GirderSection, ModelError> {
    positive(&[
        ("I-girder height", i.height),
        ("I-girder top flange width", i.top_flange_width),
        ("I-girder top flange thickness", i.top_flange_thickness),
        ("I-girder bottom flange width", i.bottom_flange_width),
        (
            "I-girder bottom flange thickness",
            i.bottom_flange_thickness,
        ),
        ("I-girder web thickness", i.web_thickness),
    ])?;
    let web_height = i.height - i.top_flange_thickness - i.bottom_flange_thickness;
    if web_height <= 0.0 {
        return Err(misfit(format!(
            "the I-girder's flanges ({} m and {} m) leave no web in its {} m height",
            i.top_flange_thickness, i.bottom_flange_thickness, i.height
        )));
    }
    if i.web_thickness > i.top_flange_width.min(i.bottom_flange_width) {
        return Err(misfit(format!(
            "the I-girder's web ({} m) is wider than a flange",
            i.web_thickness
        )));
    }
    if i.top_flange_width.max(i.bottom_flange_width) > share {
        return Err(misfit(format!(
            "the I-girder's flanges ({} m and {} m) are wider than its {share} m share of the \
             deck: neighbouring girders would overlap",
            i.top_flange_width, i.bottom_flange_width
        )));
    }
    let mut sum = Integrals::default();
    let half = |w: f64| (-w / 2.0, w / 2.0);
    let z1 = i.bottom_flange_thickness;
    let z2 = z1 + web_height;
    sum.rectangle(1.0, half(i.bottom_flange_width), (0.0, z1));
    sum.rectangle(1.0, half(i.web_thickness), (z1, z2));
    sum.rectangle(1.0, half(i.top_flange_width), (z2, i.height));
    sum.rectangle(1.0, half(share), (i.height, i.height + slab + overlay));
    let torsion = rectangle_torsion(i.bottom_flange_width, i.bottom_flange_thickness)
        + rectangle_torsion(i.web_thickness, web_height)
        + rectangle_torsion(i.top_flange_width, i.top_flange_thickness)
        + share * (slab + overlay).powi(3) / 6.0;
    Ok(sum.section(torsion, i.height + slab + overlay))
}

/// The wall thicknesses of a voided unit: (top and bottom, the outer sides, the void pitch).
fn voided_walls(v: &VoidedSlabDimensions) -> (f64, f64, f64) {
    let n = v.void_count as f64;
    let pitch = v.width / n;
    let cover = (v.depth - v.void_diameter) / 2.0;
    let side = (pitch - v.void_diameter) / 2.0;
    (cover, side, pitch)
}

/// Voided slab unit: the unit's rectangle minus its circular voids (exact A and I), the topping
/// slab (deck share) and overlay on top. J: the unit as one thin-walled closed cell over its
/// outer walls (Bredt: a uniformly twisted multi-cell section of equal cells carries no shear
/// flow in its inner webs), walls the cover over the voids and the outer side webs, plus the
/// topping b t³/6 (Hambly).
fn voided_slab(
    v: VoidedSlabDimensions,
    share: f64,
    slab: f64,
    overlay: f64,
) -> Result<GirderSection, ModelError> {
    positive(&[
        ("voided slab width", v.width),
        ("voided slab depth", v.depth),
        ("voided slab void diameter", v.void_diameter),
    ])?;
    if v.void_count == 0 {
        return Err(misfit("a voided slab unit needs at least one void".into()));
    }
    if v.width > share * (1.0 + 1e-12) {
        return Err(misfit(format!(
            "the voided slab unit ({} m) is wider than its {share} m share of the deck",
            v.width
        )));
    }
    let (cover, side, pitch) = voided_walls(&v);
    if cover <= 0.0 || side <= 0.0 {
        return Err(misfit(format!(
            "{} voids of {} m do not fit in a {} m × {} m unit with walls around them",
            v.void_count, v.void_diameter, v.width, v.depth
        )));
    }
    let mut sum = Integrals::default();
    sum.rectangle(1.0, (-v.width / 2.0, v.width / 2.0), (0.0, v.depth));
    for k in 0..v.void_count {
        let y = -v.width / 2.0 + pitch * (k as f64 + 0.5);
        sum.remove_circle(v.void_diameter / 2.0, y, v.depth / 2.0);
    }
    let top = v.depth + slab + overlay;
    sum.rectangle(1.0, (-share / 2.0, share / 2.0), (v.depth, top));
    let enclosed_width = v.width - side;
    let enclosed_height = v.depth - cover;
    let line_integral = 2.0 * enclosed_width / cover + 2.0 * enclosed_height / side;
    let closed = 4.0 * (enclosed_width * enclosed_height).powi(2) / line_integral;
    let torsion = closed + share * (slab + overlay).powi(3) / 6.0;
    Ok(sum.section(torsion, top))
}

/// A transverse strip `width` wide of a voided slab deck under a topping `thickness` thick.
///
/// Across the bridge the unit's depth d acts with its voids: a cut at lateral distance η from a
/// void's axis has I(η) = (d³ − c³)/12 per unit length, c = 2√(r² − η²) the void's chord. A
/// member bending across the voids has its flexibilities in series, so the effective depth
/// d_e is that of the harmonic mean of I over a pitch s: d_e³/12 = s / ∫ dη / I(η) (midpoint
/// rule, 2000 points: the integrand is smooth). The strip is then the plate of depth d_e and
/// the topping bonded on it (exact composite I), J = b (d_e + t)³/6 (Hambly).
pub fn voided_transverse_strip(
    v: &VoidedSlabDimensions,
    width: f64,
    thickness: f64,
) -> MemberSection {
    let (_, _, pitch) = voided_walls(v);
    let r = v.void_diameter / 2.0;
    let d3 = v.depth.powi(3);
    const POINTS: usize = 2000;
    let flexibility: f64 = (0..POINTS)
        .map(|k| {
            let eta = pitch * ((k as f64 + 0.5) / POINTS as f64 - 0.5);
            let chord = 2.0 * (r * r - eta * eta).max(0.0).sqrt();
            12.0 / (d3 - chord.powi(3))
        })
        .sum::<f64>()
        / POINTS as f64;
    let effective_depth = (12.0 / flexibility).cbrt();
    let mut sum = Integrals::default();
    sum.rectangle(1.0, (-width / 2.0, width / 2.0), (0.0, effective_depth));
    sum.rectangle(
        1.0,
        (-width / 2.0, width / 2.0),
        (effective_depth, effective_depth + thickness),
    );
    let total = effective_depth + thickness;
    let s = sum.section(0.0, total);
    MemberSection {
        area: width * (v.depth + thickness) - std::f64::consts::PI * r * r * width / pitch,
        second_moment_y: s.second_moment_y,
        second_moment_z: s.second_moment_z,
        torsion_constant: width * total.powi(3) / 6.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn deck(slab: f64, overlay: f64) -> DeckLayers {
        DeckLayers {
            slab_thickness: slab,
            structural_overlay_thickness: overlay,
            ..DeckLayers::default()
        }
    }

    fn close(a: f64, b: f64, tolerance: f64) -> bool {
        (a - b).abs() <= tolerance * b.abs().max(1e-300)
    }

    #[test]
    fn t_beam_properties_match_the_two_rectangle_closed_form() {
        // Web 0.4 × 1.0 under a flange 2.0 × 0.2 (no overlay): A = 0.4 + 0.4 = 0.8 m²,
        // centroid (0.4·0.5 + 0.4·1.1)/0.8 = 0.8 m, I_y = Σ(bh³/12 + A d²)
        //   = 0.4/12·1 + 0.4·0.09 + 2·0.008/12 + 0.4·0.09 = 0.073333… + 0.0013333… = 0.10533… m⁴.
        let s = GirderShape::TBeam(TBeamDimensions {
            height: 1.2,
            web_thickness: 0.4,
        })
        .section(2.0, &deck(0.2, 0.0))
        .unwrap();
        assert!(close(s.area, 0.8, 1e-14));
        assert!(close(s.centroid_height, 0.8, 1e-14));
        let i_y = 0.4 / 12.0 + 0.4 * 0.09 + 2.0 * 0.008 / 12.0 + 0.4 * 0.09;
        assert!(close(s.second_moment_y, i_y, 1e-13));
        let i_z = 1.0 * 0.4f64.powi(3) / 12.0 + 0.2 * 8.0 / 12.0;
        assert!(close(s.second_moment_z, i_z, 1e-13));
        // J: web 1.0 × 0.4: 1.0·0.064·(1 − 0.63·0.4)/3, slab 2·0.008/6.
        let j = 0.064 * (1.0 - 0.252) / 3.0 + 2.0 * 0.008 / 6.0;
        assert!(close(s.torsion_constant, j, 1e-13));
    }

    #[test]
    fn i_girder_of_equal_flanges_has_its_precast_centroid_at_mid_height() {
        // Without a slab effect (slab share = flange width and the overlay counted), check the
        // parallel-axis sum of four rectangles against a direct computation.
        let i = IGirderDimensions {
            height: 1.6,
            top_flange_width: 0.8,
            top_flange_thickness: 0.2,
            bottom_flange_width: 0.8,
            bottom_flange_thickness: 0.2,
            web_thickness: 0.2,
        };
        let s = GirderShape::IGirder(i)
            .section(2.4, &deck(0.2, 0.0))
            .unwrap();
        let parts = [
            (0.8, 0.2, 0.1),
            (0.2, 1.2, 0.8),
            (0.8, 0.2, 1.5),
            (2.4, 0.2, 1.7),
        ];
        let area: f64 = parts.iter().map(|p| p.0 * p.1).sum();
        let zc = parts.iter().map(|p| p.0 * p.1 * p.2).sum::<f64>() / area;
        let i_y: f64 = parts
            .iter()
            .map(|&(b, h, z)| b * h.powi(3) / 12.0 + b * h * (z - zc).powi(2))
            .sum();
        assert!(close(s.area, area, 1e-14));
        assert!(close(s.centroid_height, zc, 1e-14));
        assert!(close(s.second_moment_y, i_y, 1e-13));
        assert!(close(s.depth, 1.8, 1e-15));
    }

    #[test]
    fn a_voided_unit_loses_exactly_its_voids_area_and_second_moment() {
        // 1.0 × 0.6 unit, two voids of 0.3 at mid-depth, 0.1 m topping over a 1.0 m share.
        let v = VoidedSlabDimensions {
            width: 1.0,
            depth: 0.6,
            void_diameter: 0.3,
            void_count: 2,
        };
        let s = GirderShape::VoidedSlab(v)
            .section(1.0, &deck(0.1, 0.0))
            .unwrap();
        let void = std::f64::consts::PI * 0.15f64.powi(2);
        // Symmetric about mid-depth of the unit, so the voids sit at the unit's own centroid:
        // solid 1.0 × 0.7 minus the voids, centroid from the moment of areas.
        let area = 0.7 - 2.0 * void;
        assert!(close(s.area, area, 1e-14));
        let zc = (0.7 * 0.35 - 2.0 * void * 0.3) / area;
        assert!(close(s.centroid_height, zc, 1e-14));
        let i_y = 0.343 / 12.0 + 0.7 * (0.35 - zc).powi(2)
            - 2.0 * (void * 0.15f64.powi(2) / 4.0 + void * (0.3 - zc).powi(2));
        assert!(close(s.second_moment_y, i_y, 1e-13));
        assert!(s.torsion_constant > 0.0);
    }

    #[test]
    fn the_transverse_strip_of_a_voided_deck_lies_between_its_void_and_solid_bounds() {
        // Series flexibility over a pitch: above the weakest cut (through a void's axis) and
        // below the solid plate; with vanishing voids it tends to the solid plate.
        let v = VoidedSlabDimensions {
            width: 1.0,
            depth: 0.6,
            void_diameter: 0.36,
            void_count: 2,
        };
        let s = voided_transverse_strip(&v, 1.0, 0.0);
        let solid = 0.6f64.powi(3) / 12.0;
        let weakest = (0.6f64.powi(3) - 0.36f64.powi(3)) / 12.0;
        assert!(s.second_moment_y < solid && s.second_moment_y > weakest);
        let tiny = VoidedSlabDimensions {
            void_diameter: 1e-4,
            ..v
        };
        let t = voided_transverse_strip(&tiny, 1.0, 0.0);
        assert!(close(t.second_moment_y, solid, 1e-9));
    }

    #[test]
    fn given_properties_pass_through_and_a_centroid_outside_the_depth_is_refused() {
        let p = GivenSection {
            area: 1.2,
            second_moment_y: 0.5,
            second_moment_z: 2.0,
            torsion_constant: 0.3,
            centroid_height: 0.9,
            depth: 1.5,
        };
        let s = GirderShape::Properties(p)
            .section(3.0, &deck(0.2, 0.0))
            .unwrap();
        assert_eq!(
            (s.area, s.second_moment_y, s.torsion_constant),
            (1.2, 0.5, 0.3)
        );
        let bad = GivenSection {
            centroid_height: 1.6,
            ..p
        };
        assert!(matches!(
            GirderShape::Properties(bad).section(3.0, &deck(0.2, 0.0)),
            Err(ModelError::GirderShape { .. })
        ));
    }

    #[test]
    fn misfitting_shapes_are_refused_with_their_numbers() {
        let t = GirderShape::TBeam(TBeamDimensions {
            height: 0.15,
            web_thickness: 0.3,
        });
        assert!(matches!(
            t.section(2.0, &deck(0.2, 0.0)),
            Err(ModelError::GirderShape { .. })
        ));
        let v = GirderShape::VoidedSlab(VoidedSlabDimensions {
            width: 1.0,
            depth: 0.5,
            void_diameter: 0.45,
            void_count: 3,
        });
        assert!(matches!(
            v.section(1.0, &deck(0.1, 0.0)),
            Err(ModelError::GirderShape { .. })
        ));
    }
}
