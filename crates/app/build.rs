//! Build provenance of wingcheck (the CLI and the Python extension both link this crate and
//! register [`build_info`](../src/build_info.rs) through `wingcheck_io::set_build`): the git commit (`WINGCHECK_GIT_COMMIT`), `git describe --always
//! --dirty` (`WINGCHECK_GIT_DESCRIBE`), whether tracked files had uncommitted changes
//! (`WINGCHECK_GIT_TREE`: clean, dirty or unknown) and the rustc version
//! (`WINGCHECK_RUSTC_VERSION`). Outside a git checkout (a source tarball) or without git every
//! git fact is `unknown`, and the build still works.
//!
//! Cargo re-runs this script when HEAD, the branch it points to or the index moves, and when a
//! source file changes (the dirty flag follows the tree). Only this crate and the front ends
//! above it are rebuilt then: the libraries below get the facts at run time, so an edit never
//! recompiles them for provenance. Paths are watched from the workspace root (two levels up).

use std::path::{Path, PathBuf};
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
fn watch(path: &Path) {
    let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap_or_default()).join("../..");
    let path = root.join(path);
    if path.exists() {
        println!("cargo:rerun-if-changed={}", path.display());
    }
}

fn main() {
    let commit = git(&["rev-parse", "HEAD"]);
    let describe = commit.as_ref().and_then(|_| git(&["describe", "--always", "--dirty", "--abbrev=12"]));
    let tree = match &describe {
        Some(d) if d.ends_with("-dirty") => "dirty",
        Some(_) => "clean",
        None => "unknown",
    };
    println!("cargo:rustc-env=WINGCHECK_GIT_COMMIT={}", commit.as_deref().unwrap_or("unknown"));
    println!("cargo:rustc-env=WINGCHECK_GIT_DESCRIBE={}", describe.as_deref().unwrap_or("unknown"));
    println!("cargo:rustc-env=WINGCHECK_GIT_TREE={tree}");
    if commit.is_some() {
        // HEAD and the branch it points to (worktrees keep HEAD in their own git dir, branch refs
        // in the common dir), packed refs, and the index (staging changes the dirty flag).
        if let Some(dir) = git(&["rev-parse", "--absolute-git-dir"]) {
            watch(&PathBuf::from(&dir).join("HEAD"));
            watch(&PathBuf::from(&dir).join("index"));
        }
        if let Some(common) = git(&["rev-parse", "--path-format=absolute", "--git-common-dir"]) {
            let common = PathBuf::from(common);
            if let Some(refname) = git(&["symbolic-ref", "-q", "HEAD"]) {
                watch(&common.join(refname));
            }
            watch(&common.join("packed-refs"));
        }
        // The tracked sources: an edit makes the tree dirty (or clean again).
        for p in [
            "src",
            "crates",
            "configs",
            "tests",
            "scripts",
            "docs",
            "proofs",
            "Cargo.toml",
            "Cargo.lock",
            "python/src",
            "python/wingcheck",
            "python/tests",
            "python/Cargo.toml",
            "python/pyproject.toml",
        ] {
            watch(Path::new(p));
        }
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
