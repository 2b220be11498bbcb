//! Build-time provenance for the report: the git commit of the checkout (`unknown` when not
//! built from a git checkout or without git) and the rustc version, as the environment
//! variables `WINGCHECK_GIT_COMMIT` and `WINGCHECK_RUSTC_VERSION`. Cargo re-runs this script
//! when HEAD moves (a commit, a checkout) so the embedded commit follows the checkout.

use std::path::PathBuf;
use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git").args(args).output().ok()?;
    if !out.status.success() {
        return None;
    }
    let s = String::from_utf8(out.stdout).ok()?.trim().to_string();
    (!s.is_empty()).then_some(s)
}

/// Watch `path` if it exists (a missing path would make cargo re-run this script every build).
fn watch(path: PathBuf) {
    if path.exists() {
        println!("cargo:rerun-if-changed={}", path.display());
    }
}

fn main() {
    let commit = git(&["rev-parse", "HEAD"]).unwrap_or_else(|| "unknown".into());
    println!("cargo:rustc-env=WINGCHECK_GIT_COMMIT={commit}");
    // Dirty: tracked files differ from the commit at build time (untracked files ignored).
    let dirty = match git(&["status", "--porcelain", "--untracked-files=no"]) {
        _ if commit == "unknown" => "unknown",
        Some(_) => "yes",
        None => "no",
    };
    println!("cargo:rustc-env=WINGCHECK_GIT_DIRTY={dirty}");
    // Re-run when a tracked source changes (the dirty flag follows the tree) or the index does.
    let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap_or_default()).join("../..");
    for p in ["crates", "src", "tests", "configs", "docs", "Cargo.toml", "Cargo.lock", "README.md"] {
        watch(root.join(p));
    }
    if let Some(dir) = git(&["rev-parse", "--absolute-git-dir"]) {
        watch(PathBuf::from(&dir).join("index"));
    }
    // Re-run when HEAD or the branch it points to moves (worktrees keep HEAD in their own
    // git dir and the branch refs in the common dir; packed refs in packed-refs).
    if let Some(dir) = git(&["rev-parse", "--absolute-git-dir"]) {
        watch(PathBuf::from(&dir).join("HEAD"));
    }
    if let (Some(common), Some(refname)) =
        (git(&["rev-parse", "--path-format=absolute", "--git-common-dir"]), git(&["symbolic-ref", "-q", "HEAD"]))
    {
        let common = PathBuf::from(common);
        watch(common.join(&refname));
        watch(common.join("packed-refs"));
    }
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let version = Command::new(rustc)
        .arg("--version")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "unknown".into());
    println!("cargo:rustc-env=WINGCHECK_RUSTC_VERSION={version}");
    println!("cargo:rerun-if-changed=build.rs");
}
