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

/// The crate table of docs/architecture.md ("## Crate dependencies": one row per library crate,
/// the wingcheck crates it depends on) is the dependency graph of the Cargo.toml files: every
/// row's list equals the crate's `[dependencies]` on other wingcheck crates (dev-dependencies
/// aside), and every crate under crates/ has a row. A new dependency arrow fails here until the
/// page says it.
#[test]
fn the_crate_table_is_the_dependency_graph() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let doc = std::fs::read_to_string(root.join("docs/architecture.md")).unwrap();
    let table = doc.split("## Crate dependencies").nth(1).expect("the crate table").split("\n## ").next().unwrap();
    let mut documented = std::collections::BTreeMap::new();
    for line in table.lines().filter(|l| l.starts_with("| `")) {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let name = cells[1].trim_matches('`').to_string();
        let mut deps: Vec<String> =
            cells[2].split(',').map(|d| d.trim().trim_matches('`').to_string()).filter(|d| !d.is_empty() && d != "—").collect();
        deps.sort();
        documented.insert(name, deps);
    }
    let mut actual = std::collections::BTreeMap::new();
    for entry in std::fs::read_dir(root.join("crates")).unwrap() {
        let dir = entry.unwrap().path();
        let manifest = std::fs::read_to_string(dir.join("Cargo.toml")).unwrap();
        // the [dependencies] section only (not dev- or build-dependencies)
        let deps_section = manifest.split("\n[dependencies]").nth(1).unwrap_or("").split("\n[").next().unwrap();
        let mut deps: Vec<String> = deps_section
            .lines()
            .filter_map(|l| l.trim().strip_prefix("wingcheck-"))
            .map(|rest| rest.split(|c: char| !(c.is_alphanumeric() || c == '-')).next().unwrap().to_string())
            .collect();
        deps.sort();
        actual.insert(dir.file_name().unwrap().to_string_lossy().to_string(), deps);
    }
    assert_eq!(documented, actual, "docs/architecture.md's crate table against the Cargo.toml files");
}
