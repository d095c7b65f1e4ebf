//! Tests of the traffic generator against the model it names (spec
//! docs/design/btls-traffic-generator.md): counts against the lane flows (Poisson), classes
//! against the fractions (binomial), gross weights against their mixture, the minimum gap, the
//! HeDS CDF (Kolmogorov–Smirnov), determinism and the checks.

use super::*;
use crate::road::SampleRng;
use crate::traffic::TravelDirection;
use crate::units::KN;

const FORWARD: TravelDirection = TravelDirection::Forward;
const BACKWARD: TravelDirection = TravelDirection::Backward;

fn normal(mean: f64, sd: f64, bounds: (f64, f64)) -> NormalMixture {
    NormalMixture::single(mean, sd, bounds.0, bounds.1)
}

fn spacing(mean: f64, sd: f64) -> NormalMixture {
    normal(mean, sd, AXLE_SPACING_BOUNDS)
}

fn share(mean: f64, sd: f64) -> NormalMixture {
    normal(mean, sd, AXLE_SHARE_BOUNDS)
}

fn band_table(mean: [f64; 3]) -> TandemLoadShareTable {
    let band = GvwBandLoadShares {
        mean,
        standard_deviation: [0.03, 0.04, 0.05],
    };
    TandemLoadShareTable {
        bands: vec![band; 11],
        share_lower_bound: AXLE_SHARE_BOUNDS.0,
        share_upper_bound: AXLE_SHARE_BOUNDS.1,
    }
}

/// Made-up parameters: one mode per gross weight except 2 axles (two modes), direction 2 a
/// little heavier than direction 1.
fn parameters() -> GraveParameters {
    let gvw = |mean_kn: f64, sd_kn: f64| normal(mean_kn * KN, sd_kn * KN, GROSS_WEIGHT_BOUNDS);
    let two_modes = NormalMixture {
        modes: vec![
            NormalMode {
                weight: 0.4,
                mean: 80.0 * KN,
                standard_deviation: 15.0 * KN,
            },
            NormalMode {
                weight: 0.6,
                mean: 160.0 * KN,
                standard_deviation: 25.0 * KN,
            },
        ],
        lower_bound: GROSS_WEIGHT_BOUNDS.0,
        upper_bound: GROSS_WEIGHT_BOUNDS.1,
    };
    GraveParameters {
        gross_weight: [
            [
                two_modes.clone(),
                gvw(220.0, 40.0),
                gvw(300.0, 50.0),
                gvw(400.0, 60.0),
            ],
            [
                two_modes,
                gvw(240.0, 40.0),
                gvw(320.0, 50.0),
                gvw(450.0, 60.0),
            ],
        ],
        axle_spacings: [
            vec![spacing(5.0, 0.5)],
            vec![spacing(4.0, 0.5), spacing(1.3, 0.1)],
            vec![spacing(3.5, 0.3), spacing(5.0, 0.5), spacing(1.3, 0.1)],
            vec![
                spacing(3.4, 0.3),
                spacing(6.0, 0.6),
                spacing(1.3, 0.1),
                spacing(1.3, 0.1),
            ],
        ],
        two_axle_load_shares: vec![share(0.35, 0.03), share(0.65, 0.03)],
        three_axle_load_shares: vec![share(0.30, 0.03), share(0.35, 0.03), share(0.35, 0.03)],
        four_axle_load_shares: band_table([0.22, 0.33, 0.45]),
        five_axle_load_shares: band_table([0.18, 0.30, 0.52]),
    }
}

const FRACTIONS: [f64; 4] = [0.2, 0.1, 0.3, 0.4];

fn block(truck_flow: f64) -> FlowBlock {
    FlowBlock {
        truck_flow,
        speed_mean: 24.0,
        speed_standard_deviation: 1.0,
        class_fractions: FRACTIONS,
    }
}

/// A lane whose hourly flow varies gently over the day: 30 + 10 sin(2π h/24) veh/h.
fn daily_lane(direction: TravelDirection, lane: usize) -> LaneFlow {
    let blocks = (0..24)
        .map(|h| block(30.0 + 10.0 * (std::f64::consts::TAU * h as f64 / 24.0).sin()))
        .collect();
    LaneFlow {
        direction,
        lane,
        block_seconds: DEFAULT_BLOCK_SECONDS,
        blocks,
    }
}

