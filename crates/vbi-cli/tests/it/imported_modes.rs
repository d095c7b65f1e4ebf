//! End-to-end tests of runs and studies on a bridge known only by its modes (`type =
//! "imported"`, issue 15.2): the static reference from the modal flexibility of the modes given,
//! with a warning that says it is truncated.

use std::path::Path;

use crate::common::{repository_root, vbi};

/// `vbi run --format json` of the three-axle truck at 80 km/h on a good road over `bridge`.
fn run_json(dir: &Path, bridge: &Path, extra: &str) -> serde_json::Value {
    let scenario = dir.join("scenario.toml");
    std::fs::write(
        &scenario,
        format!(
            "[scenario]\nbridge = \"{}\"\nvehicle = \"three-axle-truck-36t\"\nroad = \"good\"\n\
             speed_kmh = 80\nmodes = 10\n{extra}",
            bridge.display()
        ),
    )
    .unwrap();
    let out = vbi()
        .arg("run")
        .arg(&scenario)
        .args(["--format", "json"])
        .assert()
        .success();
    serde_json::from_slice(&out.get_output().stdout).unwrap()
}

fn entry<'a>(v: &'a serde_json::Value, name: &str, quantity: &str) -> &'a serde_json::Value {
    v["stations"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == name && s["quantity"] == quantity)
        .unwrap_or_else(|| panic!("{name} {quantity}"))
}

