//! Cross-section properties: the thin-walled precast box girder (with its share of the deck slab
//! and the structural overlay) and the plain frame-member section the FE stage uses.

use serde::{Deserialize, Serialize};

use super::ModelError;

/// Geometry of one composite box girder: the precast box, whose top flange is the girder's share
/// of the deck slab, plus the structural concrete overlay on top of that flange.
///
/// ```text
///   |<-------------- top_flange_width -------------->|
///   +================================================+   overlay_thickness (structural overlay)
///   +------------------------------------------------+
///   |            top_slab_thickness (deck slab)      |
///   +-------+----------------------------------+-----+
///            \  web (horizontal thickness)    /         ^
///             \      cell                    /          | height (bottom of box
///              \                            /           |  to top of the slab)
///               +--------------------------+            |
///               |  bottom_slab_thickness   |            v
///               +--------------------------+
///               |<----- bottom_width ----->|
/// ```
/// Each web rises outwards with `web_inclination` horizontal per unit rise.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BoxGirderGeometry {
    /// Height of the precast box from its soffit to the top of the deck slab [m].
    pub height: f64,
    /// Width of the top flange, which is the girder's share of the deck slab [m].
    pub top_flange_width: f64,
    /// Outer width of the bottom slab (soffit) [m].
    pub bottom_width: f64,
    /// Thickness of the top slab (deck slab) [m]; the paper's 18 cm.
    pub top_slab_thickness: f64,
    /// Web thickness, measured horizontally [m].
    pub web_thickness: f64,
    /// Bottom slab thickness [m].
    pub bottom_slab_thickness: f64,
    /// Outward horizontal run of each web per unit rise [-]; 0 for vertical webs.
    pub web_inclination: f64,
    /// Structural concrete overlay over the whole top flange [m]; the paper's 4 cm. May be 0.
    pub overlay_thickness: f64,
}

/// A validated box-girder section and its properties, computed from [`BoxGirderGeometry`].
///
/// Axes: y lateral, z up; `second_moment_y` is about the horizontal centroidal axis (vertical
/// bending), `second_moment_z` about the vertical one (lateral bending).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BoxGirderSection {
    geometry: BoxGirderGeometry,
    area: f64,
    second_moment_y: f64,
    second_moment_z: f64,
    torsion_constant: f64,
    centroid_height: f64,
}

/// Area, centroid and second moments of a simple polygon from its vertices (counter-clockwise
/// gives positive area), by Green's theorem. Returns (A, ∫y dA, ∫z dA, ∫y² dA, ∫z² dA).
/// Hand-written: a few lines, not worth a dependency.
pub(super) fn polygon_integrals(points: &[(f64, f64)]) -> [f64; 5] {
    let mut out = [0.0; 5];
    for i in 0..points.len() {
        let (y0, z0) = points[i];
        let (y1, z1) = points[(i + 1) % points.len()];
        let c = y0 * z1 - y1 * z0;
        out[0] += c / 2.0;
        out[1] += (y0 + y1) * c / 6.0;
        out[2] += (z0 + z1) * c / 6.0;
        out[3] += (y0 * y0 + y0 * y1 + y1 * y1) * c / 12.0;
        out[4] += (z0 * z0 + z0 * z1 + z1 * z1) * c / 12.0;
    }
    out
}

