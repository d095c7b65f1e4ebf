//! Bridge models as the engineer describes them: spans, supports, sections, girders, materials.
//!
//! Two kinds of model ([`BridgeModel`]):
//! - [`ContinuousBeam`]: a 2D Euler–Bernoulli beam over any number of spans, each support pinned,
//!   roller, fixed or elastic;
//! - [`Grillage`]: the 3D grillage of a multi-girder precast box-girder bridge, as in the paper
//!   §4.1 (Fig. 7): composite box girders, slab strips and support diaphragms across them, and
//!   bearings under every girder at every support.
//!
//! [`paper_bridge`] builds the paper's nine prototype bridges (see [`presets`]).

pub mod damage;
pub mod damping;
pub mod girder;
pub mod imported;
pub mod imported_modes;
pub mod mode_kind;
pub mod presets;
pub mod section;
pub mod station;

use serde::{Deserialize, Serialize};

pub use damage::{Damage, StiffnessLoss, SupportChange};
pub use damping::{ModeDamping, RayleighCoefficients, RayleighDamping};
pub use girder::{
    GirderSection, GirderShape, GivenSection, IGirderDimensions, TBeamDimensions,
    VoidedSlabDimensions,
};
pub use imported::{ImportedDeckLine, ImportedMatrices};
pub use imported_modes::ImportedModes;
pub use presets::{bridge_preset, paper_bridge, paper_girder_geometry, paper_girder_height};
pub use section::{BoxGirderGeometry, BoxGirderSection, MemberSection};

/// Direction of a nodal degree of freedom in global axes (x along the bridge, y lateral to the
/// left, z up).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Direction {
    /// Translation along x (longitudinal) [m].
    TranslationX,
    /// Translation along y (lateral) [m].
    TranslationY,
    /// Translation along z (vertical) [m].
    TranslationZ,
    /// Rotation about x (torsion of a girder) [rad].
    RotationX,
    /// Rotation about y (bending in the vertical plane) [rad].
    RotationY,
    /// Rotation about z (bending in the horizontal plane) [rad].
    RotationZ,
}

impl Direction {
    /// The six directions in the order of a 3D frame node's DOFs (u, v, w, θx, θy, θz).
    pub const ALL: [Direction; 6] = [
        Direction::TranslationX,
        Direction::TranslationY,
        Direction::TranslationZ,
        Direction::RotationX,
        Direction::RotationY,
        Direction::RotationZ,
    ];
}