fn generate(
    lanes: Vec<LaneFlow>,
    headway: HeadwayModel,
    seed: u64,
    days: u64,
) -> Vec<RecordedTruck> {
    TrafficGenerator::new(parameters(), lanes, headway, seed, days, 30.0)
        .unwrap()
        .collect()
}

/// Spec §1–2 (BTLS's Poisson model, `FlowGenerator.cpp:274-282`): over 200 days each hour
/// block's truck count is a Poisson count of mean days × Q_h × 1 h; every block's count lies
/// within 4 standard deviations √(mean) of it (the minimum-gap thinning, about 1 s in 90 s
/// here, costs about 1 %, a quarter of the allowance). Times rise, end within the horizon, and
/// every truck is a valid record.
#[test]
fn free_flow_hourly_counts_match_the_lane_flow_within_four_poisson_deviations() {
    let days = 200;
    let lane = daily_lane(FORWARD, 1);
    let trucks = generate(vec![lane.clone()], HeadwayModel::FreeFlow, 11, days);
    let mut counts = [0.0; 24];
    for truck in &trucks {
        counts[(truck.arrival_time / 3600.0) as usize % 24] += 1.0;
        truck.check().unwrap();
    }
    for (h, count) in counts.iter().enumerate() {
        let expected = days as f64 * lane.blocks[h].truck_flow;
        assert!(
            (count - expected).abs() < 4.0 * expected.sqrt(),
            "hour {h}: {count} trucks, expected {expected}"
        );
    }
    assert!(trucks
        .windows(2)
        .all(|w| w[0].arrival_time <= w[1].arrival_time));
    assert!(trucks.last().unwrap().arrival_time <= days as f64 * 86_400.0);
    assert!(trucks.iter().all(|t| t.lane == 1 && t.direction == FORWARD));
}

/// Spec §3.1 step 2 (`VehicleGenGrave.cpp:37-52`): the share of each class (2, 3, 4, 5 axles)
/// lies within 4 binomial standard deviations √(n p (1 − p)) of its fraction.
#[test]
fn class_fractions_of_generated_trucks_lie_within_four_binomial_deviations() {
    let trucks = generate(
        vec![daily_lane(FORWARD, 1), daily_lane(BACKWARD, 1)],
        HeadwayModel::FreeFlow,
        5,
        40,
    );
    let n = trucks.len() as f64;
    for (c, p) in FRACTIONS.iter().enumerate() {
        let count = trucks
            .iter()
            .filter(|t| t.axle_loads.len() == c + 2)
            .count() as f64;
        let sd = (n * p * (1.0 - p)).sqrt();
        assert!(
            (count - n * p).abs() < 4.0 * sd,
            "{} axles: {count} of {n}",
            c + 2
        );
    }
}