impl BoxGirderSection {
    /// Validates the geometry and computes the section properties.
    ///
    /// A, centroid and second moments are exact for the polygonal outline (outer outline minus
    /// the cell, plus the overlay). The torsion constant is Bredt's thin-walled closed-section
    /// formula J = 4A_m² / ∮ds/t over the wall centreline (top wall thickness = slab + overlay,
    /// web thickness normal to the web), plus the open-section term Σ b t³/3 of the two flange
    /// cantilevers.
    pub fn new(geometry: BoxGirderGeometry) -> Result<Self, ModelError> {
        let g = geometry;
        for (quantity, value) in [
            ("box girder height", g.height),
            ("box girder top flange width", g.top_flange_width),
            ("box girder bottom width", g.bottom_width),
            ("box girder top slab thickness", g.top_slab_thickness),
            ("box girder web thickness", g.web_thickness),
            ("box girder bottom slab thickness", g.bottom_slab_thickness),
        ] {
            super::require_positive(quantity, value)?;
        }
        for (quantity, value) in [
            ("box girder web inclination", g.web_inclination),
            ("box girder overlay thickness", g.overlay_thickness),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(ModelError::Negative { quantity, value });
            }
        }
        let web_height = g.height - g.top_slab_thickness - g.bottom_slab_thickness;
        if web_height <= 0.0 {
            return Err(ModelError::SlabsTooThick {
                height: g.height,
                top_slab_thickness: g.top_slab_thickness,
                bottom_slab_thickness: g.bottom_slab_thickness,
            });
        }
        let half_bottom = g.bottom_width / 2.0;
        let web_top = g.height - g.top_slab_thickness;
        // Outer face of a web at height z: half_bottom + inclination · z.
        let outer = |z: f64| half_bottom + g.web_inclination * z;
        let inner_bottom = outer(g.bottom_slab_thickness) - g.web_thickness;
        if inner_bottom <= 0.0 {
            return Err(ModelError::WebsTooThick {
                bottom_width: g.bottom_width,
                web_thickness: g.web_thickness,
            });
        }
        let half_top = g.top_flange_width / 2.0;
        if half_top < outer(web_top) {
            return Err(ModelError::FlangeNarrowerThanBox {
                top_flange_width: g.top_flange_width,
                box_top_width: 2.0 * outer(web_top),
            });
        }
        let outline = [
            (-half_bottom, 0.0),
            (half_bottom, 0.0),
            (outer(web_top), web_top),
            (half_top, web_top),
            (half_top, g.height),
            (-half_top, g.height),
            (-half_top, web_top),
            (-outer(web_top), web_top),
        ];
        let cell = [
            (-inner_bottom, g.bottom_slab_thickness),
            (inner_bottom, g.bottom_slab_thickness),
            (outer(web_top) - g.web_thickness, web_top),
            (-(outer(web_top) - g.web_thickness), web_top),
        ];
        let overlay_top = g.height + g.overlay_thickness;
        let overlay = [
            (-half_top, g.height),
            (half_top, g.height),
            (half_top, overlay_top),
            (-half_top, overlay_top),
        ];
        let mut sum = [0.0; 5];
        for (polygon, sign) in [(&outline[..], 1.0), (&cell[..], -1.0), (&overlay[..], 1.0)] {
            let p = polygon_integrals(polygon);
            for k in 0..5 {
                sum[k] += sign * p[k];
            }
        }
        let area = sum[0];
        let centroid_lateral = sum[1] / area;
        let centroid_height = sum[2] / area;
        let second_moment_z = sum[3] - area * centroid_lateral * centroid_lateral;
        let second_moment_y = sum[4] - area * centroid_height * centroid_height;

        // Bredt over the wall centreline.
        let top_wall = g.top_slab_thickness + g.overlay_thickness;
        let z_top = g.height - g.top_slab_thickness / 2.0;
        let z_bottom = g.bottom_slab_thickness / 2.0;
        let centreline = |z: f64| outer(z) - g.web_thickness / 2.0;
        let width_top = 2.0 * centreline(z_top);
        let width_bottom = 2.0 * centreline(z_bottom);
        let cell_height = z_top - z_bottom;
        let enclosed_area = (width_top + width_bottom) / 2.0 * cell_height;
        let slope = (1.0 + g.web_inclination * g.web_inclination).sqrt();
        let web_length = cell_height * slope;
        let web_normal_thickness = g.web_thickness / slope;
        let line_integral = width_top / top_wall
            + width_bottom / g.bottom_slab_thickness
            + 2.0 * web_length / web_normal_thickness;
        let closed = 4.0 * enclosed_area * enclosed_area / line_integral;
        let cantilever = (half_top - outer(web_top)).max(0.0);
        let open = 2.0 * cantilever * top_wall.powi(3) / 3.0;
        Ok(Self {
            geometry,
            area,
            second_moment_y,
            second_moment_z,
            torsion_constant: closed + open,
            centroid_height,
        })
    }

    /// The geometry this section was computed from.
    pub fn geometry(&self) -> &BoxGirderGeometry {
        &self.geometry
    }
    /// Cross-section area A [m²], overlay included.
    pub fn area(&self) -> f64 {
        self.area
    }
    /// Second moment of area about the horizontal centroidal axis I_y [m⁴] (vertical bending).
    pub fn second_moment_y(&self) -> f64 {
        self.second_moment_y
    }
    /// Second moment of area about the vertical centroidal axis I_z [m⁴] (lateral bending).
    pub fn second_moment_z(&self) -> f64 {
        self.second_moment_z
    }
    /// Saint-Venant torsion constant J [m⁴] (Bredt, closed cell, plus flange cantilevers).
    pub fn torsion_constant(&self) -> f64 {
        self.torsion_constant
    }
    /// Height of the centroid above the soffit [m].
    pub fn centroid_height(&self) -> f64 {
        self.centroid_height
    }
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

