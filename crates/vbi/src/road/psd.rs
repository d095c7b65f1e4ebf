//! ISO 8608 displacement power spectral density (paper Eq. 21) and roughness classes.

use serde::{Deserialize, Serialize};

use super::RoadError;

/// Reference spatial frequency n₀ of ISO 8608 [cycles/m] (0.1 cycles/m, paper Eq. 21).
pub const REFERENCE_SPATIAL_FREQUENCY: f64 = 0.1;

/// One-sided displacement PSD of ISO 8608, paper Eq. 21:
/// G_d(n) = G_d(n₀) (n / n₀)^(−w), n₀ = 0.1 cycles/m.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DisplacementPsd {
    /// G_d(n₀), the PSD at the reference spatial frequency [m³] (= m²/(cycle/m)). No default.
    pub psd_at_reference: f64,
    /// Waviness w [-], the negative slope on log–log axes (default 2, ISO 8608 and the paper).
    pub waviness: f64,
}

impl DisplacementPsd {
    /// A PSD; G_d(n₀) must be finite and ≥ 0, the waviness finite and > 0.
    pub fn new(psd_at_reference: f64, waviness: f64) -> Result<DisplacementPsd, RoadError> {
        if !(psd_at_reference.is_finite() && psd_at_reference >= 0.0) {
            return Err(RoadError::InvalidPsdAtReference { psd_at_reference });
        }
        if !(waviness.is_finite() && waviness > 0.0) {
            return Err(RoadError::InvalidWaviness { waviness });
        }
        Ok(DisplacementPsd {
            psd_at_reference,
            waviness,
        })
    }

    /// G_d(n) [m³] at spatial frequency n [cycles/m] > 0 (Eq. 21).
    pub fn value(&self, spatial_frequency: f64) -> f64 {
        self.psd_at_reference
            * (spatial_frequency / REFERENCE_SPATIAL_FREQUENCY).powf(-self.waviness)
    }

    /// The variance ∫ G_d(n) dn over [n₁, n₂] [m²] in closed form (the continuous integral,
    /// which the discrete sums of Eq. 22 approximate).
    pub fn band_variance(&self, lower: f64, upper: f64) -> f64 {
        let w = self.waviness;
        let scale = self.psd_at_reference * REFERENCE_SPATIAL_FREQUENCY.powf(w);
        if (w - 1.0).abs() < 1e-12 {
            scale * (upper / lower).ln()
        } else {
            scale * (upper.powf(1.0 - w) - lower.powf(1.0 - w)) / (1.0 - w)
        }
    }
}

/// The spatial frequency n₀ at which a roughness G_d(n₀) is read: two conventions of the
/// literature that differ by a factor (n₀'/0.1)^w ≈ 2.53 for w = 2 (docs/paper-reproduction.md,
/// "Two readings of the paper's road classes").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PsdReference {
    /// ISO 8608 (and the paper's Eq. 21): n₀ = 0.1 cycles/m.
    Iso8608,
    /// Dodds & Robson (1973), as used by Deng & Cai (2010) and much of the VBI literature:
    /// n₀ = 1/(2π) cycles/m (a spatial angular frequency of 1 rad/m).
    DoddsRobson,
}

impl PsdReference {
    /// n₀ [cycles/m].
    pub fn spatial_frequency(self) -> f64 {
        match self {
            PsdReference::Iso8608 => REFERENCE_SPATIAL_FREQUENCY,
            PsdReference::DoddsRobson => 0.5 / std::f64::consts::PI,
        }
    }

    /// The name in input files (`iso-8608`, `dodds-robson`).
    pub fn name(self) -> &'static str {
        match self {
            PsdReference::Iso8608 => "iso-8608",
            PsdReference::DoddsRobson => "dodds-robson",
        }
    }

    /// The reference of a name, case-insensitive; `None` if unknown.
    pub fn from_name(name: &str) -> Option<PsdReference> {
        [PsdReference::Iso8608, PsdReference::DoddsRobson]
            .into_iter()
            .find(|r| r.name().eq_ignore_ascii_case(name.trim()))
    }

    /// G_d(0.1 cycles/m) [m³] of a roughness G_d(n₀) read at this reference, for waviness w:
    /// G_d(0.1) = G_d(n₀) (n₀/0.1)^w (Eq. 21 evaluated at 0.1 cycles/m).
    pub fn to_iso_reference(self, psd_at_reference: f64, waviness: f64) -> f64 {
        psd_at_reference * (self.spatial_frequency() / REFERENCE_SPATIAL_FREQUENCY).powf(waviness)
    }
}

