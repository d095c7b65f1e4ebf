use super::*;
use crate::analysis::StationScope;
use crate::modal::Quantity;
use crate::model::{BeamSection, BridgeModel, ContinuousBeam};
use crate::vehicle::preset;

/// A pinned continuous beam of `spans` [m] (EI = 1e10 N·m², m̄ = 1e4 kg/m, ζ = 0.02), 6 modes.
fn beam_bridge(spans: Vec<f64>) -> BridgeSpec {
    let mut beam = ContinuousBeam::pinned(
        spans,
        BeamSection {
            flexural_rigidity: 1e10,
            mass_per_length: 1e4,
        },
    );
    beam.damping_ratio = 0.02;
    BridgeSpec::new(BridgeModel::ContinuousBeam(beam), 6)
}

/// A 25 m simply supported beam ([`beam_bridge`]) crossed by the quarter car at 20 m/s on the
/// default 'medium' road: small enough for a unit test.
fn small_scenario() -> Scenario {
    Scenario {
        name: "small".into(),
        bridge_label: "25 m beam".into(),
        bridge: beam_bridge(vec![25.0]),
        vehicle: preset("quarter-car").expect("a preset"),
        motion: Motion::constant(20.0, 0.0),
        rerun_mode_counts: vec![2],
        fatigue_details: Vec::new(),
        ..Scenario::default()
    }
}

#[test]
fn a_scenario_survives_a_json_round_trip_unchanged() {
    for scenario in [Scenario::default(), small_scenario()] {
        let text = serde_json::to_string(&scenario).expect("serialisable");
        let back: Scenario = serde_json::from_str(&text).expect("readable");
        assert_eq!(back, scenario);
    }
}

#[test]
fn run_crossing_equals_the_stages_called_one_by_one_bit_for_bit() {
    let mut scenario = small_scenario();
    // The check of the step is a stage of its own (crossing::time_step_check, tested there).
    scenario.solver.time_step_check = false;
    let bridge = prepare_bridge(&scenario.bridge).expect("prepared");
    let result = run_crossing(&bridge, &scenario).expect("run");

    // The same stages by hand.
    let fe = discretise(&scenario.bridge.model, &scenario.bridge.mesh).expect("meshed");
    let basis = solve_modes(&fe, &scenario.bridge.modal).expect("modes");
    let influence = influence_lines(&fe).expect("influence lines");
    let crossing = crossing_of(&scenario).expect("crossing");
    let history = simulate(&basis, &crossing, &scenario.solver).expect("simulated");
    let report = analyse(&basis, &influence, &history, &scenario.analysis).expect("analysed");

    assert_eq!(result.history, history);
    assert_eq!(result.report.stations, report.stations);
    assert_eq!(result.report.rdm, report.rdm);
    assert_eq!(result.report.truncated_runs.len(), 1);
    assert_eq!(result.report.truncated_runs[0].mode_count, 2);
}

#[test]
fn a_history_whose_tables_disagree_with_its_sizes_is_refused_by_the_analysis() {
    let scenario = small_scenario();
    let bridge = prepare_bridge(&scenario.bridge).expect("prepared");
    let good = run_crossing(&bridge, &scenario).expect("run").history;
    let mut history = good.clone();
    history.modal_displacement.pop();
    let (basis, influence) = (&bridge.basis, &bridge.influence);
    let analysed = analyse(basis, influence, &history, &scenario.analysis);
    assert!(
        matches!(analysed, Err(AnalysisError::Mismatch { .. })),
        "a short table is an error, not a panic: {analysed:?}"
    );
    // Beside a good run, the good one keeps its report.
    let runs = [(&history, &scenario.analysis), (&good, &scenario.analysis)];
    let cache = StaticReferenceCache::default();
    let reports = analyse_runs(basis, influence, &runs, &cache);
    assert!(matches!(reports[0], Err(AnalysisError::Mismatch { .. })));
    let alone = analyse(basis, influence, &good, &scenario.analysis);
    assert_eq!(reports[1].as_ref().ok(), alone.as_ref().ok());
    let responses =
        crate::analysis::corrected_station_responses(&bridge.basis, &bridge.influence, &history);
    assert!(matches!(responses, Err(AnalysisError::Mismatch { .. })));
    // A (deserialised) history that claims more instants than instants × modes can count is
    // refused too, not an overflow.
    let mut huge = good.clone();
    huge.step_count = usize::MAX / 2 + 1;
    let analysed = analyse(basis, influence, &huge, &scenario.analysis);
    assert!(
        matches!(analysed, Err(AnalysisError::Mismatch { .. })),
        "{analysed:?}"
    );
    let responses =
        crate::analysis::corrected_station_responses(&bridge.basis, &bridge.influence, &huge);
    assert!(matches!(responses, Err(AnalysisError::Mismatch { .. })));
}

#[test]
fn a_scenario_on_another_bridge_is_refused() {
    let scenario = small_scenario();
    let bridge = prepare_bridge(&scenario.bridge).expect("prepared");
    let mut other = scenario.clone();
    other.bridge.mesh.element_length = 0.5;
    assert_eq!(
        run_crossing(&bridge, &other).unwrap_err(),
        PipelineError::BridgeMismatch
    );
}

#[test]
fn rerun_mode_counts_beyond_the_kept_modes_are_refused_before_the_crossing() {
    let mut scenario = small_scenario();
    let bridge = prepare_bridge(&scenario.bridge).expect("prepared");
    let kept = bridge.basis.mode_count();
    scenario.rerun_mode_counts = vec![kept + 1];
    assert_eq!(
        run_crossing(&bridge, &scenario).unwrap_err(),
        PipelineError::RerunModeCount {
            mode_count: kept + 1,
            available: kept,
            solved: 6,
        }
    );
}

