//! The stress at a detail from the effects of its station: the elastic section of a steel
//! I-girder, alone or composite with a concrete slab (transformed by the modular ratio), and a
//! stress-concentration factor.
//!
//! Engineer's beam theory (e.g. Gere & Goodno, *Mechanics of Materials*, §5.5 and §5.8):
//! - the direct stress at height y above the bottom face under a sagging moment M is
//!   σ = M (ȳ − y)/I, tension positive, with ȳ the elastic neutral axis's height and I the
//!   second moment of area about it;
//! - the shear stress in the web at height y under a shear force V is τ = V Q(y)/(I t_w), with
//!   Q(y) the first moment about the neutral axis of the section above y (Jourawski).
//!
//! A composite slab counts as steel of width b_c/n (n = E_s/E_c, the modular ratio: EN 1994-2
//! §5.4.2.2 for short-term loads such as traffic, n₀ = E_a/E_cm), uncracked: the stress ranges
//! of traffic on a deck in sagging.

use thiserror::Error;

/// A rectangular plate of a section: width × thickness [m].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Plate {
    /// Width [m].
    pub width: f64,
    /// Thickness [m].
    pub thickness: f64,
}

/// A concrete slab on the top flange, as one rectangle.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ConcreteSlab {
    /// The effective width (EN 1994-2 §5.4.1.2) and the thickness [m].
    pub plate: Plate,
    /// The gap between the top flange's top face and the slab's soffit (a haunch) [m].
    pub haunch: f64,
    /// n = E_steel/E_concrete [-].
    pub modular_ratio: f64,
}

/// A welded or rolled steel I-girder, bottom flange, web and top flange, optionally composite.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct GirderSection {
    /// The bottom flange [m].
    pub bottom_flange: Plate,
    /// The web: thickness t_w and depth between the flanges (its `width` is its depth) [m].
    pub web: Plate,
    /// The top flange [m].
    pub top_flange: Plate,
    /// A concrete slab acting with the girder; None for the steel girder alone.
    pub slab: Option<ConcreteSlab>,
}

/// Where on the girder's steel a detail lies.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Fibre {
    /// The bottom face of the bottom flange (a cover-plate end, a flange splice, an attachment
    /// on the flange).
    BottomFlange,
    /// The top face of the bottom flange: the toe of the web-to-flange weld and of the
    /// transverse stiffeners' welds.
    WeldToe,
    /// The top face of the top flange (shear connectors' welds).
    TopFlange,
    /// The elastic neutral axis (for a shear stress).
    NeutralAxis,
    /// A height above the bottom face [m].
    Height(f64),
}

/// A section that cannot carry the stresses asked of it.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SectionError {
    /// A dimension that is not positive and finite.
    #[error("the {what} is {value} m; expected a positive length")]
    NotPositive { what: &'static str, value: f64 },
    /// A modular ratio that is not positive.
    #[error(
        "the modular ratio is {0}; expected a positive E_steel/E_concrete (about 6 for traffic)"
    )]
    ModularRatio(f64),
    /// A fibre outside the steel.
    #[error("the fibre is at {height} m; expected a height in the steel, 0 to {depth} m")]
    OutsideSteel { height: f64, depth: f64 },
    /// A shear stress asked outside the web.
    #[error(
        "a shear stress is read in the web, between {from} and {to} m; the fibre is at {height} m"
    )]
    ShearOutsideWeb { height: f64, from: f64, to: f64 },
}

/// One rectangle of the transformed section: its width, and its bottom's and top's heights
/// above the bottom face [m].
#[derive(Debug, Clone, Copy)]
struct Rectangle {
    width: f64,
    bottom: f64,
    top: f64,
}

impl Rectangle {
    fn area(&self) -> f64 {
        self.width * (self.top - self.bottom)
    }
    fn centroid(&self) -> f64 {
        0.5 * (self.bottom + self.top)
    }
    fn own_second_moment(&self) -> f64 {
        self.width * (self.top - self.bottom).powi(3) / 12.0
    }
}

impl GirderSection {
    /// Refuses a dimension that is not a positive length.
    pub fn check(&self) -> Result<(), SectionError> {
        let mut lengths = vec![
            ("bottom flange's width", self.bottom_flange.width),
            ("bottom flange's thickness", self.bottom_flange.thickness),
            ("web's depth", self.web.width),
            ("web's thickness", self.web.thickness),
            ("top flange's width", self.top_flange.width),
            ("top flange's thickness", self.top_flange.thickness),
        ];
        if let Some(slab) = &self.slab {
            lengths.push(("slab's width", slab.plate.width));
            lengths.push(("slab's thickness", slab.plate.thickness));
            if !(slab.haunch >= 0.0 && slab.haunch.is_finite()) {
                return Err(SectionError::NotPositive {
                    what: "haunch",
                    value: slab.haunch,
                });
            }
            if !(slab.modular_ratio > 0.0 && slab.modular_ratio.is_finite()) {
                return Err(SectionError::ModularRatio(slab.modular_ratio));
            }
        }
        match lengths
            .into_iter()
            .find(|(_, v)| !(*v > 0.0 && v.is_finite()))
        {
            Some((what, value)) => Err(SectionError::NotPositive { what, value }),
            None => Ok(()),
        }
    }

