//! `vbi lifetime`: the daily static maxima of a traffic file against the closed form of a simple
//! span (the midspan moment's influence line x/2 | (L − x)/2 is extreme with an axle at its
//! kink, so a rigid group of axles has its largest moment with one of its axles at midspan), and
//! the refusals `vbi check` shares with it.

use std::path::{Path, PathBuf};

use vbi::traffic::RecordedTruck;
use vbi_input::traffic_file::{TrafficFileReader, TrafficFormat};

use crate::common::{repository_root, vbi};

const SPAN: f64 = 30.0;

fn example() -> PathBuf {
    repository_root().join("examples/lifetime/pybtls-20-trucks-1x30.toml")
}

fn trucks() -> Vec<RecordedTruck> {
    let path =
        repository_root().join("examples/lifetime/traffic/pybtls_written_20_trucks.castor.txt");
    TrafficFileReader::open(&path, TrafficFormat::Castor)
        .unwrap()
        .map(Result::unwrap)
        .collect()
}

/// The largest midspan moment [N·m] of a group of trucks at one speed (a rigid set of axles at
/// offsets `behind` [m] behind the first front axle): the largest over "axle j at midspan".
fn closed_form_midspan_moment(axles: &[(f64, f64)]) -> f64 {
    let line = |x: f64| {
        if (0.0..=SPAN).contains(&x) {
            x.min(SPAN - x) / 2.0
        } else {
            0.0
        }
    };
    axles
        .iter()
        .map(|&(at_midspan, _)| {
            axles
                .iter()
                .map(|&(behind, load)| load * line(SPAN / 2.0 - (behind - at_midspan)))
                .sum::<f64>()
        })
        .fold(0.0, f64::max)
}

fn block_maxima(out: &Path) -> Vec<(u64, String, String, f64)> {
    let text = std::fs::read_to_string(out.join("block_maxima.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("block,station,quantity,static,time_s,trucks")
    );
    lines
        .map(|line| {
            let cells: Vec<&str> = line.split(',').collect();
            (
                cells[0].parse().unwrap(),
                cells[1].into(),
                cells[2].into(),
                cells[3].parse().unwrap(),
            )
        })
        .collect()
}

#[test]
fn daily_midspan_moments_equal_the_simple_span_closed_form_of_each_day_s_trucks() {
    let dir = tempfile::tempdir().unwrap();
    vbi()
        .arg("lifetime")
        .arg(example())
        .arg("--out")
        .arg(dir.path())
        .assert()
        .success();
    // The trucks, grouped as they share the deck (all at 25 m/s: a group is rigid).
    let trucks = trucks();
    assert!(trucks.iter().all(|t| t.speed == 25.0));
    let mut expected = [0.0f64; 2];
    let mut group: Vec<(f64, f64)> = Vec::new();
    let mut group_start = f64::NEG_INFINITY;
    let mut group_leaves = f64::NEG_INFINITY;
    let mut close = |group: &mut Vec<(f64, f64)>, start: f64| {
        if !group.is_empty() {
            let day = (start / 86_400.0) as usize;
            expected[day] = expected[day].max(closed_form_midspan_moment(group));
            group.clear();
        }
    };
    for truck in &trucks {
        if truck.arrival_time > group_leaves {
            close(&mut group, group_start);
            group_start = truck.arrival_time;
        }
        let lead = (truck.arrival_time - group_start) * truck.speed;
        for (offset, load) in truck.axle_offsets().iter().zip(&truck.axle_loads) {
            group.push((lead + offset, *load));
        }
        group_leaves =
            group_leaves.max(truck.arrival_time + (SPAN + truck.wheelbase()) / truck.speed);
    }
    close(&mut group, group_start);
    let moments: Vec<(u64, f64)> = block_maxima(dir.path())
        .into_iter()
        .filter(|(_, station, quantity, _)| {
            station == "span1_mid_section" && quantity == "bending_moment"
        })
        .map(|(block, _, _, value)| (block, value))
        .collect();
    assert_eq!(moments.len(), 2);
    for (day, (block, value)) in moments.iter().enumerate() {
        assert_eq!(*block, day as u64);
        // The FE influence line's ordinates are exact to the static solve's round-off.
        assert!(
            (value - expected[day]).abs() < 1e-9 * expected[day],
            "day {day}: {value} against {}",
            expected[day]
        );
    }
    // PyBTLS 1.0.1 samples the same day 1 at 0.1 s: 3255.0 kN·m (docs/lifetime.md), at or below.
    assert!(
        moments[0].1 >= 3255.0e3 - 50.0 && moments[0].1 < 3255.0e3 * 1.0025,
        "{}",
        moments[0].1
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("lifetime.json")).unwrap())
            .unwrap();
    assert_eq!(summary["trucks"], 20);
    assert_eq!(summary["blocks"], 2);
}

