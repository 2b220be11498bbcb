//! The build's provenance, recorded by this crate's build script (git commit, `git describe`,
//! clean or dirty tree, rustc): one record for both front ends, so the CLI's outputs and the
//! Python package's name the same build facts.

use wingcheck_io::{BuildInfo, TreeState};

/// The build this crate was compiled in (from build.rs; `unknown` facts outside a git checkout).
pub fn build_info() -> BuildInfo {
    BuildInfo {
        version: env!("CARGO_PKG_VERSION").to_string(),
        commit: env!("WINGCHECK_GIT_COMMIT").to_string(),
        tree: match env!("WINGCHECK_GIT_TREE") {
            "clean" => TreeState::Clean,
            "dirty" => TreeState::Dirty,
            _ => TreeState::Unknown,
        },
        describe: env!("WINGCHECK_GIT_DESCRIBE").to_string(),
        rustc: env!("WINGCHECK_RUSTC_VERSION").to_string(),
    }
}

/// Register [`build_info`] as the build every output's provenance names
/// ([`wingcheck_io::set_build`]; a front end calls this once at start-up).
pub fn register_build() {
    wingcheck_io::set_build(build_info());
}