    /// The steel's depth [m].
    pub fn steel_depth(&self) -> f64 {
        self.bottom_flange.thickness + self.web.width + self.top_flange.thickness
    }

    /// The transformed section's rectangles, bottom up.
    fn rectangles(&self) -> Vec<Rectangle> {
        let web_bottom = self.bottom_flange.thickness;
        let web_top = web_bottom + self.web.width;
        let depth = self.steel_depth();
        let mut parts = vec![
            Rectangle {
                width: self.bottom_flange.width,
                bottom: 0.0,
                top: web_bottom,
            },
            Rectangle {
                width: self.web.thickness,
                bottom: web_bottom,
                top: web_top,
            },
            Rectangle {
                width: self.top_flange.width,
                bottom: web_top,
                top: depth,
            },
        ];
        if let Some(slab) = &self.slab {
            let bottom = depth + slab.haunch;
            parts.push(Rectangle {
                width: slab.plate.width / slab.modular_ratio,
                bottom,
                top: bottom + slab.plate.thickness,
            });
        }
        parts
    }

    /// The elastic neutral axis's height above the bottom face, ȳ = Σ Aᵢ yᵢ / Σ Aᵢ [m].
    pub fn neutral_axis(&self) -> f64 {
        let parts = self.rectangles();
        let area: f64 = parts.iter().map(Rectangle::area).sum();
        parts.iter().map(|p| p.area() * p.centroid()).sum::<f64>() / area
    }

    /// The second moment of area about the neutral axis, I = Σ (Iᵢ + Aᵢ (yᵢ − ȳ)²) [m⁴], in
    /// steel units.
    pub fn second_moment(&self) -> f64 {
        let centre = self.neutral_axis();
        self.rectangles()
            .iter()
            .map(|p| p.own_second_moment() + p.area() * (p.centroid() - centre).powi(2))
            .sum()
    }

    /// A fibre's height above the bottom face [m].
    pub fn height_of(&self, fibre: Fibre) -> f64 {
        match fibre {
            Fibre::BottomFlange => 0.0,
            Fibre::WeldToe => self.bottom_flange.thickness,
            Fibre::TopFlange => self.steel_depth(),
            Fibre::NeutralAxis => self.neutral_axis(),
            Fibre::Height(height) => height,
        }
    }

    /// The direct stress per unit sagging moment at a fibre of the steel, (ȳ − y)/I [Pa per
    /// N·m]: positive (tension) below the neutral axis.
    pub fn direct_stress_per_moment(&self, fibre: Fibre) -> Result<f64, SectionError> {
        self.check()?;
        let height = self.height_in_steel(fibre)?;
        Ok((self.neutral_axis() - height) / self.second_moment())
    }

    /// The web's shear stress per unit shear force at a fibre, Q(y)/(I t_w) [Pa per N], with
    /// Q(y) the first moment about the neutral axis of the transformed section above y.
    pub fn shear_stress_per_force(&self, fibre: Fibre) -> Result<f64, SectionError> {
        self.check()?;
        let height = self.height_in_steel(fibre)?;
        let (from, to) = (
            self.bottom_flange.thickness,
            self.bottom_flange.thickness + self.web.width,
        );
        if !(from..=to).contains(&height) {
            return Err(SectionError::ShearOutsideWeb { height, from, to });
        }
        let centre = self.neutral_axis();
        let first_moment: f64 = self
            .rectangles()
            .iter()
            .filter(|p| p.top > height)
            .map(|p| {
                let part = Rectangle {
                    bottom: p.bottom.max(height),
                    ..*p
                };
                part.area() * (part.centroid() - centre)
            })
            .sum();
        Ok(first_moment / (self.second_moment() * self.web.thickness))
    }

    fn height_in_steel(&self, fibre: Fibre) -> Result<f64, SectionError> {
        let (height, depth) = (self.height_of(fibre), self.steel_depth());
        if (0.0..=depth).contains(&height) {
            Ok(height)
        } else {
            Err(SectionError::OutsideSteel { height, depth })
        }
    }
}