/// A named road class: the paper's four (§3.2), ISO 8608 classes A–H at their geometric
/// means (docs/verification.md §8), and the five classes of Dodds & Robson (1973) at the
/// geometric means of their ranges, read at their own n₀ = 1/(2π) cycles/m
/// ([`PsdReference::DoddsRobson`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RoughnessClass {
    /// The paper's 'smooth': no roughness, G_d(n₀) = 0.
    Smooth,
    /// The paper's 'good': G_d(n₀) = 8 × 10⁻⁶ m³.
    Good,
    /// The paper's 'medium': G_d(n₀) = 64 × 10⁻⁶ m³.
    Medium,
    /// The paper's 'poor': G_d(n₀) = 128 × 10⁻⁶ m³.
    Poor,
    /// ISO 8608 class A: 16 × 10⁻⁶ m³.
    A,
    /// ISO 8608 class B: 64 × 10⁻⁶ m³.
    B,
    /// ISO 8608 class C: 256 × 10⁻⁶ m³.
    C,
    /// ISO 8608 class D: 1024 × 10⁻⁶ m³.
    D,
    /// ISO 8608 class E: 4096 × 10⁻⁶ m³.
    E,
    /// ISO 8608 class F: 16384 × 10⁻⁶ m³.
    F,
    /// ISO 8608 class G: 65536 × 10⁻⁶ m³.
    G,
    /// ISO 8608 class H: 262144 × 10⁻⁶ m³.
    H,
    /// Dodds & Robson 'very good' (2–8 × 10⁻⁶ m³ at n₀ = 1/2π): 4 × 10⁻⁶ m³.
    #[serde(rename = "dr-very-good")]
    DoddsVeryGood,
    /// Dodds & Robson 'good' (8–32 × 10⁻⁶ m³): 16 × 10⁻⁶ m³.
    #[serde(rename = "dr-good")]
    DoddsGood,
    /// Dodds & Robson 'average' (32–128 × 10⁻⁶ m³): 64 × 10⁻⁶ m³.
    #[serde(rename = "dr-average")]
    DoddsAverage,
    /// Dodds & Robson 'poor' (128–512 × 10⁻⁶ m³): 256 × 10⁻⁶ m³.
    #[serde(rename = "dr-poor")]
    DoddsPoor,
    /// Dodds & Robson 'very poor' (512–2048 × 10⁻⁶ m³): 1024 × 10⁻⁶ m³.
    #[serde(rename = "dr-very-poor")]
    DoddsVeryPoor,
}

impl RoughnessClass {
    /// Every class, the paper's first.
    pub const ALL: [RoughnessClass; 17] = [
        RoughnessClass::Smooth,
        RoughnessClass::Good,
        RoughnessClass::Medium,
        RoughnessClass::Poor,
        RoughnessClass::A,
        RoughnessClass::B,
        RoughnessClass::C,
        RoughnessClass::D,
        RoughnessClass::E,
        RoughnessClass::F,
        RoughnessClass::G,
        RoughnessClass::H,
        RoughnessClass::DoddsVeryGood,
        RoughnessClass::DoddsGood,
        RoughnessClass::DoddsAverage,
        RoughnessClass::DoddsPoor,
        RoughnessClass::DoddsVeryPoor,
    ];

    /// The Dodds & Robson classes, smoothest first.
    pub const DODDS_ROBSON: [RoughnessClass; 5] = [
        RoughnessClass::DoddsVeryGood,
        RoughnessClass::DoddsGood,
        RoughnessClass::DoddsAverage,
        RoughnessClass::DoddsPoor,
        RoughnessClass::DoddsVeryPoor,
    ];

    /// The ISO 8608 classes A–H.
    pub const ISO: [RoughnessClass; 8] = [
        RoughnessClass::A,
        RoughnessClass::B,
        RoughnessClass::C,
        RoughnessClass::D,
        RoughnessClass::E,
        RoughnessClass::F,
        RoughnessClass::G,
        RoughnessClass::H,
    ];

    /// Where the class's G_d(n₀) is read: at 1/(2π) cycles/m for the Dodds & Robson classes, at
    /// 0.1 cycles/m for the others.
    pub fn reference(self) -> PsdReference {
        if RoughnessClass::DODDS_ROBSON.contains(&self) {
            PsdReference::DoddsRobson
        } else {
            PsdReference::Iso8608
        }
    }

