//! Crossings integrated together (`solver::simulate_batch`, `crossing::run_crossings`, what
//! `vbi study` runs) give exactly what each gives alone (`crossing::run_crossing`): the shared
//! position-dependent work (contact shapes, on-deck products, the coupled LU) must not change a
//! bit of any history or report. The reference is the unbatched path itself; the invariant is
//! bit-for-bit equality, so there is no tolerance.

use vbi::analysis::StationScope;
use vbi::crossing::{
    crossing_of, integration_batches, prepare_bridge, repeats_run, run_crossing, run_crossings,
    run_distinct_crossings, same_crossing_bit_for_bit, same_run_but_road_seed, BridgeSpec, Motion,
    PipelineError, PreparedBridge, Scenario,
};
use vbi::model::paper_bridge;
use vbi::road::{BumpShape, EventShape, EventTracks, RoadEvent, RoadSpec, RoughnessClass};
use vbi::solver::{Recording, SolverError};
use vbi::vehicle::preset;

/// The paper's 2 × 20 m grillage at a 4 m mesh with 10 modes (small enough for a debug build),
/// crossed by the built-in five-axle truck.
fn bridge() -> PreparedBridge {
    let mut spec = BridgeSpec::new(paper_bridge(2, 20.0), 10);
    spec.mesh.element_length = 4.0;
    prepare_bridge(&spec).expect("the paper bridge")
}

fn scenario(bridge: &PreparedBridge, class: RoughnessClass, seed: u64, speed_kmh: f64) -> Scenario {
    let mut scenario = Scenario {
        road: RoadSpec::of_class(class),
        ..Scenario::default()
    };
    scenario.bridge = bridge.spec.clone();
    scenario.road.seed = seed;
    scenario.motion = Motion::constant(speed_kmh / 3.6, 0.0);
    scenario.analysis.stations = StationScope::RdmStation;
    scenario
}

/// Roads of two classes and four seeds at 120 km/h (one batch), one crossing at 80 km/h and one
/// of another vehicle (each its own group within the batch): the mix a study's batch can hold.
fn mixed_scenarios(bridge: &PreparedBridge) -> Vec<Scenario> {
    let mut scenarios = Vec::new();
    for seed in 1..=4 {
        scenarios.push(scenario(bridge, RoughnessClass::Poor, seed, 120.0));
        scenarios.push(scenario(bridge, RoughnessClass::Medium, seed, 120.0));
    }
    scenarios.push(scenario(bridge, RoughnessClass::Poor, 9, 80.0));
    let mut quarter_car = scenario(bridge, RoughnessClass::Poor, 10, 120.0);
    quarter_car.vehicle = preset("quarter-car").expect("a preset");
    scenarios.push(quarter_car);
    scenarios
}

/// Runs `scenarios` together ([`run_crossings`]) and checks each result's crossing, history and
/// report against its crossing run alone, bit for bit; whether a tyre left the road.
fn each_result_is_that_of_its_crossing_alone(
    bridge: &PreparedBridge,
    scenarios: &[Scenario],
) -> bool {
    let refs: Vec<&Scenario> = scenarios.iter().collect();
    let together = run_crossings(bridge, &refs, Recording::Everything);
    let mut tyres_left_the_road = false;
    for (scenario, batched) in scenarios.iter().zip(together) {
        let alone = run_crossing(bridge, scenario).expect("the crossing alone");
        let batched = batched.expect("the crossing in the batch");
        tyres_left_the_road |= !alone.history.contact_losses.is_empty();
        assert!(same_crossing_bit_for_bit(
            &batched.crossing,
            &alone.crossing
        ));
        assert_eq!(batched.history, alone.history);
        assert_eq!(batched.report, alone.report);
    }
    tyres_left_the_road
}