#[test]
fn the_rdm_station_scope_agrees_with_the_full_analysis_at_the_rdm_station() {
    let mut scenario = small_scenario();
    scenario.rerun_mode_counts.clear();
    let bridge = prepare_bridge(&scenario.bridge).expect("prepared");
    let full = run_crossing(&bridge, &scenario).expect("run");
    scenario.analysis.stations = StationScope::RdmStation;
    let one = run_crossing(&bridge, &scenario).expect("run");
    assert_eq!(full.report.rdm, one.report.rdm);
    assert_eq!(full.report.rdm_station, one.report.rdm_station);
}

/// Every f64 of a scenario reads back from its JSON bit for bit: serde_json's default float
/// parser is approximate (about one value in nine came back one ulp off here), so the workspace
/// enables its `float_roundtrip` feature. 2000 speeds spread over [0, 3) m/s and beyond.
#[test]
fn every_number_of_a_scenario_reads_back_from_json_bit_for_bit() {
    let mut scenario = Scenario::default();
    let mut x = 0.123_456_789_f64;
    for i in 0..2000 {
        x = (x * 3.987_654_321 + 0.314_159).fract();
        scenario.motion.speed = 3.0 * x + i as f64 * 1e-3;
        scenario.motion.lateral_position = -x * 1e-7;
        let text = serde_json::to_string(&scenario).expect("serialisable");
        let back: Scenario = serde_json::from_str(&text).expect("readable");
        assert_eq!(back.motion.speed.to_bits(), scenario.motion.speed.to_bits());
        assert_eq!(
            back.motion.lateral_position.to_bits(),
            scenario.motion.lateral_position.to_bits()
        );
    }
}

#[test]
fn corrected_histories_peak_at_the_reported_corrected_maxima_and_tend_to_the_static_at_a_crawl() {
    // Consistency with the DAF report (its corrected dynamic maximum is the extreme of the same
    // series, summed in another order) and the static limit of the mode-acceleration method (docs/theory.md): at
    // 0.5 m/s the corrected deflection and moment equal the exact static ones within 0.5 % of
    // their peaks, where six plain modes miss the moment by more.
    let mut scenario = small_scenario();
    let bridge = prepare_bridge(&scenario.bridge).expect("prepared");
    let result = run_crossing(&bridge, &scenario).expect("run");
    let corrected = crate::analysis::corrected_station_responses(
        &bridge.basis,
        &bridge.influence,
        &result.history,
    )
    .expect("analysed")
    .expect("a correction exists");
    for entry in &result.report.stations {
        let s = bridge
            .basis
            .stations
            .iter()
            .position(|t| t.name == entry.name)
            .unwrap();
        let series = corrected[s]
            .iter()
            .find(|(q, _)| *q == entry.quantity)
            .map(|(_, values)| values)
            .expect("a corrected series of every reported quantity");
        assert!(
            entry.static_corrected,
            "the headline is the corrected series"
        );
        let reported = entry.converged.dynamic_max;
        let extreme = series
            .iter()
            .cloned()
            .max_by(|a, b| (a * reported.signum()).total_cmp(&(b * reported.signum())))
            .unwrap();
        // The report takes the extreme between the instants (analysis::continuous_extreme):
        // at least the sampled one (to round-off: 1e-12 relative, the sums in another order),
        // and within the series' change over one step of it.
        let sign = reported.signum();
        let step_change = series
            .windows(2)
            .map(|w| (w[1] - w[0]).abs())
            .fold(0.0f64, f64::max);
        assert!(
            sign * (reported - extreme) >= -1e-12 * reported.abs()
                && (reported - extreme).abs() <= step_change,
            "{} {:?}: {extreme} vs {reported}",
            entry.name,
            entry.quantity
        );
    }

    scenario.motion.speed = 0.5;
    scenario.road = crate::road::RoadSpec::of_class(crate::road::RoughnessClass::Smooth);
    let result = run_crossing(&bridge, &scenario).expect("crawl");
    let corrected = crate::analysis::corrected_station_responses(
        &bridge.basis,
        &bridge.influence,
        &result.history,
    )
    .unwrap()
    .unwrap();
    let reference = crate::analysis::static_reference(&bridge.influence, &result.history).unwrap();
    let stations = bridge.basis.stations.len();
    let all: Vec<usize> = (0..stations).collect();
    let forces =
        crate::analysis::static_force_reference(&bridge.influence, &result.history, &all).unwrap();
    for s in 0..stations {
        for (q, (quantity, series)) in corrected[s].iter().enumerate() {
            let exact: Vec<f64> = match quantity {
                Quantity::Deflection | Quantity::BendingMoment => reference.history(s, *quantity),
                Quantity::ShearForce | Quantity::SupportReaction => forces[s].clone(),
            };
            let peak = exact.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if peak == 0.0 {
                continue;
            }
            let worst = series
                .iter()
                .zip(&exact)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(
                worst < 0.005 * peak,
                "station {s} quantity {q}: {worst} vs peak {peak}"
            );
        }
    }
}