#[test]
fn a_bad_traffic_line_and_an_unknown_lane_are_refused_by_check_and_by_lifetime_alike() {
    let dir = tempfile::tempdir().unwrap();
    let good = std::fs::read_to_string(
        repository_root().join("examples/lifetime/traffic/pybtls_written_20_trucks.castor.txt"),
    )
    .unwrap();
    let lines: Vec<&str> = good.lines().collect();
    // Line 3's speed made unreadable; line 2 in lane 2 of direction 1, which a beam's default
    // lanes (lane 1 of each direction) do not have.
    let bad_speed = format!(
        "{}\n{}\n{}X{}\n",
        lines[0],
        lines[1],
        &lines[2][..18],
        &lines[2][19..]
    );
    let bad_lane = format!("{}\n{}2{}\n", lines[0], &lines[1][..30], &lines[1][31..]);
    let toml = std::fs::read_to_string(example()).unwrap();
    for (traffic, expected) in [
        (bad_speed, "traffic.txt:3:19"),
        (bad_lane, "traffic.txt:2:1"),
    ] {
        std::fs::write(dir.path().join("traffic.txt"), &traffic).unwrap();
        let file = dir.path().join("lifetime.toml");
        std::fs::write(
            &file,
            toml.replace("traffic/pybtls_written_20_trucks.castor.txt", "traffic.txt"),
        )
        .unwrap();
        for command in [vec!["check"], vec!["lifetime", "--out"]] {
            let mut cmd = vbi();
            cmd.args(&command);
            if command.len() > 1 {
                cmd.arg(dir.path().join("out"));
            }
            let output = cmd.arg(&file).assert().code(2);
            let stderr = String::from_utf8_lossy(&output.get_output().stderr).to_string();
            // Both commands run the same stream (vbi_input::lifetime::run): the same located
            // message.
            assert!(stderr.contains(expected), "{command:?}: {stderr}");
            if expected.ends_with(":1") {
                assert!(
                    stderr.contains("lane 2 of direction 1"),
                    "{command:?}: {stderr}"
                );
            }
        }
        assert!(!dir.path().join("out/block_maxima.csv").exists());
    }
}

/// The rows of return_levels.csv as (station, quantity, model, period, [value, low, high,
/// bootstrap_low, bootstrap_high], loaded_blocks, [location, scale, shape]).
type LevelRow = (String, String, String, f64, [f64; 5], usize, [f64; 3]);

