//! Which clause and which input apply to a station: worked examples computed by hand from the
//! clauses (docs/verification.md §25).

use super::clauses::*;
use super::*;
use crate::fe::StationTarget;
use crate::model::{paper_bridge, ContinuousBeam};
use std::f64::consts::PI;

fn inputs(span_lengths: Vec<f64>, bending_frequencies: Vec<f64>) -> CodeInputs {
    CodeInputs {
        span_lengths,
        line_offsets: Vec::new(),
        section: Some(BeamSection {
            flexural_rigidity: 2.0e10,
            mass_per_length: 1.5e4,
        }),
        bending_frequencies,
        measured_frequencies: false,
        axle_count: 3,
        psd_at_reference: Some(64e-6),
    }
}

fn station(position: f64, over_support: bool) -> Station {
    Station {
        name: format!("x{position}"),
        position,
        target: StationTarget::Section,
        over_support,
        support: over_support,
    }
}

fn find<'a>(
    factors: &'a [CodeImpactFactor],
    code: DesignCode,
    provision: &str,
) -> &'a CodeImpactFactor {
    factors
        .iter()
        .find(|f| f.code == code && f.provision == provision)
        .unwrap_or_else(|| panic!("no {code:?} {provision} in {factors:?}"))
}

/// A 30 m simple span, mid-span moment, 3-axle truck on a road of G_d = 64 × 10⁻⁶ m³ (ISO B):
/// JTG μ(π/(2l²)√(EI/m)); JTJ 0.3·15/40 = 0.1125; AASHTO LRFD 0.33 and 0.15; AASHTO Standard
/// 15.24/(30 + 38.1) = 0.22379; CSA S6 0.25; AS 5100 0.30; EN φ_fat = 1.2 (15 m from a joint).
#[test]
fn simple_span_mid_span_moment_worked_example() {
    let inputs = inputs(vec![30.0], vec![3.2, 12.8]);
    let factors = station_factors(&inputs, &station(15.0, false), Quantity::BendingMoment);
    let f = PI / (2.0 * 900.0) * (2.0e10_f64 / 1.5e4).sqrt();
    let code = find(&factors, DesignCode::JtgD60, "code_frequency");
    assert!((code.impact_factor - (0.1767 * f.ln() - 0.0157)).abs() < 1e-12);
    let computed = find(&factors, DesignCode::JtgD60, "computed_frequency");
    assert!((computed.impact_factor - (0.1767 * 3.2_f64.ln() - 0.0157)).abs() < 1e-12);
    let jtj = find(&factors, DesignCode::Jtj021, "span").impact_factor;
    assert!((jtj - 0.1125).abs() < 1e-15);
    assert_eq!(
        find(&factors, DesignCode::AashtoLrfd, "strength_service").impact_factor,
        0.33
    );
    assert_eq!(
        find(&factors, DesignCode::AashtoLrfd, "fatigue").impact_factor,
        0.15
    );
    let standard = find(&factors, DesignCode::AashtoStandard, "loaded_length").impact_factor;
    assert!((standard - 15.24 / 68.1).abs() < 1e-12);
    assert_eq!(
        find(&factors, DesignCode::CsaS6, "cl_w_axles").impact_factor,
        0.25
    );
    assert_eq!(
        find(&factors, DesignCode::As5100, "moving_traffic").impact_factor,
        0.30
    );
    let en = find(&factors, DesignCode::En1991, "fatigue_roughness").impact_factor;
    assert!((en - 0.2).abs() < 1e-15);
    assert!((code.daf() - 1.0 - code.impact_factor).abs() < 1e-15);
}

/// Over the interior support of 20 m + 40 m spans, the negative moment reads JTG's f₂ formula
/// (23.651, l = the longest span, 40 m) and vbi's fundamental frequency; the span rules read
/// the mean of the adjacent spans, 30 m (AASHTO Standard §3.8.2.2(e)).
#[test]
fn interior_support_negative_moment_reads_f2_and_the_mean_span() {
    let inputs = inputs(vec![20.0, 40.0], vec![2.5, 4.0]);
    let support = station(20.0, true);
    let factors = station_factors(&inputs, &support, Quantity::BendingMoment);
    let f2 = 23.651 / (2.0 * PI * 1600.0) * (2.0e10_f64 / 1.5e4).sqrt();
    let code = find(&factors, DesignCode::JtgD60, "code_frequency");
    assert!((code.impact_factor - jtg_d60_impact_factor(f2)).abs() < 1e-12);
    assert!(code.basis.starts_with("f2 = "), "{}", code.basis);
    // The FE route reads the fundamental frequency for every effect (§4.3.2; issue 46: it read
    // the second mode for a hogging moment).
    let computed = find(&factors, DesignCode::JtgD60, "computed_frequency");
    assert_eq!(computed.impact_factor, jtg_d60_impact_factor(2.5));
    // CSA S6: the loaded length of a hogging moment is both spans, 60 m: five CL-W axles, 0.25.
    let csa = find(&factors, DesignCode::CsaS6, "cl_w_axles");
    assert_eq!(csa.impact_factor, 0.25);
    assert!(csa.basis.starts_with("5 CL-W axle(s)"), "{}", csa.basis);
    let standard = find(&factors, DesignCode::AashtoStandard, "loaded_length").impact_factor;
    assert!((standard - 15.24 / 68.1).abs() < 1e-12);
    let jtj = find(&factors, DesignCode::Jtj021, "span").impact_factor;
    assert!((jtj - 0.1125).abs() < 1e-15);
    // The reaction there is no negative moment: f1 and vbi's first frequency.
    let reaction = station_factors(&inputs, &support, Quantity::SupportReaction);
    let computed = find(&reaction, DesignCode::JtgD60, "computed_frequency");
    assert_eq!(computed.impact_factor, jtg_d60_impact_factor(2.5));
}