/// Invalid bridge data; each variant carries the offending numbers.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelError {
    /// A quantity that must be strictly positive and finite is not.
    #[error("{quantity} must be a positive finite number, got {value}")]
    NotPositive {
        /// What the number is.
        quantity: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A quantity that must be zero or positive and finite is not.
    #[error("{quantity} must be zero or a positive finite number, got {value}")]
    Negative {
        /// What the number is.
        quantity: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A damping ratio outside [0, 1).
    #[error("damping ratio {damping_ratio} is outside [0, 1)")]
    DampingRatio {
        /// The offending value [-].
        damping_ratio: f64,
    },
    /// A per-mode damping list without a ratio.
    #[error("a per-mode damping list needs at least one ratio")]
    NoDampingRatios,
    /// Rayleigh damping fitted to two equal frequencies.
    #[error("Rayleigh damping needs two different frequencies, got {frequency} Hz twice")]
    RayleighEqualFrequencies {
        /// The frequency given twice [Hz].
        frequency: f64,
    },
    /// A Rayleigh fit with a negative coefficient (negative damping at some frequency).
    #[error(
        "the two damping ratios fit a negative {coefficient} = {value:e}: that damping would be \
         negative at some frequencies; choose ratios with ω₁/ω₂ ≤ ζ₂/ζ₁ ≤ ω₂/ω₁"
    )]
    RayleighNegative {
        /// Which coefficient.
        coefficient: &'static str,
        /// Its value [1/s for α, s for β].
        value: f64,
    },
    /// A Rayleigh fit that overdamps a retained mode.
    #[error(
        "Rayleigh damping gives mode {mode} ({frequency:.3} Hz) a damping ratio of {damping_ratio}, \
         not below 1; fit it to frequencies nearer the modes used or keep fewer modes"
    )]
    RayleighOverdamped {
        /// The mode, numbered from 1 among the retained ones.
        mode: usize,
        /// Its frequency [Hz].
        frequency: f64,
        /// Its fitted ratio [-].
        damping_ratio: f64,
    },
    /// A damage region that is not inside the bridge, or empty.
    #[error(
        "damage region {index} from x = {start} m to {end} m is not inside the bridge (0 to \
         {length} m) with its start before its end"
    )]
    DamageRegion {
        /// Index of the stiffness loss (0-based).
        index: usize,
        /// Its start [m].
        start: f64,
        /// Its end [m].
        end: f64,
        /// The bridge length [m].
        length: f64,
    },
    /// A factor on E outside (0, 1].
    #[error("damage region {index} has an elastic modulus factor of {factor}, outside (0, 1]")]
    DamageFactor {
        /// Index of the stiffness loss (0-based).
        index: usize,
        /// The factor [-].
        factor: f64,
    },
    /// A damage region on a girder that does not exist.
    #[error(
        "damage region {index} is on girder {girder} (0-based), but the bridge has {girder_count}"
    )]
    DamageGirder {
        /// Index of the stiffness loss (0-based).
        index: usize,
        /// The girder given (0-based).
        girder: usize,
        /// Number of girders.
        girder_count: usize,
    },
    /// A changed support that does not exist, or is changed twice.
    #[error(
        "support change {index} names support {support} (0-based), which is not one of the \
         {support_count} supports or is changed twice"
    )]
    SupportChange {
        /// Index of the change (0-based).
        index: usize,
        /// The support given (0-based).
        support: usize,
        /// Number of supports.
        support_count: usize,
    },
    /// Imported matrices, DOF map and deck lines that do not fit together.
    #[error("imported model: {message}")]
    ImportedMatrices {
        /// What does not fit.
        message: String,
    },
    /// A model with no span.
    #[error("a bridge needs at least one span")]
    NoSpans,
    /// The supports do not match the spans (there must be one more support than spans).
    #[error("{span_count} spans need {} supports, got {support_count}", span_count + 1)]
    SupportCount {
        /// Number of spans.
        span_count: usize,
        /// Number of supports given.
        support_count: usize,
    },
    /// A grillage needs at least one girder.
    #[error("a grillage needs at least one girder")]
    NoGirders,
    /// The girders do not fit on the deck.
    #[error(
        "{girder_count} girders at {girder_spacing} m spacing span {} m, wider than the {deck_width} m deck",
        (*girder_count as f64 - 1.0) * girder_spacing
    )]
    DeckTooNarrow {
        /// Deck width [m].
        deck_width: f64,
        /// Number of girders.
        girder_count: usize,
        /// Girder spacing [m].
        girder_spacing: f64,
    },
    /// The girders' top flanges (their deck shares) are narrower than their boxes.
    #[error(
        "a top flange of {top_flange_width} m is narrower than the box top, {box_top_width} m wide"
    )]
    FlangeNarrowerThanBox {
        /// The flange width [m].
        top_flange_width: f64,
        /// Outer width of the box at the underside of the top slab [m].
        box_top_width: f64,
    },
    /// Bearings given for a number of support lines other than the grillage's.
    #[error("{bearing_count} bearings given for {support_count} support lines; give one per line")]
    BearingCount {
        /// Support lines.
        support_count: usize,
        /// Bearings given.
        bearing_count: usize,
    },
    /// A skew angle outside −45° to 45°.
    #[error("a skew angle of {degrees}° is outside −45° to 45°")]
    SkewAngle {
        /// The angle [°].
        degrees: f64,
    },
    /// Barriers whose centre is not on the deck's own half.
    #[error(
        "the barriers' centre {edge_distance} m from each edge is not on the {deck_width} m deck's \
         own half"
    )]
    BarrierEdge {
        /// Their distance from the edge [m].
        edge_distance: f64,
        /// The deck width [m].
        deck_width: f64,
    },
    /// A girder shape whose parts do not fit together (T-beam, I-girder, voided slab, given
    /// properties).
    #[error("{message}")]
    GirderShape {
        /// What does not fit, with the numbers.
        message: String,
    },
    /// The two slabs leave no room for the webs.
    #[error("slabs of {top_slab_thickness} m and {bottom_slab_thickness} m do not fit in a {height} m deep box")]
    SlabsTooThick {
        /// Box height [m].
        height: f64,
        /// Top slab thickness [m].
        top_slab_thickness: f64,
        /// Bottom slab thickness [m].
        bottom_slab_thickness: f64,
    },
    /// The two webs leave no cell.
    #[error("two webs {web_thickness} m thick leave no cell in a {bottom_width} m wide box")]
    WebsTooThick {
        /// Box bottom width [m].
        bottom_width: f64,
        /// Web thickness [m].
        web_thickness: f64,
    },
}

pub(crate) fn require_positive(quantity: &'static str, value: f64) -> Result<f64, ModelError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ModelError::NotPositive { quantity, value })
    }
}

pub(crate) fn require_non_negative(quantity: &'static str, value: f64) -> Result<f64, ModelError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(ModelError::Negative { quantity, value })
    }
}

fn require_damping(damping_ratio: f64) -> Result<(), ModelError> {
    if damping_ratio.is_finite() && (0.0..1.0).contains(&damping_ratio) {
        Ok(())
    } else {
        Err(ModelError::DampingRatio { damping_ratio })
    }
}

/// Checks a damping law and the damage of a bridge of these spans and girders.
fn validate_damping_and_damage(
    mode_damping: Option<&ModeDamping>,
    damage: &Damage,
    span_lengths: &[f64],
    girder_count: usize,
) -> Result<(), ModelError> {
    if let Some(law) = mode_damping {
        law.validate()?;
    }
    let length = span_lengths.iter().sum();
    damage.validate(length, girder_count, span_lengths.len() + 1)
}