fn return_levels(out: &Path) -> Vec<LevelRow> {
    let text = std::fs::read_to_string(out.join("return_levels.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("station,quantity,model,period_years,return_level,low,high,bootstrap_low,bootstrap_high,fitted,location,scale,shape")
    );
    lines
        .map(|line| {
            let c: Vec<&str> = line.split(',').collect();
            let f = |i: usize| c[i].parse::<f64>().unwrap_or(f64::NAN);
            (
                c[0].into(),
                c[1].into(),
                c[2].into(),
                f(3),
                [f(4), f(5), f(6), f(7), f(8)],
                c[9].parse().unwrap(),
                [f(10), f(11), f(12)],
            )
        })
        .collect()
}

#[test]
fn return_levels_are_the_library_s_fits_of_the_written_block_maxima() {
    use vbi::statistics::extreme_value::ExtremeValueModel;
    let dir = tempfile::tempdir().unwrap();
    vbi()
        .arg("lifetime")
        .arg(repository_root().join("examples/lifetime/auxerre-3-days-hourly-1x30.toml"))
        .arg("--out")
        .arg(dir.path())
        .assert()
        .success();
    let maxima = block_maxima(dir.path());
    let rows = return_levels(dir.path());
    assert_parquet_is_the_csv(dir.path(), "block_maxima");
    assert_parquet_is_the_csv(dir.path(), "return_levels");
    // Three effects, three laws (GEV and Gumbel of the block maxima; GP of the peaks), two
    // periods.
    assert_eq!(rows.len(), 18);
    let (block_rows, peak_rows): (Vec<&LevelRow>, Vec<&LevelRow>) =
        rows.iter().partition(|row| row.2 != "gpd");
    assert_eq!(peak_rows.len(), 6);
    for (_, quantity, _, _, level, fitted, law) in &peak_rows {
        // 1000 exceedances (the default) over the threshold, each level above it.
        assert_eq!(*fitted, 1000);
        let sign = if quantity == "deflection" { -1.0 } else { 1.0 };
        assert!(sign * level[0] > law[0] && sign * level[1] < sign * level[0]);
        assert!(
            level[3].is_nan() && level[4].is_nan(),
            "no bootstrap for peaks"
        );
    }
    for (station, quantity, model, period, level, loaded, law) in block_rows {
        // The law is the library's fit of this effect's block maxima as magnitudes.
        let values: Vec<f64> = maxima
            .iter()
            .filter(|(_, s, q, _)| s == station && q == quantity)
            .map(|(_, _, _, v)| v.abs())
            .filter(|v| *v > 0.0)
            .collect();
        assert_eq!(values.len(), *loaded);
        let model = match model.as_str() {
            "gev" => ExtremeValueModel::Gev,
            "gumbel" => ExtremeValueModel::Gumbel,
            other => panic!("model {other}"),
        };
        let fit = model.fit(&values).unwrap();
        assert_eq!([fit.location, fit.scale, fit.shape], *law);
        // The level is its quantile of (1 − 1/T)^(b/d), b = 1 h, d = 250 days; the effect's sign.
        let p =
            vbi::statistics::extreme_value::non_exceedance_probability(*period, 1.0 / 24.0, 250.0);
        let sign = if quantity == "deflection" { -1.0 } else { 1.0 };
        assert_eq!(level[0], sign * fit.quantile(p));
        // Each interval holds the level.
        let [value, low, high, bootstrap_low, bootstrap_high] = level.map(|v| sign * v);
        assert!(low < value && value < high, "{quantity} {period}");
        assert!(
            bootstrap_low <= value && value <= bootstrap_high,
            "{quantity} {period}"
        );
    }
    // The return-level plot, as PNG and SVG.
    for extension in ["png", "svg"] {
        let figure = dir.path().join(format!("return_levels.{extension}"));
        assert!(
            std::fs::metadata(&figure).unwrap().len() > 1000,
            "{figure:?}"
        );
    }
    // A longer period has the higher level, by each law (rows of one law are consecutive).
    for pair in rows.chunks(2) {
        assert!(pair[1].4[0].abs() > pair[0].4[0].abs());
    }
}

#[test]
fn progress_goes_to_a_log_as_lines_of_the_traffic_file_read() {
    // Standard error is a pipe here: log lines, one per block at interval 0, the last at 100 %.
    let dir = tempfile::tempdir().unwrap();
    let traffic =
        repository_root().join("examples/lifetime/traffic/auxerre_3_days_2_lanes.castor.txt");
    let kilobytes = std::fs::metadata(&traffic).unwrap().len().div_ceil(1000);
    let done = vbi()
        .arg("lifetime")
        .arg(repository_root().join("examples/lifetime/auxerre-3-days-1x30.toml"))
        .args(["--progress-interval", "0", "--out"])
        .arg(dir.path())
        .assert()
        .success();
    let stderr = String::from_utf8_lossy(&done.get_output().stderr).to_string();
    let lines: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("progress: "))
        .collect();
    assert_eq!(lines.len(), 3, "{stderr}");
    let last = format!("progress: {kilobytes}/{kilobytes} kB of traffic (100.0 %), ");
    assert!(lines[2].starts_with(&last), "{}", lines[2]);
    assert!(lines[2].contains("ETA 0 s"), "{}", lines[2]);
}

