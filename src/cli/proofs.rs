//! `wingcheck certify` and `wingcheck verify`: exact certificates.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use wingcheck_claims::certify;

use super::common::ConfigArgs;

/// Arguments of `wingcheck certify`.
#[derive(Debug, Args)]
pub struct CertifyArgs {
    #[command(flatten)]
    config: ConfigArgs,
    /// Directory for the certificate set (replaced as a whole, atomically).
    #[arg(long, default_value = "proofs")]
    out: PathBuf,
}

/// Arguments of `wingcheck verify`.
#[derive(Debug, Args)]
pub struct VerifyArgs {
    /// Directory of a certificate set (index.json and the files it lists).
    #[arg(default_value = "proofs")]
    path: PathBuf,
    /// Pin the set to a configuration: with `--config FILE` and/or `--set key=value` the set must
    /// have been made for exactly that configuration (else any self-consistent set of any
    /// configuration verifies).
    #[command(flatten)]
    expected: ConfigArgs,
}

pub fn certify(a: CertifyArgs) -> anyhow::Result<()> {
    let cfg = a.config.load()?;
    let start = Instant::now();
    let written = wingcheck_app::ops::certify(&cfg, &a.out, &wingcheck_app::Cancel::new())?;
    let files = written.files;
    for f in &files {
        println!("wrote {}", f.display());
    }
    for n in &written.notes {
        println!("note: {n}");
    }
    println!(
        "{} files (certificates and index.json) for config sha256 {} in {:.2} s; re-check with `wingcheck verify {}`",
        files.len(),
        certify::manifest::config_hash(&cfg),
        start.elapsed().as_secs_f64(),
        a.out.display()
    );
    Ok(())
}

pub fn verify(a: VerifyArgs) -> anyhow::Result<()> {
    let pinned = a.expected.source().is_given();
    let expected = if pinned && !a.path.is_file() { Some(a.expected.load()?) } else { None };
    let start = Instant::now();
    let set = wingcheck_app::ops::verify(&a.path, expected.as_ref())?;
    let w = &set.config.wing;
    println!(
        "certificate set {} for config sha256 {}\n  wing: span = {}, rho = {}, rho_xc = {}, ei = {}, gj = {}, ip = {}, xi = {}",
        a.path.display(),
        set.config_sha256,
        certify::format_decimal(w.span),
        certify::format_decimal(w.rho),
        certify::format_decimal(w.rho_xc),
        certify::format_decimal(w.ei),
        certify::format_decimal(w.gj),
        certify::format_decimal(w.ip),
        certify::format_decimal(w.xi),
    );
    for c in &set.certs {
        println!("ok  {} [{}]: {}", c.role.id, c.fact.kind.as_str(), c.fact.statement);
    }
    for (claim, text) in &set.conclusions {
        println!("{claim}: {text}");
    }
    println!(
        "{} certificates verified in {:.3} s (parameters re-derived and checked in exact rational arithmetic; \
         the statements above are the verifier's own)",
        set.certs.len(),
        start.elapsed().as_secs_f64()
    );
    if pinned {
        println!("the set was made for the expected configuration (--config/--set; sha256 {})", set.config_sha256);
    } else {
        println!(
            "not pinned: these facts are about the set's own configuration above; pass --config FILE and/or \
             --set key=value to require it to be yours"
        );
    }
    Ok(())
}