fn require_spans(span_lengths: &[f64]) -> Result<(), ModelError> {
    if span_lengths.is_empty() {
        return Err(ModelError::NoSpans);
    }
    for &length in span_lengths {
        require_positive("span length", length)?;
    }
    Ok(())
}

/// An isotropic linear-elastic material.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Young's modulus E [Pa]; default 3.45e10 (the paper's C50 concrete, 3.45×10⁴ MPa).
    pub elastic_modulus: f64,
    /// Density ρ [kg/m³]; default 2500 (the paper).
    pub density: f64,
    /// Poisson's ratio ν [-]; default 0.2 (concrete). Gives G = E / (2(1 + ν)).
    pub poisson_ratio: f64,
}

impl Default for Material {
    fn default() -> Self {
        Material {
            elastic_modulus: 3.45e10,
            density: 2500.0,
            poisson_ratio: 0.2,
        }
    }
}

impl Material {
    /// Shear modulus G = E / (2(1 + ν)) [Pa].
    pub fn shear_modulus(&self) -> f64 {
        self.elastic_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// Checks that E and ρ are positive and −1 < ν < 0.5.
    pub fn validate(&self) -> Result<(), ModelError> {
        require_positive("elastic modulus", self.elastic_modulus)?;
        require_positive("density", self.density)?;
        if !(self.poisson_ratio.is_finite()
            && self.poisson_ratio > -1.0
            && self.poisson_ratio < 0.5)
        {
            return Err(ModelError::NotPositive {
                quantity: "1 + Poisson's ratio and 0.5 − Poisson's ratio",
                value: self.poisson_ratio,
            });
        }
        Ok(())
    }
}

/// A support of a continuous beam.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum SupportKind {
    /// Deflection restrained, rotation free.
    Pinned,
    /// Deflection restrained, rotation free (same as pinned in a 2D beam without axial DOF).
    Roller,
    /// Deflection and rotation restrained.
    Fixed,
    /// Vertical and rotational springs.
    Elastic {
        /// Vertical spring stiffness [N/m] (≥ 0).
        vertical_stiffness: f64,
        /// Rotational spring stiffness [N·m/rad] (≥ 0).
        rotational_stiffness: f64,
    },
}

/// Flexural rigidity and mass of a beam section.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BeamSection {
    /// Flexural rigidity EI [N·m²].
    pub flexural_rigidity: f64,
    /// Structural mass per length m̄ [kg/m].
    pub mass_per_length: f64,
}

impl BeamSection {
    /// The section of a box girder: EI = E·I_y, m̄ = ρ·A.
    pub fn from_box_girder(section: &BoxGirderSection, material: &Material) -> Self {
        Self::from_girder(&GirderSection::from(*section), material)
    }

    /// The section of a grillage girder: EI = E·I_y, m̄ = ρ·A.
    pub fn from_girder(section: &GirderSection, material: &Material) -> Self {
        BeamSection {
            flexural_rigidity: material.elastic_modulus * section.second_moment_y,
            mass_per_length: material.density * section.area,
        }
    }
}

/// A 2D Euler–Bernoulli continuous beam: 2 DOF per node (deflection w, slope dw/dx).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContinuousBeam {
    /// Span lengths from the first support [m]; at least one.
    pub span_lengths: Vec<f64>,
    /// Supports, one more than spans, from x = 0.
    pub supports: Vec<SupportKind>,
    /// The section, uniform along the beam.
    pub section: BeamSection,
    /// Uniform non-structural mass (pavement) [kg/m]; default 0.
    pub added_mass_per_length: f64,
    /// Modal damping ratio ζ [-] of every mode (unless `mode_damping` is given); default 0.
    pub damping_ratio: f64,
    /// A ratio per mode or Rayleigh damping instead of `damping_ratio`; default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mode_damping: Option<ModeDamping>,
    /// Stiffness losses and changed supports; default none (intact).
    #[serde(default, skip_serializing_if = "Damage::is_intact")]
    pub damage: Damage,
}

impl ContinuousBeam {
    /// A beam with pinned supports everywhere, no added mass and no damping.
    pub fn pinned(span_lengths: Vec<f64>, section: BeamSection) -> Self {
        let supports = vec![SupportKind::Pinned; span_lengths.len() + 1];
        ContinuousBeam {
            span_lengths,
            supports,
            section,
            added_mass_per_length: 0.0,
            damping_ratio: 0.0,
            mode_damping: None,
            damage: Damage::default(),
        }
    }

