//! Fatigue strength curves (S–N curves) of steel details: the number of cycles N_R that a detail
//! endures at a constant stress range.
//!
//! **EN 1993-1-9:2005** (Eurocode 3, Part 1-9: Fatigue), §7.1 and Figures 7.1 and 7.2; second
//! source: Nussbaumer, Borges & Davaine, *Fatigue Design of Steel and Composite Structures*
//! (ECCS Eurocode Design Manual, 2011), §4.4.
//! - Direct stress ranges (Figure 7.1), category Δσ_C (the range at 2 × 10⁶ cycles):
//!   Δσ_R³ N_R = Δσ_C³ · 2 × 10⁶ for N_R ≤ 5 × 10⁶; the constant-amplitude fatigue limit
//!   Δσ_D = (2/5)^{1/3} Δσ_C = 0.737 Δσ_C; Δσ_R⁵ N_R = Δσ_D⁵ · 5 × 10⁶ for
//!   5 × 10⁶ ≤ N_R ≤ 10⁸; the cut-off limit Δσ_L = (5/100)^{1/5} Δσ_D = 0.549 Δσ_D, below which
//!   a range does no damage.
//! - Shear stress ranges (Figure 7.2), category Δτ_C: Δτ_R⁵ N_R = Δτ_C⁵ · 2 × 10⁶ for
//!   N_R ≤ 10⁸; the cut-off Δτ_L = (2/100)^{1/5} Δτ_C = 0.457 Δτ_C.
//! - Partial factors (§3, Table 3.1; §6.2 and §8(2)): the damage of a range Δσ is that of
//!   γ_Ff Δσ on the curve Δσ_C/γ_Mf, which is that of γ_Ff γ_Mf Δσ on the characteristic
//!   curve (the knee and the cut-off scale with the category). Both default to 1: the
//!   characteristic damage.
//!
//! **AASHTO LRFD Bridge Design Specifications**, 9th ed. (2020), §6.6.1.2.5: the nominal fatigue
//! resistance (ΔF)_n = (A/N)^{1/3} (Eq. 6.6.1.2.5-2), with the detail category constant A of
//! Table 6.6.1.2.5-1 and the constant-amplitude fatigue threshold (ΔF)_TH of Table
//! 6.6.1.2.5-3. Under variable-amplitude traffic every range counts on the finite-life line,
//! N_R = A/Δf³, without a cut-off (the effective stress range of §6.6.1.2.5 and of the Manual
//! for Bridge Evaluation, 3rd ed., §7.2.5, after NCHRP Report 299, Moses, Schilling & Raju 1987);
//! the threshold is the infinite-life check of the Fatigue I limit state, reported beside.

use crate::units::KSI;

/// The number of cycles at which EN 1993-1-9's categories are defined (Figures 7.1 and 7.2).
pub const REFERENCE_CYCLES: f64 = 2.0e6;
/// EN 1993-1-9 Figure 7.1: the knee of the direct-stress curves (the constant-amplitude
/// fatigue limit Δσ_D) [cycles].
pub const KNEE_CYCLES: f64 = 5.0e6;
/// EN 1993-1-9 Figures 7.1 and 7.2: the cut-off limit's number of cycles.
pub const CUT_OFF_CYCLES: f64 = 1.0e8;

/// The detail categories Δσ_C of EN 1993-1-9 Tables 8.1–8.10 for direct stress [MPa].
pub const EUROCODE_DIRECT_CATEGORIES_MPA: [f64; 14] = [
    160.0, 140.0, 125.0, 112.0, 100.0, 90.0, 80.0, 71.0, 63.0, 56.0, 50.0, 45.0, 40.0, 36.0,
];
/// The detail categories Δτ_C of EN 1993-1-9 Tables 8.1–8.10 for shear stress [MPa].
pub const EUROCODE_SHEAR_CATEGORIES_MPA: [f64; 2] = [100.0, 80.0];

/// Whether a detail's stress is a direct (normal) stress or a shear stress: EN 1993-1-9 gives
/// each its own curve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StressKind {
    /// A normal stress σ (from a bending moment): Figure 7.1.
    Direct,
    /// A shear stress τ (from a shear force): Figure 7.2.
    Shear,
}

/// An AASHTO LRFD detail category (Table 6.6.1.2.5-1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum AashtoCategory {
    A,
    B,
    BPrime,
    C,
    CPrime,
    D,
    E,
    EPrime,
}

