//! The design codes' dynamic allowances, one function per clause, each as the clause states it.
//!
//! Every function returns the impact factor IM (also written μ or DLA) as a fraction [-]: the
//! design dynamic response is (1 + IM) times the static one, which is what vbi's DAF measures.
//! The worked examples of the tests below are recorded in docs/verification.md §25 and
//! docs/design-codes.md, with the clause each comes from.

use std::f64::consts::PI;

/// Metres per foot (exact, by the international yard of 1959).
pub const FOOT: f64 = 0.3048;

/// JTG D60-2015 §4.3.2, Eq. (4.3.2): the impact coefficient μ of a highway bridge from its
/// fundamental frequency f [Hz]:
///
/// ```text
/// μ = 0.05                      f < 1.5 Hz
/// μ = 0.1767 ln f − 0.0157      1.5 Hz ≤ f ≤ 14 Hz
/// μ = 0.45                      f > 14 Hz
/// ```
///
/// (The code's branches do not quite meet: 0.0559 at 1.5 Hz and 0.4506 at 14 Hz.)
pub fn jtg_d60_impact_factor(frequency_hz: f64) -> f64 {
    if frequency_hz < 1.5 {
        0.05
    } else if frequency_hz <= 14.0 {
        0.1767 * frequency_hz.ln() - 0.0157
    } else {
        0.45
    }
}

/// Which of the code's fundamental-frequency formulas of JTG D60-2015 (commentary to §4.3.2)
/// applies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JtgFrequencyFormula {
    /// A simply supported beam: f = π/(2l²) √(EI_c/m_c).
    SimplySupported,
    /// A continuous beam, for positive moments and shear forces: f₁ = 13.616/(2πl²) √(EI_c/m_c).
    ContinuousPositive,
    /// A continuous beam, for negative (hogging) moments: f₂ = 23.651/(2πl²) √(EI_c/m_c).
    ContinuousNegative,
}

impl JtgFrequencyFormula {
    /// The coefficient c of f = c/(2πl²) √(EI_c/m_c): π² for a simple span (π/(2l²) = π²/(2πl²)),
    /// 13.616 and 23.651 for a continuous beam.
    pub fn coefficient(self) -> f64 {
        match self {
            JtgFrequencyFormula::SimplySupported => PI * PI,
            JtgFrequencyFormula::ContinuousPositive => 13.616,
            JtgFrequencyFormula::ContinuousNegative => 23.651,
        }
    }
}

/// The fundamental frequency [Hz] of JTG D60-2015's commentary to §4.3.2:
/// f = c/(2πl²) √(EI_c/m_c), with c of [`JtgFrequencyFormula::coefficient`], l the span [m],
/// EI_c the flexural rigidity of the mid-span section [N·m²] and m_c its mass per length
/// [kg/m] (G/g).
pub fn jtg_d60_frequency(
    formula: JtgFrequencyFormula,
    span_length: f64,
    flexural_rigidity: f64,
    mass_per_length: f64,
) -> f64 {
    formula.coefficient() / (2.0 * PI * span_length * span_length)
        * (flexural_rigidity / mass_per_length).sqrt()
}

/// The superstructure rows of JTJ 021-89 Table 2.3.2.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Jtj021Superstructure {
    /// Reinforced and prestressed concrete girders, rigid frames and arch spandrel structures:
    /// 1 + μ = 1.3 for L ≤ 5 m, 1.0 for L ≥ 45 m, linear between.
    ConcreteGirder,
    /// Steel bridges: 1 + μ = 1 + 15/(37.5 + L).
    Steel,
}

/// JTJ 021-89 §2.3.2, Table 2.3.2 (the span-length rule that JTG D60-2004 replaced by the
/// frequency rule): μ from the span L [m] of the superstructure row.
pub fn jtj_021_impact_factor(row: Jtj021Superstructure, span_length: f64) -> f64 {
    match row {
        Jtj021Superstructure::ConcreteGirder => 0.3 * ((45.0 - span_length) / 40.0).clamp(0.0, 1.0),
        Jtj021Superstructure::Steel => 15.0 / (37.5 + span_length),
    }
}

/// The limit states and components of AASHTO LRFD Table 3.6.2.1-1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LrfdCase {
    /// Deck joints, all limit states: 75 %.
    DeckJoints,
    /// All other components, fatigue and fracture limit state: 15 %.
    Fatigue,
    /// All other components, all other limit states (strength, service): 33 %.
    StrengthAndService,
}