/// AASHTO Standard §3.8.2.2(d): the shear force 10 m into a 30 m span reads the length to the
/// far reaction, 20 m: I = 15.24/(20 + 38.1) = 0.26231.
#[test]
fn shear_reads_the_length_to_the_far_reaction() {
    let inputs = inputs(vec![30.0, 30.0], vec![3.0, 4.0]);
    let factors = station_factors(&inputs, &station(10.0, false), Quantity::ShearForce);
    let standard = find(&factors, DesignCode::AashtoStandard, "loaded_length").impact_factor;
    assert!((standard - 15.24 / 58.1).abs() < 1e-12);
}

/// EN 1991-2: 3 m from the end joint φ = 1.2 · 1.3 (1 − 3/26); a road of ISO class C is
/// "medium" (1.4); ISO D and rougher are outside Annex B and get no factor.
#[test]
fn eurocode_factor_by_roughness_and_joint_distance() {
    let mut inputs = inputs(vec![30.0], vec![3.0]);
    let near_joint = station_factors(&inputs, &station(3.0, false), Quantity::Deflection);
    let en = find(&near_joint, DesignCode::En1991, "fatigue_roughness").impact_factor;
    assert!((en - (1.2 * 1.3 * 23.0 / 26.0 - 1.0)).abs() < 1e-12);
    inputs.psd_at_reference = Some(256e-6);
    let medium = station_factors(&inputs, &station(15.0, false), Quantity::Deflection);
    let en = find(&medium, DesignCode::En1991, "fatigue_roughness").impact_factor;
    assert!((en - 0.4).abs() < 1e-15);
    inputs.psd_at_reference = Some(1024e-6);
    let rough = station_factors(&inputs, &station(15.0, false), Quantity::Deflection);
    assert!(rough.iter().all(|f| f.code != DesignCode::En1991));
}

/// A model without EI and m (an imported basis) and without bending modes gives no JTG value,
/// and every other code still answers.
#[test]
fn missing_section_and_frequencies_drop_only_the_jtg_values() {
    let mut inputs = inputs(vec![30.0], vec![]);
    inputs.section = None;
    let factors = station_factors(&inputs, &station(15.0, false), Quantity::Deflection);
    assert!(factors.iter().all(|f| f.code != DesignCode::JtgD60));
    // JTJ, LRFD ×2, AASHTO Standard, CSA S6, AS 5100.2 ×3 (one per design load), EN.
    assert_eq!(factors.len(), 9);
}

/// The whole section of a grillage sums its girders' E·I_y and ρ·A plus the pavement: for the
/// paper's 3 × 30 m bridge the total mass is the girders' and pavement's, and for a beam the
/// section itself with its added mass.
#[test]
fn whole_section_sums_the_girders() {
    let model = paper_bridge(3, 30.0);
    let BridgeModel::Grillage(grillage) = &model else {
        panic!("the paper's bridge is a grillage")
    };
    let total = whole_section(&model).unwrap();
    let mut ei = 0.0;
    let mut m = 0.0;
    for i in 0..grillage.girder_count {
        let s = grillage.girder_section(i).unwrap();
        ei += grillage.material.elastic_modulus * s.second_moment_y;
        m += grillage.material.density * s.area + grillage.added_mass_per_length(i);
    }
    assert!((total.flexural_rigidity / ei - 1.0).abs() < 1e-14);
    assert!((total.mass_per_length / m - 1.0).abs() < 1e-14);
    let mut beam = ContinuousBeam::pinned(
        vec![25.0],
        BeamSection {
            flexural_rigidity: 1e10,
            mass_per_length: 1e4,
        },
    );
    beam.added_mass_per_length = 500.0;
    let section = whole_section(&BridgeModel::ContinuousBeam(beam)).unwrap();
    assert_eq!(section.mass_per_length, 10_500.0);
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

/// Every variant of [`DesignCode`], in the order of its declaration: serde's variant index
/// (0, 1, ... until it has no variant) read back as the enum, so that the list needs no update
/// when a code is added.
fn declared_codes() -> Vec<DesignCode> {
    use serde::de::value::{Error, U32Deserializer};
    (0..)
        .map_while(|index| DesignCode::deserialize(U32Deserializer::<Error>::new(index)).ok())
        .collect()
}

/// The registry has one line for every code, each code once, in the order of the declaration
/// of [`DesignCode`] (the order of the factors in every table and figure); and the names read
/// from it are the ones tables and figures have always printed.
#[test]
fn the_registry_lists_every_design_code_once_in_declaration_order() {
    let declared = declared_codes();
    assert_eq!(declared.len(), 7, "{declared:?}");
    let registered: Vec<DesignCode> = REGISTRY.iter().map(|entry| entry.code).collect();
    assert_eq!(registered, declared);
    let names: Vec<&str> = declared.iter().map(|code| code.name()).collect();
    assert_eq!(
        names,
        [
            "JTG D60-2015",
            "JTJ 021-89",
            "AASHTO LRFD",
            "AASHTO Standard 2002",
            "CSA S6",
            "AS 5100.2:2017",
            "EN 1991-2:2003",
        ]
    );
    let serde_names: Vec<String> = declared
        .iter()
        .map(|code| serde_json::to_string(code).unwrap())
        .collect();
    assert_eq!(
        serde_names,
        [
            "\"jtg_d60\"",
            "\"jtj021\"",
            "\"aashto_lrfd\"",
            "\"aashto_standard\"",
            "\"csa_s6\"",
            "\"as5100\"",
            "\"en1991\"",
        ]
    );
}