#[test]
fn crossings_run_together_give_each_crossings_own_history_and_report_bit_for_bit() {
    let bridge = bridge();
    let mut scenarios = mixed_scenarios(&bridge);
    // Every station analysed: the wheels' values shared with runs of other targets.
    let mut every_station = scenario(&bridge, RoughnessClass::Medium, 11, 120.0);
    every_station.analysis.stations = StationScope::All;
    scenarios.push(every_station);
    let tyres_left_the_road = each_result_is_that_of_its_crossing_alone(&bridge, &scenarios);
    // The poor road at 120 km/h makes tyres leave the road: the path where a crossing's contact
    // set differs from the others' (its own LU) is covered.
    assert!(tyres_left_the_road, "no crossing lost contact");
}

#[test]
fn recording_for_the_daf_analysis_keeps_the_report_and_leaves_out_the_rates_and_the_vehicle() {
    let bridge = bridge();
    let scenarios = mixed_scenarios(&bridge);
    let refs: Vec<&Scenario> = scenarios.iter().take(3).collect();
    let full = run_crossings(&bridge, &refs, Recording::Everything);
    let lean = run_crossings(&bridge, &refs, Recording::ForDafAnalysis);
    for (full, lean) in full.into_iter().zip(lean) {
        let (full, lean) = (full.expect("full"), lean.expect("lean"));
        assert_eq!(lean.report, full.report);
        assert_eq!(
            lean.history.modal_displacement,
            full.history.modal_displacement
        );
        assert_eq!(lean.history.contact_force, full.history.contact_force);
        assert!(
            lean.history.modal_velocity.is_empty() && lean.history.modal_acceleration.is_empty()
        );
        assert!(lean.history.vehicle_displacement.is_empty());
        assert!(!full.history.modal_velocity.is_empty());
    }
}

/// The streamed path ([`Recording::OutcomeOnly`]: each instant analysed as the solver computes
/// it, no history held) against the recorded one ([`Recording::ForDafAnalysis`], the histories
/// analysed after the run): the reports must be equal bit for bit (compared through their
/// `Debug` text, which tells every f64 apart but NaN payloads), and the streamed history holds
/// the run's outcome without its tables.
#[test]
fn crossings_analysed_as_they_are_integrated_give_the_reports_of_their_recorded_histories_bit_for_bit(
) {
    let bridge = bridge();
    let mut scenarios = mixed_scenarios(&bridge);
    let mut every_station = scenario(&bridge, RoughnessClass::Medium, 11, 120.0);
    every_station.analysis.stations = StationScope::All;
    scenarios.push(every_station);
    scenarios.extend(scenarios_with_repeats(&bridge));
    // A crossing that fails part-way, first of its batch and of its group of wheel paths: a
    // bump of 1e300 m on its road (no input check refuses a road event of the library's API)
    // overflows its tyre forces once the truck reaches it; its analysis is abandoned inside a
    // panel of instants, and the others of its group go on without it.
    let mut bumped = scenario(&bridge, RoughnessClass::Poor, 31, 120.0);
    bumped.road.events.push(RoadEvent {
        tracks: EventTracks::Both,
        shape: EventShape::Bump {
            centre: 13.3,
            length: 1.0,
            height: 1e300,
            shape: BumpShape::Cosine,
        },
    });
    scenarios.insert(0, bumped);
    let refs: Vec<&Scenario> = scenarios.iter().collect();
    let recorded = run_crossings(&bridge, &refs, Recording::ForDafAnalysis);
    let streamed = run_crossings(&bridge, &refs, Recording::OutcomeOnly);
    let mut failed = 0;
    for (recorded, streamed) in recorded.iter().zip(&streamed) {
        let (recorded, streamed) = match (recorded, streamed) {
            (Ok(recorded), Ok(streamed)) => (recorded, streamed),
            (Err(recorded), Err(streamed)) => {
                assert_eq!(format!("{recorded:?}"), format!("{streamed:?}"));
                let part_way = matches!(
                    streamed,
                    PipelineError::Crossing(SolverError::NonFinite { time }) if *time > 0.0
                );
                assert!(part_way, "the crossing fails part-way: {streamed:?}");
                failed += 1;
                continue;
            }
            _ => panic!("one path failed and the other did not"),
        };
        assert_eq!(
            format!("{:?}", streamed.report),
            format!("{:?}", recorded.report)
        );
        let (history, full) = (&streamed.history, &recorded.history);
        assert_eq!(history.step_count, full.step_count);
        assert_eq!(history.exit_step, full.exit_step);
        assert_eq!(history.contact_losses, full.contact_losses);
        assert_eq!(history.contacts, full.contacts);
        assert!(history.modal_displacement.is_empty() && history.contact_position.is_empty());
    }
    assert_eq!(failed, 1, "the bumped crossing fails on both paths");
}

