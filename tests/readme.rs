//! The README is a user guide: short, no unfilled placeholder, no development diary (commit
//! hashes, dated sittings), the two set-up commands as CI runs them, and every relative link of
//! the README and docs/ pointing at a file that exists.

use std::path::{Path, PathBuf};

fn repo(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)
}

fn read(rel: &str) -> String {
    std::fs::read_to_string(repo(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

/// Words of `text` made of ASCII letters, digits and `_`.
fn words(text: &str) -> impl Iterator<Item = &str> {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).filter(|w| !w.is_empty())
}

/// An unfilled placeholder: an upper-case word of two or more parts joined by `_` (e.g.
/// `FIRST_BUILD_COST`) that is not one of the environment variables the README names.
fn placeholders(text: &str) -> Vec<&str> {
    const NAMED: [&str; 4] = ["PROPTEST_RNG_SEED", "CARGO_TARGET_DIR", "RAYON_NUM_THREADS", "SLURM_CPUS_PER_TASK"];
    words(text)
        .filter(|w| w.contains('_') && w.chars().all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_'))
        .filter(|w| w.split('_').filter(|p| !p.is_empty()).count() >= 2 && !NAMED.contains(w))
        .collect()
}

/// A word that looks like a commit hash: 7 to 40 lower-case hex digits with at least one digit
/// and one letter.
fn commit_hashes(text: &str) -> Vec<&str> {
    words(text)
        .filter(|w| (7..=40).contains(&w.len()) && w.chars().all(|c| c.is_ascii_digit() || ('a'..='f').contains(&c)))
        .filter(|w| w.chars().any(|c| c.is_ascii_digit()) && w.chars().any(|c| c.is_ascii_alphabetic()))
        .collect()
}

/// Dates of the form 2026-12-06: a speed diary's, not a user guide's.
fn dates(text: &str) -> Vec<String> {
    let b = text.as_bytes();
    (0..b.len().saturating_sub(9))
        .filter(|&i| {
            let d = |j: usize| b[i + j].is_ascii_digit();
            d(0) && d(1) && d(2) && d(3) && b[i + 4] == b'-' && d(5) && d(6) && b[i + 7] == b'-' && d(8) && d(9)
        })
        .map(|i| text[i..i + 10].to_string())
        .collect()
}

#[test]
fn the_lints_catch_what_they_are_for() {
    // the lints themselves, on the kinds of text they exist to catch
    assert_eq!(placeholders("cost\n\nFIRST_BUILD_COST\n"), ["FIRST_BUILD_COST"]);
    assert!(placeholders("set PROPTEST_RNG_SEED=1; `--allow-large`").is_empty());
    assert_eq!(commit_hashes("against commit 04a9818 (bd794c4)"), ["04a9818", "bd794c4"]);
    assert!(commit_hashes("deadbeef 1234567 decade").is_empty());
    assert_eq!(dates("measured 2026-12-06 08:18"), ["2026-12-06"]);
}

#[test]
fn the_readme_is_a_short_user_guide_without_placeholders_or_a_diary() {
    let readme = read("README.md");
    let lines = readme.lines().count();
    assert!(lines <= 300, "README.md has {lines} lines; a user guide is about 250 (history goes to docs/)");
    assert!(placeholders(&readme).is_empty(), "unfilled placeholders in README.md: {:?}", placeholders(&readme));
    assert!(commit_hashes(&readme).is_empty(), "commit hashes in README.md: {:?}", commit_hashes(&readme));
    assert!(dates(&readme).is_empty(), "dated entries in README.md (a diary goes to docs/): {:?}", dates(&readme));
    for phrase in ["tried and dropped", "this sitting", "sitting of"] {
        assert!(!readme.to_lowercase().contains(phrase), "README.md reads like a diary: {phrase:?}");
    }
}

#[test]
fn the_readme_shows_the_two_set_up_commands_and_ci_runs_its_test_command() {
    let readme = read("README.md");
    for command in
        ["cargo run --release -- report", "cargo test --workspace --release", "cargo install --locked --path ."]
    {
        assert!(readme.contains(command), "README.md does not show `{command}`");
    }
    assert!(!readme.contains("cargo install --path"), "an install without --locked ignores Cargo.lock");
    let ci = read(".ci/run");
    assert!(
        ci.lines().any(|l| l.trim() == "cargo test --workspace --release"),
        ".ci/run runs the README's test command"
    );
}

/// Relative link targets `[text](target)` of a Markdown text, without `#anchor`s.
fn links(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find("](") {
        rest = &rest[at + 2..];
        let Some(end) = rest.find(')') else { break };
        let target = rest[..end].split('#').next().unwrap_or("").trim();
        if !target.is_empty() && !target.contains("://") && !target.starts_with("mailto:") {
            out.push(target.to_string());
        }
        rest = &rest[end..];
    }
    out
}

#[test]
fn every_relative_link_of_the_readme_and_docs_points_at_a_file() {
    let mut pages = vec![PathBuf::from("README.md")];
    for e in std::fs::read_dir(repo("docs")).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "md") {
            pages.push(p.strip_prefix(repo("")).unwrap().to_path_buf());
        }
    }
    let mut broken = Vec::new();
    let mut checked = 0;
    for page in &pages {
        let text = read(page.to_str().unwrap());
        let base = repo(page.to_str().unwrap()).parent().unwrap().to_path_buf();
        for target in links(&text) {
            checked += 1;
            if !base.join(&target).exists() {
                broken.push(format!("{}: {target}", page.display()));
            }
        }
    }
    assert!(checked > 20, "only {checked} links found: the link reader is broken");
    assert!(broken.is_empty(), "links to files that do not exist:\n{}", broken.join("\n"));
}
