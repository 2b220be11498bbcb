//! Outputs a user can load and trust without reading the source (issue 24): every CSV file
//! (`simulate --out run.csv`, a search's CSVs, the report's) read with a standard CSV reader
//! (the `csv` crate) has numpy-safe column names, each listed in docs/outputs.md with a unit or
//! as dimensionless, and no unexplained empty cell; every JSON output (config, check --json,
//! simulate --json, run.json, results.json, best.json, manifest.json, every provenance record,
//! the certificate index) validates against its committed schema in docs/schema/ (boon, a JSON
//! Schema 2020-12 validator), and the committed schemas are what `wingcheck schema` generates.
//! A partial `--config` file runs as the same keys given with `--set`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

fn wingcheck(args: &[&str]) -> Output {
    let o = Command::new(env!("CARGO_BIN_EXE_wingcheck")).args(args).output().expect("binary runs");
    assert!(o.status.success(), "wingcheck {args:?}: {}", String::from_utf8_lossy(&o.stderr));
    o
}

fn repo(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)
}

/// A short run of the paper's configuration (the outputs' shape does not depend on the horizon).
const SHORT: [&str; 2] = ["--set", "horizon.t_end=0.5"];

/// docs/outputs.md's tables, by the file each section (`## \`name\``) describes: column → unit.
/// The report's figure CSVs are keyed `report-line`, `report-field` and `region-map-ab.csv`.
fn documented() -> BTreeMap<String, BTreeMap<String, String>> {
    let doc = std::fs::read_to_string(repo("docs/outputs.md")).unwrap();
    let mut out: BTreeMap<String, BTreeMap<String, String>> = BTreeMap::new();
    let mut section = String::new();
    for line in doc.lines() {
        if let Some(h) = line.strip_prefix("## ") {
            section = h.trim_matches('`').to_string();
            continue;
        }
        if line.starts_with("Line plots") {
            section = "report-line".into();
        } else if line.starts_with("Fields (") {
            section = "report-field".into();
        } else if line.contains("(`region-map-ab.csv`)") {
            section = "region-map-ab.csv".into();
        }
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        if cells.len() >= 4 && cells[1].starts_with('`') && !cells[2].is_empty() {
            for name in cells[1].split(", ") {
                out.entry(section.clone())
                    .or_default()
                    .insert(name.trim_matches('`').to_string(), cells[2].to_string());
            }
        }
    }
    out
}

/// A documented unit: a unit (symbol) or a declaration that the column is dimensionless.
fn is_unit(u: &str) -> bool {
    !u.is_empty() && u != "?" && !u.eq_ignore_ascii_case("none")
}

/// Reads a CSV with the `csv` crate: header and records (every record as long as the header).
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::Reader::from_path(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let header: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
    let rows: Vec<Vec<String>> =
        r.records().map(|rec| rec.unwrap().iter().map(String::from).collect()).collect::<Vec<_>>();
    for row in &rows {
        assert_eq!(row.len(), header.len(), "{}: a record of another length", path.display());
    }
    (header, rows)
}

/// Every column of `header` is numpy-safe and documented in `section` with a unit; a column
/// named after a configuration key (`control__a`) must be a key documented with a unit.
fn check_columns(
    path: &Path,
    header: &[String],
    section: &BTreeMap<String, String>,
    config: &BTreeMap<String, String>,
) {
    for col in header {
        assert!(wingcheck_io::is_column_name(col), "{}: column {col:?} is not numpy-safe", path.display());
        let unit = match section.get(col.as_str()) {
            Some(u) => u.clone(),
            None if col.contains("__") => {
                assert!(section.contains_key("<section>__<key>"), "{}: {col} undocumented", path.display());
                let key = col.replace("__", ".");
                config
                    .get(&key)
                    .cloned()
                    .unwrap_or_else(|| panic!("{}: {key} not in the config-key table", path.display()))
            }
            None => panic!("{}: column {col} is not listed in docs/outputs.md", path.display()),
        };
        assert!(is_unit(&unit), "{}: column {col} has no unit ({unit:?})", path.display());
    }
}

/// The JSON Schema validator over the committed schemas.
struct Schemas {
    schemas: boon::Schemas,
    index: BTreeMap<String, boon::SchemaIndex>,
}

