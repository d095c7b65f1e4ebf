//! The static lifetime analysis against closed forms (a simple span's moment and shear under
//! one and two axles), against a dense sampling of the same effect history, and the block
//! bookkeeping (day boundaries, days without traffic, the stream's order).

use super::*;
use crate::traffic::TravelDirection;

pub(crate) const SPAN: f64 = 30.0;

/// The midspan moment line of a simple span: x/2 left of the middle, (L − x)/2 right of it.
pub(crate) fn midspan_moment() -> EffectLine {
    EffectLine::continuous(vec![0.0, SPAN / 2.0, SPAN], vec![0.0, SPAN / 4.0, 0.0]).unwrap()
}

/// The shear just right of the quarter point: −x/L left of it, 1 − x/L right of it.
pub(crate) fn quarter_shear() -> EffectLine {
    let q = SPAN / 4.0;
    EffectLine::with_jumps(
        vec![0.0, q, SPAN],
        vec![0.0, -0.25, 0.0],
        vec![0.0, 0.75, 0.0],
    )
    .unwrap()
}

pub(crate) fn truck(
    time: f64,
    lane: usize,
    direction: TravelDirection,
    spacings: &[f64],
    loads: &[f64],
) -> RecordedTruck {
    RecordedTruck {
        arrival_time: time,
        lane,
        direction,
        speed: 25.0,
        axle_spacings: spacings.to_vec(),
        axle_loads: loads.to_vec(),
    }
}

pub(crate) fn analysis(lines: Vec<EffectLine>) -> StaticLifetime {
    StaticLifetime {
        deck_length: SPAN,
        lanes: vec![
            LifetimeLane {
                direction: TravelDirection::Forward,
                number: 1,
                lateral_position: 1.75,
            },
            LifetimeLane {
                direction: TravelDirection::Backward,
                number: 1,
                lateral_position: -1.75,
            },
        ],
        effects: vec![LifetimeEffect::new(
            "mid".into(),
            Quantity::BendingMoment,
            vec![lines[0].clone(), lines[0].clone()],
        )]
        .into_iter()
        .chain(
            lines
                .into_iter()
                .skip(1)
                .map(|l| LifetimeEffect::new("q".into(), Quantity::ShearForce, vec![l.clone(), l])),
        )
        .collect(),
        block_seconds: SECONDS_PER_DAY,
        record_end: None,
        blocks: BlockRange::ALL,
    }
}

/// The trucks placed on the 30 m deck: direction 1 in lane index 0, direction 2 in 1.
fn placed(trucks: &[RecordedTruck]) -> Vec<PlacedTruck> {
    (trucks.iter())
        .map(|t| {
            PlacedTruck::new(
                t,
                usize::from(t.direction == TravelDirection::Backward),
                SPAN,
            )
        })
        .collect()
}

fn maxima(
    analysis: &StaticLifetime,
    trucks: Vec<RecordedTruck>,
) -> (Vec<BlockMaximum>, LifetimeCounts) {
    let mut rows = Vec::new();
    let counts =
        static_block_maxima(analysis, trucks, |block| rows.extend_from_slice(block)).unwrap();
    (rows, counts)
}

#[test]
fn one_axle_gives_the_simple_span_midspan_moment_p_l_over_4() {
    let p = 100e3;
    let (rows, counts) = maxima(
        &analysis(vec![midspan_moment()]),
        vec![truck(10.0, 1, TravelDirection::Forward, &[], &[p])],
    );
    assert_eq!(counts.events, 1);
    assert_eq!(rows.len(), 1);
    assert!((rows[0].value - p * SPAN / 4.0).abs() < 1e-9 * p * SPAN);
    // At the instant the axle is at midspan: 10 s + 15 m / 25 m/s.
    assert!((rows[0].time - 10.6).abs() < 1e-12);
}

#[test]
fn two_axles_give_the_closed_form_midspan_moment_and_both_directions_agree() {
    // P at midspan and P at a behind it: M = P L/4 + P (L/2 − a)/2 (a < L/2).
    let (p, a) = (80e3, 6.0);
    let expected = p * SPAN / 4.0 + p * (SPAN / 2.0 - a) / 2.0;
    for direction in [TravelDirection::Forward, TravelDirection::Backward] {
        let (rows, _) = maxima(
            &analysis(vec![midspan_moment()]),
            vec![truck(0.0, 1, direction, &[a], &[p, p])],
        );
        assert!(
            (rows[0].value - expected).abs() < 1e-9 * expected,
            "{direction:?}: {}",
            rows[0].value
        );
    }
}

