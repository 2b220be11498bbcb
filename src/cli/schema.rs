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

pub fn run(a: SchemaArgs) -> anyhow::Result<()> {
    std::fs::create_dir_all(&a.out).with_context(|| format!("create {}", a.out.display()))?;
    for (name, s) in wingcheck_app::schemas() {
        let path = a.out.join(format!("{name}.schema.json"));
        wingcheck_io::write_file_atomic(&path, wingcheck_app::schema_text(&s).as_bytes())?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
