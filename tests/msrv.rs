//! The minimum Rust version Cargo.toml declares is true of the dependency tree that Cargo.lock
//! pins: no package the build or the tests resolve declares a newer `rust-version`.
//!
//! Packages that declare no `rust-version` cannot be checked this way; they are listed when the
//! test fails so a reader sees what the declaration rests on. The workspace uses resolver "3"
//! (MSRV-aware), so `cargo update` keeps choosing versions that hold this test.

use std::process::Command;

use serde_json::Value;

/// "1.85" or "1.85.0" as (major, minor, patch).
fn version(v: &str) -> (u64, u64, u64) {
    let mut parts = v.split('.').map(|p| p.parse::<u64>().unwrap_or_else(|_| panic!("rust-version {v:?}")));
    let major = parts.next().unwrap_or(0);
    let minor = parts.next().unwrap_or(0);
    let patch = parts.next().unwrap_or(0);
    (major, minor, patch)
}

#[test]
fn no_locked_dependency_needs_a_newer_rust_than_the_workspace_declares() {
    check_lock(env!("CARGO_MANIFEST_DIR"), "wingcheck", 100, &["--offline"]);
}

/// The Python extension is a workspace of its own (python/Cargo.lock, built by `pip install
/// ./python`): it declares the same minimum and its lock holds the same. Not `--offline`: the
/// extension's own crates (pyo3, numpy) are fetched here if the package was never built.
#[test]
fn no_dependency_locked_for_the_python_package_needs_a_newer_rust() {
    check_lock(concat!(env!("CARGO_MANIFEST_DIR"), "/python"), "wingcheck-python", 60, &[]);
}

/// Every package that `dir`'s Cargo.lock resolves declares at most the `rust-version` of the
/// package `root` (which must declare one, equal to the CLI's); at least `min_resolved`
/// packages are resolved and most of them declare a version (the check is not vacuous).
fn check_lock(dir: &str, root: &str, min_resolved: usize, flags: &[&str]) {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .args(["metadata", "--format-version", "1", "--locked"])
        .args(flags)
        .current_dir(dir)
        .output()
        .expect("cargo metadata runs");
    assert!(out.status.success(), "cargo metadata: {}", String::from_utf8_lossy(&out.stderr));
    let meta: Value = serde_json::from_slice(&out.stdout).expect("cargo metadata prints JSON");

    let packages = meta["packages"].as_array().expect("packages");
    let root = packages.iter().find(|p| p["name"] == root).expect("the root package");
    let declared = root["rust_version"].as_str().expect("Cargo.toml declares rust-version");
    assert_eq!(declared, env!("CARGO_PKG_RUST_VERSION"), "{dir}: one minimum Rust version");
    let msrv = version(declared);

    let resolved: std::collections::BTreeSet<&str> =
        meta["resolve"]["nodes"].as_array().expect("resolve.nodes").iter().filter_map(|n| n["id"].as_str()).collect();
    let mut newer = Vec::new();
    let mut undeclared = 0;
    for p in packages.iter().filter(|p| p["id"].as_str().is_some_and(|id| resolved.contains(id))) {
        match p["rust_version"].as_str() {
            Some(v) if version(v) > msrv => newer.push(format!(
                "{} {} needs {v}",
                p["name"].as_str().unwrap_or("?"),
                p["version"].as_str().unwrap_or("?")
            )),
            Some(_) => {}
            None => undeclared += 1,
        }
    }
    assert!(
        newer.is_empty(),
        "Cargo.toml declares rust-version {declared}, but Cargo.lock pins packages that need more \
         ({undeclared} more declare none):\n{}",
        newer.join("\n")
    );
    // The check is not vacuous: most of the tree declares a version.
    assert!(
        resolved.len() > min_resolved && undeclared < resolved.len() / 2,
        "{undeclared} of {} undeclared",
        resolved.len()
    );
}