#[test]
fn a_shear_jump_reaches_its_one_sided_limit() {
    // One axle P: the quarter-point shear's supremum is 0.75 P, its limit as the axle passes
    // the section from the right side (the section's line jumps from −0.25 to 0.75).
    let p = 50e3;
    let (rows, _) = maxima(
        &analysis(vec![midspan_moment(), quarter_shear()]),
        vec![truck(0.0, 1, TravelDirection::Forward, &[], &[p])],
    );
    let shear = rows.iter().find(|r| r.effect == 1).unwrap();
    assert!((shear.value - 0.75 * p).abs() < 1e-9 * p, "{}", shear.value);
}

/// A dense sampling of E(t) over an event: every sample at or below the continuous extreme,
/// and the largest within the change of E over one step.
#[test]
fn the_continuous_maximum_bounds_a_dense_sampling_and_is_reached_by_it() {
    let line = EffectLine::continuous(
        (0..=30).map(|k| k as f64).collect(),
        (0..=30)
            .map(|k| ((k as f64) * 0.2).sin() * 4.0 + 0.1 * k as f64)
            .collect(),
    )
    .unwrap();
    let trucks = vec![
        truck(
            0.0,
            1,
            TravelDirection::Forward,
            &[3.2, 5.1, 1.3],
            &[60e3, 90e3, 70e3, 70e3],
        ),
        truck(
            0.3,
            1,
            TravelDirection::Backward,
            &[4.0, 1.2],
            &[50e3, 80e3, 80e3],
        ),
        truck(1.1, 1, TravelDirection::Forward, &[5.5], &[40e3, 60e3]),
    ];
    let analysis = analysis(vec![line.clone()]);
    let placed = placed(&trucks);
    let lines = [line.clone(), line];
    let extreme = event::event_extreme(&placed, &lines, SPAN, 1.0);
    let step = 1e-4;
    let mut sampled: f64 = 0.0;
    for i in 0..40_000 {
        let e = event::effect_at(&placed, &lines, SPAN, i as f64 * step);
        assert!(
            e <= extreme.value * (1.0 + 1e-12),
            "E({}) = {e} above {}",
            i as f64 * step,
            extreme.value
        );
        sampled = sampled.max(e);
    }
    // |dE/dt| ≤ Σ w × max |η'| × v = 770 kN × 0.9 /m × 25 m/s; one step changes E by ≤ 1.8 kN·m.
    assert!(
        extreme.value - sampled < 2e3,
        "{} − {sampled}",
        extreme.value
    );
    let (rows, counts) = maxima(&analysis, trucks);
    assert_eq!(counts.events, 1);
    assert_eq!(counts.multiple_presence_events, 1);
    assert_eq!(rows[0].value, extreme.value);
    assert_eq!(rows[0].trucks, 3);
}

#[test]
fn blocks_are_days_in_order_with_zero_for_days_without_trucks() {
    let p = 100e3;
    let day = SECONDS_PER_DAY;
    let trucks = vec![
        truck(100.0, 1, TravelDirection::Forward, &[], &[p]),
        truck(200.0, 1, TravelDirection::Forward, &[], &[2.0 * p]),
        // Day 1 has none; day 2 one at its end, whose maximum falls in day 3.
        truck(3.0 * day - 0.1, 1, TravelDirection::Forward, &[], &[p]),
        truck(
            3.0 * day + 50.0,
            1,
            TravelDirection::Forward,
            &[],
            &[0.5 * p],
        ),
    ];
    let (rows, counts) = maxima(&analysis(vec![midspan_moment()]), trucks);
    let blocks: Vec<(u64, f64)> = rows
        .iter()
        .map(|r| (r.block, r.value / (p * SPAN / 4.0)))
        .collect();
    assert_eq!(counts.blocks, 4);
    assert_eq!(blocks.len(), 4);
    for (got, expected) in blocks.iter().zip([(0, 2.0), (1, 0.0), (2, 0.0), (3, 1.0)]) {
        assert_eq!(got.0, expected.0);
        assert!((got.1 - expected.1).abs() < 1e-12, "{blocks:?}");
    }
}