impl AashtoCategory {
    /// Every category, in the table's order.
    pub const ALL: [AashtoCategory; 8] = [
        AashtoCategory::A,
        AashtoCategory::B,
        AashtoCategory::BPrime,
        AashtoCategory::C,
        AashtoCategory::CPrime,
        AashtoCategory::D,
        AashtoCategory::E,
        AashtoCategory::EPrime,
    ];

    /// The category's name as the tables write it: A, B, B', C, C', D, E, E'.
    pub fn name(self) -> &'static str {
        match self {
            AashtoCategory::A => "A",
            AashtoCategory::B => "B",
            AashtoCategory::BPrime => "B'",
            AashtoCategory::C => "C",
            AashtoCategory::CPrime => "C'",
            AashtoCategory::D => "D",
            AashtoCategory::E => "E",
            AashtoCategory::EPrime => "E'",
        }
    }

    /// The category of a name (A, B, B', C, C', D, E, E').
    pub fn of_name(name: &str) -> Option<AashtoCategory> {
        AashtoCategory::ALL.into_iter().find(|c| c.name() == name)
    }

    /// The detail category constant A of Table 6.6.1.2.5-1 [ksi³].
    pub fn constant_ksi3(self) -> f64 {
        1.0e8
            * match self {
                AashtoCategory::A => 250.0,
                AashtoCategory::B => 120.0,
                AashtoCategory::BPrime => 61.0,
                AashtoCategory::C | AashtoCategory::CPrime => 44.0,
                AashtoCategory::D => 22.0,
                AashtoCategory::E => 11.0,
                AashtoCategory::EPrime => 3.9,
            }
    }

    /// The constant-amplitude fatigue threshold (ΔF)_TH of Table 6.6.1.2.5-3 [ksi].
    pub fn threshold_ksi(self) -> f64 {
        match self {
            AashtoCategory::A => 24.0,
            AashtoCategory::B => 16.0,
            AashtoCategory::BPrime => 12.0,
            AashtoCategory::C => 10.0,
            AashtoCategory::CPrime => 12.0,
            AashtoCategory::D => 7.0,
            AashtoCategory::E => 4.5,
            AashtoCategory::EPrime => 2.6,
        }
    }
}

/// A detail's fatigue strength curve.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "family", rename_all = "snake_case")]
pub enum SnCurve {
    /// EN 1993-1-9, Figure 7.1 (direct) or 7.2 (shear).
    Eurocode {
        /// The detail category Δσ_C or Δτ_C: the range at 2 × 10⁶ cycles [Pa].
        category: f64,
        /// Direct or shear stress.
        stress: StressKind,
        /// γ_Ff γ_Mf: the product of the partial factors for fatigue loads and fatigue strength
        /// (EN 1993-1-9 §3 and Table 3.1) [-]; 1 for the characteristic curve.
        partial_factor: f64,
    },
    /// AASHTO LRFD Table 6.6.1.2.5-1, on the finite-life line without a cut-off.
    Aashto {
        /// The detail category.
        category: AashtoCategory,
    },
}

impl SnCurve {
    /// EN 1993-1-9's characteristic curve of a direct-stress category Δσ_C [Pa].
    pub fn eurocode_direct(category: f64) -> SnCurve {
        SnCurve::Eurocode {
            category,
            stress: StressKind::Direct,
            partial_factor: 1.0,
        }
    }

    /// The slope m of the curve at 2 × 10⁶ cycles: 3 for direct stress (both families), 5 for
    /// EN 1993-1-9's shear curve. The fatigue DAF is the m-th root of a damage ratio.
    pub fn slope(&self) -> f64 {
        match self {
            SnCurve::Eurocode {
                stress: StressKind::Shear,
                ..
            } => 5.0,
            _ => 3.0,
        }
    }

    /// The range at 2 × 10⁶ cycles on the characteristic curve [Pa]: Δσ_C, or (A/2 × 10⁶)^{1/3}.
    pub fn reference_range(&self) -> f64 {
        match *self {
            SnCurve::Eurocode { category, .. } => category,
            SnCurve::Aashto { category } => {
                (category.constant_ksi3() / REFERENCE_CYCLES).cbrt() * KSI
            }
        }
    }