/// The rear axles started off the road profile, where the road reads 0, and stepped onto it by
/// 1–3 cm at the start of the approach (issue 14). Invariant: every tyre's position at t = 0
/// lies inside the profile, the road input of the last tyre is continuous from t = 0 (no jump
/// larger than the profile's own change over one sample, bounded by the largest sample
/// difference), and the samples that the shorter extent held keep their values (to 1e-12 m:
/// the same harmonics evaluated at the same absolute positions), so the extension changes
/// nothing the front axle reads.
#[test]
fn every_tyre_starts_on_the_road_profile_and_the_front_axles_road_is_unchanged() {
    let mut scenario = small_scenario();
    scenario.vehicle = preset("tractor-semitrailer-5axle").expect("a preset");
    let crossing = crossing_of(&scenario).expect("a crossing");
    let road = &crossing.road;
    let first = crossing.first_vehicle();
    let rear = first
        .vehicle
        .contacts
        .iter()
        .map(|c| c.longitudinal_offset)
        .fold(0.0, f64::min);
    assert!(rear < -10.0, "a long vehicle: last tyre {rear} m behind");
    assert!(road.start <= first.start_position + rear);
    assert_eq!(first.start_position, -scenario.road.approach_length);
    let x_rear = first.start_position + rear;
    let largest_step = road
        .left
        .windows(2)
        .map(|w| (w[1] - w[0]).abs())
        .fold(0.0, f64::max);
    let track = crate::road::Track::Left;
    let (at_start, _) = road.elevation_and_slope(track, x_rear);
    let (just_after, _) = road.elevation_and_slope(track, x_rear + 0.01);
    assert!(
        (at_start - just_after).abs() <= largest_step,
        "{at_start} → {just_after}"
    );
    let (start, end) = scenario
        .road
        .extent_for_bridge(scenario.bridge.model.length());
    let shorter = generate(&scenario.road, start, end, scenario.road.seed).expect("a road");
    let offset = ((start - road.start) / road.spacing).round() as usize;
    // The spacings agree to round-off of length / intervals (1e-15 relative).
    assert!((shorter.spacing - road.spacing).abs() < 1e-12 * road.spacing);
    for (j, h) in shorter.left.iter().enumerate() {
        assert!((road.left[offset + j] - h).abs() < 1e-12, "sample {j}");
    }
}

/// A 35 m simply supported beam (m̄ = 18358 kg/m) with EI = 4.865e10 N·m², or that number typed
/// as if in kN·m² (1000 × too soft), crossed by the quarter car.
fn thirty_five_metre_beam_scenario(flexural_rigidity: f64) -> Scenario {
    let beam = ContinuousBeam::pinned(
        vec![35.0],
        BeamSection {
            flexural_rigidity,
            mass_per_length: 18358.0,
        },
    );
    Scenario {
        bridge: BridgeSpec::new(BridgeModel::ContinuousBeam(beam), 4),
        free_vibration_duration: Some(0.2),
        rerun_mode_counts: Vec::new(),
        fatigue_details: Vec::new(),
        ..small_scenario()
    }
}

/// EI typed in kN·m² ran without a word (issue 14: 1.86 m static deflection on a 35 m span).
/// References: the closed form PL³/(48EI) of the quarter car's weight at mid-span (0.604 m here,
/// above span/100 = 0.35 m), and EN 1991-2 Figure 6.10's band of first frequencies (0.96–19.9 Hz for
/// 35 m once widened by 3; the soft beam's f₁ = (π/L)²√(EI/m̄)/2π = 0.066 Hz). The same beam
/// with EI in N·m² (f₁ = 2.09 Hz, 0.6 mm) gets neither warning.
#[test]
fn a_bridge_a_thousand_times_too_soft_is_warned_about_its_deflection_and_frequency() {
    use crate::solver::SolverWarning;
    let ei = 4.865e10;
    let soft = thirty_five_metre_beam_scenario(ei / 1000.0);
    let bridge = prepare_bridge(&soft.bridge).expect("prepared");
    let result = run_crossing(&bridge, &soft).expect("run");
    let weight = preset("quarter-car")
        .map(|_| (3000.0 + 350.0) * 9.81)
        .unwrap();
    let closed_form = weight * 35f64.powi(3) / (48.0 * ei / 1000.0);
    let deflection = result.report.warnings.iter().find_map(|w| match w {
        SolverWarning::StaticDeflectionImplausible {
            deflection, limit, ..
        } => Some((*deflection, *limit)),
        _ => None,
    });
    let (deflection, limit) = deflection.expect("a deflection warning");
    assert!((limit - 0.35).abs() < 1e-12);
    // Tolerance 1e-3: the exact static influence line sampled every v·Δt ≤ 2 cm near its flat
    // maximum; the gravity constant of the vehicle (9.81 or 9.80665) differs by 3.4e-4.
    assert!(
        (deflection - closed_form).abs() < 1e-3 * closed_form,
        "{deflection} vs {closed_form}"
    );
    let (low, high) = plausibility::eurocode_frequency_band(35.0).unwrap();
    assert!(
        (low - 23.58 * 35f64.powf(-0.592)).abs() < 1e-12
            && (high - 94.76 * 35f64.powf(-0.748)).abs() < 1e-12
    );
    assert!(result
        .report
        .warnings
        .iter()
        .any(|w| matches!(w, SolverWarning::FrequencyImplausible { frequency_hz, .. } if *frequency_hz < 0.1)));
    // `vbi check` sees the soft beam before any solve: its closed-form bracket of f₁
    // (0.066–0.150 Hz) lies below the band.
    assert!(plausibility::model_warning(&soft.bridge.model).is_some());
    let sound = thirty_five_metre_beam_scenario(ei);
    assert!(plausibility::model_warning(&sound.bridge.model).is_none());
    let bridge = prepare_bridge(&sound.bridge).expect("prepared");
    let result = run_crossing(&bridge, &sound).expect("run");
    assert!(!result.report.warnings.iter().any(|w| matches!(
        w,
        SolverWarning::StaticDeflectionImplausible { .. }
            | SolverWarning::FrequencyImplausible { .. }
    )));
}

