//! `vbi lifetime` with fatigue details (issue 51): fatigue.csv holds the rows of the table of
//! lifetime fatigue outputs, each block's damages (fatigue_blocks.csv) sum to the record's, and
//! a shard is refused (rainflow carries the residue across the whole record).

use crate::common::{repository_root, vbi};

fn column(table: &str, name: &str) -> Vec<String> {
    let mut reader = csv::Reader::from_reader(table.as_bytes());
    let at = (reader.headers().unwrap().iter())
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    (reader.records())
        .map(|r| r.unwrap()[at].to_string())
        .collect()
}

#[test]
fn lifetime_fatigue_tables_hold_the_record_s_damage_and_each_day_s() {
    let example = repository_root().join("examples/fatigue/auxerre-3-days-composite-30m.toml");
    let out = tempfile::tempdir().unwrap();
    let output = vbi()
        .args(["lifetime", example.to_str().unwrap(), "--out"])
        .arg(out.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(
        stdout.contains("fatigue (static, the record as one history"),
        "{stdout}"
    );
    let fatigue = std::fs::read_to_string(out.path().join("fatigue.csv")).unwrap();
    let header: Vec<&str> = vbi::outputs::LIFETIME_FATIGUE_OUTPUTS
        .iter()
        .map(|r| r.name)
        .collect();
    assert_eq!(fatigue.lines().next().unwrap(), header.join(","));
    let details = column(&fatigue, "detail");
    assert_eq!(details.len(), 3);
    let blocks = std::fs::read_to_string(out.path().join("fatigue_blocks.csv")).unwrap();
    let damages = column(&fatigue, "static_damage");
    let per_year = column(&fatigue, "static_damage_per_year");
    let days = column(&fatigue, "record_days");
    for (i, detail) in details.iter().enumerate() {
        let total: f64 = damages[i].parse().unwrap();
        assert!(total > 0.0, "{detail}");
        let by_block: f64 = column(&blocks, &format!("{detail}_static_damage"))
            .iter()
            .map(|v| v.parse::<f64>().unwrap())
            .sum();
        assert!(
            (by_block - total).abs() <= 1e-12 * total,
            "{detail}: {by_block} {total}"
        );
        let (year, days): (f64, f64) = (per_year[i].parse().unwrap(), days[i].parse().unwrap());
        assert!((year - total * 365.25 / days).abs() <= 1e-12 * year);
    }
    // The same stress history and cycles on three curves: the cycle counts agree; category
    // 56 does more damage than 71; AASHTO's line, without a cut-off, counts every cycle.
    let cycles = column(&fatigue, "static_cycles");
    assert!(cycles.iter().all(|c| *c == cycles[0]));
    let damage: Vec<f64> = damages.iter().map(|d| d.parse().unwrap()).collect();
    assert!(damage[1] > damage[0]);
    assert_eq!(column(&fatigue, "static_damaging_cycles")[2], cycles[2]);
}

#[test]
fn a_shard_of_a_lifetime_with_fatigue_details_is_refused_with_exit_2() {
    let example = repository_root().join("examples/fatigue/auxerre-3-days-composite-30m.toml");
    let out = tempfile::tempdir().unwrap();
    let output = vbi()
        .args([
            "lifetime",
            example.to_str().unwrap(),
            "--shard",
            "1/2",
            "--out",
        ])
        .arg(out.path())
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("a shard cannot count fatigue"), "{stderr}");
}
