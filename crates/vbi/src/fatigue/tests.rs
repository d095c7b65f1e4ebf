//! The fatigue module against its references: ASTM E1049-85's worked example, closed forms of
//! constant-amplitude and block loading on EN 1993-1-9's and AASHTO's curves, the curves' own
//! printed constants, and a hand calculation of a composite girder's section.

use super::*;
use crate::model::station::Quantity;
use crate::units::{KSI, MPA};

/// ASTM E1049-85 (2017) §5.4.4, Fig. 6 and Table 4: the history −2, 1, −3, 5, −1, 3, −4, 4, −2
/// counts half cycles of ranges 3, 6 and 9, one and a half of range 4 and one of range 8.
#[test]
fn rainflow_equals_the_astm_e1049_worked_example() {
    let history = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0];
    let counts = count_by_range(&rainflow(&history));
    assert_eq!(
        counts,
        vec![(3.0, 0.5), (4.0, 1.5), (6.0, 0.5), (8.0, 1.0), (9.0, 0.5)]
    );
}

/// Samples between the reversals, repeated values and a flat start change no count: the rule
/// reads reversals only (ASTM E1049 §5.4.4.1).
#[test]
fn rainflow_reads_reversals_only() {
    let history = [
        0.0, 0.0, -2.0, -1.0, 1.0, 1.0, 0.0, -3.0, 5.0, 4.0, -1.0, 3.0, 3.0, -4.0, 0.0, 4.0, -2.0,
    ];
    let mut reference = vec![0.0, -2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0];
    assert_eq!(
        count_by_range(&rainflow(&history)),
        count_by_range(&rainflow(&reference))
    );
    reference.truncate(2);
    assert_eq!(
        rainflow(&reference),
        vec![Cycle {
            range: 2.0,
            mean: -1.0,
            count: 0.5
        }]
    );
    assert!(rainflow(&[1.0, 1.0, 1.0]).is_empty());
    assert!(rainflow(&[]).is_empty());
}

/// Counting a history in two parts with one counter carried across (a lifetime's events one after
/// another) gives the counts of the whole history: the residue of the first part closes with the
/// second.
#[test]
fn rainflow_carried_across_two_histories_equals_the_concatenated_history() {
    let first: Vec<f64> = (0..300)
        .map(|i| (0.37 * i as f64).sin() * (1.0 + 0.01 * i as f64))
        .collect();
    let second: Vec<f64> = (0..500)
        .map(|i| 2.0 * (0.21 * i as f64).cos() - 0.5)
        .collect();
    let whole: Vec<f64> = first.iter().chain(&second).copied().collect();
    let mut counter = RainflowCounter::new();
    let mut cycles = Vec::new();
    for &x in &first {
        counter.push(x, |c| cycles.push(c));
    }
    for &x in &second {
        counter.push(x, |c| cycles.push(c));
    }
    counter.finish(|c| cycles.push(c));
    assert_eq!(cycles, rainflow(&whole));
    // Every reversal but the first closes one range: the counts sum to (reversals − 1)/2.
    let total: f64 = cycles.iter().map(|c| c.count).sum();
    assert!(total > 25.0, "{total}");
}