#[test]
fn a_stream_out_of_order_an_unknown_lane_and_a_bad_truck_are_refused_with_the_truck_number() {
    let a = analysis(vec![midspan_moment()]);
    let good = |t| truck(t, 1, TravelDirection::Forward, &[], &[1e3]);
    let run = |trucks| static_block_maxima(&a, trucks, |_| {});
    assert!(matches!(
        run(vec![good(5.0), good(4.0)]),
        Err(LifetimeError::OutOfOrder(OutOfOrder { truck: 2, .. }))
    ));
    let mut other = good(6.0);
    other.lane = 3;
    assert!(matches!(
        run(vec![good(5.0), other]),
        Err(LifetimeError::UnknownLane {
            truck: 2,
            direction: 1,
            lane: 3,
            ..
        })
    ));
    let mut bad = good(6.0);
    bad.speed = 0.0;
    assert!(matches!(
        run(vec![good(5.0), bad]),
        Err(LifetimeError::Truck { truck: 2, .. })
    ));
}

#[test]
fn a_hogging_line_governs_in_the_negative_sense() {
    let line = EffectLine::continuous(vec![0.0, 15.0, 30.0], vec![0.0, -3.0, 0.0]).unwrap();
    let effect = LifetimeEffect::new(
        "support".into(),
        Quantity::BendingMoment,
        vec![line.clone(), line],
    );
    assert_eq!(effect.sense, -1.0);
    let a = StaticLifetime {
        effects: vec![effect],
        ..analysis(vec![midspan_moment()])
    };
    let (rows, _) = maxima(
        &a,
        vec![truck(0.0, 1, TravelDirection::Forward, &[], &[1e3])],
    );
    assert!((rows[0].value + 3e3).abs() < 1e-9);
}

#[test]
fn a_midspan_shear_s_plus_and_minus_half_to_round_off_governs_positive() {
    // The FE lines give the ±½ jump to round-off: −0.5000000000001 and 0.4999999999999.
    let line = EffectLine::with_jumps(
        vec![0.0, 15.0, 30.0],
        vec![0.0, -0.500_000_000_000_1, 0.0],
        vec![0.0, 0.499_999_999_999_9, 0.0],
    )
    .unwrap();
    let effect = LifetimeEffect::new("mid".into(), Quantity::ShearForce, vec![line.clone(), line]);
    assert_eq!(effect.sense, 1.0);
}

/// The default tabulation (`DEFAULT_POINTS_PER_ELEMENT` per 1 m element) of an FE beam's
/// midspan deflection line against the closed form δ(x) = x (3L² − 4x²) / (48 EI) (x ≤ L/2,
/// Maxwell–Betti; Euler–Bernoulli): one axle at the knot at midspan gives P L³ / (48 EI) to
/// the static solve's round-off; two axles, whose extreme lies between knots, agree with the
/// closed form's extreme (found on a 1 mm grid) within the linear interpolant's bound
/// Σw × h²/8 × max|δ''| = Σw × h²/8 × L/(4 EI), h = 0.25 m.
#[test]
fn default_deflection_maxima_of_an_fe_beam_match_the_closed_form_within_the_tabulation_bound() {
    use crate::crossing::BridgeSpec;
    use crate::model::{BeamSection, BridgeModel, ContinuousBeam};
    let rigidity = 35e9 * 1.5;
    let beam = BridgeModel::ContinuousBeam(ContinuousBeam::pinned(
        vec![SPAN],
        BeamSection {
            flexural_rigidity: rigidity,
            mass_per_length: 18_000.0,
        },
    ));
    let lanes = analysis(vec![midspan_moment()]).lanes;
    let prepared = prepare_static(
        &BridgeSpec::new(beam, 10),
        lanes,
        SECONDS_PER_DAY,
        DEFAULT_POINTS_PER_ELEMENT,
        &[Quantity::Deflection],
    )
    .unwrap();
    assert_eq!(prepared.effects.len(), 1);
    assert_eq!(prepared.effects[0].sense, -1.0);
    let closed_form = |x: f64| {
        let x = x.min(SPAN - x);
        if x <= 0.0 {
            0.0
        } else {
            -x * (3.0 * SPAN * SPAN - 4.0 * x * x) / (48.0 * rigidity)
        }
    };
    let p = 100e3;
    let (rows, _) = maxima(
        &prepared,
        vec![truck(0.0, 1, TravelDirection::Forward, &[], &[p])],
    );
    let exact = p * closed_form(SPAN / 2.0);
    assert!(
        (rows[0].value - exact).abs() < 1e-9 * exact.abs(),
        "{} against {exact}",
        rows[0].value
    );

    let a = 4.3;
    let (rows, _) = maxima(
        &prepared,
        vec![truck(
            0.0,
            1,
            TravelDirection::Backward,
            &[a],
            &[p, 1.5 * p],
        )],
    );
    let exact = (0..=(SPAN + a) as usize * 1000)
        .map(|i| {
            let front = i as f64 / 1000.0;
            p * closed_form(front) + 1.5 * p * closed_form(front - a)
        })
        .fold(0.0, f64::min);
    let h = 1.0 / DEFAULT_POINTS_PER_ELEMENT as f64;
    let bound = 2.5 * p * h * h / 8.0 * SPAN / (4.0 * rigidity);
    assert!(
        (rows[0].value - exact).abs() <= bound,
        "{} against {exact}: {:e} beyond the bound {bound:e}",
        rows[0].value,
        (rows[0].value - exact).abs()
    );
}

