//! `wingcheck schema`: the JSON Schemas of the configuration and of every JSON output,
//! generated from the Rust types that write them (schemars), as committed under docs/schema/.
//! `wingcheck schema --out docs/schema` regenerates them (`just schema`); the test
//! `tests/outputs.rs` checks that the committed files equal what this prints and that every
//! output validates against its schema.

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;

/// Arguments of `wingcheck schema`.
#[derive(Debug, Args)]
pub struct SchemaArgs {
    /// Directory to write the schemas into (one `NAME.schema.json` per document).
    #[arg(long, default_value = "docs/schema")]
    out: PathBuf,
}

/// Marker of a schema directory: `--out` is replaced (atomically) only when it is missing, empty
/// or a schema directory holding nothing but the files its marker lists.
pub const MARKER: &str = ".wingcheck-schema";

pub fn run(a: SchemaArgs) -> anyhow::Result<()> {
    let files: Vec<(String, Vec<u8>)> = wingcheck_app::schemas()
        .into_iter()
        .map(|(name, s)| (format!("{name}.schema.json"), wingcheck_app::schema_text(&s).into_bytes()))
        .collect();
    wingcheck_io::write_marked_dir(&a.out, MARKER, "wingcheck schema", "a schema directory", &files)
        .with_context(|| format!("schema --out {}", a.out.display()))?;
    for (name, _) in &files {
        println!("wrote {}", a.out.join(name).display());
    }
    Ok(())
}