#[test]
fn integration_batches_hold_the_road_samples_of_one_crossing_up_to_the_limit() {
    let bridge = bridge();
    let scenarios = mixed_scenarios(&bridge);
    let refs: Vec<&Scenario> = scenarios.iter().collect();
    // The eight 120 km/h roads in batches of three; the 80 km/h and the quarter car alone.
    assert_eq!(
        integration_batches(&refs, 3),
        vec![vec![0, 1, 2], vec![3, 4, 5], vec![6, 7], vec![8], vec![9]]
    );
    assert_eq!(integration_batches(&refs, 0).len(), scenarios.len());
}

/// Smooth roads of three seeds at 120 km/h (the same crossing: 'smooth' reads no seed), a
/// medium road between them, and a fourth smooth road with another analysis scope.
fn scenarios_with_repeats(bridge: &PreparedBridge) -> Vec<Scenario> {
    let mut scenarios = vec![
        scenario(bridge, RoughnessClass::Smooth, 1, 120.0),
        scenario(bridge, RoughnessClass::Medium, 1, 120.0),
        scenario(bridge, RoughnessClass::Smooth, 2, 120.0),
        scenario(bridge, RoughnessClass::Smooth, 3, 120.0),
        scenario(bridge, RoughnessClass::Smooth, 4, 120.0),
    ];
    scenarios[4].analysis.stations = StationScope::All;
    scenarios
}

#[test]
fn a_crossing_repeated_with_a_seed_its_road_does_not_read_gets_the_result_of_the_first_bit_for_bit()
{
    let bridge = bridge();
    let scenarios = scenarios_with_repeats(&bridge);
    let refs: Vec<&Scenario> = scenarios.iter().collect();
    assert!(!scenarios[0].road.reads_seed() && scenarios[1].road.reads_seed());
    assert!(same_run_but_road_seed(refs[0], refs[2]) && same_run_but_road_seed(refs[0], refs[3]));
    // Another road, or another analysis, is another run.
    assert!(!same_run_but_road_seed(refs[0], refs[1]));
    assert!(!same_run_but_road_seed(refs[0], refs[4]));
    // The crossings of the smooth roads are the same bit for bit: run_crossings copies them.
    let crossing = |i: usize| crossing_of(refs[i]).expect("a crossing");
    let first = crossing(0);
    assert!(repeats_run((refs[0], &first), (refs[2], &crossing(2))));
    assert!(!repeats_run((refs[0], &first), (refs[1], &crossing(1))));
    each_result_is_that_of_its_crossing_alone(&bridge, &scenarios);
    // Without the copies, the repeats read their first run's one result.
    let runs = run_distinct_crossings(&bridge, &refs, Recording::ForDafAnalysis);
    assert_eq!(runs.len(), scenarios.len());
    for repeat in [2, 3] {
        assert!(std::ptr::eq(runs.result(repeat), runs.result(0)));
    }
    assert!(!std::ptr::eq(runs.result(1), runs.result(0)));
    assert!(!std::ptr::eq(runs.result(4), runs.result(0)));
}

#[test]
fn integration_batches_put_a_repeated_crossing_beside_its_first_beyond_the_limit() {
    let bridge = bridge();
    let scenarios = scenarios_with_repeats(&bridge);
    let refs: Vec<&Scenario> = scenarios.iter().collect();
    // Two distinct crossings per batch: the smooth road's repeats join its batch without
    // counting; the smooth road with another analysis is a distinct run.
    assert_eq!(
        integration_batches(&refs, 2),
        vec![vec![0, 1, 2, 3], vec![4]]
    );
}
