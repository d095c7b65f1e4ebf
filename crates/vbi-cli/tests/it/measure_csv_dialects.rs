//! End-to-end tests of `[measurement.csv_format]`: the CSV files that data loggers write
//! (examples/measurements/dialects: ../field_4x30/fast.csv, SYNTHETIC, rewritten as a catman /
//! Excel export and as a Campbell TOA5 file), and the located refusal of a file read with the
//! wrong dialect, by `vbi check` and `vbi measure` alike.

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::common::{check_and_measure as measure, repository_root, vbi};

/// The channels without their CSV column and unit names, which differ between the dialects.
fn channels_without_names(report: &Value) -> Value {
    let mut channels = report["channels"].clone();
    for c in channels.as_array_mut().expect("channels") {
        let c = c.as_object_mut().expect("a channel object");
        c.remove("column");
        c.remove("unit");
    }
    channels
}

#[test]
fn the_catman_and_toa5_examples_give_the_numbers_of_the_plain_csv_bit_for_bit() {
    // Reference: examples/measurements/field_4x30/fast.toml on its plain CSV; generate.py keeps
    // every digit and each timestamp is fast.csv's time exactly, so the parsed values, and so
    // every number of the report, are identical.
    let examples = repository_root().join("examples/measurements");
    let dir = tempfile::tempdir().unwrap();
    let plain = measure(
        &examples.join("field_4x30/fast.toml"),
        &dir.path().join("plain"),
    );
    assert!(!plain["identified_frequencies"]
        .as_array()
        .unwrap()
        .is_empty());
    for (name, units) in [
        ("catman_excel", ["mm", "µm/m"]),
        ("campbell_toa5", ["mm", "microstrain"]),
    ] {
        let file = examples.join(format!("dialects/{name}.toml"));
        let report = measure(&file, &dir.path().join(name));
        assert_eq!(
            channels_without_names(&report),
            channels_without_names(&plain),
            "{name}"
        );
        assert_eq!(
            report["identified_frequencies"], plain["identified_frequencies"],
            "{name}"
        );
        let got: Vec<&str> = report["channels"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["unit"].as_str().unwrap())
            .collect();
        assert_eq!(got, units, "{name}: the units of the unit line or the TOML");
    }
}

/// A clean record: time at 100 Hz and a deflection bump −sin²(πt/4) mm over 4 s, as rows
/// `(time, value)` of text with a decimal point.
fn samples() -> Vec<(String, String)> {
    (0..600)
        .map(|i| {
            let t = i as f64 / 100.0;
            let u = if t <= 4.0 {
                -(std::f64::consts::PI * t / 4.0).sin().powi(2)
            } else {
                0.0
            };
            (format!("{t:.2}"), format!("{u:.6}"))
        })
        .collect()
}

/// The rows joined by `separator`, with decimal commas when `comma`.
fn rows(separator: &str, comma: bool) -> String {
    samples()
        .iter()
        .map(|(t, u)| {
            let row = format!("{t}{separator}{u}\n");
            if comma {
                row.replace('.', ",")
            } else {
                row
            }
        })
        .collect()
}

const DEFLECTION: &str = "[[measurement.channels]]\nname = \"u\"\nkind = \"deflection\"\n";

/// Writes `m.toml` (the `[measurement]` keys, then `format` as the csv_format table's keys,
/// then the channel) and `m.csv` (bytes).
fn write_case(dir: &Path, format: &str, channel: &str, csv: &[u8]) -> PathBuf {
    let toml = format!(
        "[measurement]\ncsv = \"m.csv\"\ntime_column = \"time_s\"\n\
         [measurement.filter]\ncutoff_hz = 2.0\n\
         [measurement.csv_format]\n{format}\n{channel}"
    );
    std::fs::write(dir.join("m.csv"), csv).unwrap();
    let path = dir.join("m.toml");
    std::fs::write(&path, toml).unwrap();
    path
}

/// `vbi check` and `vbi measure` on the case: both exit 2 with the same located message
/// (standard error), which is returned.
fn refused(path: &Path) -> String {
    let check = vbi().arg("check").arg(path).assert().code(2);
    let check = String::from_utf8_lossy(&check.get_output().stderr).to_string();
    let measure = vbi()
        .arg("measure")
        .arg(path)
        .arg("--out")
        .arg(path.parent().unwrap().join("out"))
        .assert()
        .code(2);
    let measure = String::from_utf8_lossy(&measure.get_output().stderr).to_string();
    let first_error = |s: &str| {
        s.lines()
            .find(|l| l.starts_with("error: "))
            .unwrap_or("")
            .to_string()
    };
    assert_eq!(first_error(&check), first_error(&measure));
    check
}