impl Schemas {
    fn committed() -> Schemas {
        let mut schemas = boon::Schemas::new();
        let mut compiler = boon::Compiler::new();
        let mut index = BTreeMap::new();
        for e in std::fs::read_dir(repo("docs/schema")).unwrap() {
            let path = e.unwrap().path();
            if !path.to_string_lossy().ends_with(".schema.json") {
                continue; // the directory's marker, .wingcheck-schema
            }
            let name = path.file_name().unwrap().to_string_lossy().trim_end_matches(".schema.json").to_string();
            let value: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
            let loc = format!("file:///schema/{name}.schema.json");
            compiler.add_resource(&loc, value).unwrap();
            index.insert(name, compiler.compile(&loc, &mut schemas).unwrap_or_else(|e| panic!("{loc}: {e:#}")));
        }
        Schemas { schemas, index }
    }

    fn validate(&self, schema: &str, what: &str, doc: &Value) {
        let i = *self.index.get(schema).unwrap_or_else(|| panic!("no committed schema {schema}"));
        if let Err(e) = self.schemas.validate(doc, i) {
            panic!("{what} does not validate against docs/schema/{schema}.schema.json: {e}");
        }
        assert_eq!(doc["schema_version"], 1, "{what}: schema_version");
    }

    fn validate_file(&self, schema: &str, path: &Path) -> Value {
        let doc: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        self.validate(schema, &path.display().to_string(), &doc);
        doc
    }
}

fn json(o: &Output) -> Value {
    serde_json::from_slice(&o.stdout).expect("JSON on stdout")
}

#[test]
fn the_committed_schemas_are_the_generated_ones() {
    let dir = tempfile::tempdir().unwrap();
    wingcheck(&["schema", "--out", dir.path().to_str().unwrap()]);
    let names = |d: &Path| {
        std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
            .collect::<BTreeSet<_>>()
    };
    assert_eq!(names(dir.path()), names(&repo("docs/schema")), "run `wingcheck schema --out docs/schema`");
    for n in names(dir.path()) {
        let made = std::fs::read_to_string(dir.path().join(&n)).unwrap();
        let committed = std::fs::read_to_string(repo("docs/schema").join(&n)).unwrap();
        assert!(made == committed, "docs/schema/{n} is stale: run `wingcheck schema --out docs/schema` (just schema)");
    }
    // the validator is not vacuous: a document of any output's schema needs its fields (the
    // config's keys are all optional, a partial file being merged over the default: its
    // schema refuses an unknown key instead; tests/config_schema.rs checks its ranges)
    let schemas = Schemas::committed();
    for (name, &i) in &schemas.index {
        let vacuous = if name == "config" { serde_json::json!({"wing": {"spam": 1}}) } else { serde_json::json!({}) };
        assert!(schemas.schemas.validate(&vacuous, i).is_err(), "{name} accepts {vacuous}");
    }
}