/// AASHTO LRFD Bridge Design Specifications §3.6.2.1, Table 3.6.2.1-1: the dynamic load
/// allowance IM applied to the design truck or tandem (not to the lane load). Wood components
/// take half of it (§3.6.2.3).
pub fn aashto_lrfd_dynamic_load_allowance(case: LrfdCase) -> f64 {
    match case {
        LrfdCase::DeckJoints => 0.75,
        LrfdCase::Fatigue => 0.15,
        LrfdCase::StrengthAndService => 0.33,
    }
}

/// AASHTO Standard Specifications for Highway Bridges (17th ed., 2002) §3.8.2.1, Eq. (3-1):
/// I = 50/(L + 125) ≤ 0.30 with the loaded length L in feet (§3.8.2.2); L here in metres,
/// converted by [`FOOT`].
pub fn aashto_standard_impact_fraction(loaded_length: f64) -> f64 {
    let feet = loaded_length / FOOT;
    (50.0 / (feet + 125.0)).min(0.30)
}

/// CSA S6 (Canadian Highway Bridge Design Code) §3.8.4.5.3: the dynamic load allowance of the
/// CL-W truck by the number of its axles that load the component: 0.40 for one axle, 0.30 for
/// two, 0.25 for three or more (deck joints: 0.50).
pub fn csa_s6_dynamic_load_allowance(axle_count: usize) -> f64 {
    match axle_count {
        0 | 1 => 0.40,
        2 => 0.30,
        _ => 0.25,
    }
}

/// The design loads of AS 5100.2:2017 Table 7.7.2.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum As5100Load {
    /// W80 wheel load and A160 axle load: 0.40.
    SingleAxleOrWheel,
    /// M1600 tri-axle group: 0.35.
    TriaxleGroup,
    /// M1600 moving traffic load: 0.30.
    MovingTraffic,
}

/// AS 5100.2:2017 §7.7.2, Table 7.7.2: the dynamic load allowance α of a design load.
pub fn as_5100_dynamic_load_allowance(load: As5100Load) -> f64 {
    match load {
        As5100Load::SingleAxleOrWheel => 0.40,
        As5100Load::TriaxleGroup => 0.35,
        As5100Load::MovingTraffic => 0.30,
    }
}

/// Surface roughness of EN 1991-2:2003 Annex B.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EurocodeRoughness {
    /// "Good" roughness: φ_fat = 1.2.
    Good,
    /// "Medium" roughness: φ_fat = 1.4.
    Medium,
}

/// EN 1991-2:2003 Annex B (fatigue life assessment of road bridges), B(6): the damage-equivalent
/// dynamic amplification factor φ_fat of a surface's roughness, less one. (The load models of
/// §4.3 for the ultimate limit state include dynamic amplification in their values and have no
/// separate factor.)
pub fn en_1991_2_fatigue_impact_factor(roughness: EurocodeRoughness) -> f64 {
    match roughness {
        EurocodeRoughness::Good => 0.2,
        EurocodeRoughness::Medium => 0.4,
    }
}