#[test]
fn event_peaks_keep_exactly_the_largest_event_extremes_and_the_maxima_are_unchanged() {
    // One-axle trucks far apart: each is an event of moment P L/4. Keeping 5 exceedances keeps
    // the 6 largest loads' moments; the block maxima are those of static_block_maxima.
    let prepared = analysis(vec![midspan_moment()]);
    let loads: Vec<f64> = (0..40)
        .map(|i| 1.0e5 + ((i * 7919) % 40) as f64 * 1.0e3)
        .collect();
    let trucks: Vec<RecordedTruck> = loads
        .iter()
        .enumerate()
        .map(|(i, &p)| truck(i as f64 * 3600.0, 1, TravelDirection::Forward, &[], &[p]))
        .collect();
    let mut peaks = EventPeaks::new(&prepared, 5);
    let mut rows = Vec::new();
    static_maxima_and_peaks(&prepared, trucks.clone(), &mut peaks, |block| {
        rows.extend_from_slice(block)
    })
    .unwrap();
    let mut want: Vec<f64> = loads.iter().map(|p| p * SPAN / 4.0).collect();
    want.sort_by(|a, b| b.total_cmp(a));
    let kept = peaks.values(0);
    assert_eq!(kept.len(), 6);
    for (k, w) in kept.iter().zip(&want) {
        assert!((k - w).abs() <= 1e-9 * w, "{k} against {w}");
    }
    assert_eq!(rows, maxima(&prepared, trucks).0);
}

/// A deterministic stream of mixed trucks (1 to 5 axles, both directions, some following
/// closely enough to share the deck) over `days` days: a test record whose events vary.
fn mixed_stream(days: f64, count: usize) -> Vec<RecordedTruck> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut time = 0.0;
    let gap = days * SECONDS_PER_DAY / count as f64;
    (0..count)
        .map(|_| {
            time += if next() < 0.2 {
                1.5
            } else {
                2.0 * gap * next()
            };
            let axles = 1 + (next() * 5.0) as usize;
            let direction = match next() < 0.5 {
                true => TravelDirection::Forward,
                false => TravelDirection::Backward,
            };
            let spacings: Vec<f64> = (1..axles).map(|_| 1.2 + 4.0 * next()).collect();
            let loads: Vec<f64> = (0..axles).map(|_| 20e3 + 100e3 * next()).collect();
            truck(time, 1, direction, &spacings, &loads)
        })
        .collect()
}

/// Per effect, each block's (value, time, trucks) of its largest event.
type BlockRows = Vec<Vec<(f64, f64, usize)>>;

/// The block maxima and peaks of every event's extreme, computed for every event: the
/// reference the bounded pass (bound.rs) must equal bit for bit.
fn every_event_maxima(
    analysis: &StaticLifetime,
    trucks: &[RecordedTruck],
    exceedances: usize,
) -> (BlockRows, Vec<Vec<f64>>) {
    let placed = placed(trucks);
    let effects = analysis.effects.len();
    let mut blocks: BlockRows = vec![Vec::new(); effects];
    let mut all: Vec<Vec<f64>> = vec![Vec::new(); effects];
    event::for_each_event(placed, |event| {
        for (e, effect) in analysis.effects.iter().enumerate() {
            let x = event::event_extreme(event, &effect.lines, analysis.deck_length, effect.sense);
            let block = (x.time / analysis.block_seconds).floor() as usize;
            let rows = &mut blocks[e];
            if rows.len() <= block {
                rows.resize(block + 1, (0.0, 0.0, 0));
            }
            if effect.sense * x.value > effect.sense * rows[block].0 {
                rows[block] = (x.value, x.time, event.len());
            }
            if effect.sense * x.value > 0.0 {
                all[e].push(effect.sense * x.value);
            }
        }
    })
    .unwrap();
    for values in &mut all {
        values.sort_by(|a, b| b.total_cmp(a));
        values.truncate(exceedances + 1);
    }
    (blocks, all)
}

