//! docs/architecture.md's owner table names real items: every backticked Rust path in the
//! table's "owner" column resolves to a crate under crates/, and its last segments name items
//! defined there (a `fn`, `struct`, `enum`, `trait`, `type`, `const`, `static`, `mod` or a
//! `pub` field of that name in the crate's sources). A renamed or moved owner fails here.

use std::path::Path;

/// The crate's sources, concatenated.
fn crate_sources(dir: &Path) -> String {
    let mut text = String::new();
    let mut stack = vec![dir.join("src")];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|e| e == "rs") {
                text.push_str(&std::fs::read_to_string(&p).unwrap());
            }
        }
    }
    text
}

fn defines(sources: &str, name: &str) -> bool {
    let ends_word = |rest: &str| !rest.starts_with(|c: char| c.is_alphanumeric() || c == '_');
    let found =
        |pattern: String| sources.match_indices(&pattern).any(|(i, _)| ends_word(&sources[i + pattern.len()..]));
    ["fn", "struct", "enum", "trait", "type", "const", "static", "mod"].iter().any(|kw| found(format!("{kw} {name}")))
        || found(format!("pub {name}:"))
        || found(format!("pub(crate) {name}:"))
}

#[test]
fn every_owner_in_the_table_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let doc = std::fs::read_to_string(root.join("docs/architecture.md")).unwrap();
    let table = doc.split("## Who owns which quantity").nth(1).expect("the owner table").split("\n## ").next().unwrap();
    let mut checked = 0;
    for line in table.lines().filter(|l| l.starts_with('|') && !l.starts_with("|---")) {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let Some(owner) = cells.get(2) else { continue };
        for path in owner.split('`').skip(1).step_by(2) {
            let segments: Vec<&str> = path.split("::").collect();
            let krate = root.join("crates").join(segments[0]);
            if !krate.is_dir() {
                continue; // not a Rust path (a file name, prose)
            }
            let sources = crate_sources(&krate);
            for name in &segments[1..] {
                let name = name.trim_end_matches("()");
                assert!(
                    defines(&sources, name),
                    "docs/architecture.md: `{path}`: no `{name}` in crates/{}",
                    segments[0]
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 30, "only {checked} owners checked: is the table still there?");
}