    /// Checks every number and the support count.
    pub fn validate(&self) -> Result<(), ModelError> {
        require_spans(&self.span_lengths)?;
        if self.supports.len() != self.span_lengths.len() + 1 {
            return Err(ModelError::SupportCount {
                span_count: self.span_lengths.len(),
                support_count: self.supports.len(),
            });
        }
        for support in &self.supports {
            if let SupportKind::Elastic {
                vertical_stiffness,
                rotational_stiffness,
            } = *support
            {
                require_non_negative("vertical spring stiffness", vertical_stiffness)?;
                require_non_negative("rotational spring stiffness", rotational_stiffness)?;
            }
        }
        require_positive("flexural rigidity", self.section.flexural_rigidity)?;
        require_positive("mass per length", self.section.mass_per_length)?;
        require_non_negative("added mass per length", self.added_mass_per_length)?;
        require_damping(self.damping_ratio)?;
        validate_damping_and_damage(
            self.mode_damping.as_ref(),
            &self.damage,
            &self.span_lengths,
            1,
        )
    }
}

/// The bearings of one support line of a grillage.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BearingKind {
    /// Vertical, longitudinal and lateral translation restrained.
    Pinned,
    /// Vertical translation restrained; horizontal movement released.
    Roller,
}

/// Which support lines restrain lateral (y) translation.
///
/// The paper releases "the horizontal movement" at the rollers. Read literally (both
/// horizontal directions), the whole deck then swings laterally as a cantilever in plan from the
/// pinned line, a mode near 0.2 Hz for the 4×40 m bridge that no real bridge has: its piers
/// carry lateral stoppers (shear keys). The default therefore restrains lateral movement at
/// every support line and releases only the longitudinal one at the rollers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LateralRestraint {
    /// Only the pinned line (rollers free in both horizontal directions).
    PinnedLine,
    /// Every support line (guided bearings or lateral stoppers). Default.
    #[default]
    AllSupports,
}

/// Thicknesses and densities of the deck layers over the girders.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DeckLayers {
    /// Deck slab thickness, the top flange of every box [m]; default 0.18 (the paper).
    pub slab_thickness: f64,
    /// Structural concrete overlay acting with the girder [m]; default 0.04 (the paper).
    pub structural_overlay_thickness: f64,
    /// Non-structural concrete pavement, added mass only [m]; default 0.04 (the paper).
    pub pavement_concrete_thickness: f64,
    /// Asphalt surfacing, added mass only [m]; default 0.10 (the paper).
    pub asphalt_thickness: f64,
    /// Asphalt density [kg/m³]; default 2400 (assumption: 24 kN/m³ of the Chinese code JTG D60).
    pub asphalt_density: f64,
}

impl Default for DeckLayers {
    fn default() -> Self {
        DeckLayers {
            slab_thickness: 0.18,
            structural_overlay_thickness: 0.04,
            pavement_concrete_thickness: 0.04,
            asphalt_thickness: 0.10,
            asphalt_density: 2400.0,
        }
    }
}

/// The precast box of every girder (the top flange width and thickness come from the deck).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BoxGirderDimensions {
    /// Height from soffit to the top of the deck slab [m].
    pub height: f64,
    /// Outer bottom width [m].
    pub bottom_width: f64,
    /// Web thickness, measured horizontally [m].
    pub web_thickness: f64,
    /// Bottom slab thickness [m].
    pub bottom_slab_thickness: f64,
    /// Outward horizontal run of each web per unit rise [-].
    pub web_inclination: f64,
}

/// The diaphragms (cross beams) over the supports.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Diaphragm {
    /// Thickness along the bridge [m]; presets use 0.4.
    pub width: f64,
    /// Depth [m]; presets use the girder height.
    pub depth: f64,
}

/// Diaphragms inside the spans, equally spaced: `per_span` of them at L·k/(per_span + 1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct IntermediateDiaphragms {
    /// Number in each span [-], at least 1.
    pub per_span: usize,
    /// Their section (thickness along the bridge and depth) [m].
    pub section: Diaphragm,
}

/// The two edge barriers (parapets), one on each edge of the deck: mass only, carried by the
/// edge girder on its side with its eccentricity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Barriers {
    /// Mass of each barrier per length [kg/m].
    pub mass_per_length: f64,
    /// Distance of each barrier's centre of mass from its deck edge, inwards [m].
    pub edge_distance: f64,
}

/// How a grillage girder's bearings hold it at one support line (the same under every girder).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Bearing {
    /// Vertical stiffness of the bearing under each girder [N/m]; `None`: rigid.
    pub vertical_stiffness: Option<f64>,
    /// Stiffness of the bearing under each girder against rotation about the support line
    /// (θy) [N·m/rad]; 0: free, as the paper's bearings.
    pub rotational_stiffness: f64,
    /// Whether each girder may twist on its bearing (a single bearing under it rather than a
    /// pair): the rotation about the bridge axis θx is then not restrained.
    pub torsion_free: bool,
}

impl Default for Bearing {
    /// Rigid vertically, free to rotate about the support line, torsion held (the paper).
    fn default() -> Self {
        Bearing {
            vertical_stiffness: None,
            rotational_stiffness: 0.0,
            torsion_free: false,
        }
    }
}