/// The 25 m beam of examples/bridges/ss-beam-25m.toml with 50 vertical bending modes on the
/// default 1 m mesh (up to 13.8 kHz).
fn fifty_mode_beam_of_25_m() -> BridgeSpec {
    let beam = ContinuousBeam::pinned(
        vec![25.0],
        BeamSection {
            flexural_rigidity: 3.5e10 * 1.3901,
            mass_per_length: 18358.0,
        },
    );
    let mut bridge = BridgeSpec::new(BridgeModel::ContinuousBeam(beam), 50);
    bridge.modal.keep_kinds = vec![crate::modal::ModeKind::VerticalBending];
    bridge
}

/// 50 modes of the 25 m beam of examples/bridges/ss-beam-25m.toml on the default 1 m mesh reach
/// the rotation-dominated top of the FE spectrum (13.8 kHz), which set Δt = 3.6 µs (issue 14).
/// With the sprung mass on a smooth road the default step now resolves the modes up to
/// 5 × f₁ (f₁ = 4.09 Hz, docs/verification.md §9) and is capped at 1 ms, ≥ 275 × the former.
#[test]
fn fifty_fe_modes_of_a_beam_do_not_set_a_microsecond_time_step() {
    let bridge = fifty_mode_beam_of_25_m();
    let scenario = Scenario {
        bridge,
        vehicle: preset("sprung-mass").expect("a preset"),
        road: crate::road::RoadSpec::of_class(crate::road::RoughnessClass::Smooth),
        rerun_mode_counts: Vec::new(),
        fatigue_details: Vec::new(),
        ..small_scenario()
    };
    let prepared = prepare_bridge(&scenario.bridge).expect("prepared");
    let modes = &prepared.basis.modes;
    assert_eq!(modes.len(), 50);
    let former = 1.0 / (20.0 * modes.iter().map(|m| m.frequency_hz()).fold(0.0, f64::max));
    assert!(former < 4e-6, "the former step {former} s");
    let crossing = crossing_of(&scenario).expect("a crossing");
    let dt = default_time_step(&prepared.basis, &crossing, &scenario.solver);
    assert_eq!(dt, scenario.solver.max_time_step);
    for mode in modes
        .iter()
        .filter(|m| m.frequency_hz() <= 5.0 * modes[0].frequency_hz())
    {
        assert!(dt <= 1.0 / (20.0 * mode.frequency_hz()));
    }
}

/// A generated road carries no roughness above its band's n₂ (3 cycles/m by default): the
/// crossing excites the bridge through it up to v·n₂, not up to the samples' Nyquist rate
/// v/(2Δx) (0.05 m samples: 10 cycles/m), and the default step resolves the modes up to 5 × that
/// ([`crate::solver::road_frequency`]). The reference is the step the Nyquist rate set before
/// (issue 48: 3.6 times the steps on a lifetime event of two trucks, whose DAFs moved by
/// 3 × 10⁻⁷). On a 'poor' road at 30 m/s, the five-axle truck on the 50-mode 25 m beam: every
/// deflection and moment DAF at the default step equals the reference's within 10⁻⁴, a tenth
/// of the check's own tolerance ([`crate::analysis::TIME_STEP_TOLERANCE`], 10⁻³; the step's
/// error falls as Δt², so a tenth of it means a step resolving 3× more than needed).
#[test]
fn the_default_step_on_a_generated_road_resolves_its_band_and_gives_the_dafs_of_the_nyquist_step() {
    let bridge = fifty_mode_beam_of_25_m();
    let mut scenario = Scenario {
        bridge,
        vehicle: preset("tractor-semitrailer-5axle").expect("a preset"),
        road: crate::road::RoadSpec::of_class(crate::road::RoughnessClass::Poor),
        motion: Motion::constant(30.0, 0.0),
        rerun_mode_counts: Vec::new(),
        fatigue_details: Vec::new(),
        ..small_scenario()
    };
    scenario.solver.time_step_check = false;
    let prepared = prepare_bridge(&scenario.bridge).expect("prepared");
    let crossing = crossing_of(&scenario).expect("a crossing");
    assert_eq!(crossing.road.highest_spatial_frequency, Some(3.0));
    let road = crate::solver::road_frequency(&crossing.road, 30.0);
    assert!((road - 90.0).abs() < 1e-9, "{road} Hz");
    let nyquist = 30.0 / (2.0 * crossing.road.spacing);
    let default = run_crossing(&prepared, &scenario).expect("a run");
    // The former step: the modes up to 5 × the Nyquist rate resolved at 20 steps a period.
    let highest = (prepared.basis.modes.iter())
        .map(|m| m.frequency_hz())
        .filter(|&f| f <= 5.0 * nyquist)
        .fold(0.0, f64::max);
    let former = 1.0 / (20.0 * highest);
    assert!(
        default.report.time_step > 2.5 * former,
        "{} s against {former} s",
        default.report.time_step
    );
    scenario.solver.time_step = Some(former);
    let reference = run_crossing(&prepared, &scenario).expect("a run");
    for (at_default, at_former) in default
        .report
        .stations
        .iter()
        .zip(&reference.report.stations)
    {
        if !matches!(
            at_default.quantity,
            Quantity::Deflection | Quantity::BendingMoment
        ) {
            continue;
        }
        let (a, b) = (
            at_default.converged.daf.unwrap(),
            at_former.converged.daf.unwrap(),
        );
        assert!(
            (a - b).abs() < 1e-4,
            "{} {:?}: {a} against {b}",
            at_default.name,
            at_default.quantity
        );
    }
}