    /// G_d(n₀) [m³] of the class, at its own n₀ ([`reference`](Self::reference)).
    pub fn psd_at_reference(self) -> f64 {
        let micro = match self {
            RoughnessClass::Smooth => 0.0,
            RoughnessClass::Good => 8.0,
            RoughnessClass::Medium => 64.0,
            RoughnessClass::Poor => 128.0,
            RoughnessClass::A => 16.0,
            RoughnessClass::B => 64.0,
            RoughnessClass::C => 256.0,
            RoughnessClass::D => 1024.0,
            RoughnessClass::E => 4096.0,
            RoughnessClass::F => 16384.0,
            RoughnessClass::G => 65536.0,
            RoughnessClass::H => 262144.0,
            RoughnessClass::DoddsVeryGood => 4.0,
            RoughnessClass::DoddsGood => 16.0,
            RoughnessClass::DoddsAverage => 64.0,
            RoughnessClass::DoddsPoor => 256.0,
            RoughnessClass::DoddsVeryPoor => 1024.0,
        };
        micro * 1.0e-6
    }

    /// The name used in input files and on the command line (`smooth`, `good`, `medium`,
    /// `poor`, `A` … `H`, `dr-very-good` … `dr-very-poor`).
    pub fn name(self) -> &'static str {
        match self {
            RoughnessClass::Smooth => "smooth",
            RoughnessClass::Good => "good",
            RoughnessClass::Medium => "medium",
            RoughnessClass::Poor => "poor",
            RoughnessClass::A => "A",
            RoughnessClass::B => "B",
            RoughnessClass::C => "C",
            RoughnessClass::D => "D",
            RoughnessClass::E => "E",
            RoughnessClass::F => "F",
            RoughnessClass::G => "G",
            RoughnessClass::H => "H",
            RoughnessClass::DoddsVeryGood => "dr-very-good",
            RoughnessClass::DoddsGood => "dr-good",
            RoughnessClass::DoddsAverage => "dr-average",
            RoughnessClass::DoddsPoor => "dr-poor",
            RoughnessClass::DoddsVeryPoor => "dr-very-poor",
        }
    }

    /// The class of a name, case-insensitive; `None` if unknown.
    pub fn from_name(name: &str) -> Option<RoughnessClass> {
        RoughnessClass::ALL
            .into_iter()
            .find(|c| c.name().eq_ignore_ascii_case(name.trim()))
    }

    /// The ISO 8608 class (A–H) whose limits contain G_d(n₀) [m³]: class limits lie at half
    /// and double the geometric mean; A extends down to 0 and H upwards without bound.
    /// `None` for a negative or non-finite value.
    pub fn iso_class_of(psd_at_reference: f64) -> Option<RoughnessClass> {
        if !(psd_at_reference.is_finite() && psd_at_reference >= 0.0) {
            return None;
        }
        RoughnessClass::ISO
            .into_iter()
            .find(|c| psd_at_reference < 2.0 * c.psd_at_reference())
            .or(Some(RoughnessClass::H))
    }
}

/// The roughness of a road: a named class or a custom G_d(n₀).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Roughness {
    /// A named class.
    Class(RoughnessClass),
    /// A custom G_d(n₀) [m³].
    Custom {
        /// G_d(n₀) [m³].
        psd_at_reference: f64,
    },
}

impl Roughness {
    /// Where G_d(n₀) is read unless the road says otherwise: the class's own reference, ISO
    /// 8608's for a custom value.
    pub fn reference(self) -> PsdReference {
        match self {
            Roughness::Class(c) => c.reference(),
            Roughness::Custom { .. } => PsdReference::Iso8608,
        }
    }

    /// G_d(n₀) [m³], at its reference n₀.
    pub fn psd_at_reference(self) -> f64 {
        match self {
            Roughness::Class(c) => c.psd_at_reference(),
            Roughness::Custom { psd_at_reference } => psd_at_reference,
        }
    }