/// A 3D grillage of a multi-girder precast box-girder bridge (the paper §4.1, Fig. 7).
///
/// Girder i (0 = rightmost) lies at y = (i − (N−1)/2)·spacing. Each girder is a composite
/// [`BoxGirderSection`] whose top flange is its share of the deck: `spacing` for an inner
/// girder, `spacing/2 + overhang` for an edge girder, overhang = (deck width − (N−1)·spacing)/2.
/// The remaining pavement is a uniform added mass on each girder by the same shares.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Grillage {
    /// Span lengths [m]; at least one.
    pub span_lengths: Vec<f64>,
    /// Bearings of each support line, one more than spans; exactly one should be pinned.
    pub supports: Vec<BearingKind>,
    /// Which support lines restrain lateral translation; default [`LateralRestraint::AllSupports`].
    pub lateral_restraint: LateralRestraint,
    /// Skew angle θ of the support lines from the normal to the girders [rad], from −45° to
    /// 45°; default 0 (square). Positive: the left side (y > 0) of each support line lies
    /// ahead, at x + y·tan θ. Spans are measured along the girders.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub skew_angle: f64,
    /// Deck width [m]; the paper's field bridges: 8.5.
    pub deck_width: f64,
    /// Number of girders N ≥ 1.
    pub girder_count: usize,
    /// Centre-to-centre girder spacing [m].
    pub girder_spacing: f64,
    /// The girders' shape (the paper: precast boxes).
    pub girder: GirderShape,
    /// The edge girders' shape (the two outer girders), if it differs; default: `girder`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edge_girder: Option<GirderShape>,
    /// Edge barriers (parapets); default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub barriers: Option<Barriers>,
    /// Deck slab, overlay and pavement.
    pub deck: DeckLayers,
    /// Support diaphragms.
    pub diaphragm: Diaphragm,
    /// Diaphragms inside the spans; default none (the paper).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub intermediate_diaphragms: Option<IntermediateDiaphragms>,
    /// The bearings of each support line, one per line; empty (the default): every bearing
    /// [`Bearing::default`].
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bearings: Vec<Bearing>,
    /// Target spacing of the transverse slab-strip members [m]; each span gets
    /// round(L / spacing) equal strips (at least 2).
    pub transverse_member_spacing: f64,
    /// Concrete of girders, slab and diaphragms; default [`Material::default`].
    pub material: Material,
    /// Modal damping ratio ζ [-] of every mode (unless `mode_damping` is given); default 0.05
    /// (the paper).
    pub damping_ratio: f64,
    /// A ratio per mode or Rayleigh damping instead of `damping_ratio`; default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mode_damping: Option<ModeDamping>,
    /// Stiffness losses and changed supports; default none (intact).
    #[serde(default, skip_serializing_if = "Damage::is_intact")]
    pub damage: Damage,
}

/// Whether a number is zero (serde: a square grillage writes no skew angle).
fn is_zero(value: &f64) -> bool {
    *value == 0.0
}

/// The largest skew angle a grillage may have [rad] (45°): the transverse members follow the
/// support lines (a skew mesh), which grillage practice keeps to moderate skews.
pub const MAX_SKEW_ANGLE: f64 = std::f64::consts::FRAC_PI_4;

impl Grillage {
    /// The longitudinal offset of each girder line's nodes [m]: y·tan θ, shifted so that the
    /// smallest is 0 (the deck's x then starts at the first support of the acute corner).
    pub fn line_offsets(&self) -> Vec<f64> {
        let tan = self.skew_angle.tan();
        let raw: Vec<f64> = self.girder_positions().iter().map(|y| y * tan).collect();
        let least = raw.iter().copied().fold(f64::INFINITY, f64::min);
        raw.iter().map(|o| o - least).collect()
    }

    /// Whether the support lines are skewed across two girders or more (one girder has no
    /// offset to make).
    pub fn is_skewed(&self) -> bool {
        self.skew_angle != 0.0 && self.girder_count > 1
    }

    /// The deck's extent along x over every girder line [m]: the spans' length plus the skew's
    /// offset across the outer girders.
    pub fn deck_length(&self) -> f64 {
        let offsets = self.line_offsets();
        let spread = offsets.iter().copied().fold(0.0, f64::max);
        self.span_lengths.iter().sum::<f64>() + spread
    }

    /// Lateral positions y of the girders [m], ascending (right to left).
    pub fn girder_positions(&self) -> Vec<f64> {
        let n = self.girder_count;
        (0..n)
            .map(|i| (i as f64 - (n as f64 - 1.0) / 2.0) * self.girder_spacing)
            .collect()
    }

    /// Deck width carried by girder `i` [m] (its top flange width).
    pub fn deck_share(&self, i: usize) -> f64 {
        let n = self.girder_count;
        if n == 1 {
            return self.deck_width;
        }
        let overhang = (self.deck_width - (n as f64 - 1.0) * self.girder_spacing) / 2.0;
        if i == 0 || i + 1 == n {
            self.girder_spacing / 2.0 + overhang
        } else {
            self.girder_spacing
        }
    }

