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
    /// Directory for the certificates.
    #[arg(long, default_value = "proofs")]
    out: PathBuf,
}

/// Arguments of `wingcheck verify`.
#[derive(Debug, Args)]
pub struct VerifyArgs {
    /// Directory (or single file) of certificates.
    #[arg(default_value = "proofs")]
    path: PathBuf,
}

pub fn certify(a: CertifyArgs) -> anyhow::Result<()> {
    let cfg = a.config.load()?;
    let start = Instant::now();
    let files = certify::write_all(&cfg, &a.out)?;
    for f in &files {
        println!("wrote {}", f.display());
    }
    println!(
        "{} certificates in {:.2} s; re-check with `wingcheck verify {}`",
        files.len(),
        start.elapsed().as_secs_f64(),
        a.out.display()
    );
    Ok(())
}

pub fn verify(a: VerifyArgs) -> anyhow::Result<()> {
    let registry = certify::registry();
    let start = Instant::now();
    let results = if a.path.is_dir() {
        wingcheck_cert::verify_dir_with(&a.path, &registry)
    } else {
        vec![(a.path.clone(), wingcheck_cert::verify_file_with(&a.path, &registry))]
    };
    if results.is_empty() {
        anyhow::bail!("no certificates (*.json) in {}", a.path.display());
    }
    let mut failed = 0;
    for (path, r) in &results {
        match r {
            Ok(v) => println!("ok      {}: {}\n        {}", path.display(), v.statement, v.detail),
            Err(e) => {
                failed += 1;
                println!("REJECTED {}: {e}", path.display());
            }
        }
    }
    println!(
        "{} verified, {failed} rejected, in {:.2} s (exact rational arithmetic, independent of the solvers)",
        results.len() - failed,
        start.elapsed().as_secs_f64()
    );
    if failed > 0 {
        anyhow::bail!("{failed} certificate(s) rejected");
    }
    Ok(())
}
