use super::*;
use crate::analysis::StationScope;
use crate::modal::Quantity;
use crate::model::{BeamSection, BridgeModel, ContinuousBeam};
use crate::vehicle::preset;

/// A 25 m simply supported beam (EI = 1e10 N·m², m̄ = 1e4 kg/m, ζ = 0.02) with 6 modes, crossed
/// by the quarter car at 20 m/s on the default 'medium' road: small enough for a unit test.
fn small_scenario() -> Scenario {
    let mut beam = ContinuousBeam::pinned(
        vec![25.0],
        BeamSection {
            flexural_rigidity: 1e10,
            mass_per_length: 1e4,
        },
    );
    beam.damping_ratio = 0.02;
    let bridge = BridgeSpec::new(BridgeModel::ContinuousBeam(beam), 6);
    Scenario {
        name: "small".into(),
        bridge_label: "25 m beam".into(),
        bridge,
        vehicle: preset("quarter-car").expect("a preset"),
        motion: Motion {
            speed: 20.0,
            lateral_position: 0.0,
        },
        rerun_mode_counts: vec![2],
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
    let scenario = small_scenario();
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
        let q = match entry.quantity {
            Quantity::Deflection => 0,
            Quantity::BendingMoment => 1,
        };
        let reported = entry.corrected_dynamic_max.expect("a corrected maximum");
        let extreme = corrected[s][q]
            .iter()
            .cloned()
            .max_by(|a, b| (a * reported.signum()).total_cmp(&(b * reported.signum())))
            .unwrap();
        // The report sums the modes as running partial sums, this as one dot product: the
        // same terms in another order, equal to round-off (1e-12 relative for six terms).
        assert!(
            (extreme - reported).abs() <= 1e-12 * reported.abs(),
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
    for s in 0..stations {
        for (q, statics) in [&reference.deflection, &reference.bending_moment]
            .iter()
            .enumerate()
        {
            let exact: Vec<f64> = (0..result.history.step_count)
                .map(|i| statics[i * stations + s])
                .collect();
            let peak = exact.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if peak == 0.0 {
                continue;
            }
            let worst = corrected[s][q]
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