    /// Whether girder `i` is an edge girder (the outer two of two or more).
    pub fn is_edge_girder(&self, i: usize) -> bool {
        self.girder_count > 1 && (i == 0 || i + 1 == self.girder_count)
    }

    /// The shape of girder `i`: `edge_girder` for the outer two, if given, else `girder`.
    pub fn girder_shape(&self, i: usize) -> &GirderShape {
        match &self.edge_girder {
            Some(edge) if self.is_edge_girder(i) => edge,
            _ => &self.girder,
        }
    }

    /// The composite section of girder `i` with its deck share.
    pub fn girder_section(&self, i: usize) -> Result<GirderSection, ModelError> {
        self.girder_shape(i).section(self.deck_share(i), &self.deck)
    }

    /// The bearing of support line `j`.
    pub fn bearing(&self, j: usize) -> Bearing {
        self.bearings.get(j).copied().unwrap_or_default()
    }

    /// Barrier masses by girder line: (line, mass per length [kg/m], lateral offset of the
    /// barrier's centre of mass from the girder's axis [m]).
    pub fn barrier_loads(&self) -> Vec<(usize, f64, f64)> {
        let Some(b) = self.barriers else {
            return Vec::new();
        };
        let positions = self.girder_positions();
        let edge = self.deck_width / 2.0 - b.edge_distance;
        let last = self.girder_count - 1;
        vec![
            (0, b.mass_per_length, -edge - positions[0]),
            (last, b.mass_per_length, edge - positions[last]),
        ]
    }

    /// The structural mass of the whole grillage model [kg]: girders with their pavement,
    /// diaphragms and barriers (the slab strips carry none: the slab is in the girders).
    pub fn total_mass(&self) -> Result<f64, ModelError> {
        let length: f64 = self.span_lengths.iter().sum();
        let rho = self.material.density;
        let mut mass = 0.0;
        for i in 0..self.girder_count {
            mass += (rho * self.girder_section(i)?.area + self.added_mass_per_length(i)) * length;
        }
        let positions = self.girder_positions();
        // Diaphragms follow the support lines: their length is the girders' span over cos θ.
        let across = (positions[self.girder_count - 1] - positions[0]) / self.skew_angle.cos();
        let diaphragm = |d: &Diaphragm| rho * d.width * d.depth * across;
        if self.girder_count > 1 {
            mass += diaphragm(&self.diaphragm) * self.supports.len() as f64;
            if let Some(d) = &self.intermediate_diaphragms {
                mass += diaphragm(&d.section) * (d.per_span * self.span_lengths.len()) as f64;
            }
        }
        if let Some(b) = &self.barriers {
            mass += 2.0 * b.mass_per_length * length;
        }
        Ok(mass)
    }

    /// Pavement mass carried by girder `i` [kg/m]:
    /// share · (ρ_concrete · t_pavement + ρ_asphalt · t_asphalt).
    pub fn added_mass_per_length(&self, i: usize) -> f64 {
        self.deck_share(i)
            * (self.material.density * self.deck.pavement_concrete_thickness
                + self.deck.asphalt_density * self.deck.asphalt_thickness)
    }

    /// Thickness of the slab strips: slab plus structural overlay [m].
    pub fn slab_strip_thickness(&self) -> f64 {
        self.deck.slab_thickness + self.deck.structural_overlay_thickness
    }

    /// Checks every number, that the girders fit on the deck and that every section is valid.
    pub fn validate(&self) -> Result<(), ModelError> {
        require_spans(&self.span_lengths)?;
        if self.supports.len() != self.span_lengths.len() + 1 {
            return Err(ModelError::SupportCount {
                span_count: self.span_lengths.len(),
                support_count: self.supports.len(),
            });
        }
        if self.girder_count == 0 {
            return Err(ModelError::NoGirders);
        }
        require_positive("deck width", self.deck_width)?;
        require_positive("girder spacing", self.girder_spacing)?;
        if (self.girder_count as f64 - 1.0) * self.girder_spacing > self.deck_width {
            return Err(ModelError::DeckTooNarrow {
                deck_width: self.deck_width,
                girder_count: self.girder_count,
                girder_spacing: self.girder_spacing,
            });
        }
        self.material.validate()?;
        require_positive("deck slab thickness", self.deck.slab_thickness)?;
        for (quantity, value) in [
            (
                "structural overlay thickness",
                self.deck.structural_overlay_thickness,
            ),
            (
                "pavement concrete thickness",
                self.deck.pavement_concrete_thickness,
            ),
            ("asphalt thickness", self.deck.asphalt_thickness),
            ("asphalt density", self.deck.asphalt_density),
        ] {
            require_non_negative(quantity, value)?;
        }
        require_positive("diaphragm width", self.diaphragm.width)?;
        require_positive("diaphragm depth", self.diaphragm.depth)?;
        require_positive("transverse member spacing", self.transverse_member_spacing)?;
        for i in 0..self.girder_count {
            self.girder_section(i)?;
        }
        self.validate_additions()?;
        require_damping(self.damping_ratio)?;
        validate_damping_and_damage(
            self.mode_damping.as_ref(),
            &self.damage,
            &self.span_lengths,
            self.girder_count,
        )
    }
}

