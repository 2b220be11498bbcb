//! `wingcheck compare`: the command line prints the library's comparison
//! (`wingcheck_app::compare`) and draws it.

use std::process::{Command, Output};

use wingcheck_app::compare::{compare, table, Entrant};
use wingcheck_app::{ConfigSource, Front, WorkPolicy};
use wingcheck_model::{Cancel, ControllerKind};

fn wingcheck(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wingcheck")).args(args).output().expect("binary runs")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

const SHORT: [&str; 2] = ["--set", "horizon.t_end=2"];

/// The library's comparison of pd and dobc on the short horizon.
fn library() -> wingcheck_app::compare::Comparison {
    let cfg = ConfigSource { file: None, text: None, set: vec!["horizon.t_end=2".into()] }.load().unwrap();
    let entrants = [
        ("pd".to_string(), Entrant::BuiltIn(ControllerKind::Pd)),
        ("dobc".to_string(), Entrant::BuiltIn(ControllerKind::Dobc)),
    ];
    compare(&cfg, &entrants, WorkPolicy { allow_large: false, front: Front::Cli }, &Cancel::new()).unwrap()
}

#[test]
fn the_cli_prints_the_librarys_comparison_and_draws_it() {
    // Reference: wingcheck_app::compare for the same configuration and controllers (the CLI
    // only parses and prints): every cell of the library's table (value ± error in the tool's
    // number format) is printed, in the header's order.
    let reference = library();
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("compare.svg");
    let o = wingcheck(&["compare", "--controllers", "pd,dobc", SHORT[0], SHORT[1], "--svg", svg.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let out = text(&o.stdout);
    let (header, rows) = table(&reference);
    let first = out.lines().next().unwrap();
    assert!(first.starts_with("metric") && first.find("pd") < first.find("dobc"), "{out}");
    for (row, line) in rows.iter().zip(out.lines().skip(1)) {
        for cell in row {
            assert!(line.contains(cell.as_str()), "missing {cell:?} in {line:?}");
        }
    }
    assert_eq!(header.len(), 3);
    // the SVG: one document, four panels (q, θ, τ1, τ2), both controllers in the legends
    let doc_text = std::fs::read_to_string(&svg).unwrap();
    let doc = roxmltree::Document::parse(&doc_text).expect("well-formed SVG");
    let panels = doc.root_element().children().filter(|n| n.has_tag_name("svg")).count();
    assert_eq!(panels, 4);
    for label in ["pd", "dobc", "q(s,t) (m)", "θ(s,t) (rad)", "τ1 (N)", "τ2 (N m)"] {
        assert!(doc.descendants().any(|n| n.text().is_some_and(|t| t.trim() == label)), "no text {label:?}");
    }
    // the same input draws the same bytes
    let again = dir.path().join("again.svg");
    let o = wingcheck(&["compare", "--controllers", "pd,dobc", SHORT[0], SHORT[1], "--svg", again.to_str().unwrap()]);
    assert!(o.status.success());
    assert_eq!(std::fs::read(&again).unwrap(), doc_text.as_bytes());
}

#[test]
fn bad_arguments_fail_cleanly_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("c.png");
    let o = wingcheck(&["compare", SHORT[0], SHORT[1], "--svg", png.to_str().unwrap()]);
    assert!(!o.status.success() && text(&o.stderr).contains(".svg"), "{}", text(&o.stderr));
    assert!(!png.exists());
    let o = wingcheck(&["compare", "--controllers", "pd,lqr"]);
    assert!(!o.status.success() && text(&o.stderr).contains("--controllers lqr"), "{}", text(&o.stderr));
    assert!(!text(&o.stderr).contains("panicked"));
}