/// EN 1993-1-9:2005 Figure 7.1 and 7.2 print the knee and the cut-off as Δσ_D = 0.737 Δσ_C,
/// Δσ_L = 0.549 Δσ_D and Δτ_L = 0.457 Δτ_C; the curve gives 2 × 10⁶ cycles at Δσ_C, 5 × 10⁶
/// at Δσ_D from both branches, 10⁸ at Δσ_L, and no damage below it.
#[test]
fn eurocode_curves_have_the_knee_and_cut_off_of_en_1993_1_9_figures_7_1_and_7_2() {
    let category = 71.0 * MPA;
    let curve = SnCurve::eurocode_direct(category);
    let relative = |a: f64, b: f64| ((a - b) / b).abs();
    assert!(relative(curve.cycles_to_failure(category), 2.0e6) < 1e-14);
    let knee = (0.4f64).cbrt() * category;
    assert_eq!((knee / category * 1000.0).round(), 737.0);
    assert!(relative(curve.cycles_to_failure(knee), 5.0e6) < 1e-12);
    assert!(relative(curve.cycles_to_failure(knee * (1.0 + 1e-12)), 5.0e6) < 1e-10);
    let cut_off = curve.cut_off();
    assert_eq!((cut_off / knee * 1000.0).round(), 549.0);
    assert!(relative(curve.cycles_to_failure(cut_off * (1.0 + 1e-12)), 1.0e8) < 1e-10);
    assert_eq!(curve.damage(cut_off * 0.999, 1.0e9), 0.0);
    let shear = SnCurve::Eurocode {
        category: 80.0 * MPA,
        stress: StressKind::Shear,
        partial_factor: 1.0,
    };
    assert_eq!((shear.cut_off() / (80.0 * MPA) * 1000.0).round(), 457.0);
    assert!(relative(shear.cycles_to_failure(80.0 * MPA), 2.0e6) < 1e-14);
    assert!(relative(shear.cycles_to_failure(40.0 * MPA), 2.0e6 * 32.0) < 1e-12);
    // γ_Ff γ_Mf = 1.35: Δσ_C/1.35 endures 2 × 10⁶ cycles, and the cut-off moves with it.
    let factored = SnCurve::Eurocode {
        category,
        stress: StressKind::Direct,
        partial_factor: 1.35,
    };
    assert!(relative(factored.cycles_to_failure(category / 1.35), 2.0e6) < 1e-14);
    assert!(relative(factored.cut_off(), cut_off / 1.35) < 1e-14);
}

/// AASHTO LRFD Table 6.6.1.2.5-1: category C has A = 44 × 10⁸ ksi³, so a 10 ksi range endures
/// 4.4 × 10⁶ cycles and 68.95 MPa (10 ksi) the same; no cut-off on the finite-life line.
#[test]
fn aashto_curve_is_the_finite_life_line_of_table_6_6_1_2_5_1() {
    let curve = SnCurve::Aashto {
        category: AashtoCategory::C,
    };
    let cycles = curve.cycles_to_failure(10.0 * KSI);
    assert!(((cycles - 4.4e6) / 4.4e6).abs() < 1e-12, "{cycles}");
    assert!(((KSI - 6.894_757e6) / KSI).abs() < 1e-7);
    let tiny = curve.cycles_to_failure(0.1 * KSI);
    assert!(((tiny - 4.4e12) / 4.4e12).abs() < 1e-12);
    for category in AashtoCategory::ALL {
        assert_eq!(AashtoCategory::of_name(category.name()), Some(category));
    }
}

/// Constant-amplitude loading: a history alternating between ±Δσ/2 over 2n reversals counts
/// n − ½ cycles of Δσ, and Miner's sum is (n − ½)/N_R with N_R from the curve's closed form on
/// each branch: 2 × 10⁶ (Δσ_C/Δσ)³, 5 × 10⁶ (Δσ_D/Δσ)⁵, and 0 below Δσ_L.
#[test]
fn constant_amplitude_damage_equals_the_closed_form_on_each_branch() {
    let category = 90.0 * MPA;
    let curve = SnCurve::eurocode_direct(category);
    let knee = (0.4f64).cbrt() * category;
    let n = 5000;
    for (range, expected_cycles_to_failure) in [
        (120.0 * MPA, 2.0e6 * (90.0f64 / 120.0).powi(3)),
        (60.0 * MPA, 5.0e6 * (knee / (60.0 * MPA)).powi(5)),
        (30.0 * MPA, f64::INFINITY),
    ] {
        let history: Vec<f64> = (0..2 * n)
            .map(|i| {
                if i % 2 == 0 {
                    0.5 * range
                } else {
                    -0.5 * range
                }
            })
            .collect();
        let mut sum = DamageSum::new(curve);
        rainflow(&history).into_iter().for_each(|c| sum.add(c));
        assert_eq!(sum.cycles, n as f64 - 0.5);
        let expected = (n as f64 - 0.5) / expected_cycles_to_failure;
        assert!(
            (sum.damage - expected).abs() <= 1e-12 * expected,
            "{} MPa: {} against {expected}",
            range / MPA,
            sum.damage
        );
        // The equivalent range at 2 × 10⁶ cycles does that damage in 2 × 10⁶ cycles on the m = 3
        // line: Δσ_C D^{1/3}.
        let equivalent = sum.equivalent_range_2e6();
        assert!((equivalent - category * expected.cbrt()).abs() <= 1e-9 * category);
    }
}