/// The example's lifetime file with 10 days of traffic from vbi's generator (the test Grave
/// folder, seed `seed`) instead of its traffic file, in `dir`.
fn generated(dir: &Path, seed: u64) -> PathBuf {
    let data = repository_root().join("crates/vbi-input/tests/files/data/grave");
    let text = std::fs::read_to_string(example()).unwrap();
    let (head, bridge) = text.split_once("[bridge]").unwrap();
    let head = head
        .lines()
        .filter(|l| !l.starts_with("traffic_"))
        .collect::<Vec<_>>()
        .join("\n");
    let text = format!(
        "{head}\n[lifetime.generator]\nparameters = \"{}\"\nlane_flow_file = \"{}\"\ndays = 10\nseed = {seed}\n\n[bridge]{bridge}",
        data.join("site").display(),
        data.join("lane-flow.csv").display()
    );
    let path = dir.join(format!("generated-{seed}.toml"));
    std::fs::write(&path, text).unwrap();
    path
}

/// The example's lifetime file with dynamics, screening ratio `ratio`, in `dir`.
fn with_dynamics(dir: &Path, ratio: f64) -> PathBuf {
    let text = std::fs::read_to_string(example()).unwrap();
    let traffic = repository_root().join("examples/lifetime/traffic");
    let text = text
        .replace("\"traffic/", &format!("\"{}/", traffic.display()))
        .replace(
            "block_days = 1\n",
            &format!("block_days = 1\ndynamics = true\nscreening_ratio = {ratio}\n"),
        );
    let path = dir.join("dynamics.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// events.csv's rows: (event, station, quantity, static, crossing_static, total, time_s).
type EventRow = (u64, String, String, f64, f64, f64, f64);

fn event_rows(out: &Path) -> Vec<EventRow> {
    let text = std::fs::read_to_string(out.join("events.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("event,trucks,station,quantity,static,crossing_static,total,daf,time_s")
    );
    lines
        .map(|line| {
            let c: Vec<&str> = line.split(',').collect();
            let number = |i: usize| c[i].parse::<f64>().unwrap();
            let event = c[0].parse().unwrap();
            (
                event,
                c[2].into(),
                c[3].into(),
                number(4),
                number(5),
                number(6),
                number(8),
            )
        })
        .collect()
}

/// With dynamics: the static columns of block_maxima.csv are those of the static run, string
/// for string; each block's total is the largest total of its integrated events in events.csv;
/// each event's crossing has the lifetime's static extreme (its trucks carry their recorded
/// loads at their recorded times: the moment to 1e-9, the deflection within the tabulation
/// bound 1e-4, the shear within the crossing's sampling of its jump, 2 v Δt / L ≈ 1.7e-3); and
/// an event's total is the same whichever events the screening integrates.
/// Every cell of `table`.parquet in `out` equals its CSV cell: text as text, whole numbers as
/// unsigned integers, other numbers as the same double bit for bit, empty cells as nulls.
fn assert_parquet_is_the_csv(out: &Path, table: &str) {
    use parquet::file::reader::{FileReader, SerializedFileReader};
    use parquet::record::Field;
    let csv = std::fs::read_to_string(out.join(format!("{table}.csv"))).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    let file = std::fs::File::open(out.join(format!("{table}.parquet"))).unwrap();
    let reader = SerializedFileReader::new(file).unwrap();
    let rows: Vec<_> = reader
        .get_row_iter(None)
        .unwrap()
        .map(|r| r.unwrap())
        .collect();
    assert_eq!(rows.len() + 1, lines.len(), "{table}");
    let header: Vec<&str> = lines[0].split(',').collect();
    for (row, line) in rows.iter().zip(&lines[1..]) {
        let cells: Vec<&str> = line.split(',').collect();
        for ((name, field), (column, cell)) in row.get_column_iter().zip(header.iter().zip(&cells))
        {
            assert_eq!(name, column);
            match field {
                Field::Null => assert!(cell.is_empty(), "{table} {column}: {cell}"),
                Field::Str(text) => assert_eq!(text, cell),
                Field::ULong(value) => assert_eq!(value.to_string(), *cell),
                Field::Double(value) => {
                    assert_eq!(value.to_bits(), cell.parse::<f64>().unwrap().to_bits())
                }
                other => panic!("{table} {column}: {other:?}"),
            }
        }
    }
}

#[test]
fn dynamics_add_the_total_block_maxima_of_the_events_integrated_and_keep_the_static_ones() {
    let dir = tempfile::tempdir().unwrap();
    let run = |ratio: f64, out: &str| {
        let out = dir.path().join(out);
        vbi()
            .arg("lifetime")
            .arg(with_dynamics(dir.path(), ratio))
            .arg("--out")
            .arg(&out)
            .assert()
            .success();
        out
    };
    let fixed = dir.path().join("static");
    vbi()
        .args(["lifetime".as_ref(), example().as_os_str(), "--out".as_ref()])
        .arg(&fixed)
        .assert()
        .success();
    let every = run(0.0, "every");
    let text = std::fs::read_to_string(every.join("block_maxima.csv")).unwrap();
    let static_text = std::fs::read_to_string(fixed.join("block_maxima.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("block,station,quantity,static,time_s,trucks,total,daf")
    );
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    for (row, static_line) in rows.iter().zip(static_text.lines().skip(1)) {
        assert_eq!(row[..6].join(","), static_line);
    }
    let events = event_rows(&every);
    assert_parquet_is_the_csv(&every, "block_maxima");
    assert_parquet_is_the_csv(&every, "events");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(every.join("lifetime.json")).unwrap())
            .unwrap();
    assert_eq!(summary["dynamics"], true);
    assert_eq!(summary["dynamic_events"]["integrated"], 18);
    assert_eq!(summary["dynamic_events"]["refused"], 0);
    for name in ["daf_against_static.png", "daf_against_static.svg"] {
        assert!(every.join(name).exists(), "{name}");
    }
    // The codes' DAFs beside each effect's total, without the fatigue factors.
    let codes = summary["effects"][1]["total"]["design_codes"]
        .as_array()
        .unwrap();
    assert!(codes
        .iter()
        .any(|c| c["code"] == "AASHTO LRFD" && c["daf"] == 1.33));
    for row in &rows {
        let (block, total): (u64, f64) = (row[0].parse().unwrap(), row[6].parse().unwrap());
        let largest = events
            .iter()
            .filter(|e| e.1 == row[1] && e.2 == row[2] && (e.6 / 86_400.0) as u64 == block)
            .map(|e| e.5)
            .fold(0.0f64, |a, b| if b.abs() > a.abs() { b } else { a });
        assert_eq!(total, largest, "block {block} {} {}", row[1], row[2]);
    }
    for (event, _, quantity, fixed, crossing, _, _) in &events {
        let tolerance = match quantity.as_str() {
            "bending_moment" => 1e-9,
            "deflection" => 1e-4,
            _ => 2.0 * 25.0 * 1e-3 / SPAN,
        };
        let relative = (crossing - fixed).abs() / fixed.abs();
        assert!(
            relative < tolerance,
            "event {event} {quantity}: {relative:e}"
        );
    }
    let screened = run(0.9, "screened");
    let screened_events = event_rows(&screened);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(screened.join("lifetime.json")).unwrap())
            .unwrap();
    let integrated = summary["dynamic_events"]["integrated"].as_u64().unwrap();
    assert!(
        (2..18).contains(&integrated),
        "{integrated} events integrated"
    );
    for row in &screened_events {
        assert!(events.contains(row), "event {}'s row {row:?}", row.0);
    }
}

/// Each effect's governing event, written as a `vbi run` scenario, replays: the run's dynamic
/// extreme of the effect is the largest total of events.csv, bit for bit (the same vehicles,
/// speeds written to read back exactly, the same road seed; every effect here is read by
/// `vbi run` in its own sense, the events' static extremes being of that sign).
#[test]
fn the_governing_events_replay_as_vbi_run_scenarios_with_the_same_totals() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    vbi()
        .arg("lifetime")
        .arg(with_dynamics(dir.path(), 0.9))
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let events = event_rows(&out);
    for quantity in ["deflection", "bending_moment", "shear_force"] {
        let largest = events
            .iter()
            .filter(|e| e.2 == quantity)
            .map(|e| e.5)
            .fold(0.0f64, |a, b| if b.abs() > a.abs() { b } else { a });
        let scenario = out
            .join("governing")
            .join(format!("span1_mid_section-{quantity}"))
            .join("scenario.toml");
        let replay = dir.path().join(format!("replay-{quantity}"));
        vbi()
            .arg("run")
            .arg(&scenario)
            .arg("--out")
            .arg(&replay)
            .assert()
            .success();
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(replay.join("summary.json")).unwrap())
                .unwrap();
        let entry = summary["stations"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["name"] == "span1_mid_section" && s["quantity"] == quantity)
            .unwrap();
        assert_eq!(
            entry["dynamic_max"].as_f64().unwrap(),
            largest,
            "{quantity}"
        );
    }
}