#[test]
fn the_bounded_pass_gives_every_event_s_block_maxima_and_peaks_bit_for_bit() {
    // Hourly blocks, so that many blocks open and close; a sagging moment, a shear with its
    // jump and a hogging-like line of both signs.
    let both_signs =
        EffectLine::continuous(vec![0.0, 10.0, 20.0, SPAN], vec![0.0, -3.0, 1.0, 0.0]).unwrap();
    let mut prepared = analysis(vec![
        midspan_moment(),
        quarter_shear(),
        both_signs,
        smooth_line(),
    ]);
    prepared.block_seconds = 3600.0;
    let trucks = mixed_stream(2.0, 6000);
    let exceedances = 50;
    let mut peaks = EventPeaks::new(&prepared, exceedances);
    let mut rows = Vec::new();
    static_maxima_and_peaks(&prepared, trucks.clone(), &mut peaks, |block| {
        rows.extend_from_slice(block)
    })
    .unwrap();
    let (blocks, all) = every_event_maxima(&prepared, &trucks, exceedances);
    for (e, reference) in blocks.iter().enumerate() {
        let got: Vec<(f64, f64, usize)> = (rows.iter().filter(|r| r.effect == e))
            .map(|r| (r.value, r.time, r.trucks))
            .collect();
        assert_eq!(got.len(), reference.len(), "effect {e}: blocks");
        for (block, (g, r)) in got.iter().zip(reference).enumerate() {
            if r.2 == 0 {
                assert_eq!(g.0, 0.0, "effect {e}, block {block}");
            } else {
                assert_eq!(g, r, "effect {e}, block {block}");
            }
        }
        assert_eq!(peaks.values(e), all[e], "effect {e}: peaks");
    }
}

/// A smooth line of both signs tabulated at 121 knots, as an FE deflection or continuous-beam
/// moment line is: the coarse bound's simplification drops most of them.
fn smooth_line() -> EffectLine {
    let knots: Vec<f64> = (0..=120).map(|k| k as f64 * SPAN / 120.0).collect();
    let ordinates = (knots.iter())
        .map(|x| 5.0 * (std::f64::consts::PI * x / SPAN).sin() - 2.0 * (x / SPAN).powi(3))
        .collect();
    EffectLine::continuous(knots, ordinates).unwrap()
}

#[test]
fn the_extreme_bounds_are_never_below_the_computed_extreme_and_the_coarse_one_is_tight() {
    let lines = [midspan_moment(), quarter_shear(), smooth_line()];
    let prepared = analysis(lines.to_vec());
    assert!(ExtremeBounds::new(&prepared).coarse[2].0[0].knots().len() < 30);
    let bounds = ExtremeBounds::new(&prepared);
    let placed = placed(&mixed_stream(0.05, 3000));
    let mut events = 0;
    event::for_each_event(placed, |event| {
        events += 1;
        for (e, effect) in prepared.effects.iter().enumerate() {
            let x = event::event_extreme(event, &effect.lines, SPAN, effect.sense);
            let bound = bounds.bound(e, event);
            assert!(effect.sense * x.value <= bound, "{} > {bound}", x.value);
            let coarse = bounds.coarse_bound(e, event);
            assert!(effect.sense * x.value <= coarse, "{} > {coarse}", x.value);
            // Within 2 δ W of the exact extreme, δ = 1 % of the largest ordinate.
            let weight: f64 = event.iter().flat_map(|t| &t.loads).sum();
            let largest = effect.lines[0].dominant_ordinate().abs();
            assert!(coarse - effect.sense * x.value <= 2.0 * 0.01 * largest * weight);
            // The bound of one truck is its gross weight times the line's peak (L/4, 0.75).
            if event.len() == 1 {
                let weight: f64 = event[0].loads.iter().sum();
                let peak = effect.lines[0].dominant_ordinate().abs();
                assert!((bound - weight * peak).abs() <= 1e-13 * bound);
            }
        }
    })
    .unwrap();
    assert!(events > 1000, "{events} events");
}

