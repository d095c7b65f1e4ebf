//! `vbi report` of a run directory and of a study directory: the structure of the page (key
//! results first, the contents, numbered sections, every figure with a caption, units in the
//! table headers), checked on the HTML text and, where a Chromium is installed (CI installs
//! Debian's `chromium`), on the DOM that a real browser builds from it.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::vbi;
use crate::run::SMALL;

/// A Chromium to render with: `VBI_CHROMIUM`, or `chromium` / `chromium-browser` on the PATH.
fn chromium() -> Option<PathBuf> {
    if let Some(path) = std::env::var_os("VBI_CHROMIUM") {
        return Some(PathBuf::from(path));
    }
    ["chromium", "chromium-browser", "google-chrome"]
        .iter()
        .find_map(|name| {
            let found = Command::new("sh")
                .args(["-c", &format!("command -v {name}")])
                .output()
                .ok()?;
            let path = String::from_utf8(found.stdout).ok()?.trim().to_string();
            (found.status.success() && !path.is_empty()).then(|| PathBuf::from(path))
        })
}

/// The DOM that headless Chromium builds from the file (None without a Chromium).
fn rendered_dom(file: &Path) -> Option<String> {
    let Some(browser) = chromium() else {
        eprintln!("no Chromium found (VBI_CHROMIUM, chromium): the browser check is skipped");
        return None;
    };
    let url = format!("file://{}", file.canonicalize().unwrap().display());
    let output = Command::new(&browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-dev-shm-usage",
            "--dump-dom",
            &url,
        ])
        .output()
        .unwrap_or_else(|e| panic!("running {}: {e}", browser.display()));
    assert!(output.status.success(), "{output:?}");
    Some(String::from_utf8(output.stdout).unwrap())
}

/// The checks that hold for both kinds of report, on the file's text or the browser's DOM.
fn assert_structure(html: &str, sections: &[&str]) {
    let key = html.find("id=\"key-results\"").expect("a key-results box");
    let contents = html.find("id=\"contents\"").expect("a table of contents");
    assert!(key < contents, "key results come first");
    let mut last = contents;
    for (i, heading) in sections.iter().enumerate() {
        let at = html
            .find(&format!("<h2>{}. {heading}</h2>", i + 1))
            .unwrap_or_else(|| panic!("section {}. {heading}", i + 1));
        assert!(at > last, "{heading} in order");
        last = at;
        assert!(
            html.contains(&format!(">{heading}</a>")),
            "{heading} in the contents"
        );
    }
    let figures = html.matches("<figure>").count();
    assert_eq!(
        html.matches("<figcaption>").count(),
        figures,
        "every figure has a caption"
    );
    assert!(
        !html.contains("<figcaption>Figure "),
        "a sentence, not a file name"
    );
    assert!(!html.contains("{\""), "no raw JSON");
    assert!(
        !html.contains("NaN") && !html.contains("Some("),
        "no debug values"
    );
}

/// A `vbi run --out` directory of the `SMALL` scenario, in a new temporary directory.
fn run_directory() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("small.toml");
    std::fs::write(&scenario, SMALL).unwrap();
    let out = dir.path().join("out");
    vbi()
        .args([
            "run",
            scenario.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .assert()
        .success();
    (dir, out)
}

#[test]
fn the_report_of_a_run_directory_opens_with_its_key_results() {
    let (dir, out) = run_directory();
    vbi()
        .args(["report", out.to_str().unwrap()])
        .assert()
        .success();
    let file = out.join("report.html");
    let html = std::fs::read_to_string(&file).unwrap();
    let sections = [
        "DAF at every station",
        "Computed DAF against the design codes",
        "Figures",
        "Natural frequencies",
        "Provenance",
    ];
    assert_structure(&html, &sections);
    for text in [
        "design codes, 1 + IM of the moment",
        "converged DAF_u",
        "converged DAF_M",
        "sprung-mass",
        "100 km/h",
        "kN·m",
    ] {
        assert!(html.contains(text), "{text}");
    }
    let svgs = std::fs::read_dir(&out)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "svg")
        })
        .count();
    assert_eq!(
        html.matches("<figure>").count(),
        svgs,
        "every figure of the directory"
    );
    if let Some(dom) = rendered_dom(&file) {
        assert_structure(&dom, &sections);
        assert_eq!(dom.matches("<figure>").count(), svgs);
    }
    // A directory that is neither a study's nor a run's is refused.
    vbi()
        .args(["report", dir.path().to_str().unwrap()])
        .assert()
        .code(2);
}

#[test]
fn the_report_of_a_study_has_statistics_and_no_paper_comparison_unless_it_is_the_papers() {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("s.toml");
    std::fs::write(
        &study,
        "[study]\nseed = 3\nsamples = 3\n[study.axes]\nspeed_kmh = [60, 90]\n\
         [scenario]\nvehicle = \"moving-force\"\nroad = \"medium\"\nmodes = 6\n\
         [bridge]\ntype = \"continuous_beam\"\nspan_lengths_m = [20.0]\n\
         supports = [\"pinned\", \"roller\"]\ndamping_ratio = 0.02\n[bridge.section]\n\
         flexural_rigidity_n_m2 = 4.86535e10\nmass_per_length_kg_per_m = 18358.0\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    vbi()
        .args([
            "study",
            study.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .assert()
        .success();
    let file = out.join("report.html");
    let html = std::fs::read_to_string(&file).unwrap();
    let sections = [
        "Stations",
        "Statistics per group of cases",
        "Cut-off modes K1 and K2 (the paper's Table 2)",
        "Computed DAF against the design codes",
        "Figures",
        "Provenance",
        "Inputs",
    ];
    assert_structure(&html, &sections);
    assert!(
        !html.contains("Against the paper's statements"),
        "not the paper's study"
    );
    // Issue 46, item 9: three road samples per speed support no characteristic value, and the
    // key results pool the two speeds: neither is called characteristic.
    for text in [
        "the 95th percentile of its 2 combinations",
        "not a characteristic value",
        "converged DAF_M",
        "p95 ",
        "(not characteristic, n = 3)",
    ] {
        assert!(html.contains(text), "{text}");
    }
    assert!(!html.contains("characteristic (95 % fractile)"));
    if let Some(dom) = rendered_dom(&file) {
        assert_structure(&dom, &sections);
    }
}

/// Figures are written whole or not at all (issue 17, defect 5): after a run no hidden
/// `.partial` file is left; a figure abandoned while drawing (a hidden `.stem.partial.svg`) is
/// not embedded; a torn SVG under a final name is refused with exit 2 naming it, never embedded.
#[test]
fn a_report_never_embeds_a_torn_figure() {
    let (_dir, out) = run_directory();
    let hidden: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.') && n != ".vbi.lock")
        .collect();
    assert!(hidden.is_empty(), "{hidden:?}");
    std::fs::write(out.join(".abandoned.partial.svg"), "<svg><g>").unwrap();
    vbi()
        .args(["report", out.to_str().unwrap()])
        .assert()
        .success();
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(
        !html.contains("<svg><g>"),
        "an abandoned figure is not embedded"
    );
    let whole = std::fs::read_to_string(out.join("design_codes.svg")).unwrap();
    std::fs::write(out.join("design_codes.svg"), &whole[..whole.len() / 2]).unwrap();
    let output = vbi()
        .args(["report", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("design_codes.svg") && stderr.contains("not a whole SVG"),
        "{stderr}"
    );
}