/// simulate --out run.csv (and run.json), simulate --json, config, check --json, a 2 × 2
/// search and the certificate index: loaded by standard readers, documented, valid.
#[test]
fn every_output_is_documented_and_valid() {
    let docs = documented();
    let config_units = docs["Configuration keys"].clone();
    let schemas = Schemas::committed();
    let dir = tempfile::tempdir().unwrap();
    let d = |n: &str| dir.path().join(n);

    // simulate: run.csv with its sidecar, run.json, the --json summary
    let csv = d("run.csv");
    let o = wingcheck(&[&["simulate", "--json", "--out", csv.to_str().unwrap()][..], &SHORT].concat());
    schemas.validate("simulate", "simulate --json", &json(&o));
    let modes = json(&wingcheck(&["modes", "--json", "--count", "3"]));
    schemas.validate("modes", "modes --json", &modes);
    assert_eq!(
        modes["provenance"]["config_sha256"],
        json(&wingcheck(&["simulate", "--json"]))["provenance"]["config_sha256"]
    );
    let (header, rows) = read_csv(&csv);
    check_columns(&csv, &header, &docs["run.csv"], &config_units);
    assert_eq!(rows.len(), 51, "0.5 s at 0.01 s: 51 samples");
    assert!(
        rows.iter().flatten().all(|c| c.parse::<f64>().is_ok_and(f64::is_finite)),
        "run.csv: a cell is not a finite number"
    );
    let side = schemas.validate_file("provenance", &wingcheck_io::sidecar_path(&csv));
    assert_eq!(side["files"][0]["file"], "run.csv");
    let cfg =
        wingcheck_model::apply_overrides(&wingcheck_model::Config::paper(), &["horizon.t_end=0.5".into()]).unwrap();
    assert_eq!(side["config_sha256"], cfg.sha256(), "the sidecar names the configuration that ran");
    let run_json = d("run.json");
    wingcheck(&[&["simulate", "--out", run_json.to_str().unwrap()][..], &SHORT].concat());
    schemas.validate_file("run", &run_json);

    // the configuration and the ledger
    let c = json(&wingcheck(&["config"]));
    let i = schemas.index["config"];
    assert!(schemas.schemas.validate(&c, i).is_ok(), "wingcheck config does not validate");
    let ledger = json(&wingcheck(&[&["check", "--json"][..], &SHORT].concat()));
    schemas.validate("check", "check --json", &ledger);
    assert_eq!(ledger["config_sha256"], cfg.sha256());

    // a search
    let out = d("search");
    let o = Command::new(env!("CARGO_BIN_EXE_wingcheck"))
        .args(
            [
                &[
                    "search",
                    "--over",
                    "control.a=1e-4,1",
                    "--over",
                    "control.b=1,2",
                    "--best",
                    "-tau1_rms_N",
                    "--out",
                    out.to_str().unwrap(),
                ][..],
                &SHORT,
            ]
            .concat(),
        )
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in ["results.csv", "failures.csv", "boundary.csv", "timings.csv"] {
        let (header, rows) = read_csv(&out.join(f));
        check_columns(&out.join(f), &header, &docs[f], &config_units);
        if f == "results.csv" {
            check_result_cells(&header, &rows);
        }
    }
    let results = schemas.validate_file("results", &out.join("results.json"));
    // one name per metric: results.json's units and metrics are keyed by results.csv's columns
    let (header, _) = read_csv(&out.join("results.csv"));
    for (m, u) in results["units"].as_object().unwrap() {
        assert!(header.contains(m), "results.json names {m}, which is not a results.csv column");
        assert!(is_unit(&docs["results.csv"][m]), "{m} ({u})");
    }
    for p in results["points"].as_array().unwrap() {
        for m in p["metrics"].as_object().unwrap().keys() {
            assert!(header.contains(m), "a point's metric {m} is not a results.csv column");
        }
    }
    // --best takes results.csv's column name, and best.json names the metric the same way
    let best = schemas.validate_file("best", &out.join("best.json"));
    assert_eq!((best["metric"].as_str(), best["order"].as_str()), (Some("tau1_rms_N"), Some("descending")));
    schemas.validate_file("manifest", &out.join("manifest.json"));
    let prov = schemas.validate_file("provenance", &out.join("provenance.json"));
    let listed: BTreeSet<&str> =
        prov["files"].as_array().unwrap().iter().map(|f| f["file"].as_str().unwrap()).collect();
    assert_eq!(listed, BTreeSet::from(["results.csv", "failures.csv", "boundary.csv", "timings.csv"]));

    // the committed certificate set's index
    let index: Value = serde_json::from_str(&std::fs::read_to_string(repo("proofs/index.json")).unwrap()).unwrap();
    assert!(schemas.schemas.validate(&index, schemas.index["proofs-index"]).is_ok(), "proofs/index.json");
}

/// results.csv: no empty text or flag cell; an empty metric cell is named by missing_metrics,
/// and settled is false exactly when settling_time_s is empty.
fn check_result_cells(header: &[String], rows: &[Vec<String>]) {
    let col = |n: &str| header.iter().position(|h| h == n).unwrap_or_else(|| panic!("no column {n}"));
    // missing_metrics names the empty cells by their column names
    let metrics: Vec<(usize, String)> = wingcheck_search::METRICS.iter().map(|m| (col(m), m.clone())).collect();
    for row in rows {
        let missing: BTreeSet<&str> = match row[col("missing_metrics")].as_str() {
            "none" => BTreeSet::new(),
            list => list.split(';').collect(),
        };
        for (i, cell) in row.iter().enumerate() {
            match metrics.iter().find(|(c, _)| *c == i) {
                Some((_, m)) => assert_eq!(cell.is_empty(), missing.contains(m.as_str()), "{m}: {row:?}"),
                None => assert!(!cell.is_empty(), "empty {} in {row:?}", header[i]),
            }
        }
        assert_eq!(row[col("settled")] == "false", row[col("settling_time_s")].is_empty());
    }
}

