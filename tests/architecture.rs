//! docs/architecture.md against the code:
//! - its owner table names real items: every backticked Rust path in the table's "owner" column
//!   resolves to a crate under crates/, and its last segments name items defined there (a `fn`,
//!   `struct`, `enum`, `trait`, `type`, `const`, `static`, `mod` or a `pub` field of that name in
//!   the crate's library sources). A renamed or moved owner fails here;
//! - its crate table is the dependency graph of the Cargo.toml files;
//! - no two files of a library crate import each other, directly or around a loop.

use std::path::Path;

/// The crate's library sources ([`crate_modules`]), concatenated.
fn crate_sources(dir: &Path) -> String {
    crate_modules(&dir.join("src")).values().map(|p| std::fs::read_to_string(p).unwrap()).collect()
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
        let mut deps: Vec<String> = cells[2]
            .split(',')
            .map(|d| d.trim().trim_matches('`').to_string())
            .filter(|d| !d.is_empty() && d != "—")
            .collect();
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

// ---------------------------------------------------------------------------------------------
// No import circles between the files of a library crate.
//
// The graph: one node per source file of crates/<crate>/src (files named `*_tests.rs`, test
// modules kept in files of their own, are no nodes). File A has an arrow to file B when A's code
// (comments, strings and characters removed) names a path into B's module:
//   - a `use` of a path starting with `crate`, `super`, `self` or a child module of A's module,
//   - or such a path written inline (`crate::a::b::f(..)`, `super::x::Y`, `child::g()`),
// where the path `crate::a::b::Item` goes to the file of the longest prefix that is a module
// with a file of its own (`a/b.rs` or `a/b/mod.rs`, else `a.rs`, ...). Paths are read relative
// to the module they are written in, inline `mod name { .. }` blocks (tests) included.
// Not arrows, because they say nothing about which file needs which:
//   - `mod child;`: declaring a module is the module tree itself, not a use of it;
//   - `pub use` / `pub(crate) use` (any `pub` re-export): it hands names on; the files that take
//     those names get the arrow, to the re-exporting file (re-exports are not followed);
//   - a path into a module that contains A (A's parent files up to lib.rs): a module always
//     sees its parents, so a loop through a parent is the module tree, not a circle of files.
// ---------------------------------------------------------------------------------------------

use std::collections::{BTreeMap, BTreeSet};
use std::path::PathBuf;

/// A module path: `[]` = lib.rs, `["a", "b"]` = a/b.rs or a/b/mod.rs.
type ModPath = Vec<String>;

/// A library crate's source files by module path.
fn crate_modules(src: &Path) -> BTreeMap<ModPath, PathBuf> {
    let mut modules = BTreeMap::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                stack.push(p);
                continue;
            }
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            let Some(stem) = name.strip_suffix(".rs") else { continue };
            let top = d == src;
            if stem.ends_with("_tests") || (top && stem == "main") || d == src.join("bin") {
                continue; // a test module's own file, or a binary: no module of the library
            }
            let mut path: ModPath =
                d.strip_prefix(src).unwrap().iter().map(|c| c.to_string_lossy().into_owned()).collect();
            if stem != "mod" && !(top && stem == "lib") {
                path.push(stem.to_string());
            }
            modules.insert(path, p);
        }
    }
    modules
}

/// Index just past a `/* .. */` comment (nested) that starts at `i`.
fn block_comment_end(c: &[char], mut i: usize) -> usize {
    let mut depth = 0;
    while i + 1 < c.len() {
        if c[i] == '/' && c[i + 1] == '*' {
            (depth, i) = (depth + 1, i + 2);
        } else if c[i] == '*' && c[i + 1] == '/' {
            (depth, i) = (depth - 1, i + 2);
            if depth == 0 {
                return i;
            }
        } else {
            i += 1;
        }
    }
    c.len()
}

/// Index just past a literal closed by `close` whose body starts at `i` (`\` escapes unless raw).
fn literal_end(c: &[char], mut i: usize, close: &[char], raw: bool) -> usize {
    while i < c.len() && !c[i..].starts_with(close) {
        i += if c[i] == '\\' && !raw { 2 } else { 1 };
    }
    (i + close.len()).min(c.len())
}

