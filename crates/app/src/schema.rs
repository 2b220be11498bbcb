//! Every JSON Schema of docs/schema/: the configuration and every JSON output, generated from
//! the Rust types that write them (schemars).

/// Every schema: the file name stem and the schema.
pub fn schemas() -> Vec<(&'static str, schemars::Schema)> {
    use schemars::schema_for;
    vec![
        ("config", wingcheck_model::config_schema()),
        ("check", schema_for!(wingcheck_claims::Ledger)),
        ("simulate", schema_for!(crate::SimulateSummary)),
        ("modes", schema_for!(crate::ModesDocument)),
        ("run", schema_for!(wingcheck_sim::output::RunDocument<'static>)),
        ("results", schema_for!(wingcheck_search::records::ResultsDocument)),
        ("best", schema_for!(wingcheck_search::records::BestDocument)),
        ("manifest", schema_for!(wingcheck_search::Manifest)),
        ("provenance", schema_for!(wingcheck_io::Provenance)),
        ("proofs-index", schema_for!(wingcheck_claims::certify::manifest::Manifest)),
    ]
}

/// The text of one schema file (pretty JSON, trailing newline).
pub fn schema_text(s: &schemars::Schema) -> String {
    serde_json::to_string_pretty(s).expect("a schema serialises") + "\n"
}