#[test]
fn a_known_record_end_keeps_the_last_trucks_tail_in_the_last_block_and_hands_on_every_block() {
    // Two days of record: a truck crossing midnight at the end counts in day 1 (its extreme at
    // 2 days + 0.1 s); with four days of record it counts in day 2, and the fourth, empty, day
    // is handed on too.
    let p = 100e3;
    let day = SECONDS_PER_DAY;
    let trucks = vec![
        truck(100.0, 1, TravelDirection::Forward, &[], &[p]),
        truck(
            2.0 * day - 0.5,
            1,
            TravelDirection::Forward,
            &[],
            &[2.0 * p],
        ),
    ];
    let mut prepared = analysis(vec![midspan_moment()]);
    let (rows, _) = maxima(&prepared, trucks.clone());
    assert_eq!(
        rows.len(),
        3,
        "without an end: the tail makes a third block"
    );
    prepared.record_end = Some(2.0 * day);
    let (rows, counts) = maxima(&prepared, trucks.clone());
    assert_eq!(counts.blocks, 2);
    assert_eq!(rows[1].value, 2.0 * p * SPAN / 4.0);
    assert!(rows[1].time > 2.0 * day);
    prepared.record_end = Some(4.0 * day);
    let (rows, counts) = maxima(&prepared, trucks);
    assert_eq!(counts.blocks, 4);
    assert_eq!((rows[1].value, rows[1].trucks), (0.0, 0));
    assert_eq!(rows[2].value, 2.0 * p * SPAN / 4.0);
    assert_eq!((rows[3].value, rows[3].trucks), (0.0, 0));
}

#[test]
fn the_sweep_gives_the_extreme_of_evaluating_every_breakpoint_afresh() {
    // Every event of a mixed stream (1 to 5 axles, both directions, followers and meetings),
    // four lines (a kink, a jump, both signs, a smooth curve), both senses: the sweep's extreme
    // equals the direct evaluation's to rounding (a few ulps of the weight × the line's peak).
    let lines = [
        midspan_moment(),
        quarter_shear(),
        EffectLine::continuous(vec![0.0, 10.0, 20.0, SPAN], vec![0.0, -3.0, 1.0, 0.0]).unwrap(),
        smooth_line(),
    ];
    let placed = placed(&mixed_stream(0.1, 3000));
    let (mut events, mut several) = (0, 0);
    event::for_each_event(placed, |trucks| {
        events += 1;
        several += usize::from(trucks.len() > 1);
        // The event moved to t = 0: the direct evaluation reads positions off the record's
        // clock (t − t₀ loses t × 2⁻⁵² s, a position error of 2⁻⁵² × t × v), the sweep does not.
        let origin = trucks[0].arrival;
        let trucks: Vec<PlacedTruck> = (trucks.iter())
            .map(|t| PlacedTruck {
                arrival: t.arrival - origin,
                leaves: t.leaves - origin,
                ..t.clone()
            })
            .collect();
        let trucks = &trucks[..];
        let weight: f64 = trucks.iter().flat_map(|t| &t.loads).sum();
        for line in &lines {
            let pair = [line.clone(), line.clone()];
            let scale = weight * line.ordinate_range().0.abs().max(line.ordinate_range().1);
            for sense in [1.0, -1.0] {
                let sweep = event::event_extreme(trucks, &pair, SPAN, sense);
                let direct = event::event_extreme_at_breakpoints(trucks, &pair, SPAN, sense);
                assert!(
                    (sweep.value - direct.value).abs() <= 1e-14 * scale,
                    "{} against {} ({} trucks)",
                    sweep.value,
                    direct.value,
                    trucks.len()
                );
                if sweep.value != 0.0 {
                    // Its instant gives the value: the direct E there, or a one-sided limit.
                    let near = |dt: f64| event::effect_at(trucks, &pair, SPAN, sweep.time + dt);
                    let closest = [near(-1e-9), near(0.0), near(1e-9)]
                        .into_iter()
                        .map(|e| (e - sweep.value).abs())
                        .fold(f64::INFINITY, f64::min);
                    assert!(closest <= 1e-6 * scale, "{closest} at {}", sweep.time);
                }
            }
        }
    })
    .unwrap();
    assert!(
        events > 1000 && several > 100,
        "{events} events, {several} with several"
    );
}