/// Section properties of a straight frame member in its local axes (x along the member, z up,
/// y = z × x).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MemberSection {
    /// Area A [m²].
    pub area: f64,
    /// Second moment about local y, I_y [m⁴]: bending in the vertical plane.
    pub second_moment_y: f64,
    /// Second moment about local z, I_z [m⁴]: bending in the horizontal plane.
    pub second_moment_z: f64,
    /// Saint-Venant torsion constant J [m⁴].
    pub torsion_constant: f64,
}

impl MemberSection {
    /// A solid rectangle `width` (horizontal, across the member) × `depth` (vertical) [m]:
    /// A = bd, I_y = bd³/12, I_z = db³/12, J = β·a·c³ with c the shorter and a the longer side,
    /// β = (1 − 0.63 c/a)/3 (the usual approximation, within 4 % of the series solution).
    pub fn rectangle(width: f64, depth: f64) -> Self {
        let (long, short) = if width >= depth {
            (width, depth)
        } else {
            (depth, width)
        };
        MemberSection {
            area: width * depth,
            second_moment_y: width * depth.powi(3) / 12.0,
            second_moment_z: depth * width.powi(3) / 12.0,
            torsion_constant: long * short.powi(3) * (1.0 - 0.63 * short / long) / 3.0,
        }
    }

    /// A strip of deck slab in a grillage: tributary `width` [m] (along the bridge) of a slab
    /// `thickness` [m] thick. I_y = b t³/12 and, as in grillage practice (Hambly), J = b t³/6:
    /// half of the plate's torsional stiffness b t³/3 is given to each direction.
    pub fn slab_strip(width: f64, thickness: f64) -> Self {
        MemberSection {
            area: width * thickness,
            second_moment_y: width * thickness.powi(3) / 12.0,
            second_moment_z: thickness * width.powi(3) / 12.0,
            torsion_constant: width * thickness.powi(3) / 6.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rectangular_tube(side: f64, wall: f64) -> BoxGirderGeometry {
        BoxGirderGeometry {
            height: side,
            top_flange_width: side,
            bottom_width: side,
            top_slab_thickness: wall,
            web_thickness: wall,
            bottom_slab_thickness: wall,
            web_inclination: 0.0,
            overlay_thickness: 0.0,
        }
    }

    #[test]
    fn square_tube_properties_match_the_closed_forms() {
        // Square tube, outer side 1 m, wall 0.05 m: A = b² − (b − 2t)², I = (b⁴ − (b − 2t)⁴)/12
        // exactly; Bredt J = 4A_m²/∮ds/t = t·a³ with a = b − t the centreline side.
        let (b, t) = (1.0, 0.05);
        let s = BoxGirderSection::new(rectangular_tube(b, t)).unwrap();
        let bi: f64 = b - 2.0 * t;
        assert!((s.area() - (b * b - bi * bi)).abs() < 1e-12);
        let i = (b.powi(4) - bi.powi(4)) / 12.0;
        assert!((s.second_moment_y() - i).abs() < 1e-12);
        assert!((s.second_moment_z() - i).abs() < 1e-12);
        assert!((s.centroid_height() - 0.5).abs() < 1e-12);
        let a = b - t;
        assert!((s.torsion_constant() - t * a.powi(3)).abs() < 1e-12);
    }

    #[test]
    fn overlay_and_flanges_raise_the_centroid() {
        let mut g = rectangular_tube(1.2, 0.18);
        g.top_flange_width = 2.4;
        g.overlay_thickness = 0.04;
        g.web_inclination = 0.2;
        let s = BoxGirderSection::new(g).unwrap();
        assert!(s.centroid_height() > 0.6);
        assert!(s.area() > 0.0 && s.second_moment_y() > 0.0 && s.torsion_constant() > 0.0);
    }

    #[test]
    fn invalid_geometry_is_rejected_with_its_numbers() {
        let mut g = rectangular_tube(1.0, 0.05);
        g.web_thickness = 0.6;
        assert!(matches!(
            BoxGirderSection::new(g),
            Err(ModelError::WebsTooThick { web_thickness, .. }) if web_thickness == 0.6
        ));
        let mut g = rectangular_tube(1.0, 0.05);
        g.top_slab_thickness = 0.6;
        g.bottom_slab_thickness = 0.5;
        assert!(matches!(
            BoxGirderSection::new(g),
            Err(ModelError::SlabsTooThick { .. })
        ));
        let mut g = rectangular_tube(1.0, 0.05);
        g.height = -1.0;
        assert!(matches!(
            BoxGirderSection::new(g),
            Err(ModelError::NotPositive { value, .. }) if value == -1.0
        ));
        let mut g = rectangular_tube(1.0, 0.05);
        g.top_flange_width = 0.8;
        assert!(matches!(
            BoxGirderSection::new(g),
            Err(ModelError::FlangeNarrowerThanBox { .. })
        ));
    }
}