/// Block loading: n₁ cycles of ±3 units then n₂ of ±1 about zero (a unit of 20 MPa), from rest
/// to rest. ASTM's rule counts n₁ − ½ cycles of range 6, n₂ − ½ of range 2, and half cycles of
/// ranges 3 (the start), 4 (the change of block) and 1 (the end); Miner's sum is the closed form
/// Σ nᵢ/N_R(Δσᵢ) over those counts, on the AASHTO line (no cut-off: every range counts).
#[test]
fn block_loading_damage_equals_the_closed_form() {
    let (n1, n2) = (400usize, 3000usize);
    let unit = 20.0 * MPA;
    let mut history = vec![0.0];
    history.extend((0..n1).flat_map(|_| [3.0 * unit, -3.0 * unit]));
    history.extend((0..n2).flat_map(|_| [unit, -unit]));
    history.push(0.0);
    let counts = count_by_range(&rainflow(&history));
    let expected_counts = vec![
        (unit, 0.5),
        (2.0 * unit, n2 as f64 - 0.5),
        (3.0 * unit, 0.5),
        (4.0 * unit, 0.5),
        (6.0 * unit, n1 as f64 - 0.5),
    ];
    assert_eq!(counts, expected_counts);
    let curve = SnCurve::Aashto {
        category: AashtoCategory::D,
    };
    let a = 22.0e8 * KSI.powi(3);
    let closed_form: f64 = expected_counts
        .iter()
        .map(|(range, count)| count * range.powi(3) / a)
        .sum();
    let mut sum = DamageSum::new(curve);
    rainflow(&history).into_iter().for_each(|c| sum.add(c));
    assert!((sum.damage - closed_form).abs() <= 1e-12 * closed_form);
}

/// A dynamic history that is the static one scaled by 1.1 has the damage ratio 1.1³ on the m = 3
/// branch, so its fatigue DAF is 1.1; the cut-off-free DAF is 1.1 whatever the branch.
#[test]
fn fatigue_daf_of_a_scaled_history_is_the_scale() {
    let detail = FatigueDetail {
        name: "bottom flange".into(),
        station: "span1_mid_g1".into(),
        quantity: Quantity::BendingMoment,
        stress_per_effect: 10.0,
        stress_concentration: 1.0,
        fibre: "bottom flange".into(),
        curve: SnCurve::eurocode_direct(36.0 * MPA),
    };
    let static_moment: Vec<f64> = (0..201)
        .map(|i| 8.0e6 * (std::f64::consts::PI * i as f64 / 200.0).sin())
        .collect();
    let dynamic: Vec<f64> = static_moment.iter().map(|m| 1.1 * m).collect();
    let fatigue = DetailFatigue::of(&detail, &dynamic, &static_moment);
    let daf = fatigue.amplification.fatigue_daf.expect("static damage");
    assert!((daf - 1.1).abs() < 1e-12, "{daf}");
    let straight = fatigue.amplification.fatigue_daf_straight_line.unwrap();
    assert!((straight - 1.1).abs() < 1e-12);
    assert!((fatigue.dynamic.max_stress - 88.0 * MPA).abs() < 1e-6 * MPA);
    // Below the cut-off the static history does no damage: no damage ratio, but the
    // straight-line DAF stays.
    let small: Vec<f64> = static_moment.iter().map(|m| m / 10.0).collect();
    let small_dynamic: Vec<f64> = small.iter().map(|m| 1.1 * m).collect();
    let below = DetailFatigue::of(&detail, &small_dynamic, &small);
    assert_eq!(below.amplification.fatigue_daf, None);
    assert!((below.amplification.fatigue_daf_straight_line.unwrap() - 1.1).abs() < 1e-12);
}