/// The station acceleration column (a modal sum Σ cₖ q̈ₖ) is the second derivative of the
/// paper's modal-sum deflection column in the sense of the average-acceleration Newmark scheme (β = ¼, γ = ½), whose recurrence gives
/// exactly (u_{i+1} − 2u_i + u_{i−1})/Δt² = (a_{i+1} + 2a_i + a_{i−1})/4 for any linear
/// combination of the modal coordinates: a round-off identity (tolerance 1e-7 of the peak
/// acceleration, the second difference losing about 8 digits of the deflection).
#[test]
fn station_accelerations_are_the_newmark_second_difference_of_the_deflections() {
    let mut scenario = small_scenario();
    scenario.rerun_mode_counts.clear();
    // One β for every mode, so that the recurrence holds for their sum (period-matched modes
    // each keep it with their own β: a_period_matched_mode_keeps_its_phase_…).
    scenario.solver.period_matched_modes = false;
    let bridge = prepare_bridge(&scenario.bridge).expect("prepared");
    let result = run_crossing(&bridge, &scenario).expect("a run");
    let columns = station_history_columns(&bridge, &result.history).expect("columns");
    let find = |name: &str| &columns.iter().find(|c| c.name == name).unwrap().values;
    let station = &bridge.basis.stations[0].name;
    let (u, a) = (
        find(&format!("{station}_paper_deflection_m")),
        find(&format!("{station}_acceleration_m_s2")),
    );
    let dt = result.history.time_step;
    let peak = a.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    assert!(peak > 0.0);
    for i in 1..u.len() - 1 {
        let difference = (u[i + 1] - 2.0 * u[i] + u[i - 1]) / (dt * dt);
        let average = (a[i + 1] + 2.0 * a[i] + a[i - 1]) / 4.0;
        assert!(
            (difference - average).abs() <= 1e-7 * peak,
            "instant {i}: {difference} vs {average}"
        );
    }
}

/// vehicles.csv: one displacement and one acceleration column per vehicle DOF, a position and a
/// force column per contact, and the positions are those the solver used.
#[test]
fn vehicle_columns_hold_every_dof_and_contact_of_every_vehicle() {
    let mut scenario = small_scenario();
    scenario.rerun_mode_counts.clear();
    scenario.platoon_size = 2;
    let bridge = prepare_bridge(&scenario.bridge).expect("prepared");
    let result = run_crossing(&bridge, &scenario).expect("a run");
    let history = &result.history;
    let columns = vehicle_history_columns(history);
    let dofs = history.vehicle_dof_count();
    assert_eq!(dofs, 4, "two quarter cars");
    assert_eq!(columns.len(), 1 + 2 * dofs + 2 * history.contacts.len());
    assert_eq!(columns[1].name, "v1_body_bounce_displacement_m");
    let last = columns.last().unwrap();
    assert_eq!(last.name, "v2_contact1_force_n");
    let x = &columns[columns.len() - 2].values;
    assert_eq!(x[10], history.contact_position[10 * 2 + 1]);
}

/// `lane_pattern` places the scenario's vehicle in lane 1 (its `lateral_position_m`) and a copy
/// in the mirrored lane 2: abreast, same direction (`side_by_side`), or the other way
/// (`meeting`), both from the start of their approach, so both reach their deck entries
/// together; a platoon, further traffic and overlapping lanes are refused.
#[test]
fn lane_patterns_place_a_mirrored_copy_as_documented_and_refuse_what_makes_no_sense() {
    use crate::crossing::vehicle_runs;
    use crate::crossing::{Entry, LanePattern, TrafficVehicle};
    use crate::solver::TravelDirection::{Backward, Forward};
    let mut scenario = Scenario::default();
    scenario.motion.lateral_position = -1.875;
    assert_eq!(vehicle_runs(&scenario).unwrap().len(), 1);
    for (pattern, direction) in [
        (LanePattern::SideBySide, Forward),
        (LanePattern::Meeting, Backward),
    ] {
        scenario.lane_pattern = pattern;
        let runs = vehicle_runs(&scenario).unwrap();
        assert_eq!(runs.len(), 2);
        assert_eq!(
            (runs[0].direction, runs[0].lateral_position),
            (Forward, -1.875)
        );
        assert_eq!(
            (runs[1].direction, runs[1].lateral_position),
            (direction, 1.875)
        );
        assert_eq!(runs[1].start_position, runs[0].start_position);
    }
    let refusal = |scenario: &Scenario| vehicle_runs(scenario).unwrap_err().to_string();
    let mut platoon = scenario.clone();
    platoon.platoon_size = 2;
    assert!(refusal(&platoon).contains("platoon_size = 2"));
    let mut traffic = scenario.clone();
    traffic.traffic.push(TrafficVehicle {
        label: "car".into(),
        vehicle: scenario.vehicle.clone(),
        motion: scenario.motion.clone(),
        entry: Entry::Time(20.0),
    });
    assert!(refusal(&traffic).contains("[[traffic]]"));
    let mut narrow = scenario.clone();
    narrow.motion.lateral_position = 0.5;
    assert!(refusal(&narrow).contains("the two lanes overlap"));
    // The default pattern is not serialised: a scenario without one serialises as before.
    let text = serde_json::to_string(&Scenario::default()).unwrap();
    assert!(!text.contains("lane_pattern"));
}