/// Spec §3.1 steps 3–7: the gross weights of 5-axle trucks in each direction have the mean
/// and standard deviation of that direction's one-mode mixture (400 ± 60 kN forward,
/// 450 ± 60 kN backward: the direction is used) within 4 standard errors (σ/√n and σ/√(2n));
/// every truck's axle loads sum to its gross weight to 1e-9, its spacings and gross weight lie
/// in their bounds, its loads are positive, and 4- and 5-axle groups share their load equally.
#[test]
fn gross_weights_follow_their_mixture_and_axle_loads_sum_to_them() {
    let mut lanes = vec![daily_lane(FORWARD, 1), daily_lane(BACKWARD, 1)];
    for lane in &mut lanes {
        for block in &mut lane.blocks {
            block.truck_flow = 200.0;
            block.class_fractions = [0.0, 0.0, 0.0, 1.0];
        }
    }
    let trucks = generate(lanes, HeadwayModel::FreeFlow, 3, 4);
    for (direction, mean) in [(FORWARD, 400.0 * KN), (BACKWARD, 450.0 * KN)] {
        let w: Vec<f64> = trucks
            .iter()
            .filter(|t| t.direction == direction)
            .map(|t| t.gross_weight())
            .collect();
        let n = w.len() as f64;
        let sample_mean = w.iter().sum::<f64>() / n;
        let sd = (w.iter().map(|x| (x - sample_mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let sigma = 60.0 * KN;
        assert!(n > 15_000.0);
        assert!(
            (sample_mean - mean).abs() < 4.0 * sigma / n.sqrt(),
            "{direction:?}: {sample_mean}"
        );
        assert!(
            (sd - sigma).abs() < 4.0 * sigma / (2.0 * n).sqrt(),
            "{direction:?}: {sd}"
        );
    }
    let mixed = generate(vec![daily_lane(FORWARD, 1)], HeadwayModel::FreeFlow, 4, 20);
    for truck in trucks.iter().chain(&mixed) {
        let gvw = truck.gross_weight();
        assert!(gvw >= GROSS_WEIGHT_BOUNDS.0 && gvw <= GROSS_WEIGHT_BOUNDS.1);
        assert!(truck
            .axle_spacings
            .iter()
            .all(|s| *s >= AXLE_SPACING_BOUNDS.0 && *s <= AXLE_SPACING_BOUNDS.1));
        assert!(truck.axle_loads.iter().all(|p| *p > 0.0));
        if truck.axle_loads.len() > 3 {
            assert!(truck.axle_loads[2..].windows(2).all(|w| w[0] == w[1]));
        }
    }
    // The generator's GVW is the drawn one: recompute from a lane's stream.
    let parameters = parameters();
    let mut rng = SampleRng::new(9, 0);
    for _ in 0..2000 {
        let truck = parameters.draw_truck(FORWARD, &FRACTIONS, &mut rng);
        let sum: f64 = truck.axle_loads.iter().sum();
        assert!((sum - truck.gross_weight).abs() <= 1e-9 * truck.gross_weight);
    }
}

/// Spec §1 (`FlowGenerator.cpp:103-139`): at a high flow (1500 veh/h, where the minimum gap
/// binds) and scattered speeds (20 ± 5 m/s), no truck comes closer than B_s = 1 m to the last
/// axle of the truck ahead in its lane while its front axle is on the no-overlap length L:
/// the clear distance, linear in time, is checked at both ends of that interval. For each
/// headway model.
#[test]
fn no_truck_catches_the_one_ahead_within_the_no_overlap_length() {
    let length = 30.0;
    for headway in [
        HeadwayModel::FreeFlow,
        HeadwayModel::Heds(heds_table()),
        HeadwayModel::Constant { gap_s: 0.5 },
    ] {
        let mut lane = LaneFlow::uniform(FORWARD, 1, block(1500.0));
        for block in &mut lane.blocks {
            (block.speed_mean, block.speed_standard_deviation) = (20.0, 5.0);
        }
        let trucks: Vec<_> =
            TrafficGenerator::new(parameters(), vec![lane], headway.clone(), 8, 1, length)
                .unwrap()
                .collect();
        assert!(trucks.len() > 1000);
        let mut closest = f64::INFINITY;
        for pair in trucks.windows(2) {
            let (a, b) = (&pair[0], &pair[1]);
            let clear = |t: f64| {
                a.speed * (t - a.arrival_time) - a.wheelbase() - b.speed * (t - b.arrival_time)
            };
            let least = clear(b.arrival_time).min(clear(b.arrival_time + length / b.speed));
            closest = closest.min(least);
        }
        assert!(closest >= MIN_GAP_SPACE - 1e-9, "{headway:?}: {closest} m");
    }
}

/// The minimum gap's two cases by hand: a slower follower needs T_g; a faster one must still
/// be B_s + B_t v_b behind when its front reaches L.
#[test]
fn the_minimum_gap_keeps_the_buffer_at_the_end_of_the_no_overlap_length() {
    assert_eq!(minimum_gap(None, 20.0, 50.0), MIN_GAP_TIME);
    let tg = (10.0 + 1.0) / 20.0 + 0.1;
    assert_eq!(minimum_gap(Some((25.0, 10.0)), 20.0, 50.0), tg);
    let g = minimum_gap(Some((20.0, 10.0)), 25.0, 50.0);
    let rear_of_a = 20.0 * (g + 50.0 / 25.0) - 10.0;
    assert!((rear_of_a - (50.0 + 1.0 + 0.1 * 25.0)).abs() < 1e-9);
}

/// A made-up HeDS table: F₁ = 0.01 t², F₂ = 0.04 t − 0.03, and three flow rows that join F₂
/// at 1.5 s (0.03); the 100 veh/h row reaches F(4 s) = 0.15.
fn heds_table() -> HedsTable {
    let row = |flow_upper: f64, a: f64, b: f64| HedsFlowRow {
        flow_upper,
        cdf: QuadraticCdf {
            a,
            b,
            c: 0.03 - a * 2.25 - b * 1.5,
        },
    };
    HedsTable {
        below_one_second: QuadraticCdf {
            a: 0.01,
            b: 0.0,
            c: 0.0,
        },
        one_to_one_and_a_half_seconds: QuadraticCdf {
            a: 0.0,
            b: 0.04,
            c: -0.03,
        },
        by_flow: vec![
            row(80.0, -0.002, 0.05),
            row(100.0, -0.004, 0.07),
            row(150.0, 0.002, 0.06),
        ],
    }
}

/// Spec §2 (O'Brien & Caprani 2005; `FlowGenerator.cpp:156-198`): 20 000 gaps at Q = 100
/// veh/h follow the table's piecewise CDF (quadratics to 4 s, then the exponential tail of mean
/// 36 s) within the Kolmogorov–Smirnov bound 1.63/√n (1 % level); the share of gaps up to 4 s is
/// F(4 s) = 0.15 as tabulated, within 4 binomial standard deviations. Flows above the last row
/// use the last row (vbi's fix).
#[test]
fn heds_gaps_follow_the_tabulated_quadratic_cdf_within_the_kolmogorov_smirnov_bound() {
    let table = heds_table();
    table.check().unwrap();
    assert_eq!(table.row(100.0).unwrap().flow_upper, 100.0);
    assert_eq!(table.row(90.0).unwrap().flow_upper, 100.0);
    assert_eq!(table.row(1000.0).unwrap().flow_upper, 150.0);
    assert!((table.cdf(4.0, 100.0) - 0.15).abs() < 1e-12);
    let mut rng = SampleRng::new(21, 0);
    let mut gaps: Vec<f64> = (0..20_000)
        .map(|_| table.sample_gap(100.0, &mut rng))
        .collect();
    gaps.sort_by(f64::total_cmp);
    let n = gaps.len() as f64;
    let ks = gaps
        .iter()
        .enumerate()
        .map(|(i, &t)| {
            let f = table.cdf(t, 100.0);
            (f - i as f64 / n).max((i + 1) as f64 / n - f)
        })
        .fold(0.0, f64::max);
    assert!(ks < 1.63 / n.sqrt(), "D = {ks}");
    let short = gaps.iter().filter(|&&t| t <= 4.0).count() as f64;
    assert!(
        (short / n - 0.15).abs() < 4.0 * (0.15 * 0.85 / n).sqrt(),
        "{}",
        short / n
    );
}

/// The quadratic's inverse is the rising branch's root, for a concave, a convex and a linear
/// piece, and BTLS's dipping first piece (F₁ falls below 0.6 s and rises to 1 s).
#[test]
fn the_quadratic_inverse_returns_the_rising_root() {
    let pieces = [
        (
            QuadraticCdf {
                a: -0.004,
                b: 0.07,
                c: -0.066,
            },
            1.5,
            4.0,
        ),
        (
            QuadraticCdf {
                a: 0.002,
                b: 0.06,
                c: -0.0645,
            },
            1.5,
            4.0,
        ),
        (
            QuadraticCdf {
                a: 0.0,
                b: 0.04,
                c: -0.03,
            },
            1.0,
            1.5,
        ),
        (
            QuadraticCdf {
                a: 0.0119,
                b: -0.0143,
                c: 0.0041,
            },
            0.61,
            1.0,
        ),
    ];
    for (cdf, low, high) in pieces {
        for k in 0..=10 {
            let t = low + (high - low) * k as f64 / 10.0;
            assert!((cdf.inverse(cdf.at(t)) - t).abs() < 1e-9, "{cdf:?} at {t}");
        }
    }
}

/// Spec §6: the same seed gives the same trucks bit for bit; a lane's trucks are the same
/// with or without another lane (each lane its own stream); another seed gives other trucks.
#[test]
fn the_same_seed_gives_the_same_trucks_and_lanes_do_not_depend_on_each_other() {
    let both = || {
        vec![
            daily_lane(FORWARD, 1),
            daily_lane(BACKWARD, 1),
            daily_lane(FORWARD, 2),
        ]
    };
    let first = generate(both(), HeadwayModel::Heds(heds_table()), 42, 3);
    assert_eq!(
        first,
        generate(both(), HeadwayModel::Heds(heds_table()), 42, 3)
    );
    let alone = generate(
        vec![daily_lane(BACKWARD, 1)],
        HeadwayModel::Heds(heds_table()),
        42,
        3,
    );
    let merged: Vec<_> = first
        .iter()
        .filter(|t| t.direction == BACKWARD)
        .cloned()
        .collect();
    assert_eq!(alone, merged);
    assert_ne!(
        first,
        generate(both(), HeadwayModel::Heds(heds_table()), 43, 3)
    );
    assert!(first
        .windows(2)
        .all(|w| w[0].arrival_time <= w[1].arrival_time));
}

/// A mixture picks its modes in proportion to their weights and falls back to its bound when
/// it cannot reach inside (after [`MAX_REDRAWS`]); a band table skips bands without data.
#[test]
fn mixtures_pick_modes_by_weight_and_clamp_when_out_of_reach() {
    let mixture = NormalMixture {
        modes: vec![
            NormalMode {
                weight: 0.25,
                mean: 0.0,
                standard_deviation: 0.0,
            },
            NormalMode {
                weight: 0.75,
                mean: 1.0,
                standard_deviation: 0.0,
            },
        ],
        lower_bound: -1.0,
        upper_bound: 2.0,
    };
    let mut rng = SampleRng::new(1, 0);
    let n = 40_000.0;
    let ones = (0..n as usize)
        .filter(|_| mixture.sample(&mut rng) == 1.0)
        .count() as f64;
    assert!((ones / n - 0.75).abs() < 4.0 * (0.75 * 0.25 / n).sqrt());
    let unreachable = NormalMixture::single(10.0, 0.0, 0.0, 5.0);
    assert_eq!(unreachable.sample(&mut rng), 5.0);
    let mut table = band_table([0.2, 0.3, 0.5]);
    table.bands[10] = GvwBandLoadShares {
        mean: [0.0; 3],
        standard_deviation: [0.0; 3],
    };
    table.bands[9].mean = [0.1, 0.2, 0.7];
    assert_eq!(table.band(900.0 * KN).unwrap().mean, [0.1, 0.2, 0.7]);
    assert_eq!(table.band(80.0 * KN), Some(&table.bands[1]));
    assert_eq!(table.band(10.0 * KN), Some(&table.bands[0]));
}

/// The checks name the field at fault and what is allowed.
#[test]
fn the_checks_name_the_field_at_fault() {
    let field = |result: Result<TrafficGenerator, GeneratorError>| result.unwrap_err().field;
    let lanes = || vec![daily_lane(FORWARD, 1)];
    let build = |p: GraveParameters, l: Vec<LaneFlow>, h: HeadwayModel| {
        TrafficGenerator::new(p, l, h, 1, 1, 30.0)
    };
    let mut p = parameters();
    p.gross_weight[1][2].modes[0].standard_deviation = -1.0;
    assert_eq!(
        field(build(p, lanes(), HeadwayModel::FreeFlow)),
        "gross_weight[direction 2][4 axles].modes[0].standard_deviation"
    );
    let mut p = parameters();
    p.axle_spacings[1].pop();
    assert_eq!(
        field(build(p, lanes(), HeadwayModel::FreeFlow)),
        "axle_spacings[3 axles]"
    );
    let mut l = lanes();
    l[0].blocks[5].class_fractions = [0.2, 0.2, 0.2, 0.2];
    let error = build(parameters(), l, HeadwayModel::FreeFlow).unwrap_err();
    assert_eq!(error.field, "lanes[0].blocks[5].class_fractions");
    assert!(error.to_string().contains("sum to 1"), "{error}");
    let mut l = lanes();
    l[0].blocks[0].truck_flow = 0.0;
    assert_eq!(
        field(build(parameters(), l, HeadwayModel::FreeFlow)),
        "lanes[0].blocks[0].truck_flow"
    );
    let mut l = lanes();
    l.push(daily_lane(FORWARD, 1));
    assert_eq!(
        field(build(parameters(), l, HeadwayModel::FreeFlow)),
        "lanes[1].lane"
    );
    let mut heds = heds_table();
    heds.by_flow.swap(0, 1);
    assert_eq!(
        field(build(parameters(), lanes(), HeadwayModel::Heds(heds))),
        "heds.by_flow[1]"
    );
    assert_eq!(
        field(build(
            parameters(),
            lanes(),
            HeadwayModel::Constant { gap_s: 0.0 }
        )),
        "headway.gap_s"
    );
    assert_eq!(
        field(TrafficGenerator::new(
            parameters(),
            lanes(),
            HeadwayModel::FreeFlow,
            1,
            0,
            30.0
        )),
        "days"
    );
}