/// The code's tokens: identifiers, `::` and single punctuation characters; comments (doc
/// comments too), string and character literals dropped.
fn tokens(text: &str) -> Vec<String> {
    let c: Vec<char> = text.chars().collect();
    let (mut out, mut i) = (Vec::new(), 0);
    while i < c.len() {
        let at = |k: usize| c.get(i + k).copied().unwrap_or(' ');
        if c[i] == '/' && at(1) == '/' {
            i = literal_end(&c, i, &['\n'], true);
        } else if c[i] == '/' && at(1) == '*' {
            i = block_comment_end(&c, i);
        } else if c[i] == '"' {
            i = literal_end(&c, i + 1, &['"'], false);
        } else if c[i] == 'r' && (at(1) == '"' || (at(1) == '#' && matches!(at(2), '"' | '#'))) {
            let hashes = c[i + 1..].iter().take_while(|&&h| h == '#').count();
            let close: Vec<char> = std::iter::once('"').chain(std::iter::repeat_n('#', hashes)).collect();
            i = literal_end(&c, i + 2 + hashes, &close, true);
        } else if c[i] == '\'' && (at(1) == '\\' || at(2) == '\'') {
            i = literal_end(&c, i + 1, &['\''], false); // a character, not a lifetime
        } else if c[i].is_alphanumeric() || c[i] == '_' {
            let start = i;
            while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
                i += 1;
            }
            out.push(c[start..i].iter().collect());
        } else if c[i] == ':' && at(1) == ':' {
            out.push("::".to_string());
            i += 2;
        } else {
            if !c[i].is_whitespace() {
                out.push(c[i].to_string());
            }
            i += 1;
        }
    }
    out
}

/// The paths of the `use` tree at `t[*i]`, each in full (`super::a::{B, c::D}` gives
/// `super::a::B` and `super::a::c::D`); `*i` is left on the `,`, `}` or `;` that ends it.
fn use_tree(t: &[String], i: &mut usize, prefix: &[String], out: &mut Vec<ModPath>) {
    let mut path = prefix.to_vec();
    while let Some(tok) = t.get(*i) {
        match tok.as_str() {
            "{" => {
                *i += 1;
                while t.get(*i).is_some_and(|s| s != "}") {
                    use_tree(t, i, &path, out);
                    if t.get(*i).is_some_and(|s| s == ",") {
                        *i += 1;
                    }
                }
                *i += 1;
                return;
            }
            "," | "}" | ";" => break,
            "as" => *i += 2,
            "self" if !path.is_empty() => *i += 1,
            "::" | "*" => *i += 1,
            _ => {
                path.push(tok.clone());
                *i += 1;
            }
        }
    }
    out.push(path);
}

/// Whether the `use` at `t[i]` is a re-export (`pub use`, `pub(crate) use`, `pub(in a) use`).
fn is_pub_use(t: &[String], i: usize) -> bool {
    let before = |k: usize| i.checked_sub(k).map(|j| t[j].as_str());
    if before(1) == Some("pub") {
        return true;
    }
    if before(1) != Some(")") {
        return false;
    }
    let open = (0..i - 1).rev().find(|&j| t[j] == "(");
    open.is_some_and(|j| j > 0 && t[j - 1] == "pub")
}

/// Every path a file names, with the module it is written in (the file's, or an inline `mod`
/// block's inside it): the paths of its non-`pub` `use`s and the inline paths that start with
/// `crate`, `super`, `self` or a child module.
fn named_paths(t: &[String], file: &ModPath, modules: &BTreeMap<ModPath, PathBuf>) -> Vec<(ModPath, ModPath)> {
    let (mut out, mut inline, mut depth, mut i) = (Vec::new(), Vec::<(String, usize)>::new(), 0, 0);
    let here = |inline: &[(String, usize)]| [file.clone(), inline.iter().map(|m| m.0.clone()).collect()].concat();
    while i < t.len() {
        let tok = t[i].as_str();
        let after_sep = i > 0 && t[i - 1] == "::";
        match tok {
            "{" => depth += 1,
            "}" => {
                depth -= 1;
                if inline.last().is_some_and(|m| m.1 == depth) {
                    inline.pop();
                }
            }
            "mod" if t.get(i + 2).is_some_and(|s| s == "{") => {
                inline.push((t[i + 1].clone(), depth));
                (depth, i) = (depth + 1, i + 3);
                continue;
            }
            "use" => {
                let (public, mut paths) = (is_pub_use(t, i), Vec::new());
                i += 1;
                use_tree(t, &mut i, &[], &mut paths);
                if !public {
                    out.extend(paths.into_iter().map(|p| (here(&inline), p)));
                }
                continue;
            }
            _ if !after_sep && t.get(i + 1).is_some_and(|s| s == "::") => {
                let child = [here(&inline), vec![tok.to_string()]].concat();
                if matches!(tok, "crate" | "super" | "self") || modules.contains_key(&child) {
                    let mut path = vec![tok.to_string()];
                    while t.get(i + 1).is_some_and(|s| s == "::")
                        && t.get(i + 2).is_some_and(|s| s.starts_with(|c: char| c.is_alphanumeric() || c == '_'))
                    {
                        path.push(t[i + 2].clone());
                        i += 2;
                    }
                    out.push((here(&inline), path));
                }
            }
            _ => {}
        }
        i += 1;
    }
    out
}