/// The case refused with a message that holds every needle.
fn assert_refused(format: &str, channel: &str, csv: &[u8], needles: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let path = write_case(dir.path(), format, channel, csv);
    let e = refused(&path);
    for needle in needles {
        assert!(e.contains(needle), "`{needle}` not in: {e}");
    }
}

#[test]
fn a_decimal_comma_read_without_the_decimal_key_is_named_at_its_line() {
    let csv = format!("time_s;u\n{}", rows(";", true));
    assert_refused(
        "delimiter = \";\"",
        &format!("{DEFLECTION}unit = \"mm\"\n"),
        csv.as_bytes(),
        &[
            "m.csv:2:1: field `time_s`: `0,00` is not a number",
            "this looks like a decimal comma; set csv_format.decimal = \",\"",
        ],
    );
    // Comma-separated with decimal commas: each row splits into twice the columns.
    let csv = format!("time_s,u\n{}", rows(",", true));
    assert_refused(
        "",
        &format!("{DEFLECTION}unit = \"mm\"\n"),
        csv.as_bytes(),
        &[
            "m.csv:2:1: this row has 4 fields but the header has 2",
            "this looks like a decimal comma",
            "csv_format.decimal = \",\"",
        ],
    );
}

#[test]
fn a_semicolon_file_read_without_the_delimiter_key_is_named() {
    // With decimal commas: the first row splits at its commas.
    let csv = format!("time_s;u\n{}", rows(";", true));
    assert_refused(
        "",
        &format!("{DEFLECTION}unit = \"mm\"\n"),
        csv.as_bytes(),
        &[
            "m.csv:2:1: this row has 3 fields but the header has 1",
            "the header (line 1) is one cell holding `;`: set csv_format.delimiter = \";\"",
            "csv_format.decimal = \",\" too",
        ],
    );
    // With decimal points: the rows read as one cell, and the time column is not found.
    let csv = format!("time_s;u\n{}", rows(";", false));
    assert_refused(
        "",
        &format!("{DEFLECTION}unit = \"mm\"\n"),
        csv.as_bytes(),
        &[
            "m.toml:3:1: field `measurement.time_column`: column `time_s` is not in",
            "the header (line 1) is one cell holding `;`: set csv_format.delimiter = \";\"",
        ],
    );
}

#[test]
fn header_and_unit_lines_that_do_not_fit_are_refused_at_their_key() {
    let csv = format!("# SYNTHETIC\ntime_s,u\n{}", rows(",", false));
    let unit = format!("{DEFLECTION}unit = \"mm\"\n");
    assert_refused(
        "header_line = 900",
        &unit,
        csv.as_bytes(),
        &[
            "m.toml:7:1: field `measurement.csv_format.header_line`",
            "line 900 is beyond the end of",
            "m.csv, which has 602 lines",
        ],
    );
    assert_refused(
        "header_line = 2\nunit_line = 2",
        &unit,
        csv.as_bytes(),
        &[
            "m.toml:8:1: field `measurement.csv_format.unit_line`",
            "is the header_line",
        ],
    );
    // The header found by default (after the comment) taken for the unit line.
    assert_refused(
        "unit_line = 2",
        &unit,
        csv.as_bytes(),
        &[
            "m.toml:7:1: field `measurement.csv_format.unit_line`",
            "the line of the column names",
        ],
    );
    assert_refused(
        "unit_line = 700",
        &unit,
        csv.as_bytes(),
        &["field `measurement.csv_format.unit_line`", "beyond the end"],
    );
}

#[test]
fn keys_of_the_wrong_kind_or_value_are_refused_with_what_is_allowed() {
    let csv = format!("time_s;u\n{}", rows(";", true));
    let unit = format!("{DEFLECTION}unit = \"mm\"\n");
    for (format, key, needle) in [
        ("decimal = \",\"", "decimal", "ambiguous"),
        ("delimiter = \"|\"", "delimiter", "\"whitespace\""),
        (
            "delimiter = \";\"\ndecimal = \"·\"",
            "decimal",
            "expected \".\" or \",\"",
        ),
        ("header_line = 0", "header_line", "numbered from 1"),
        ("comment = \"//\"", "comment", "one ASCII character"),
        ("time_format = \"iso\"", "time_format", "\"timestamp\""),
        ("separator = \";\"", "separator", "unknown field"),
    ] {
        assert_refused(
            format,
            &unit,
            csv.as_bytes(),
            &["m.toml:", &format!("measurement.csv_format.{key}"), needle],
        );
    }
}