/// A lifetime of simulated traffic (`[lifetime.generator]`, the test site's made-up Grave
/// parameters and lane flows): the same seed gives the same block maxima string for string,
/// another seed other ones, and the number of trucks is the lane flows' total over the days
/// within 4 Poisson standard deviations (the minimum-gap thinning at these flows, well under
/// 1 %, is inside that band: 4σ is 2.3 % of the 30,000 trucks).
#[test]
fn generated_traffic_runs_at_its_lane_flows_and_is_the_same_for_the_same_seed() {
    let data = repository_root().join("crates/vbi-input/tests/files/data/grave");
    let dir = tempfile::tempdir().unwrap();
    let file = |seed: u64| generated(dir.path(), seed);
    let run = |seed: u64, out: &str| {
        let out = dir.path().join(out);
        vbi()
            .arg("lifetime")
            .arg(file(seed))
            .arg("--out")
            .arg(&out)
            .assert()
            .success();
        out
    };
    let (first, again, other) = (run(7, "first"), run(7, "again"), run(8, "other"));
    let maxima = |out: &Path| std::fs::read_to_string(out.join("block_maxima.csv")).unwrap();
    assert_eq!(maxima(&first), maxima(&again));
    assert_ne!(maxima(&first), maxima(&other));
    vbi().arg("check").arg(file(7)).assert().success();
    // The lane flows' total [trucks a day]: the second field of every block row.
    let flows = std::fs::read_to_string(data.join("lane-flow.csv")).unwrap();
    let per_day: f64 = flows
        .lines()
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|f| f.len() >= 9 && !f[2].is_empty())
        .map(|f| f[1].parse::<f64>().unwrap())
        .sum();
    let expected = 10.0 * per_day;
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(first.join("lifetime.json")).unwrap())
            .unwrap();
    let trucks = summary["trucks"].as_f64().unwrap();
    assert!(
        (trucks - expected).abs() < 4.0 * expected.sqrt(),
        "{trucks} trucks against {expected}"
    );
    assert_eq!(summary["traffic_format"], "generator");
    assert_eq!(summary["blocks"], 10);
}