/// A welded girder, bottom flange 400 × 30 mm, web 1200 × 12 mm, top flange 300 × 20 mm; by
/// hand (I = Σ b(t³ − b³)/3 about the bottom face, less A ȳ²): A = 0.0324 m², ȳ = 0.515185 m,
/// I = 0.00807329 m⁴. Composite with a 2.0 × 0.25 m slab on a 50 mm haunch at n = 6.5:
/// ȳ = 1.155359 m, I = 0.0273450 m⁴ (the same hand formula with the slab as 2.0/6.5 m of steel).
#[test]
fn girder_section_properties_equal_the_hand_calculation() {
    let steel = GirderSection {
        slab: None,
        ..composite_girder()
    };
    let close = |a: f64, b: f64| ((a - b) / b).abs() < 1e-12;
    assert!(close(steel.neutral_axis(), 0.515185185185186));
    assert!(close(steel.second_moment(), 0.00807328888888889));
    let bottom = steel.direct_stress_per_moment(Fibre::BottomFlange).unwrap();
    assert!(close(bottom, 0.515185185185186 / 0.00807328888888889));
    let top = steel.direct_stress_per_moment(Fibre::TopFlange).unwrap();
    assert!(close(top, (0.515185185185186 - 1.25) / 0.00807328888888889));
    let composite = GirderSection {
        slab: Some(ConcreteSlab {
            plate: Plate {
                width: 2.0,
                thickness: 0.25,
            },
            haunch: 0.05,
            modular_ratio: 6.5,
        }),
        ..steel
    };
    assert!(close(composite.neutral_axis(), 1.15535885167464));
    assert!(close(composite.second_moment(), 0.0273449692553061));
    let weld_toe = composite.direct_stress_per_moment(Fibre::WeldToe).unwrap();
    assert!(close(
        weld_toe,
        (1.15535885167464 - 0.03) / 0.0273449692553061
    ));
    assert!(matches!(
        composite.direct_stress_per_moment(Fibre::Height(1.4)),
        Err(SectionError::OutsideSteel { .. })
    ));
}

/// The web's shear stress Q/(I t_w) at the neutral axis and at the weld toe equals the first
/// moment integrated numerically over the section above the fibre (the midpoint rule within each
/// plate, exact for the linear integrand but for round-off).
#[test]
fn web_shear_stress_equals_the_integrated_first_moment() {
    let section = composite_girder();
    let width_at = |y: f64| {
        if y < 0.03 {
            0.4
        } else if y < 1.23 {
            0.012
        } else if y < 1.25 {
            0.3
        } else if (1.30..1.55).contains(&y) {
            2.0 / 6.5
        } else {
            0.0
        }
    };
    let (centre, inertia) = (section.neutral_axis(), section.second_moment());
    for fibre in [Fibre::NeutralAxis, Fibre::WeldToe, Fibre::Height(0.8)] {
        let from = section.height_of(fibre);
        // Strips within each plate, so that the midpoint rule integrates the linear integrand
        // of each to round-off.
        let breaks: Vec<f64> = [from, 1.23, 1.25, 1.30, 1.55]
            .into_iter()
            .filter(|&y| y >= from)
            .collect();
        let strips = 1000;
        let first_moment: f64 = breaks
            .windows(2)
            .map(|piece| {
                let h = (piece[1] - piece[0]) / strips as f64;
                (0..strips)
                    .map(|i| {
                        let y = piece[0] + (i as f64 + 0.5) * h;
                        width_at(y) * (y - centre) * h
                    })
                    .sum::<f64>()
            })
            .sum();
        let expected = first_moment / (inertia * 0.012);
        let computed = section.shear_stress_per_force(fibre).unwrap();
        assert!(
            ((computed - expected) / expected).abs() < 1e-10,
            "{fibre:?}: {computed} {expected}"
        );
    }
    assert!(section.shear_stress_per_force(Fibre::BottomFlange).is_err());
}

/// The girder of the hand calculations: bottom flange 400 × 30 mm, web 1200 × 12 mm, top flange
/// 300 × 20 mm, under a 2.0 × 0.25 m slab on a 50 mm haunch at n = 6.5.
fn composite_girder() -> GirderSection {
    GirderSection {
        bottom_flange: Plate {
            width: 0.4,
            thickness: 0.03,
        },
        web: Plate {
            width: 1.2,
            thickness: 0.012,
        },
        top_flange: Plate {
            width: 0.3,
            thickness: 0.02,
        },
        slab: Some(ConcreteSlab {
            plate: Plate {
                width: 2.0,
                thickness: 0.25,
            },
            haunch: 0.05,
            modular_ratio: 6.5,
        }),
    }
}