    /// A short description: the class name, or `custom G_d(n0) = … m^3`.
    pub fn describe(self) -> String {
        match self {
            Roughness::Class(c) => c.name().to_string(),
            Roughness::Custom { psd_at_reference } => {
                format!("custom G_d(n0) = {psd_at_reference:e} m^3")
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: docs/verification.md §8, table of geometric means (×10⁻⁶ m³).
    #[test]
    fn iso_class_geometric_means_follow_the_reference_table() {
        let expected = [
            16.0, 64.0, 256.0, 1024.0, 4096.0, 16384.0, 65536.0, 262144.0,
        ];
        for (class, micro) in RoughnessClass::ISO.into_iter().zip(expected) {
            assert_eq!(class.psd_at_reference(), micro * 1e-6);
        }
        assert_eq!(RoughnessClass::Good.psd_at_reference(), 8e-6);
        assert_eq!(RoughnessClass::Medium.psd_at_reference(), 64e-6);
        assert_eq!(RoughnessClass::Poor.psd_at_reference(), 128e-6);
        assert_eq!(RoughnessClass::Smooth.psd_at_reference(), 0.0);
    }

    /// Dodds & Robson (1973) classes: the geometric means of their ranges 2–8, 8–32, 32–128,
    /// 128–512, 512–2048 × 10⁻⁶ m³ at n₀ = 1/(2π) cycles/m, which is (1/(0.2π))² = 2.533 times
    /// rougher when read at ISO 8608's 0.1 cycles/m for w = 2 (docs/paper-reproduction.md).
    #[test]
    fn dodds_robson_classes_sit_at_their_geometric_means_at_one_over_two_pi() {
        let ranges = [2.0, 8.0, 32.0, 128.0, 512.0, 2048.0];
        for (i, class) in RoughnessClass::DODDS_ROBSON.into_iter().enumerate() {
            let mean: f64 = (ranges[i] * ranges[i + 1] * 1e-12_f64).sqrt();
            assert!((class.psd_at_reference() / mean - 1.0).abs() < 1e-12);
            assert_eq!(class.reference(), PsdReference::DoddsRobson);
            assert_eq!(RoughnessClass::from_name(class.name()), Some(class));
        }
        assert_eq!(RoughnessClass::Medium.reference(), PsdReference::Iso8608);
        let n0 = PsdReference::DoddsRobson.spatial_frequency();
        assert!((n0 - 0.159_154_943_091_895_34).abs() < 1e-15);
        let at_iso = PsdReference::DoddsRobson.to_iso_reference(64e-6, 2.0);
        assert!((at_iso / 64e-6 - 1.0 / (0.2 * std::f64::consts::PI).powi(2)).abs() < 1e-12);
        assert!((at_iso / 64e-6 - 2.533).abs() < 1e-3);
        assert_eq!(PsdReference::Iso8608.to_iso_reference(64e-6, 2.0), 64e-6);
    }

    #[test]
    fn iso_class_of_uses_limits_at_half_and_double_the_mean() {
        assert_eq!(RoughnessClass::iso_class_of(8e-6), Some(RoughnessClass::A));
        assert_eq!(RoughnessClass::iso_class_of(64e-6), Some(RoughnessClass::B));
        assert_eq!(
            RoughnessClass::iso_class_of(128e-6),
            Some(RoughnessClass::C)
        );
        assert_eq!(RoughnessClass::iso_class_of(1.0), Some(RoughnessClass::H));
        assert_eq!(RoughnessClass::iso_class_of(-1.0), None);
    }

    #[test]
    fn names_round_trip_case_insensitively() {
        for c in RoughnessClass::ALL {
            assert_eq!(RoughnessClass::from_name(c.name()), Some(c));
        }
        assert_eq!(
            RoughnessClass::from_name("MEDIUM"),
            Some(RoughnessClass::Medium)
        );
        assert_eq!(RoughnessClass::from_name("c"), Some(RoughnessClass::C));
        assert_eq!(RoughnessClass::from_name("awful"), None);
    }

    #[test]
    fn band_variance_matches_the_closed_form_for_waviness_two() {
        // ∫ G0 n0² n⁻² dn = G0 n0² (1/n1 − 1/n2): exact, so round-off only.
        let psd = DisplacementPsd::new(64e-6, 2.0).unwrap();
        let expected = 64e-6 * 0.01 * (1.0 / 0.01 - 1.0 / 3.0);
        assert!((psd.band_variance(0.01, 3.0) - expected).abs() < 1e-15);
        assert_eq!(psd.value(0.1), 64e-6);
        assert!((psd.value(0.2) - 16e-6).abs() < 1e-18);
    }
}