#[test]
fn units_from_the_unit_line_are_checked_like_the_unit_key() {
    let good = |units: &str| format!("time_s,u\n{units}\n{}", rows(",", false));
    // Not a deflection unit: refused at the unit line's cell, with the allowed units.
    assert_refused(
        "unit_line = 2",
        DEFLECTION,
        good("s,furlong").as_bytes(),
        &[
            "m.csv:2:2: field `u`: unit `furlong` (csv_format.unit_line) is not allowed",
            "expected one of m, cm, mm",
            "measurement.channels[0].unit",
        ],
    );
    // Given in both places and different: both named.
    assert_refused(
        "unit_line = 2",
        &format!("{DEFLECTION}unit = \"mm\"\n"),
        good("s,m").as_bytes(),
        &[
            "field `measurement.channels[0].unit`: unit `mm` differs from `m`",
            "(line 2, csv_format.unit_line)",
        ],
    );
    // In neither place.
    assert_refused(
        "unit_line = 2",
        DEFLECTION,
        good("s,").as_bytes(),
        &[
            "field `measurement.channels[0].unit`",
            "has no unit for column `u`",
        ],
    );
    // A time column in another unit than seconds.
    assert_refused(
        "unit_line = 2",
        DEFLECTION,
        good("ms,mm").as_bytes(),
        &["m.csv:2:1: field `time_s`: the time column's unit is `ms`"],
    );
    // The same unit under another name is accepted, and a Latin-1 µ reads as µ.
    let dir = tempfile::tempdir().unwrap();
    let mut csv = b"time_s;u\ns;\xB5m/m\n".to_vec();
    csv.extend_from_slice(rows(";", true).as_bytes());
    let path = write_case(
        dir.path(),
        "delimiter = \";\"\ndecimal = \",\"\nunit_line = 2",
        "[[measurement.channels]]\nname = \"u\"\nkind = \"strain\"\nunit = \"microstrain\"\n",
        &csv,
    );
    vbi().arg("check").arg(&path).assert().success();
}

#[test]
fn timestamps_are_read_and_a_bad_one_is_refused_at_its_line() {
    let stamped = |bad: Option<usize>| -> String {
        let mut csv = String::from("\"time_s\",\"u\"\r\n");
        for (i, (_, u)) in samples().iter().enumerate() {
            // 100 Hz from 23:59:58 on the last day of 2025: the year rolls over.
            let ms = 86_398_000 + 10 * i;
            let (day, ms) = if ms >= 86_400_000 {
                ("2026-01-01", ms - 86_400_000)
            } else {
                ("2025-12-31", ms)
            };
            let (h, m, s, f) = (ms / 3_600_000, ms / 60_000 % 60, ms / 1000 % 60, ms % 1000);
            let sep = if Some(i) == bad { "x" } else { "T" };
            csv.push_str(&format!(
                "\"{day}{sep}{h:02}:{m:02}:{s:02}.{f:03}\",{u}\r\n"
            ));
        }
        csv
    };
    let dir = tempfile::tempdir().unwrap();
    let path = write_case(
        dir.path(),
        "time_format = \"timestamp\"",
        &format!("{DEFLECTION}unit = \"mm\"\n"),
        stamped(None).as_bytes(),
    );
    vbi().arg("check").arg(&path).assert().success();
    assert_refused(
        "time_format = \"timestamp\"",
        &format!("{DEFLECTION}unit = \"mm\"\n"),
        stamped(Some(250)).as_bytes(),
        &[
            "m.csv:252:1: field `time_s`: `2026-01-01x00:00:00.500` is not a timestamp",
            "csv_format.time_format",
        ],
    );
    // Timestamps read as seconds: the key is named.
    assert_refused(
        "",
        &format!("{DEFLECTION}unit = \"mm\"\n"),
        stamped(None).as_bytes(),
        &[
            "m.csv:2:1: field `time_s`",
            "this looks like a timestamp; set csv_format.time_format = \"timestamp\"",
        ],
    );
}
