//! The convergence indicator in the modes covers every quantity (issue 46, item 5): a run's
//! printed `daf_change` bounds the change of its DAF when four times the modes are kept, for
//! shear forces and support reactions too (docs/verification.md §30). The reference is the same
//! crossing with 40 modes at the same fixed step, so that only the modal truncation differs.

use crate::common::{repository_root, vbi};

/// `examples/scenarios/two-span-sprung-mass.toml` (a sprung mass on a good road across two
/// 20 m spans, vertical bending modes) with `modes` kept at the fixed step 1e-4 s: its stations'
/// (name, quantity) → (DAF, daf_change, DAF(K ≤ N), DAF(K > N)).
fn run_with_modes(modes: usize, dir: &std::path::Path) -> Vec<(String, f64, f64, Vec<f64>, usize)> {
    let source = repository_root().join("examples/scenarios/two-span-sprung-mass.toml");
    let text = std::fs::read_to_string(&source).unwrap();
    let text = text
        .replace("modes = 20", &format!("modes = {modes}"))
        .replace("rerun_modes = [1, 2, 4]\n", "")
        .replace("[scenario]\n", "[scenario]\ntime_step_s = 1e-4\n")
        .replace(
            "\"../bridges/",
            &format!(
                "\"{}/",
                repository_root().join("examples/bridges").display()
            ),
        );
    let path = dir.join(format!("modes{modes}.toml"));
    std::fs::write(&path, text).unwrap();
    let output = vbi()
        .args(["run", path.to_str().unwrap(), "--format", "json"])
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let numbers = |v: &serde_json::Value| -> Vec<f64> {
        v.as_array()
            .map(|a| a.iter().map(|x| x.as_f64().unwrap()).collect())
            .unwrap_or_default()
    };
    json["stations"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["daf"].is_number())
        .map(|s| {
            let key = format!(
                "{} {}",
                s["name"].as_str().unwrap(),
                s["quantity"].as_str().unwrap()
            );
            let check = numbers(&s["daf_by_check_modes"]);
            (
                key,
                s["daf"].as_f64().unwrap(),
                s["daf_change"].as_f64().unwrap(),
                numbers(&s["daf_by_modes"]),
                check.len(),
            )
        })
        .collect()
}

#[test]
fn the_daf_change_bounds_the_modal_truncation_of_every_quantity_against_four_times_the_modes() {
    let dir = tempfile::tempdir().unwrap();
    let reference = run_with_modes(40, dir.path());
    let run = run_with_modes(10, dir.path());
    let mut missed_by_the_old_window = Vec::new();
    for (key, daf, change, by_modes, check_modes) in &run {
        let (_, exact, ..) = reference.iter().find(|r| &r.0 == key).unwrap();
        let error = (daf - exact).abs();
        // Check modes up to twice the 10th mode's frequency: the 11th–14th bending modes
        // (f_k ∝ k² on each span).
        assert_eq!(*check_modes, 4, "{key}");
        assert!(
            error <= *change,
            "{key}: |DAF(10) − DAF(40)| = {error:.5} > change {change:.5}"
        );
        // The indicator before issue 46's check modes: the change over the last ⌈N/5⌉ modes.
        let n = by_modes.len();
        let old = (by_modes[n - 3..n - 1].iter())
            .map(|d| (d - by_modes[n - 1]).abs())
            .fold(0.0, f64::max);
        if error > old {
            missed_by_the_old_window.push(key.clone());
        }
    }
    // What failed before: the old window did not bound the shear forces and the reaction.
    for key in [
        "support2_section support_reaction",
        "span1_mid_section shear_force",
    ] {
        assert!(
            missed_by_the_old_window.iter().any(|k| k == key),
            "{missed_by_the_old_window:?}"
        );
    }
}
