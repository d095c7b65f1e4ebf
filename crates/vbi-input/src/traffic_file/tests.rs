//! The traffic readers against files PyBTLS 1.0.1 wrote (`pybtls.garage.write_garage_file`
//! of the same 20 trucks in its four formats, examples/lifetime/traffic/), and against the
//! values PyBTLS itself reads from them (`Vehicle._get_all_properties`, `get_time`).

use std::path::PathBuf;

use super::*;

/// Writes `trucks` as vbi's CSV: times, speeds and
/// spacings in SI with the shortest text that reads back bit for bit, loads in kN (N → kN → N
/// may move the last bit).
fn write_csv(trucks: &[RecordedTruck]) -> String {
    let mut out = format!("{CSV_HEADER}\n");
    let join = |values: &[f64], unit: f64| {
        values
            .iter()
            .map(|v| format!("{}", v / unit))
            .collect::<Vec<_>>()
            .join(";")
    };
    for t in trucks {
        out.push_str(&format!(
            "{},{},{},{},{},{}\n",
            t.arrival_time,
            if t.direction == TravelDirection::Forward {
                1
            } else {
                2
            },
            t.lane,
            t.speed,
            join(&t.axle_spacings, 1.0),
            join(&t.axle_loads, KN),
        ));
    }
    out
}

fn example(format: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/lifetime/traffic")
        .join(format!("pybtls_written_20_trucks.{format}.txt"))
}

fn read(format: &str) -> Vec<RecordedTruck> {
    let kind = TrafficFormat::from_name(format).unwrap();
    TrafficFileReader::open(&example(format), kind)
        .unwrap()
        .collect::<Result<Vec<_>, _>>()
        .unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0)
}

fn same(a: &RecordedTruck, b: &RecordedTruck) -> bool {
    close(a.arrival_time, b.arrival_time)
        && a.lane == b.lane
        && a.direction == b.direction
        && close(a.speed, b.speed)
        && a.axle_loads.len() == b.axle_loads.len()
        && a.axle_spacings.len() == b.axle_spacings.len()
        && a.axle_loads
            .iter()
            .zip(&b.axle_loads)
            .all(|(x, y)| close(*x, *y))
        && a.axle_spacings
            .iter()
            .zip(&b.axle_spacings)
            .all(|(x, y)| close(*x, *y))
}

#[test]
fn the_four_formats_pybtls_wrote_read_to_the_same_trucks() {
    let castor = read("castor");
    assert_eq!(castor.len(), 20);
    for format in ["bedit", "ditis", "mon"] {
        let other = read(format);
        assert_eq!(other.len(), 20, "{format}");
        for (i, (a, b)) in castor.iter().zip(&other).enumerate() {
            assert!(same(a, b), "{format} truck {}: {a:?} against {b:?}", i + 1);
        }
    }
}

#[test]
fn truck_9_reads_as_pybtls_reads_it() {
    // pybtls 1.0.1: Vehicle._get_all_properties() of line 9 = (9, 1, 1, 0, 8, 40, 0.0, 5, 0,
    // 576.828, 25.0, 15.2, 1, 1, 1.8, [96.138, 151.074, 109.872, 109.872, 109.872],
    // [3.6, 1.3, 6.0, 1.3, 0.0], …) and get_time() = 31200.0.
    for format in ["castor", "bedit", "ditis", "mon"] {
        let truck = &read(format)[8];
        assert!(close(truck.arrival_time, 31_200.0), "{format}");
        assert_eq!((truck.lane, truck.direction), (1, TravelDirection::Forward));
        assert!(close(truck.speed, 25.0));
        let loads_kn: Vec<f64> = truck.axle_loads.iter().map(|w| w / 1e3).collect();
        for (got, expected) in loads_kn
            .iter()
            .zip([96.138, 151.074, 109.872, 109.872, 109.872])
        {
            assert!((got - expected).abs() < 1e-9, "{format}: {loads_kn:?}");
        }
        for (got, expected) in truck.axle_spacings.iter().zip([3.6, 1.3, 6.0, 1.3]) {
            assert!(
                (got - expected).abs() < 1e-12,
                "{format}: {:?}",
                truck.axle_spacings
            );
        }
        assert!((truck.gross_weight() / 1e3 - 576.828).abs() < 1e-9);
    }
}

#[test]
fn vbi_csv_reads_back_what_it_wrote_to_the_last_bits() {
    let trucks = read("mon");
    let dir = std::env::temp_dir().join(format!("vbi-traffic-csv-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("trucks.csv");
    std::fs::write(&path, write_csv(&trucks)).unwrap();
    let back: Vec<RecordedTruck> = TrafficFileReader::open(&path, TrafficFormat::Csv)
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap();
    // Times, speeds and spacings are SI in the file and read back bit for bit; loads are in
    // kN, so that N → kN → N may move the last bit.
    assert_eq!(back.len(), trucks.len());
    for (a, b) in back.iter().zip(&trucks) {
        assert_eq!(
            (a.arrival_time, a.speed, &a.axle_spacings),
            (b.arrival_time, b.speed, &b.axle_spacings)
        );
        assert!(same(a, b), "{a:?} against {b:?}");
    }
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn bad_lines_are_refused_with_their_line_column_and_field() {
    let dir = std::env::temp_dir().join(format!("vbi-traffic-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let good = std::fs::read_to_string(example("castor")).unwrap();
    let first = good.lines().next().unwrap().to_string();
    let cases = [
        (
            format!("{}\n{}X{}", first, &first[..18], &first[19..]),
            (2, 19),
            "speed",
        ),
        (
            format!("{}3{}", &first[..29], &first[30..]),
            (1, 30),
            "direction",
        ),
        (first[..40].to_string(), (1, 40), "axle 2 weight"),
    ];
    for (text, location, field) in cases {
        let path = dir.join("bad.txt");
        std::fs::write(&path, &text).unwrap();
        let error = TrafficFileReader::open(&path, TrafficFormat::Castor)
            .unwrap()
            .find_map(Result::err)
            .unwrap_or_else(|| panic!("{text:?} was read"));
        assert_eq!(error.location, Some(location), "{error}");
        assert_eq!(error.field.as_deref(), Some(field), "{error}");
    }
    std::fs::remove_dir_all(dir).ok();
}