/// Runs `vbi lifetime FILE --out DIR` with `extra` arguments, successfully.
fn lifetime_run(file: &Path, out: &Path, extra: &[&str]) -> String {
    let done = vbi()
        .arg("lifetime")
        .arg(file)
        .arg("--out")
        .arg(out)
        .args(extra)
        .assert()
        .success();
    String::from_utf8_lossy(&done.get_output().stdout).to_string()
}

/// `vbi lifetime FILE --shard I/N` for each shard, then `vbi lifetime merge` of their
/// directories (given last first): every file of the single run's directory, byte for byte,
/// the figures and Parquet tables among them. `--resume` leaves a finished shard alone.
fn assert_shards_merge_to_the_single_run(file: &Path, count: usize, dir: &Path) {
    let whole = dir.join("whole");
    lifetime_run(file, &whole, &[]);
    let mut shards = Vec::new();
    for index in 1..=count {
        let out = dir.join(format!("shard-{index}"));
        lifetime_run(file, &out, &["--shard", &format!("{index}/{count}")]);
        shards.push(out);
    }
    let again = lifetime_run(
        file,
        &shards[0],
        &["--shard", &format!("1/{count}"), "--resume"],
    );
    assert!(again.contains("nothing to run"), "{again}");
    shards.reverse();
    let merged = dir.join("merged");
    vbi()
        .args(["lifetime", "merge"])
        .arg(file)
        .arg("--out")
        .arg(&merged)
        .args(&shards)
        .assert()
        .success();
    let files = |root: &Path| {
        let mut files = Vec::new();
        let mut stack = vec![root.to_path_buf()];
        while let Some(directory) = stack.pop() {
            for entry in std::fs::read_dir(&directory).unwrap() {
                let path = entry.unwrap().path();
                match path.is_dir() {
                    true => stack.push(path),
                    false => files.push(path.strip_prefix(root).unwrap().to_path_buf()),
                }
            }
        }
        files.retain(|f| f != Path::new(".vbi.lock"));
        files.sort();
        files
    };
    assert_eq!(files(&merged), files(&whole));
    for name in files(&whole) {
        let (a, b) = (whole.join(&name), merged.join(&name));
        assert!(
            std::fs::read(&a).unwrap() == std::fs::read(&b).unwrap(),
            "{} differs",
            name.display()
        );
    }
    // Shards that are not one run's N are refused (exit 2).
    vbi()
        .args(["lifetime", "merge"])
        .arg(file)
        .arg("--out")
        .arg(dir.join("refused"))
        .args(&shards[1..])
        .assert()
        .code(2);
}