/// The report's CSVs: each column documented, each file described in provenance.json with the
/// units of its generic columns.
#[test]
fn the_reports_csvs_are_documented() {
    let docs = documented();
    let schemas = Schemas::committed();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r");
    wingcheck(&["report", "--out", out.to_str().unwrap(), "--set", "horizon.t_end=1"]);
    let prov = schemas.validate_file("provenance", &out.join("provenance.json"));
    let described: BTreeMap<&str, &str> = prov["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| (f["file"].as_str().unwrap(), f["contents"].as_str().unwrap()))
        .collect();
    let mut csvs = 0;
    for e in std::fs::read_dir(&out).unwrap() {
        let path = e.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if !(name.ends_with(".csv") || name.ends_with(".csv.gz")) {
            continue;
        }
        csvs += 1;
        assert!(described.contains_key(name.as_str()), "{name} not in provenance.json");
        let (header, _) = if name.ends_with(".gz") {
            // the same CSV, gzip-compressed: read it back with a standard decoder
            use std::io::Read;
            let mut text = String::new();
            flate2::read::GzDecoder::new(std::fs::File::open(&path).unwrap()).read_to_string(&mut text).unwrap();
            let plain = dir.path().join(name.trim_end_matches(".gz"));
            std::fs::write(&plain, text).unwrap();
            read_csv(&plain)
        } else {
            read_csv(&path)
        };
        let section = if name == "region-map-ab.csv" {
            "region-map-ab.csv"
        } else if header.first().map(String::as_str) == Some("t_s") {
            "report-field"
        } else {
            "report-line"
        };
        check_columns(&path, &header, &docs[section], &docs["Configuration keys"]);
    }
    assert_eq!(csvs, described.len(), "provenance.json lists exactly the data files (.csv, .csv.gz)");
    schemas.validate_file("check", &out.join("ledger.json"));
}

/// A file holding only `{"control": {"a": 0.5}}` is merged over the embedded default and runs
/// exactly as `--set control.a=0.5` (check --json, run.csv and its provenance sidecar compared
/// byte for byte; run.json holds wall times, so it is not compared);
/// `config --diff` names the key with both values; unknown keys are still refused by name.
#[test]
fn a_partial_config_file_equals_the_same_keys_set() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("partial.json");
    std::fs::write(&file, r#"{"control": {"a": 0.5}}"#).unwrap();
    let f = file.to_str().unwrap();
    let by_file = wingcheck(&["check", "--json", "--config", f, "--set", "horizon.t_end=0.5"]).stdout;
    let by_set = wingcheck(&["check", "--json", "--set", "control.a=0.5", "--set", "horizon.t_end=0.5"]).stdout;
    assert!(by_file == by_set, "check --json differs between the partial file and --set");
    let (a, b) = (dir.path().join("a.csv"), dir.path().join("b.csv"));
    wingcheck(&["simulate", "--config", f, "--out", a.to_str().unwrap(), "--set", "horizon.t_end=0.5"]);
    wingcheck(&["simulate", "--set", "control.a=0.5", "--out", b.to_str().unwrap(), "--set", "horizon.t_end=0.5"]);
    assert!(std::fs::read(&a).unwrap() == std::fs::read(&b).unwrap(), "run.csv differs");
    let side = |p: &Path| std::fs::read_to_string(wingcheck_io::sidecar_path(p)).unwrap().replace("a.csv", "b.csv");
    assert_eq!(side(&a), side(&b), "the provenance (config sha256) differs");
    let diff = String::from_utf8(wingcheck(&["config", "--config", f, "--diff"]).stdout).unwrap();
    assert_eq!(diff, "control.a: 0.5 (default 1.0)\n");
    // unknown keys and repeated keys are refused, naming them
    std::fs::write(&file, r#"{"control": {"a": 0.5, "gain": 2}}"#).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_wingcheck")).args(["config", "--config", f]).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("control.gain") && err.contains("unknown field"), "{err}");
    std::fs::write(&file, r#"{"wing": {"span": 3}, "wing": {"span": 4}}"#).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_wingcheck")).args(["config", "--config", f]).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("wing") && err.contains("twice"), "{err}");
}