/// Every entry of the report gets the codes' factors, in its order; on a simple span the JTG
/// D60 value from the code's formula π/(2l²)√(EI/m) and from vbi's computed first frequency
/// agree to the FE model's frequency error (the formula is the exact Euler–Bernoulli frequency;
/// 1e-4 in μ is 0.06 % in f at 3.2 Hz, above the 0.01 % of the default mesh), and CSA S6 reads
/// the CL-W truck's axles within the span, not the quarter car's one axle.
#[test]
fn design_codes_follow_every_entry_and_the_jtg_formula_meets_the_computed_frequency() {
    let mut scenario = small_scenario();
    scenario.rerun_mode_counts.clear();
    let bridge = prepare_bridge(&scenario.bridge).expect("prepared");
    let result = run_crossing(&bridge, &scenario).expect("run");
    let report = &result.report;
    assert_eq!(report.design_codes.len(), report.stations.len());
    for (codes, entry) in report.design_codes.iter().zip(&report.stations) {
        assert_eq!(
            (codes.station_index, codes.quantity),
            (entry.station, entry.quantity)
        );
        let jtg = |provision: &str| {
            codes
                .factors
                .iter()
                .find(|f| f.code == crate::codes::DesignCode::JtgD60 && f.provision == provision)
                .map(|f| f.impact_factor)
                .expect("a JTG D60 value")
        };
        assert!((jtg("code_frequency") - jtg("computed_frequency")).abs() < 1e-4);
        let csa = codes
            .factors
            .iter()
            .find(|f| f.code == crate::codes::DesignCode::CsaS6)
            .expect("a CSA S6 value");
        // The CL-W truck's axles within the 25 m span: all five (the quarter car's one axle
        // does not count: issue 46).
        assert_eq!(csa.impact_factor, 0.25);
    }
}

/// The default road of a 3D vehicle has coherent tracks at the vehicle's own track spacing
/// (the road equals one generated with `Coherent { b, ρ = 1 }` bit for bit, and its right track
/// differs from its left); an explicit `Identical` is honoured; a 2D vehicle rides one track.
#[test]
fn the_default_tracks_are_coherent_at_the_vehicles_track_spacing() {
    use crate::road::TrackCorrelation;
    let scenario = Scenario::default();
    let crossing = crossing_of(&scenario).expect("crossing");
    let vehicle = &crossing.vehicles[0].vehicle;
    let spacing = vehicle.track_spacing();
    assert!(
        spacing > 1.0 && spacing < 3.0,
        "a truck's track: {spacing} m"
    );
    let mut explicit = scenario.road.clone();
    explicit.track_correlation = TrackCorrelation::Coherent {
        track_spacing: spacing,
        coherence_decay: 1.0,
    };
    let (start, end) = (crossing.road.start, crossing.road.end());
    let expected = generate(&explicit, start, end, explicit.seed).expect("a road");
    assert_eq!(crossing.road, expected);
    assert_ne!(crossing.road.left, crossing.road.right);

    let mut identical = scenario.clone();
    identical.road.track_correlation = TrackCorrelation::Identical;
    let road = crossing_of(&identical).expect("crossing").road;
    assert_eq!(road.left, road.right);

    let small = small_scenario();
    assert_eq!(
        crossing_of(&small).expect("crossing").vehicles[0]
            .vehicle
            .track_spacing(),
        0.0
    );
}

/// Imported matrices in other units than declared: vbi's own paper grillage exported, then its
/// K read as kN/m instead of N/m (× 1000) or its M as tonnes (× 1000). The check against the deck
/// lines' EI and mass sees each (a factor of 1000 against a band of 3), and the true export
/// passes.
#[test]
fn imported_matrices_in_the_wrong_units_are_warned_of_before_and_after_the_solve() {
    use crate::model::ImportedMatrices;
    use std::sync::Arc;
    let exported = crate::fe::export_matrices(
        &crate::model::paper_bridge(2, 20.0),
        &crate::fe::MeshOptions::default(),
    )
    .expect("exported")
    .model;
    let scaled = |model: &ImportedMatrices, stiffness: f64, mass: f64| -> BridgeModel {
        let mut m = model.clone();
        let mut k = (*m.stiffness).clone();
        k.values.iter_mut().for_each(|v| *v *= stiffness);
        let mut mm = (*m.mass).clone();
        mm.values.iter_mut().for_each(|v| *v *= mass);
        (m.stiffness, m.mass) = (Arc::new(k), Arc::new(mm));
        BridgeModel::ImportedMatrices(m)
    };
    let implausible = |model: &BridgeModel| -> Vec<String> {
        let BridgeModel::ImportedMatrices(imported) = model else {
            unreachable!()
        };
        let fe = crate::fe::discretise(model, &crate::fe::MeshOptions::default()).unwrap();
        let influence = crate::fe::statics::influence_lines(&fe).unwrap();
        plausibility::imported_warnings(imported, &influence.stations, |s| {
            let x = influence.stations[s].position;
            influence.unit_load_response(s, Quantity::Deflection, x, 0.0)
        })
        .iter()
        .map(|w| w.to_string())
        .collect()
    };
    let sound = scaled(&exported, 1.0, 1.0);
    assert!(implausible(&sound).is_empty(), "{:?}", implausible(&sound));
    assert!(plausibility::model_warning(&sound).is_none());
    let stiff = scaled(&exported, 1000.0, 1.0);
    let warnings = implausible(&stiff);
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].contains("static deflection"), "{warnings:?}");
    assert!(plausibility::model_warning(&stiff).is_some());
    let heavy = scaled(&exported, 1.0, 1000.0);
    let warnings = implausible(&heavy);
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].contains("mass moving"), "{warnings:?}");
}

