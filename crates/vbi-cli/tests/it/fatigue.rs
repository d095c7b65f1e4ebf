//! `vbi run` with fatigue details (issue 51): fatigue.csv and summary.json's `fatigue` carry
//! the rows of the table of fatigue outputs, and their numbers are rainflow and Miner on the
//! very histories that histories.csv holds.

use crate::run::{run, SMALL};

/// The small scenario with one bending detail at mid-span (W = 0.005 m³ and k_f = 1.2: about
/// 67 MPa under the 5.7 t sprung mass, above the cut-off of category 71) and one in shear at a
/// quarter (A_w = 0.0005 m²: about 110 MPa).
fn scenario_with_details() -> String {
    format!(
        "{SMALL}
[[station]]
name = \"quarter\"
span = 1
fraction = 0.25

[[fatigue_detail]]
name = \"flange\"
station = \"span1_mid_section\"
category_mpa = 71
stress_concentration = 1.2
section_modulus_m3 = 0.005

[[fatigue_detail]]
name = \"web\"
station = \"quarter\"
quantity = \"shear_force\"
category_mpa = 80
web_area_m2 = 0.0005
"
    )
}

/// One column of a CSV table, parsed.
fn column(table: &str, name: &str) -> Vec<String> {
    let mut reader = csv::Reader::from_reader(table.as_bytes());
    let at = (reader.headers().unwrap().iter())
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    reader
        .records()
        .map(|r| r.unwrap()[at].to_string())
        .collect()
}

#[test]
fn run_fatigue_is_rainflow_and_miner_on_the_histories_it_writes() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fatigue.toml");
    std::fs::write(&path, scenario_with_details()).unwrap();
    let out = dir.path().join("out");
    let (code, stdout, stderr) = run(&[
        "run",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("fatigue detail"), "{stdout}");
    let fatigue = std::fs::read_to_string(out.join("fatigue.csv")).unwrap();
    let histories = std::fs::read_to_string(out.join("histories.csv")).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(column(&fatigue, "detail"), ["flange", "web"]);
    // The header is the table of outputs, in order.
    let header = fatigue.lines().next().unwrap();
    let names: Vec<&str> = vbi::outputs::FATIGUE_OUTPUTS
        .iter()
        .map(|r| r.name)
        .collect();
    assert_eq!(header, names.join(","));
    for (i, (detail, station, stress_per_effect)) in [
        ("flange", "span1_mid_section_moment_n_m", 1.2 / 0.005),
        ("web", "quarter_shear_n", 1.0 / 0.0005),
    ]
    .into_iter()
    .enumerate()
    {
        let entry = &summary["fatigue"][i];
        assert_eq!(entry["detail"], detail);
        for (kind, history_column) in [
            ("dynamic", station.to_string()),
            (
                "static",
                station
                    .replace("_moment", "_static_moment")
                    .replace("_shear", "_static_shear"),
            ),
        ] {
            let effect: Vec<f64> = column(&histories, &history_column)
                .iter()
                .map(|v| v.parse().unwrap())
                .collect();
            let stress: Vec<f64> = effect.iter().map(|e| stress_per_effect * e).collect();
            let curve = if detail == "flange" {
                vbi::fatigue::SnCurve::eurocode_direct(71.0e6)
            } else {
                vbi::fatigue::SnCurve::Eurocode {
                    category: 80.0e6,
                    stress: vbi::fatigue::StressKind::Shear,
                    partial_factor: 1.0,
                }
            };
            let mut sum = vbi::fatigue::DamageSum::new(curve);
            vbi::fatigue::rainflow(&stress)
                .into_iter()
                .for_each(|c| sum.add(c));
            let damage = entry[format!("{kind}_damage")].as_f64().unwrap();
            let cycles = entry[format!("{kind}_cycles")].as_f64().unwrap();
            let max_range = entry[format!("{kind}_max_range")].as_f64().unwrap();
            // The CLI multiplies k_f × (1/W) × M; the recount (k_f/W) × M: equal to round-off.
            assert!(
                (damage - sum.damage).abs() <= 1e-12 * sum.damage,
                "{detail} {kind}: {damage} {}",
                sum.damage
            );
            assert_eq!(cycles, sum.cycles, "{detail} {kind}");
            assert!((max_range - sum.max_range).abs() <= 1e-12 * sum.max_range);
        }
        assert!(entry["dynamic_damage"].as_f64().unwrap() > 0.0, "{detail}");
    }
    // The flange's static range is above the cut-off: its fatigue DAF is defined and is the cube
    // root of the damage ratio.
    let flange = &summary["fatigue"][0];
    let ratio = flange["damage_ratio"].as_f64().unwrap();
    let daf = flange["fatigue_daf"].as_f64().unwrap();
    assert!((daf - ratio.cbrt()).abs() < 1e-12);
}

#[test]
fn a_detail_on_a_missing_station_is_refused_before_the_crossing_with_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(
        &path,
        scenario_with_details().replace("station = \"quarter\"", "station = \"third\""),
    )
    .unwrap();
    let (code, stdout, stderr) = run(&["run", path.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stdout.is_empty());
    assert!(
        stderr.contains("field `fatigue_detail[1].station`: no station `third`"),
        "{stderr}"
    );
}

/// The fatigue DAF's convergence indicator in the modes covers what more modes change: with 3
/// modes kept (20 m beam, the mid-span flange detail), |DAF(3) − DAF(16)| is within the
/// indicator of the 3-mode run; with 16 modes the indicator is small (below 10⁻³). (With 2 modes
/// it cannot: the second mode reads zero at mid-span, and the check modes stop at twice f₂ =
/// 8 f₁, below f₃ = 9 f₁; the peak DAF's indicator has the same blind spot.)
#[test]
fn the_fatigue_daf_change_covers_the_change_to_more_modes() {
    let dir = tempfile::tempdir().unwrap();
    let daf_and_change = |modes: usize| {
        let path = dir.path().join(format!("modes{modes}.toml"));
        let text = scenario_with_details().replace("modes = 4", &format!("modes = {modes}"));
        std::fs::write(&path, text).unwrap();
        let (code, stdout, stderr) = run(&["run", path.to_str().unwrap(), "--format", "json"]);
        assert_eq!(code, 0, "{stderr}");
        let summary: serde_json::Value = serde_json::from_str(&stdout).unwrap();
        let flange = &summary["fatigue"][0];
        (
            flange["fatigue_daf_straight_line"].as_f64().unwrap(),
            flange["fatigue_daf_straight_line_change"].as_f64().unwrap(),
        )
    };
    let (few, change_few) = daf_and_change(3);
    let (many, change_many) = daf_and_change(16);
    assert!(
        (few - many).abs() <= change_few,
        "{few} {many} {change_few}"
    );
    assert!(change_many < 1e-3, "{change_many}");
}
