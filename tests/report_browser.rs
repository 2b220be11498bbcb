//! The report in a real browser (issue 47), at the five configurations of
//! tests/report_reading.rs: headless Chromium lays the page out in a 1280 × 800 frame and in a
//! 390-px one, and the test reads the positions back:
//! - all seven ledger rows and the verdict tally end within the first 800 px at 1280 px;
//! - at 390 px nothing is wider than the frame (no horizontal scrolling).
//!
//! Ignored by a plain `cargo test` (it needs Chromium, a system package); `.ci/run` installs
//! Debian's `chromium` and runs it with `--ignored`, and then it fails — not skips — when the
//! browser is missing. Set `CHROMIUM` to use another binary.

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;

fn chromium() -> PathBuf {
    if let Some(p) = std::env::var_os("CHROMIUM") {
        return PathBuf::from(p);
    }
    for b in ["chromium", "chromium-browser", "google-chrome"] {
        if Command::new(b).arg("--version").output().is_ok_and(|o| o.status.success()) {
            return PathBuf::from(b);
        }
    }
    panic!("no headless Chromium found: install Debian's `chromium` (apt-get install -y chromium) or set CHROMIUM");
}

/// The page in frames of 1280 × 800 and 390 × 844 CSS px; what a script measures in each once
/// both have loaded, as JSON: the bottom of each ledger row and of the tally, the frame's size
/// and the document's scroll width.
fn measure(browser: &Path, index: &Path, dir: &Path) -> serde_json::Value {
    let url = format!("file://{}", index.display());
    let wrapper = format!(
        r#"<!DOCTYPE html><html><head><style>body{{margin:0}}iframe{{border:0;display:block}}</style></head><body>
<iframe id="wide" width="1280" height="800" src="{url}"></iframe>
<iframe id="narrow" width="390" height="844" src="{url}"></iframe>
<script>
function m(id) {{
  var f = document.getElementById(id), d = f.contentDocument, w = f.contentWindow;
  var rows = [].slice.call(d.querySelectorAll('#ledger-table tbody tr')).map(function (r) {{ return r.getBoundingClientRect().bottom; }});
  return {{ rows: rows, tally: d.getElementById('tally').getBoundingClientRect().bottom, height: w.innerHeight, width: w.innerWidth, scroll_width: d.documentElement.scrollWidth }};
}}
var loaded = 0;
function done() {{ if (++loaded == 2) document.body.setAttribute('data-measure', JSON.stringify({{ wide: m('wide'), narrow: m('narrow') }})); }}
document.getElementById('wide').onload = done;
document.getElementById('narrow').onload = done;
</script></body></html>"#
    );
    let page = dir.join("measure.html");
    std::fs::write(&page, wrapper).unwrap();
    let profile = tempfile::tempdir().unwrap();
    let o = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--allow-file-access-from-files",
            "--virtual-time-budget=20000",
            "--window-size=1800,1000",
            "--dump-dom",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .arg(format!("file://{}", page.display()))
        .output()
        .expect("chromium runs");
    assert!(o.status.success(), "chromium: {}", String::from_utf8_lossy(&o.stderr));
    let dom = String::from_utf8_lossy(&o.stdout);
    let start = dom.find("data-measure=\"").expect("the measuring script ran") + "data-measure=\"".len();
    let json = dom[start..].split('"').next().unwrap().replace("&quot;", "\"");
    serde_json::from_str(&json).expect("measurements as JSON")
}

fn check(browser: &Path, name: &str, sets: &[&str], tmp: &Path) {
    let out = tmp.join(name.replace([' ', ',', '=', '.'], "-"));
    let mut args = vec!["report", "--out", out.to_str().unwrap()];
    for s in sets {
        args.extend(["--set", s]);
    }
    let o = Command::new(env!("CARGO_BIN_EXE_wingcheck")).args(&args).output().unwrap();
    assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
    let m = measure(browser, &out.join("index.html"), tmp);
    let wide = &m["wide"];
    assert_eq!((wide["width"].as_f64(), wide["height"].as_f64()), (Some(1280.0), Some(800.0)), "{name}: {m}");
    let rows: Vec<f64> = wide["rows"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    assert_eq!(rows.len(), 7, "{name}: seven ledger rows");
    for (i, b) in rows.iter().enumerate() {
        assert!(*b <= 800.0, "{name}: ledger row {} ends at {b} px, below the first 1280 × 800 screen", i + 1);
    }
    assert!(wide["tally"].as_f64().unwrap() <= 800.0, "{name}: the tally is below the first screen");
    let narrow = &m["narrow"];
    let (w, sw) = (narrow["width"].as_f64().unwrap(), narrow["scroll_width"].as_f64().unwrap());
    assert!(sw <= w, "{name}: at {w} px the page is {sw} px wide (horizontal scrolling)");
    println!("{name}: last ledger row ends at {:.0} px of 800; at 390 px the page is {sw} px wide", rows[6]);
}

#[test]
#[ignore = "needs headless Chromium (Debian package `chromium`); run by .ci/run with --ignored"]
fn the_first_screen_decides_in_a_real_browser() {
    let browser = chromium();
    let tmp = tempfile::tempdir().unwrap();
    for (name, sets) in common::READER_CONFIGS {
        check(&browser, name, sets, tmp.path());
    }
}