/// The static extremes that the analysis takes instant by instant (and that the bridge's cache
/// keeps in place of the whole reference) are those of the whole static reference S(t), read
/// station by station from `static_reference`'s tables: the extreme of largest magnitude, its
/// sign and its instant. Two spans and the three-axle truck, so that stations see the wheels
/// on both sides and the moment over the pier is negative; a second run reuses the cached
/// extremes and gives the same report bit for bit.
#[test]
fn the_static_extremes_are_those_of_the_whole_static_reference_at_every_station() {
    let mut scenario = small_scenario();
    scenario.rerun_mode_counts.clear();
    scenario.bridge = beam_bridge(vec![25.0, 25.0]);
    scenario.vehicle = preset("three-axle-truck-36t").expect("a preset");
    let bridge = prepare_bridge(&scenario.bridge).expect("prepared");
    let first = run_crossing(&bridge, &scenario).expect("run");
    let reference = crate::analysis::static_reference(&bridge.influence, &first.history).unwrap();
    let mut checked = 0;
    for entry in &first.report.stations {
        if !matches!(
            entry.quantity,
            Quantity::Deflection | Quantity::BendingMoment
        ) {
            continue;
        }
        let history = reference.history(entry.station, entry.quantity);
        let (step, value) = history
            .iter()
            .enumerate()
            .fold((0, 0.0f64), |best, (i, &v)| {
                if v.abs() > best.1.abs() {
                    (i, v)
                } else {
                    best
                }
            });
        // The extreme is taken between the instants around the sampled one
        // (analysis::continuous_extreme): as large as the sampled one, in its direction, and at
        // most the sampled change over one step of the reference away from it.
        let dt = first.history.time_step;
        let step_change = [step.saturating_sub(1), (step + 1).min(history.len() - 1)]
            .map(|i| (history[i] - value).abs())
            .into_iter()
            .fold(0.0f64, f64::max);
        assert!(
            value.signum() * (entry.static_max - value) >= 0.0
                && (entry.static_max - value).abs() <= step_change,
            "{} {:?}: {} vs sampled {value}",
            entry.name,
            entry.quantity,
            entry.static_max
        );
        assert!(
            (entry.static_max_time - step as f64 * dt).abs() <= dt * (1.0 + 1e-12),
            "{} {:?}",
            entry.name,
            entry.quantity
        );
        checked += 1;
    }
    assert!(
        checked >= 6,
        "deflection and moment of three stations at least: {checked}"
    );
    let negative = first.report.stations.iter().any(|e| e.static_max < 0.0);
    assert!(
        negative,
        "a hogging moment over the pier or an upward deflection"
    );
    let again = run_crossing(&bridge, &scenario).expect("run");
    assert_eq!(again.report, first.report);
}

/// A run that gives no more instants part-way (its integration failed) leaves the other runs
/// of its group (road samples: the same wheel paths) to be analysed as they would be without
/// it: their reports are those of the recorded path, bit for bit (compared through their
/// `Debug` text), for a run abandoned before its first instant, inside a panel of instants
/// (37) and at a panel's start (40).
#[test]
fn an_abandoned_run_leaves_the_other_runs_of_its_group_their_own_reports() {
    use crate::analysis::{RunAnalyses, RunToAnalyse};
    let bridge = prepare_bridge(&small_scenario().bridge).expect("the beam");
    let scenarios: Vec<Scenario> = (1..=3)
        .map(|seed| {
            let mut scenario = small_scenario();
            scenario.road.seed = seed;
            scenario.rerun_mode_counts.clear();
            // The analyses alone, without the pipeline's check of the step.
            scenario.solver.time_step_check = false;
            scenario
        })
        .collect();
    let refs: Vec<&Scenario> = scenarios.iter().collect();
    let results: Vec<RunResult> = run_crossings(&bridge, &refs, Recording::ForDafAnalysis)
        .into_iter()
        .map(|result| result.expect("a crossing"))
        .collect();
    let histories: Vec<&ResponseHistory> = results.iter().map(|r| &r.history).collect();
    let contacts = histories[0].contacts.len();
    for abandoned_at in [0, 37, 40] {
        let runs = histories.iter().map(|history| {
            Ok(RunToAnalyse {
                paths: history.wheel_paths(),
                options: &scenarios[0].analysis,
                with_forces: true,
                time_step: history.time_step,
                with_check_modes: true,
            })
        });
        let mut analyses =
            RunAnalyses::new((&bridge.basis, &bridge.influence), runs.collect(), None);
        for i in 0..histories[0].step_count {
            for (r, history) in histories.iter().enumerate() {
                if r == 1 && i == abandoned_at {
                    analyses.abandon(1);
                }
                if r == 1 && i >= abandoned_at {
                    continue;
                }
                let forces = &history.contact_force[i * contacts..(i + 1) * contacts];
                analyses.record(r, history.modal_displacements_at(i), forces);
            }
        }
        let ended = vec![Some(histories[0]), None, Some(histories[2])];
        let mut reports = analyses.finish(ended);
        assert!(reports[1].is_none(), "no report of the abandoned run");
        for r in [0, 2] {
            let report = reports[r].take().expect("a report").expect("analysed");
            // The pipeline adds the design codes to the analysis's report.
            let analysed = DafReport {
                design_codes: Vec::new(),
                ..results[r].report.clone()
            };
            assert_eq!(format!("{report:?}"), format!("{analysed:?}"));
        }
    }
}

