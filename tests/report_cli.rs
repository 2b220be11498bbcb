//! `wingcheck report` as a user runs it: the ledger table equals `wingcheck check --json` for the
//! same configuration, and the provenance records the command line and the build's commit.

use std::process::{Command, Output};

fn wingcheck(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wingcheck")).args(args).output().expect("binary runs")
}

/// A 4-s horizon keeps both runs cheap; the ledger's structure does not depend on T.
const SHORT: [&str; 2] = ["--set", "horizon.t_end=4"];

fn text(n: roxmltree::Node) -> String {
    n.descendants().filter(|d| d.is_text()).map(|d| d.text().unwrap_or("")).collect()
}

#[test]
fn ledger_table_equals_check_json_and_provenance_names_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r");
    let o = wingcheck(&["report", SHORT[0], SHORT[1], "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = wingcheck(&["check", "--json", SHORT[0], SHORT[1]]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // Reference: the verdicts of `check --json`, an independent run of the claim checker, as
    // the page shows them: in words (the enums' display text, not the JSON's tokens).
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let want: Vec<(String, String, String)> = json["rows"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            let verdict: wingcheck_claims::Verdict = serde_json::from_value(r["verdict"].clone()).unwrap();
            let basis: wingcheck_claims::Basis = serde_json::from_value(r["basis"].clone()).unwrap();
            (r["id"].as_str().unwrap().to_string(), verdict.to_string(), basis.to_string())
        })
        .collect();

    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let doc = roxmltree::Document::parse_with_options(
        &html,
        roxmltree::ParsingOptions { allow_dtd: true, ..Default::default() },
    )
    .expect("well-formed");
    let table = doc.descendants().find(|n| n.attribute("id") == Some("ledger-table")).unwrap();
    let cell = |tr: roxmltree::Node, c: &str| {
        tr.children().find(|n| n.attribute("class") == Some(c)).map(|n| text(n).trim().to_string()).unwrap()
    };
    let got: Vec<(String, String, String)> = table
        .descendants()
        .filter(|n| n.has_tag_name("tr") && n.attribute("id").is_some())
        .map(|tr| {
            let id = tr.descendants().find(|n| n.has_tag_name("a")).map(text).unwrap();
            (id, cell(tr, "verdict"), cell(tr, "basis"))
        })
        .collect();
    assert_eq!(got, want);

    // The command line (as typed) and the commit are in the provenance section.
    assert!(html.contains("report --set horizon.t_end=4 --out"), "command line in the provenance");
    // The binary's build script embeds the checkout's commit (reference: git itself), or
    // `unknown` outside a checkout; the tree state is git's own answer (`git status`).
    let commit = doc.descendants().find(|n| n.attribute("id") == Some("git-commit")).map(text).unwrap();
    let git = |args: &[&str]| {
        std::process::Command::new("git")
            .args(args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    let tree = doc.descendants().find(|n| n.attribute("id") == Some("git-tree")).map(text).unwrap();
    match git(&["rev-parse", "HEAD"]) {
        Some(h) => {
            assert_eq!(commit, h, "provenance commit vs git rev-parse HEAD");
            let dirty = !git(&["status", "--porcelain", "--untracked-files=no"]).unwrap_or_default().is_empty();
            assert_eq!(tree.starts_with("dirty"), dirty, "tree state {tree:?} vs git status");
        }
        None => assert!(commit == "unknown" && tree.starts_with("unknown"), "{commit} {tree}"),
    }
    assert!(html.contains("rustc "), "compiler version in the provenance");
}

#[test]
fn docs_and_readme_point_inside_the_repository() {
    // Users do not have the developers' material outside the repository.
    let root = env!("CARGO_MANIFEST_DIR");
    for f in ["README.md", "docs/model.md"] {
        let t = std::fs::read_to_string(format!("{root}/{f}")).unwrap();
        assert!(!t.contains("shared/"), "{f} cites a path outside the repository");
    }
    let readme = std::fs::read_to_string(format!("{root}/README.md")).unwrap();
    assert!(readme.contains("docs/model.md"), "the README links the model");
}