/// The module of the file that `path`, written in module `here`, points into, and the name it
/// takes there (the segment after the module, or the module's own name).
fn resolve(here: &ModPath, path: &ModPath, modules: &BTreeMap<ModPath, PathBuf>) -> Option<(ModPath, String)> {
    let mut base = here.clone();
    let mut rest = path.as_slice();
    match path.first().map(String::as_str) {
        Some("crate") => (base, rest) = (Vec::new(), &path[1..]),
        Some("self") => rest = &path[1..],
        Some("super") => {
            while rest.first().is_some_and(|s| s == "super") {
                base.pop();
                rest = &rest[1..];
            }
        }
        Some(_) => {}
        None => return None,
    }
    let full = [base, rest.to_vec()].concat();
    let k = (0..=full.len()).rev().find(|&k| modules.contains_key(&full[..k]))?;
    let name = full.get(k).or(full.last()).cloned().unwrap_or_else(|| "crate".to_string());
    Some((full[..k].to_vec(), name))
}

/// A crate's arrows between files: from each file's module to each other file's module it
/// names, with the names taken (see the rule above).
type Arrows = BTreeMap<ModPath, BTreeMap<ModPath, BTreeSet<String>>>;

fn file_arrows(src: &Path) -> (BTreeMap<ModPath, PathBuf>, Arrows) {
    let modules = crate_modules(src);
    let mut arrows = Arrows::new();
    for (module, file) in &modules {
        let t = tokens(&std::fs::read_to_string(file).unwrap());
        for (here, path) in named_paths(&t, module, &modules) {
            let Some((target, name)) = resolve(&here, &path, &modules) else { continue };
            if !module.starts_with(&target) {
                arrows.entry(module.clone()).or_default().entry(target).or_default().insert(name);
            }
        }
    }
    (modules, arrows)
}

/// The circles of a graph: its strongly connected sets of two files or more.
fn circles(arrows: &Arrows) -> Vec<BTreeSet<ModPath>> {
    let reach = |from: &ModPath| {
        let (mut seen, mut stack) = (BTreeSet::new(), vec![from.clone()]);
        while let Some(m) = stack.pop() {
            for next in arrows.get(&m).into_iter().flat_map(|targets| targets.keys()) {
                if seen.insert(next.clone()) {
                    stack.push(next.clone());
                }
            }
        }
        seen
    };
    let reached: BTreeMap<&ModPath, BTreeSet<ModPath>> = arrows.keys().map(|m| (m, reach(m))).collect();
    let mut found: Vec<BTreeSet<ModPath>> = Vec::new();
    for (m, from_m) in &reached {
        let circle: BTreeSet<ModPath> =
            from_m.iter().filter(|n| reached.get(n).is_some_and(|r| r.contains(*m))).cloned().collect();
        if circle.len() > 1 && !found.contains(&circle) {
            found.push(circle);
        }
    }
    found
}

#[test]
fn no_import_circles_between_the_files_of_a_crate() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut crates: Vec<PathBuf> = std::fs::read_dir(root.join("crates")).unwrap().map(|e| e.unwrap().path()).collect();
    crates.sort();
    let (mut report, mut arrow_count) = (String::new(), 0);
    for krate in crates.iter().filter(|k| k.join("src/lib.rs").is_file()) {
        let src = krate.join("src");
        let (modules, arrows) = file_arrows(&src);
        arrow_count += arrows.values().map(BTreeMap::len).sum::<usize>();
        let shown = |m: &ModPath| modules[m].strip_prefix(root).unwrap().display().to_string();
        for circle in circles(&arrows) {
            report += &format!("circle of {} files:\n", circle.len());
            for from in &circle {
                for (to, names) in arrows[from].iter().filter(|(to, _)| circle.contains(*to)) {
                    let names: Vec<&str> = names.iter().map(String::as_str).collect();
                    report += &format!("  {} -> {}: {}\n", shown(from), shown(to), names.join(", "));
                }
            }
        }
    }
    // Reference: the library crates' files import each other along a few hundred arrows; far
    // fewer means this parser stopped reading them, and the check below would pass for nothing.
    assert!(arrow_count >= 200, "only {arrow_count} arrows between files read: is the parser still reading?");
    assert!(report.is_empty(), "import circles between the files of a crate (share through a leaf module):\n{report}");
}