/// A prepared bridge whose basis has a station table of the wrong length (its fields are
/// public) is refused by the analysis on both paths, recorded and streamed, with the same
/// error (the streamed path has no history to check, so it checks the basis itself).
#[test]
fn a_basis_with_a_station_table_of_the_wrong_length_is_refused_on_both_paths() {
    let mut bridge = prepare_bridge(&small_scenario().bridge).expect("the beam");
    bridge.basis.station_moment.push(0.0);
    let mut scenario = small_scenario();
    scenario.rerun_mode_counts.clear();
    for recording in [Recording::ForDafAnalysis, Recording::OutcomeOnly] {
        let result = run_crossings(&bridge, &[&scenario], recording).pop();
        match result {
            Some(Err(PipelineError::Analysis(AnalysisError::Mismatch { what, .. }))) => {
                assert_eq!(what, "station_moment length", "{recording:?}")
            }
            other => panic!("{recording:?}: expected the basis refused, got {other:?}"),
        }
    }
}

/// Issue 46, item 6: with two vehicles the headline DAF divides by the event's static envelope,
/// and each deflection and moment entry carries the heaviest single vehicle's own static
/// extreme beside it. Two spans of 25 m, the three-axle truck forward and a second one backward
/// entering 1 s later, so that they are on the deck together. Reference: each truck run alone as
/// its own scenario; the single-vehicle extreme is the larger of their static extremes in the
/// event's direction (both taken between the time steps, so that the time grids, offset by the
/// second truck's entry, do not matter: tolerance 1e-9 relative), and the DAF against it is
/// dynamic max / that extreme. A run of one vehicle has none.
#[test]
fn a_two_vehicle_event_states_the_heaviest_single_vehicles_static_reference_beside_its_own() {
    use crate::traffic::{Entry, Motion, TrafficVehicle, TravelDirection};
    let mut scenario = small_scenario();
    scenario.rerun_mode_counts.clear();
    scenario.bridge = beam_bridge(vec![25.0, 25.0]);
    scenario.vehicle = preset("three-axle-truck-36t").expect("a preset");
    scenario.solver.time_step_check = false;
    let oncoming = Motion {
        direction: TravelDirection::Backward,
        ..Motion::constant(15.0, 0.0)
    };
    let mut event = scenario.clone();
    event.traffic.push(TrafficVehicle {
        label: "oncoming".into(),
        vehicle: scenario.vehicle.clone(),
        motion: oncoming.clone(),
        entry: Entry::Time(1.0),
    });
    let mut alone = scenario.clone();
    alone.motion = oncoming;
    let bridge = prepare_bridge(&scenario.bridge).expect("prepared");
    let run = |s: &Scenario| run_crossing(&bridge, s).expect("a run").report;
    let (event, first, second) = (run(&event), run(&scenario), run(&alone));
    let mut checked = 0;
    for entry in &event.stations {
        let alone_extreme = |report: &DafReport| {
            report
                .stations
                .iter()
                .find(|e| e.name == entry.name && e.quantity == entry.quantity)
                .map(|e| e.static_max)
        };
        assert!(alone_extreme(&first).is_some());
        let one = first.entry(entry.station, entry.quantity).unwrap();
        assert_eq!(
            one.static_max_single_vehicle, None,
            "a run of one vehicle has none"
        );
        if !matches!(
            entry.quantity,
            Quantity::Deflection | Quantity::BendingMoment
        ) {
            assert_eq!(entry.static_max_single_vehicle, None);
            continue;
        }
        if entry.converged.daf.is_none() {
            // The deflection over the pier: no static response to divide by, and no DAF.
            assert_eq!(entry.daf_single_vehicle, None);
            continue;
        }
        let sign = entry.static_max.signum();
        let expected = [alone_extreme(&first), alone_extreme(&second)]
            .into_iter()
            .flatten()
            .filter(|v| sign * v > 0.0)
            .fold(
                0.0f64,
                |best, v| if sign * v > sign * best { v } else { best },
            );
        let single = entry
            .static_max_single_vehicle
            .expect("the single vehicle's extreme");
        assert!(
            (single / expected - 1.0).abs() < 1e-9,
            "{} {:?}: {single} vs {expected}",
            entry.name,
            entry.quantity
        );
        let daf = entry.daf_single_vehicle.expect("its DAF");
        assert!((daf - entry.converged.dynamic_max / single).abs() < 1e-12);
        checked += 1;
    }
    assert!(checked >= 5, "{checked}");
}

/// The partial sums of the fatigue indicator ([`crate::analysis::corrected_station_response_by_modes`])
/// end where the converged history is: with K = N modes they are the same series (summed in the
/// same order: equal to round-off, 10⁻¹² of the peak); with fewer, they differ.
#[test]
fn the_partial_corrected_sum_of_all_modes_is_the_converged_history() {
    let scenario = small_scenario();
    let bridge = prepare_bridge(&scenario.bridge).expect("prepared");
    let result = run_crossing(&bridge, &scenario).expect("run");
    let basis = &bridge.basis;
    let corrected =
        crate::analysis::corrected_station_responses(basis, &bridge.influence, &result.history)
            .expect("analysed")
            .expect("a correction exists");
    let n = basis.mode_count();
    for (s, series) in corrected.iter().enumerate() {
        for (quantity, converged) in series {
            let partial = crate::analysis::corrected_station_response_by_modes(
                basis,
                &bridge.influence,
                &result.history,
                (s, *quantity),
                &[1, n],
            )
            .expect("analysed")
            .expect("a correction exists");
            assert_eq!(partial.iter().map(|(k, _)| *k).collect::<Vec<_>>(), [1, n]);
            let peak = converged.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let difference = |values: &[f64]| {
                (values.iter().zip(converged)).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
            };
            assert!(
                difference(&partial[1].1) <= 1e-12 * peak,
                "{s} {quantity:?}"
            );
            assert!(difference(&partial[0].1) > 1e-6 * peak, "{s} {quantity:?}");
        }
    }
}