/// Shards merged give the single run's files byte for byte: the example's traffic file with
/// dynamics on every event (r = 0) in hourly blocks, 4 shards (the events of 2 days spread over
/// 48 blocks: some shards hold none), and 10 days of generated traffic (its end known), static,
/// in 3 shards.
#[test]
fn shards_merged_give_the_single_run_s_files_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let hourly = dir.path().join("hourly");
    std::fs::create_dir(&hourly).unwrap();
    let file = with_dynamics(&hourly, 0.0);
    let text = std::fs::read_to_string(&file).unwrap();
    let text = text.replace("block_days = 1\n", "block_days = 0.041666666666666664\n");
    std::fs::write(&file, text).unwrap();
    assert_shards_merge_to_the_single_run(&file, 4, &hourly);
    let generated_dir = dir.path().join("generated");
    std::fs::create_dir(&generated_dir).unwrap();
    let file = generated(&generated_dir, 3);
    assert_shards_merge_to_the_single_run(&file, 3, &generated_dir);
}

/// `vbi report DIR` of a lifetime's directory: its key results carry lifetime.json's numbers
/// (the GEV 100-year level of the hourly example's midspan moment, in kN·m to four significant
/// digits), and flag that level's interval as too wide to sign; a static run
/// has no assessment section; with dynamics, the report has the assessment DAF's section and
/// each governing event's `vbi run` command, and says why three days have no level.
#[test]
fn the_lifetime_report_shows_lifetime_json_s_levels_and_flags_a_wide_interval() {
    let dir = tempfile::tempdir().unwrap();
    let hourly = dir.path().join("hourly");
    let file = repository_root().join("examples/lifetime/auxerre-3-days-hourly-1x30.toml");
    lifetime_run(&file, &hourly, &[]);
    vbi().arg("report").arg(&hourly).assert().success();
    let html = std::fs::read_to_string(hourly.join("report.html")).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(hourly.join("lifetime.json")).unwrap())
            .unwrap();
    let moment = &summary["effects"][1];
    assert_eq!(moment["quantity"], "bending_moment");
    let gev = &moment["fits"]["fits"][0];
    assert_eq!(gev["model"], "gev");
    // The key results show the first return period's level (100 years here).
    let level = gev["return_levels"][0]["value"].as_f64().unwrap();
    let shown = format!("static {:.0} kN·m (GEV", level / 1e3);
    assert!(html.contains(&shown), "{shown} not in the report");
    assert!(html.contains("the GEV interval is too wide to sign"));
    assert!(!html.contains("id=\"assessment-daf\""));
    assert!(html.contains("return_levels") || html.contains("Return levels"));
    let dynamics = dir.path().join("dynamics");
    std::fs::create_dir(&dynamics).unwrap();
    let file = with_dynamics(&dynamics, 0.7);
    let out = dynamics.join("out");
    lifetime_run(&file, &out, &[]);
    vbi().arg("report").arg(&out).assert().success();
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.contains("id=\"assessment-daf\""));
    assert!(html.contains("no characteristic value: 2 block maxima are too few"));
    let scenario = out.join("governing/span1_mid_section-bending_moment/scenario.toml");
    assert!(scenario.is_file());
    assert!(html.contains(&format!("vbi run {}", scenario.display())));
}