/// EN 1991-2:2003 §4.6.1(6), Figure 4.7: the additional amplification factor near an expansion
/// joint, Δφ_fat = 1.30 (1 − D/26) ≥ 1 for a section D [m] from the joint (D ≤ 6 m); 1 beyond.
pub fn en_1991_2_joint_factor(distance_to_joint: f64) -> f64 {
    if distance_to_joint > 6.0 {
        return 1.0;
    }
    (1.30 * (1.0 - distance_to_joint.max(0.0) / 26.0)).max(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Worked examples computed by hand from the clause (docs/verification.md §25): μ(4 Hz) =
    /// 0.1767 ln 4 − 0.0157 = 0.22926; the two constant branches; the code's own branch ends.
    #[test]
    fn jtg_d60_impact_factor_follows_eq_4_3_2() {
        assert!((jtg_d60_impact_factor(4.0) - 0.229_258_2).abs() < 1e-6);
        assert_eq!(jtg_d60_impact_factor(1.2), 0.05);
        assert_eq!(jtg_d60_impact_factor(20.0), 0.45);
        assert!((jtg_d60_impact_factor(1.5) - 0.055_946).abs() < 1e-6);
        assert!((jtg_d60_impact_factor(14.0) - 0.450_622).abs() < 1e-6);
    }

    /// The simple-span formula π/(2l²)√(EI/m) is the exact first frequency of a pinned–pinned
    /// Euler–Bernoulli beam (Clough & Penzien Eq. 18-18); the continuous-beam formulas scale it
    /// by 13.616/π² and 23.651/π².
    #[test]
    fn jtg_d60_frequency_formulas_against_the_simple_beam_closed_form() {
        let (l, ei, m): (f64, f64, f64) = (30.0, 2.0e10, 1.5e4);
        let exact = PI / (2.0 * l * l) * (ei / m).sqrt();
        let simple = jtg_d60_frequency(JtgFrequencyFormula::SimplySupported, l, ei, m);
        assert!((simple / exact - 1.0).abs() < 1e-14);
        let f1 = jtg_d60_frequency(JtgFrequencyFormula::ContinuousPositive, l, ei, m);
        let f2 = jtg_d60_frequency(JtgFrequencyFormula::ContinuousNegative, l, ei, m);
        assert!((f1 / exact - 13.616 / (PI * PI)).abs() < 1e-12);
        assert!((f2 / f1 - 23.651 / 13.616).abs() < 1e-12);
    }

    /// JTJ 021-89 Table 2.3.2: the ends of the concrete row and a midpoint, 1 + μ = 1.15 at
    /// L = 25 m; the steel row 1 + 15/(37.5 + L) at L = 30 m, 1.2222.
    #[test]
    fn jtj_021_span_rule_follows_table_2_3_2() {
        let concrete = Jtj021Superstructure::ConcreteGirder;
        assert_eq!(jtj_021_impact_factor(concrete, 3.0), 0.3);
        assert_eq!(jtj_021_impact_factor(concrete, 60.0), 0.0);
        assert!((jtj_021_impact_factor(concrete, 25.0) - 0.15).abs() < 1e-15);
        assert!((jtj_021_impact_factor(concrete, 30.0) - 0.1125).abs() < 1e-15);
        let steel = jtj_021_impact_factor(Jtj021Superstructure::Steel, 30.0);
        assert!((steel - 15.0 / 67.5).abs() < 1e-15);
    }

    /// AASHTO Standard §3.8.2.1: L = 100 ft gives I = 50/225 = 0.2222; the SI form of the same
    /// clause, I = 15.24/(L + 38.1) with L in metres, agrees; short spans are capped at 0.30.
    #[test]
    fn aashto_standard_impact_fraction_follows_eq_3_1() {
        let hundred_feet = 100.0 * FOOT;
        assert!((aashto_standard_impact_fraction(hundred_feet) - 50.0 / 225.0).abs() < 1e-14);
        for l in [20.0, 30.0, 40.0, 80.0] {
            let si = 15.24 / (l + 38.1);
            assert!((aashto_standard_impact_fraction(l) - si).abs() < 1e-12);
        }
        assert_eq!(aashto_standard_impact_fraction(10.0), 0.30);
    }

    /// The fixed values of AASHTO LRFD Table 3.6.2.1-1, CSA S6 §3.8.4.5.3, AS 5100.2 Table
    /// 7.7.2 and EN 1991-2 Annex B, read from the tables.
    #[test]
    fn tabulated_allowances_follow_their_tables() {
        assert_eq!(
            aashto_lrfd_dynamic_load_allowance(LrfdCase::DeckJoints),
            0.75
        );
        assert_eq!(aashto_lrfd_dynamic_load_allowance(LrfdCase::Fatigue), 0.15);
        assert_eq!(
            aashto_lrfd_dynamic_load_allowance(LrfdCase::StrengthAndService),
            0.33
        );
        let csa: Vec<f64> = (1..=5).map(csa_s6_dynamic_load_allowance).collect();
        assert_eq!(csa, [0.40, 0.30, 0.25, 0.25, 0.25]);
        assert_eq!(
            as_5100_dynamic_load_allowance(As5100Load::MovingTraffic),
            0.30
        );
        assert_eq!(
            en_1991_2_fatigue_impact_factor(EurocodeRoughness::Medium),
            0.4
        );
    }

    /// EN 1991-2 Figure 4.7: 1.30 at the joint, 1.30 (1 − 6/26) = 1.0 at 6 m, 1 beyond.
    #[test]
    fn en_1991_2_joint_factor_follows_figure_4_7() {
        assert!((en_1991_2_joint_factor(0.0) - 1.30).abs() < 1e-15);
        assert!((en_1991_2_joint_factor(3.0) - 1.30 * 23.0 / 26.0).abs() < 1e-15);
        assert!((en_1991_2_joint_factor(6.0) - 1.0).abs() < 1e-15);
        assert_eq!(en_1991_2_joint_factor(10.0), 1.0);
    }
}