    /// The range below which a cycle does no damage [Pa], in the detail's stress (the partial
    /// factors applied): Δσ_L/(γ_Ff γ_Mf), Δτ_L/(γ_Ff γ_Mf); 0 for AASHTO's line.
    pub fn cut_off(&self) -> f64 {
        match *self {
            SnCurve::Eurocode {
                category,
                stress,
                partial_factor,
            } => eurocode_branches(category, stress).cut_off / partial_factor,
            SnCurve::Aashto { .. } => 0.0,
        }
    }

    /// The number of cycles N_R to failure at a constant range [Pa] (∞ below the cut-off, and
    /// for a zero range).
    pub fn cycles_to_failure(&self, range: f64) -> f64 {
        if range <= 0.0 {
            return f64::INFINITY;
        }
        match *self {
            SnCurve::Eurocode {
                category,
                stress,
                partial_factor,
            } => {
                let range = range * partial_factor;
                let branches = eurocode_branches(category, stress);
                if range < branches.cut_off {
                    f64::INFINITY
                } else if range >= branches.knee {
                    REFERENCE_CYCLES * (category / range).powf(branches.first_slope)
                } else {
                    KNEE_CYCLES * (branches.knee / range).powi(5)
                }
            }
            SnCurve::Aashto { category } => category.constant_ksi3() / (range / KSI).powi(3),
        }
    }

    /// Miner's damage of `count` cycles of one range: n/N_R (0 below the cut-off).
    pub fn damage(&self, range: f64, count: f64) -> f64 {
        count / self.cycles_to_failure(range)
    }

    /// The equivalent constant-amplitude range at 2 × 10⁶ cycles of a damage D, on the line of
    /// slope m through the reference range: Δσ_E,2 = Δσ_C D^{1/m} (EN 1993-1-9 §6.2 and §8(3):
    /// γ_Ff Δσ_E,2 ≤ Δσ_C/γ_Mf is D ≤ 1) [Pa], in the detail's stress (partial factors
    /// applied as in the damage).
    pub fn equivalent_range_2e6(&self, damage: f64) -> f64 {
        let factor = match *self {
            SnCurve::Eurocode { partial_factor, .. } => partial_factor,
            SnCurve::Aashto { .. } => 1.0,
        };
        self.reference_range() * damage.powf(1.0 / self.slope()) / factor
    }

    /// The curve in words: "EN 1993-1-9 direct, Δσ_C = 71 MPa (m = 3/5)", "AASHTO LRFD C".
    pub fn label(&self) -> String {
        match *self {
            SnCurve::Eurocode {
                category,
                stress,
                partial_factor,
            } => {
                let (what, slopes) = match stress {
                    StressKind::Direct => ("Δσ_C", "m = 3/5"),
                    StressKind::Shear => ("Δτ_C", "m = 5"),
                };
                let factors = if partial_factor == 1.0 {
                    String::new()
                } else {
                    format!(", γ_Ff γ_Mf = {partial_factor}")
                };
                format!(
                    "EN 1993-1-9 category {} ({what}, {slopes}{factors})",
                    category / 1.0e6
                )
            }
            SnCurve::Aashto { category } => {
                format!(
                    "AASHTO LRFD category {} (m = 3, no cut-off)",
                    category.name()
                )
            }
        }
    }
}

/// The branches of an EN 1993-1-9 curve: the slope above the knee, the knee and the cut-off
/// [Pa] of the characteristic curve.
struct EurocodeBranches {
    first_slope: f64,
    knee: f64,
    cut_off: f64,
}

/// Figure 7.1 (direct): m = 3 to Δσ_D = (2/5)^{1/3} Δσ_C, m = 5 to Δσ_L = (5/100)^{1/5} Δσ_D;
/// Figure 7.2 (shear): one line of m = 5 down to Δτ_L = (2/100)^{1/5} Δτ_C (no knee: 0).
fn eurocode_branches(category: f64, stress: StressKind) -> EurocodeBranches {
    match stress {
        StressKind::Direct => {
            let knee = (REFERENCE_CYCLES / KNEE_CYCLES).cbrt() * category;
            EurocodeBranches {
                first_slope: 3.0,
                knee,
                cut_off: (KNEE_CYCLES / CUT_OFF_CYCLES).powf(0.2) * knee,
            }
        }
        StressKind::Shear => EurocodeBranches {
            first_slope: 5.0,
            knee: 0.0,
            cut_off: (REFERENCE_CYCLES / CUT_OFF_CYCLES).powf(0.2) * category,
        },
    }
}