/// `[[lifetime.road_change]]`: the events that start from its year on are integrated on its
/// road, the others on the crossing's, each exactly as a run on that road throughout gives it
/// (events.csv's rows, string for string: an event's total is its own crossing's); a governing
/// event of a later year is replayed on its year's road. Two days of the example's traffic, a
/// year of one day (`days_per_year = 1`), 'good' then 'poor' from year 1.
#[test]
fn a_road_change_integrates_the_later_events_on_the_later_road() {
    let dir = tempfile::tempdir().unwrap();
    let file = |name: &str, road: &str, change: bool| {
        let base = with_dynamics(dir.path(), 0.0);
        let text = std::fs::read_to_string(&base).unwrap();
        let mut text = text.replace("dynamics = true\n", "dynamics = true\ndays_per_year = 1\n");
        text.push_str(&format!(
            "\n[lifetime.crossing]\nroad = \"{road}\"\nmodes = 8\n"
        ));
        if change {
            text.push_str("\n[[lifetime.road_change]]\nfrom_year = 1\nroad = \"poor\"\n");
        }
        let path = dir.path().join(format!("{name}.toml"));
        std::fs::write(&path, text).unwrap();
        path
    };
    let run = |name: &str, road: &str, change: bool| {
        let out = dir.path().join(name);
        lifetime_run(&file(name, road, change), &out, &[]);
        let text = std::fs::read_to_string(out.join("events.csv")).unwrap();
        let rows: Vec<String> = text.lines().skip(1).map(String::from).collect();
        (out, rows)
    };
    let (_, good) = run("good", "good", false);
    let (_, poor) = run("poor", "poor", false);
    let (changed_out, changed) = run("changed", "good", true);
    assert_eq!(changed.len(), good.len());
    let day = |row: &str| {
        let time: f64 = row.rsplit(',').next().unwrap().parse().unwrap();
        (time / 86_400.0).floor() as u64
    };
    let (mut early, mut late) = (0, 0);
    for ((row, on_good), on_poor) in changed.iter().zip(&good).zip(&poor) {
        match day(row) {
            0 => (early += 1, assert_eq!(row, on_good)).1,
            _ => (late += 1, assert_eq!(row, on_poor)).1,
        }
    }
    assert!(early > 0 && late > 0, "{early} early and {late} late rows");
    assert_ne!(good, poor);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(changed_out.join("lifetime.json")).unwrap())
            .unwrap();
    assert_eq!(summary["dynamic_events"]["road"], "good; from year 1 poor");
    for entry in std::fs::read_dir(changed_out.join("governing")).unwrap() {
        let scenario =
            std::fs::read_to_string(entry.unwrap().path().join("scenario.toml")).unwrap();
        let event: u64 = scenario
            .split(": event ")
            .nth(1)
            .and_then(|s| s.split(',').next())
            .unwrap()
            .parse()
            .unwrap();
        let row = changed
            .iter()
            .find(|r| r.starts_with(&format!("{event},")))
            .unwrap();
        let on_poor = day(row) >= 1;
        assert_eq!(scenario.contains("road = \"poor\""), on_poor, "{scenario}");
        assert_eq!(scenario.contains("road = \"good\""), !on_poor, "{scenario}");
    }
}