impl Grillage {
    /// Checks the skew angle, the intermediate diaphragms, the barriers and the bearings.
    fn validate_additions(&self) -> Result<(), ModelError> {
        if !(self.skew_angle.is_finite() && self.skew_angle.abs() <= MAX_SKEW_ANGLE + 1e-12) {
            return Err(ModelError::SkewAngle {
                degrees: self.skew_angle.to_degrees(),
            });
        }
        if let Some(d) = &self.intermediate_diaphragms {
            if d.per_span == 0 {
                return Err(ModelError::NotPositive {
                    quantity: "intermediate diaphragms per span",
                    value: 0.0,
                });
            }
            require_positive("intermediate diaphragm width", d.section.width)?;
            require_positive("intermediate diaphragm depth", d.section.depth)?;
        }
        if let Some(b) = &self.barriers {
            require_non_negative("barrier mass per length", b.mass_per_length)?;
            require_non_negative("barrier edge distance", b.edge_distance)?;
            if b.edge_distance >= self.deck_width / 2.0 {
                return Err(ModelError::BarrierEdge {
                    edge_distance: b.edge_distance,
                    deck_width: self.deck_width,
                });
            }
        }
        if !self.bearings.is_empty() && self.bearings.len() != self.supports.len() {
            return Err(ModelError::BearingCount {
                support_count: self.supports.len(),
                bearing_count: self.bearings.len(),
            });
        }
        for bearing in &self.bearings {
            if let Some(k) = bearing.vertical_stiffness {
                require_positive("bearing vertical stiffness", k)?;
            }
            require_non_negative("bearing rotational stiffness", bearing.rotational_stiffness)?;
        }
        Ok(())
    }
}

/// Positions x of the supports of consecutive spans [m], from 0 to their total length.
pub fn support_positions_of(span_lengths: &[f64]) -> Vec<f64> {
    let mut x = vec![0.0];
    for &l in span_lengths {
        x.push(x.last().copied().unwrap_or(0.0) + l);
    }
    x
}

/// A bridge model: what [`crate::fe::discretise`] turns into an FE model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "type")]
// A grillage's description is a few hundred bytes, built once per scenario and never in a hot
// loop: boxing it would only add an indirection to every match.
#[allow(clippy::large_enum_variant)]
pub enum BridgeModel {
    /// A 2D continuous beam.
    ContinuousBeam(ContinuousBeam),
    /// A 3D grillage of box girders.
    Grillage(Grillage),
    /// Sparse K and M from another FE program, with its DOF map and deck lines.
    ImportedMatrices(ImportedMatrices),
    /// Modes only (frequencies, shapes, station moments) from another program.
    ImportedModes(ImportedModes),
}

impl BridgeModel {
    /// Span lengths [m].
    pub fn span_lengths(&self) -> &[f64] {
        match self {
            BridgeModel::ContinuousBeam(b) => &b.span_lengths,
            BridgeModel::Grillage(g) => &g.span_lengths,
            BridgeModel::ImportedMatrices(m) => &m.span_lengths,
            BridgeModel::ImportedModes(m) => &m.span_lengths,
        }
    }

    /// Total length between the end supports [m], along the girders.
    pub fn length(&self) -> f64 {
        self.span_lengths().iter().sum()
    }

    /// The longitudinal offset of each deck line's nodes [m] on a skewed grillage
    /// ([`Grillage::line_offsets`]); empty for every other model.
    pub fn line_offsets(&self) -> Vec<f64> {
        match self {
            BridgeModel::Grillage(g) if g.is_skewed() => g.line_offsets(),
            _ => Vec::new(),
        }
    }

    /// The deck's extent along x [m]: [`length`](Self::length), plus the offset of the outer
    /// girders' supports on a skewed grillage. Vehicles are on the deck from x = 0 to this.
    pub fn deck_length(&self) -> f64 {
        match self {
            BridgeModel::Grillage(g) => g.deck_length(),
            _ => self.length(),
        }
    }

    /// Positions x of the supports [m], from 0 to the length.
    pub fn support_positions(&self) -> Vec<f64> {
        support_positions_of(self.span_lengths())
    }

    /// Modal damping ratio ζ [-] of every mode, unless [`BridgeModel::mode_damping`] is given.
    pub fn damping_ratio(&self) -> f64 {
        match self {
            BridgeModel::ContinuousBeam(b) => b.damping_ratio,
            BridgeModel::Grillage(g) => g.damping_ratio,
            BridgeModel::ImportedMatrices(m) => m.damping_ratio,
            BridgeModel::ImportedModes(m) => m.data.default_damping_ratio,
        }
    }