#[test]
fn a_crossing_on_imported_modes_uses_their_flexibility_and_says_it_is_truncated() {
    // examples/bridges/imported holds the first 10 modes of vbi's own FE model of
    // examples/bridges/two-span-beam.toml; the same crossing on that FE model with 10 modes is
    // the reference. Its static reference is exact (influence lines from K); the imported one is
    // the flexibility of 10 modes: the mid-span deflection's within 0.1 % (the modal series of
    // a deflection converges as k⁻⁴; measured 1e-4), the moment's within 5 % (k⁻²; measured
    // 2.4 %, of which part is the inertia rows in vbi's modal moments, docs/input-format.md).
    let dir = tempfile::tempdir().unwrap();
    let examples = repository_root().join("examples/bridges");
    let imported = run_json(
        dir.path(),
        &examples.join("imported/two-span-imported.toml"),
        "",
    );
    let native = run_json(dir.path(), &examples.join("two-span-beam.toml"), "");
    let relative = |quantity: &str, field: &str| -> f64 {
        let a = entry(&native, "span1_mid_section", quantity)[field]
            .as_f64()
            .unwrap();
        let b = entry(&imported, "span1_mid_section", quantity)[field]
            .as_f64()
            .unwrap();
        (a - b).abs() / a.abs()
    };
    assert!(relative("deflection", "static_max") < 1e-3);
    assert!(relative("bending_moment", "static_max") < 0.05);
    // DAFs: the dynamic responses come from the same 10 modes; the deflection's within 0.5 %.
    assert!(relative("deflection", "daf") < 5e-3);
    let warnings: Vec<&str> = imported["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w.as_str().unwrap())
        .collect();
    assert!(
        warnings
            .iter()
            .any(|w| w.contains("modal flexibility of the 10 imported modes")),
        "{warnings:?}"
    );
    // No shear or reaction: an imported basis has no modal forces.
    assert!(imported["stations"]
        .as_array()
        .unwrap()
        .iter()
        .all(|s| s["quantity"] == "deflection" || s["quantity"] == "bending_moment"));
}

#[test]
fn stations_cannot_be_added_to_imported_modes() {
    let dir = tempfile::tempdir().unwrap();
    let bridge = repository_root().join("examples/bridges/imported/two-span-imported.toml");
    let scenario = dir.path().join("scenario.toml");
    std::fs::write(
        &scenario,
        format!(
            "[scenario]\nbridge = \"{}\"\nvehicle = \"moving-force\"\n\n[[station]]\n\
             position_m = 5\n",
            bridge.display()
        ),
    )
    .unwrap();
    let out = vbi().arg("check").arg(&scenario).assert().code(2);
    let error = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(error.contains("station[0]"), "{error}");
    assert!(
        error.contains("only the stations of its station_moments_csv"),
        "{error}"
    );
}

#[test]
fn a_study_runs_on_imported_modes() {
    let dir = tempfile::tempdir().unwrap();
    let bridge = repository_root().join("examples/bridges/imported/two-span-imported.toml");
    let study = dir.path().join("study.toml");
    std::fs::write(
        &study,
        format!(
            "[study]\nname = \"modes\"\nseed = 3\nsamples = 2\n[study.axes]\nbridge = [\"{}\"]\n\
             speed_kmh = [60, 90]\n[scenario]\nvehicle = \"three-axle-truck-36t\"\n\
             road = \"good\"\nmodes = 10\n",
            bridge.display()
        ),
    )
    .unwrap();
    vbi().arg("check").arg(&study).assert().success();
    let out = dir.path().join("out");
    vbi()
        .arg("study")
        .arg(&study)
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let table = std::fs::read_to_string(out.join("cases.csv")).unwrap();
    assert_eq!(table.lines().count(), 1 + 4, "{table}");
}

#[test]
fn shapes_scaled_to_a_unit_maximum_are_warned_of_as_not_mass_normalised() {
    // The example's shapes are mass-normalised (vbi's own modes of a beam of 18 358 kg/m: they
    // imply 2/(L φ²) = 1.8e4 kg/m); scaled to a unit maximum they imply 0.05 kg/m.
    let dir = tempfile::tempdir().unwrap();
    let source = repository_root().join("examples/bridges/imported");
    for name in [
        "two-span-imported.toml",
        "frequencies.csv",
        "station_moments.csv",
    ] {
        std::fs::copy(source.join(name), dir.path().join(name)).unwrap();
    }
    let shapes = std::fs::read_to_string(source.join("shapes.csv")).unwrap();
    let bridge = dir.path().join("two-span-imported.toml");
    std::fs::write(dir.path().join("shapes.csv"), &shapes).unwrap();
    let out = vbi().arg("check").arg(&bridge).assert().success();
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(!stderr.contains("mass-normalised"), "{stderr}");
    // Every value divided by its mode's largest |value|.
    let rows: Vec<Vec<String>> = shapes
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    let modes = rows[0].len() - 2;
    let largest: Vec<f64> = (0..modes)
        .map(|k| {
            rows[1..]
                .iter()
                .map(|r| r[2 + k].parse::<f64>().unwrap().abs())
                .fold(0.0, f64::max)
        })
        .collect();
    let scaled: Vec<String> = std::iter::once(rows[0].join(","))
        .chain(rows[1..].iter().map(|r| {
            let mut row = r[..2].to_vec();
            row.extend(
                (0..modes).map(|k| format!("{:e}", r[2 + k].parse::<f64>().unwrap() / largest[k])),
            );
            row.join(",")
        }))
        .collect();
    std::fs::write(dir.path().join("shapes.csv"), scaled.join("\n") + "\n").unwrap();
    let out = vbi().arg("check").arg(&bridge).assert().success();
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(
        stderr.contains("check that the shapes are mass-normalised"),
        "{stderr}"
    );
    assert!(stderr.contains("5.000e-2 kg/m"), "{stderr}");
}

#[test]
fn influence_lines_given_with_imported_modes_make_the_static_reference_exact() {
    // examples/bridges/imported/two-span-imported-with-lines.toml adds the stations' influence
    // lines (vbi's own, exact, at the nodes) to the same 10 modes. The static maxima are then
    // those of the FE model to 2e-5 (exact at the nodes; the axles fall between nodes, where
    // the Hermite field on 5-point slopes is within 1e-5 of a line's peak, verification.md
    // §27; measured 7e-6), against 2.8 % for the moment from the modes' flexibility; the DAFs
    // to 1e-4 (the same modes), and the truncation warning is gone.
    let dir = tempfile::tempdir().unwrap();
    let examples = repository_root().join("examples/bridges");
    let imported = run_json(
        dir.path(),
        &examples.join("imported/two-span-imported-with-lines.toml"),
        "",
    );
    let native = run_json(dir.path(), &examples.join("two-span-beam.toml"), "");
    // Over the support the deflection is held (no DAF): its moment is compared.
    for (station, quantity) in [
        ("span1_mid_section", "deflection"),
        ("span1_mid_section", "bending_moment"),
        ("span2_mid_section", "deflection"),
        ("span2_mid_section", "bending_moment"),
        ("support2_section", "bending_moment"),
    ] {
        let value = |v: &serde_json::Value, field: &str| {
            entry(v, station, quantity)[field].as_f64().unwrap()
        };
        let (a, b) = (value(&native, "static_max"), value(&imported, "static_max"));
        assert!(
            (a - b).abs() <= 2e-5 * a.abs(),
            "{station} {quantity}: {a} vs {b}"
        );
        let (a, b) = (value(&native, "daf"), value(&imported, "daf"));
        assert!(
            (a - b).abs() <= 1e-4,
            "{station} {quantity} DAF: {a} vs {b}"
        );
    }
    let warnings = imported["warnings"].as_array().unwrap();
    assert!(
        !warnings
            .iter()
            .any(|w| w.as_str().unwrap().contains("modal flexibility")),
        "{warnings:?}"
    );
}

#[test]
fn influence_lines_that_miss_a_node_or_name_an_unknown_station_are_refused_at_their_cell() {
    let dir = tempfile::tempdir().unwrap();
    let source = repository_root().join("examples/bridges/imported");
    for name in [
        "frequencies.csv",
        "shapes.csv",
        "station_moments.csv",
        "two-span-imported-with-lines.toml",
    ] {
        std::fs::copy(source.join(name), dir.path().join(name)).unwrap();
    }
    let lines = std::fs::read_to_string(source.join("influence_lines.csv")).unwrap();
    let bridge = dir.path().join("two-span-imported-with-lines.toml");
    let check = |text: &str| {
        std::fs::write(dir.path().join("influence_lines.csv"), text).unwrap();
        let out = vbi().arg("check").arg(&bridge).assert().code(2);
        String::from_utf8_lossy(&out.get_output().stderr).to_string()
    };
    // The row of node x = 1 m of the first station left out: the next row (x = 2 m) is named.
    let skipped: String = lines
        .lines()
        .filter(|l| !l.starts_with("span1_mid_section,0,1,"))
        .map(|l| format!("{l}\n"))
        .collect();
    let stderr = check(&skipped);
    assert!(stderr.contains("influence_lines.csv:5:"), "{stderr}");
    assert!(
        stderr.contains("the next node of the line at y = 0 m is at 1 m"),
        "{stderr}"
    );
    let renamed = lines.replacen("span2_mid_section", "span9_mid", 1);
    let stderr = check(&renamed);
    assert!(stderr.contains("`span9_mid` is not a station"), "{stderr}");
    // A moment ordinate of 1e308 N·m/N (finite, but an infinity in every product downstream)
    // is refused at its cell.
    let huge: String = lines
        .lines()
        .map(|l| match l.strip_prefix("span1_mid_section,0,1,") {
            Some(rest) => {
                let deflection = rest.split(',').next().unwrap();
                format!("span1_mid_section,0,1,{deflection},1e308\n")
            }
            None => format!("{l}\n"),
        })
        .collect();
    let stderr = check(&huge);
    assert!(stderr.contains("influence_lines.csv:5:"), "{stderr}");
    assert!(stderr.contains("within ±10000 N·m/N"), "{stderr}");
}

#[test]
fn modal_moments_from_the_shapes_curvature_give_the_fe_models_daf() {
    // The example's shapes without its station moments: flexural_rigidity_n_m2 (the beam's EI)
    // makes the default stations and their modal moments EI·φ'' from the shapes' curvature
    // (verification.md §27: within 2e-3 of each mode's peak for the first modes); with the
    // example's influence lines as static reference, the crossing gives the FE model's DAFs
    // within 1e-3.
    let dir = tempfile::tempdir().unwrap();
    let source = repository_root().join("examples/bridges/imported");
    for name in ["frequencies.csv", "shapes.csv", "influence_lines.csv"] {
        std::fs::copy(source.join(name), dir.path().join(name)).unwrap();
    }
    let bridge = dir.path().join("curvature.toml");
    let text = "[bridge]\ntype = \"imported\"\nfrequencies_csv = \"frequencies.csv\"\n\
                shapes_csv = \"shapes.csv\"\ninfluence_lines_csv = \"influence_lines.csv\"\n\
                flexural_rigidity_n_m2 = 4.86535e10\nspan_lengths_m = [20.0, 20.0]\n\
                damping_ratio = 0.0\n";
    std::fs::write(&bridge, text).unwrap();
    let imported = run_json(dir.path(), &bridge, "");
    let native = run_json(
        dir.path(),
        &repository_root().join("examples/bridges/two-span-beam.toml"),
        "",
    );
    for (station, quantity) in [
        ("span1_mid_section", "bending_moment"),
        ("span2_mid_section", "bending_moment"),
        ("support2_section", "bending_moment"),
        ("span1_mid_section", "deflection"),
    ] {
        let daf = |v: &serde_json::Value| entry(v, station, quantity)["daf"].as_f64().unwrap();
        let (a, b) = (daf(&native), daf(&imported));
        assert!((a - b).abs() <= 1e-3, "{station} {quantity}: {a} vs {b}");
    }
    // Moments from both places at once are refused at the key.
    std::fs::copy(
        source.join("station_moments.csv"),
        dir.path().join("station_moments.csv"),
    )
    .unwrap();
    std::fs::write(
        &bridge,
        format!("{text}station_moments_csv = \"station_moments.csv\"\n"),
    )
    .unwrap();
    let out = vbi().arg("check").arg(&bridge).assert().code(2);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(stderr.contains("bridge.flexural_rigidity_n_m2"), "{stderr}");
    assert!(stderr.contains("not both"), "{stderr}");
}

/// An imported basis without stations (no station moments, no flexural rigidity) runs, and the
/// run says that it reports no DAF instead of reporting nothing in silence (issue 47).
#[test]
fn an_imported_basis_without_stations_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let source = repository_root().join("examples/bridges/imported");
    for name in ["frequencies.csv", "shapes.csv"] {
        std::fs::copy(source.join(name), dir.path().join(name)).unwrap();
    }
    let bridge = dir.path().join("no-stations.toml");
    std::fs::write(
        &bridge,
        "[bridge]\ntype = \"imported\"\nfrequencies_csv = \"frequencies.csv\"\n\
         shapes_csv = \"shapes.csv\"\ndamping_ratio = 0.0\n",
    )
    .unwrap();
    let summary = run_json(dir.path(), &bridge, "");
    assert!(summary["stations"].as_array().unwrap().is_empty());
    let warnings = summary["warnings"].as_array().unwrap();
    assert!(
        warnings
            .iter()
            .any(|w| w.as_str().unwrap().contains("no station")),
        "{warnings:?}"
    );
}