    /// The damping law that gives each mode its own ratio, if any.
    pub fn mode_damping(&self) -> Option<&ModeDamping> {
        match self {
            BridgeModel::ContinuousBeam(b) => b.mode_damping.as_ref(),
            BridgeModel::Grillage(g) => g.mode_damping.as_ref(),
            BridgeModel::ImportedMatrices(m) => m.mode_damping.as_ref(),
            // Each imported mode carries its own ratio (or the default).
            BridgeModel::ImportedModes(_) => None,
        }
    }

    /// The stiffness losses and changed supports.
    pub fn damage(&self) -> &Damage {
        match self {
            BridgeModel::ContinuousBeam(b) => &b.damage,
            BridgeModel::Grillage(g) => &g.damage,
            BridgeModel::ImportedMatrices(m) => &m.damage,
            BridgeModel::ImportedModes(m) => &m.damage,
        }
    }

    /// The stiffness losses and changed supports, to change them.
    pub fn damage_mut(&mut self) -> &mut Damage {
        match self {
            BridgeModel::ContinuousBeam(b) => &mut b.damage,
            BridgeModel::Grillage(g) => &mut g.damage,
            BridgeModel::ImportedMatrices(m) => &mut m.damage,
            BridgeModel::ImportedModes(m) => &mut m.damage,
        }
    }

    /// The same bridge with `span_count` equal spans of `span_length` [m]: the section, the
    /// deck and the end supports kept, interior supports like the first interior one (pinned
    /// for a beam, roller for a grillage, when there is none).
    pub fn resize_spans(&mut self, span_count: usize, span_length: f64) {
        /// N + 1 supports: the ends kept, the interior ones all `interior`.
        fn supports<S: Copy>(old: &[S], span_count: usize, fallback: S) -> Vec<S> {
            let first = old[0];
            let last = *old.last().unwrap_or(&first);
            let interior = old
                .get(1)
                .filter(|_| old.len() > 2)
                .copied()
                .unwrap_or(fallback);
            (0..=span_count)
                .map(|i| match i {
                    0 => first,
                    i if i == span_count => last,
                    _ => interior,
                })
                .collect()
        }
        match self {
            BridgeModel::ContinuousBeam(b) => {
                b.supports = supports(&b.supports, span_count, SupportKind::Pinned);
                b.span_lengths = vec![span_length; span_count];
            }
            BridgeModel::Grillage(g) => {
                g.supports = supports(&g.supports, span_count, BearingKind::Roller);
                if !g.bearings.is_empty() {
                    g.bearings = supports(&g.bearings, span_count, Bearing::default());
                }
                g.span_lengths = vec![span_length; span_count];
            }
            // Matrices and modes cannot be re-spanned; `is_resizable` tells the callers.
            BridgeModel::ImportedMatrices(_) | BridgeModel::ImportedModes(_) => {}
        }
    }

    /// Whether [`resize_spans`](Self::resize_spans) can change the spans (not for imported
    /// matrices or modes).
    pub fn is_resizable(&self) -> bool {
        !matches!(
            self,
            BridgeModel::ImportedMatrices(_) | BridgeModel::ImportedModes(_)
        )
    }

    /// Checks the whole model.
    pub fn validate(&self) -> Result<(), ModelError> {
        match self {
            BridgeModel::ContinuousBeam(b) => b.validate(),
            BridgeModel::Grillage(g) => g.validate(),
            BridgeModel::ImportedMatrices(m) => m.validate(),
            BridgeModel::ImportedModes(m) => m.validate(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deck_shares_add_up_to_the_deck_width() {
        let BridgeModel::Grillage(g) = paper_bridge(3, 30.0) else {
            panic!("the paper bridge is a grillage")
        };
        let total: f64 = (0..g.girder_count).map(|i| g.deck_share(i)).sum();
        assert!((total - g.deck_width).abs() < 1e-12);
        assert!(g.validate().is_ok());
    }

    #[test]
    fn beam_validation_names_the_bad_number() {
        let mut beam = ContinuousBeam::pinned(
            vec![10.0, -3.0],
            BeamSection {
                flexural_rigidity: 1.0,
                mass_per_length: 1.0,
            },
        );
        assert_eq!(
            beam.validate(),
            Err(ModelError::NotPositive {
                quantity: "span length",
                value: -3.0
            })
        );
        beam.span_lengths = vec![10.0];
        assert!(matches!(
            beam.validate(),
            Err(ModelError::SupportCount {
                span_count: 1,
                support_count: 3
            })
        ));
    }

    #[test]
    fn too_many_girders_for_the_deck_are_rejected() {
        let BridgeModel::Grillage(mut g) = paper_bridge(2, 20.0) else {
            panic!("grillage")
        };
        g.girder_count = 5;
        assert!(matches!(
            g.validate(),
            Err(ModelError::DeckTooNarrow {
                girder_count: 5,
                ..
            })
        ));
    }
}
