//! Certificates that bind what they state: the committed set is what `certify` makes today,
//! byte for byte; every forgery (with the hashes recomputed, as an adversary would) is rejected
//! with a message naming what failed, or verifies only as the weaker fact it really encodes;
//! adversarial numbers and sizes are refused before any arithmetic.

mod common;

use std::path::Path;

use common::paper_with;
use serde_json::{json, Value};
use wingcheck_claims::certify::{self, manifest, verify_set};

/// A forgery: the file edited, the edit, and what the rejection must mention.
type Forgery<'a> = (&'static str, Box<dyn Fn(&mut Value) + 'a>, &'static str);
/// A forgery with a plain function as the edit.
type PlainForgery = (&'static str, fn(&mut Value), &'static str);

fn fresh_set() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    certify::write_all(&paper_with(&[]), &dir.path().join("p")).unwrap();
    dir
}

fn read(dir: &Path, name: &str) -> Value {
    serde_json::from_slice(&std::fs::read(dir.join(name)).unwrap()).unwrap()
}

/// Rewrite a file and re-hash it in index.json, as a forger who knows the format would.
fn forge(dir: &Path, name: &str, edit: impl FnOnce(&mut Value)) {
    let mut v = read(dir, name);
    edit(&mut v);
    let text = serde_json::to_string_pretty(&v).unwrap();
    std::fs::write(dir.join(name), &text).unwrap();
    rehash(dir, name, text.as_bytes());
}

fn rehash(dir: &Path, name: &str, bytes: &[u8]) {
    let mut index = read(dir, "index.json");
    for e in index["certificates"].as_array_mut().unwrap() {
        if e["file"] == name {
            e["sha256"] = json!(manifest::sha256_hex(bytes));
        }
    }
    std::fs::write(dir.join("index.json"), serde_json::to_string_pretty(&index).unwrap()).unwrap();
}

fn edit_index(dir: &Path, edit: impl FnOnce(&mut Value)) {
    let mut index = read(dir, "index.json");
    edit(&mut index);
    std::fs::write(dir.join("index.json"), serde_json::to_string_pretty(&index).unwrap()).unwrap();
}

fn rejected(dir: &Path) -> String {
    match verify_set(dir) {
        Ok(s) => panic!("forgery accepted: {:?}", s.conclusions),
        Err(e) => e.to_string(),
    }
}

/// Remove every index entry naming certificate `id`: its listing and the claims' needs.
fn drop_from_index(dir: &Path, id: &str) {
    edit_index(dir, |v| {
        v["certificates"].as_array_mut().unwrap().retain(|e| e["id"] != id);
        for c in v["claims"].as_array_mut().unwrap() {
            c["needs"].as_array_mut().unwrap().retain(|n| n != id);
        }
    });
}

fn assert_rejected(dir: &Path, must_mention: &[&str]) {
    let e = rejected(dir);
    for m in must_mention {
        assert!(e.contains(m), "error should mention {m:?}: {e}");
    }
}

#[test]
fn committed_proofs_are_what_certify_makes_now() {
    let committed = Path::new(env!("CARGO_MANIFEST_DIR")).join("proofs");
    let fresh = certify::render_set(&paper_with(&[])).unwrap();
    let mut names: Vec<String> =
        std::fs::read_dir(&committed).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into()).collect();
    names.sort();
    let mut want: Vec<String> = fresh.iter().map(|(n, _)| n.clone()).collect();
    want.sort();
    assert_eq!(names, want, "proofs/ holds other files than certify writes; regenerate with `wingcheck certify`");
    for (name, text) in &fresh {
        let on_disk = std::fs::read_to_string(committed.join(name)).unwrap();
        assert!(on_disk == *text, "proofs/{name} is stale: regenerate with `wingcheck certify`");
    }
    let set = verify_set(&committed).unwrap();
    assert_eq!(set.certs.len(), 7);
    // The statements are the verifier's: λ of the committed lower bound, as a fraction.
    assert!(set.certs[0].fact.statement.contains("λ = -4149191/1000000"), "{}", set.certs[0].fact.statement);
}

#[test]
fn certificate_files_have_mode_0644_and_certify_replaces_the_whole_set() {
    let dir = fresh_set();
    let p = dir.path().join("p");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(p.join("w-bounds-lower.json")).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o644);
    }
    // a = 0.05 < ω₁ ≈ 0.121: W ≻ 0, so the indefinite certificate must disappear from the set.
    certify::write_all(&paper_with(&["control.a=0.05"]), &p).unwrap();
    assert!(!p.join("w-bounds-indefinite.json").exists(), "stale certificate of the old config left behind");
    let set = verify_set(&p).unwrap();
    assert!(set.certs.iter().all(|c| c.role.id != "w-bounds-indefinite"));
    assert!(set.conclusions[0].1.contains("W is positive definite"), "{}", set.conclusions[0].1);
    // No staging directories left beside it.
    let leftovers: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(leftovers.len(), 1, "{leftovers:?}");
}

#[test]
fn certify_refuses_a_directory_with_files_it_did_not_write() {
    let dir = fresh_set();
    let p = dir.path().join("p");
    std::fs::write(p.join("notes.txt"), "mine").unwrap();
    let e = certify::write_all(&paper_with(&[]), &p).unwrap_err().to_string();
    assert!(e.contains("notes.txt") && e.contains("did not write"), "{e}");
    assert_eq!(std::fs::read_to_string(p.join("notes.txt")).unwrap(), "mine");
}

#[test]
fn edited_values_are_caught_by_the_hash_or_by_the_maths() {
    let dir = fresh_set();
    let p = dir.path().join("p");
    // Edit without re-hashing: the manifest hash catches it.
    let f = p.join("w-bounds-lower.json");
    let text = std::fs::read_to_string(&f).unwrap();
    std::fs::write(&f, text.replace("-4149191/1000000", "0")).unwrap();
    assert_rejected(&p, &["w-bounds-lower.json", "hashes to"]);
    // Re-hashed: λ = 0 above the true infimum λ2 ≈ -4.154 is refuted by the exact LDLᵀ.
    rehash(&p, "w-bounds-lower.json", &std::fs::read(&f).unwrap());
    assert_rejected(&p, &["w-bounds-lower.json", "refuted", "pivot"]);
    // λ = −100 is a true (weaker) fact: it verifies, and what is printed says −100.
    forge(&p, "w-bounds-lower.json", |v| v["lambda"] = json!("-100"));
    let set = verify_set(&p).unwrap();
    assert!(set.certs[0].fact.statement.contains("λ = -100 "), "{}", set.certs[0].fact.statement);
    assert!(set.conclusions[0].1.contains("-100 < min W/κ"), "{}", set.conclusions[0].1);
}

#[test]
fn certificates_must_be_for_the_sets_config() {
    for (field, value, mention) in
        [("a", "0.5", "weights a = 1/2"), ("a", "-1", "must be ≥ 0"), ("b", "2", "config has a = 1, b = 1")]
    {
        let dir = fresh_set();
        let p = dir.path().join("p");
        forge(&p, "w-bounds-lower.json", |v| v["weights"][field] = json!(value));
        assert_rejected(&p, &["w-bounds-lower.json", mention]);
    }
    let dir = fresh_set();
    let p = dir.path().join("p");
    forge(&p, "mu-conditions-infeasible.json", |v| v["wing"]["xi"] = json!("1000"));
    assert_rejected(&p, &["mu-conditions-infeasible.json", "wing.xi = 1000"]);
    // One discretisation across the set (a 1-element bound would be a different statement).
    let dir = fresh_set();
    let p = dir.path().join("p");
    forge(&p, "w-bounds-upper.json", |v| v["elements"] = json!(1));
    assert_rejected(&p, &["elements = 1", "one discretisation"]);
    // The manifest's config edited: its hash no longer matches; re-hashed, the certificates disagree.
    let dir = fresh_set();
    let p = dir.path().join("p");
    edit_index(&p, |v| v["config"]["control"]["a"] = json!(0.5));
    assert_rejected(&p, &["config_sha256"]);
    let cfg = paper_with(&["control.a=0.5"]);
    edit_index(&p, |v| v["config_sha256"] = json!(manifest::config_hash(&cfg)));
    assert_rejected(&p, &["config has a = 1/2"]);
}

#[test]
fn text_matrices_and_systems_cannot_be_smuggled_in() {
    let cases: [PlainForgery; 6] = [
        (
            "w-bounds-lower.json",
            |v| v["statement"] = json!("W is positive definite (λ2 > 0)"),
            "unknown field `statement`",
        ),
        (
            "w-bounds-lower.json",
            |v| v["payload"] = json!({"recipe": {"name": "explicit", "params": {"rows": []}}}),
            "unknown field `payload`",
        ),
        (
            "mu-conditions-infeasible.json",
            |v| v["system"] = json!({"a": [["0"]], "b": ["-1"]}),
            "unknown field `system`",
        ),
        ("w-bounds-lower.json", |v| v["fact"] = json!("w-upper-bound"), "role w-bounds-lower needs w-lower-bound"),
        ("w-bounds-lower.json", |v| v["version"] = json!(1), "version"),
        ("w-bounds-upper.json", |v| v["witness"] = json!(["1"]), "witness: not part of a w-upper-bound"),
    ];
    for (file, edit, mention) in cases {
        let dir = fresh_set();
        let p = dir.path().join("p");
        forge(&p, file, edit);
        assert_rejected(&p, &[file, mention]);
    }
}

#[test]
fn wrong_witnesses_are_refuted() {
    let dir = fresh_set();
    let p = dir.path().join("p");
    forge(&p, "mu-conditions-infeasible.json", |v| v["witness"] = json!(["0", "0", "0"]));
    assert_rejected(&p, &["mu-conditions-infeasible.json", "refuted"]);
    let dir = fresh_set();
    let p = dir.path().join("p");
    // x = 0 gives W(x) = 0, not < 0.
    forge(&p, "w-bounds-indefinite.json", |v| {
        let n = v["witness"].as_array().unwrap().len();
        v["witness"] = json!(vec!["0"; n]);
    });
    assert_rejected(&p, &["w-bounds-indefinite.json", "W(x) = 0 is not < 0"]);
    let dir = fresh_set();
    let p = dir.path().join("p");
    forge(&p, "w-bounds-indefinite.json", |v| v["witness"].as_array_mut().unwrap().push(json!("1")));
    assert_rejected(&p, &["45 entries, 44 required"]);
    // The ratio-above state is not a negative direction at the configured a = b = 1? It is
    // (W(1,1) is indefinite too), but a ratio certificate must have b = 1.
    let dir = fresh_set();
    let p = dir.path().join("p");
    forge(&p, "w-bounds-ratio-above.json", |v| v["weights"]["b"] = json!("2"));
    assert_rejected(&p, &["needs b = 1"]);
}

#[test]
fn the_set_must_be_complete_and_only_itself() {
    // Copy one certificate over another (manifest re-hashed): id and file name disagree.
    let dir = fresh_set();
    let p = dir.path().join("p");
    std::fs::copy(p.join("w-bounds-lower.json"), p.join("w-bounds-upper.json")).unwrap();
    assert_rejected(&p, &["w-bounds-upper.json", "hashes to"]);
    rehash(&p, "w-bounds-upper.json", &std::fs::read(p.join("w-bounds-upper.json")).unwrap());
    assert_rejected(&p, &["w-bounds-upper.json", "id \"w-bounds-lower\" inside"]);
    // Delete one: missing.
    let dir = fresh_set();
    let p = dir.path().join("p");
    std::fs::remove_file(p.join("w-bounds-upper.json")).unwrap();
    assert_rejected(&p, &["w-bounds-upper.json"]);
    // Delete it and its manifest entries: the verifier's own table requires it.
    drop_from_index(&p, "w-bounds-upper");
    assert_rejected(&p, &["does not list w-bounds-upper, which the verifier requires"]);
    // Drop the indefinite certificate while the lower bound is negative: W-bounds is incomplete.
    let dir = fresh_set();
    let p = dir.path().join("p");
    std::fs::remove_file(p.join("w-bounds-indefinite.json")).unwrap();
    drop_from_index(&p, "w-bounds-indefinite");
    assert_rejected(&p, &["w-bounds-indefinite"]);
    // Drop the mu certificate: the verifier computes C3 < 0 itself and requires it.
    let dir = fresh_set();
    let p = dir.path().join("p");
    std::fs::remove_file(p.join("mu-conditions-infeasible.json")).unwrap();
    edit_index(&p, |v| {
        v["certificates"].as_array_mut().unwrap().retain(|e| e["id"] != "mu-conditions-infeasible");
        v["claims"].as_array_mut().unwrap().retain(|c| c["claim"] != "mu-conditions");
    });
    assert_rejected(&p, &["mu-conditions", "missing"]);
    // A stray file, and a stale certificate of another config.
    let dir = fresh_set();
    let p = dir.path().join("p");
    std::fs::write(p.join("old.json"), "{}").unwrap();
    assert_rejected(&p, &["old.json", "not listed"]);
    // An unknown id.
    let dir = fresh_set();
    let p = dir.path().join("p");
    edit_index(&p, |v| v["certificates"][0]["id"] = json!("made-up"));
    assert_rejected(&p, &["unknown certificate id"]);
    // No manifest at all.
    let dir = fresh_set();
    let p = dir.path().join("p");
    std::fs::remove_file(p.join("index.json")).unwrap();
    assert_rejected(&p, &["index.json"]);
}

#[test]
fn adversarial_numbers_and_sizes_are_refused_before_arithmetic() {
    let million = "9".repeat(1_000_000);
    let cases: Vec<Forgery<'_>> = vec![
        ("w-bounds-lower.json", Box::new(|v| v["lambda"] = json!("-1e99999")), "exponent"),
        ("w-bounds-lower.json", Box::new(|v| v["lambda"] = json!("-1e3000")), "exponent"),
        ("w-bounds-lower.json", Box::new(|v| v["lambda"] = json!("1/1e5")), "not an exact number"),
        ("w-bounds-lower.json", Box::new(|v| v["lambda"] = json!(format!("-{}", &million[..900_000]))), "characters"),
        ("w-bounds-lower.json", Box::new(|v| v["lambda"] = json!(format!("1/{}", &million[..900_000]))), "characters"),
        ("w-bounds-lower.json", Box::new(|v| v["weights"]["a"] = json!("1e-99999")), "exponent"),
        ("w-bounds-lower.json", Box::new(|v| v["elements"] = json!(40)), "40 outside [1, 4]"),
        ("w-bounds-lower.json", Box::new(|v| v["elements"] = json!(1e30)), "not a version-2 certificate"),
        ("w-bounds-indefinite.json", Box::new(|v| v["witness"][3] = json!(&million[..900_000])), "witness[3]"),
        ("w-bounds-indefinite.json", Box::new(|v| v["witness"] = json!(vec!["1"; 100_000])), "100000 entries"),
        ("mu-conditions-infeasible.json", Box::new(|v| v["witness"][1] = json!("1e64000")), "exponent"),
    ];
    for (file, edit, mention) in cases {
        let dir = fresh_set();
        let p = dir.path().join("p");
        forge(&p, file, edit);
        assert!(std::fs::metadata(p.join(file)).unwrap().len() <= 1 << 20);
        assert_rejected(&p, &[file, mention]);
    }
    // More than 1 MiB: refused unread.
    let dir = fresh_set();
    let p = dir.path().join("p");
    std::fs::write(p.join("w-bounds-lower.json"), vec![b' '; (1 << 20) + 1]).unwrap();
    assert_rejected(&p, &["larger than 1048576 bytes"]);
}

#[test]
fn an_si_scale_wing_certifies_and_a_forged_mu_certificate_is_refuted() {
    // Span 6 m, EI 1e7, GJ 1e6, ρ 100, I_p 10 with a = 1e-3, b = 2, ξ = 0.01: W ≻ 0 here, and
    // μ3's constant term bξEI/(2s⁴) − aρ = 2·0.01·1e7/(2·1296) − 0.1 = 62419/810 > 0 (by hand).
    let cfg = paper_with(&[
        "wing.span=6",
        "wing.ei=1e7",
        "wing.gj=1e6",
        "wing.rho=100",
        "wing.ip=10",
        "control.a=0.001",
        "control.b=2",
        "wing.xi=0.01",
    ]);
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("si");
    certify::write_all(&cfg, &p).unwrap();
    let set = verify_set(&p).unwrap();
    let ids: Vec<&str> = set.certs.iter().map(|c| c.role.id).collect();
    assert_eq!(
        ids,
        ["w-bounds-lower", "w-bounds-upper", "w-bounds-ratio-above", "w-bounds-ratio-below", "omega1-enclosure"]
    );
    assert!(set.conclusions[0].1.contains("W is positive definite on that space"), "{:?}", set.conclusions);
    assert!(set.conclusions[1].1.contains("62419/810"), "{:?}", set.conclusions);
    // Smuggle in the paper's μ3 certificate, re-parametrised for this wing: the verifier builds
    // the system itself, whose constant term is positive, so the Farkas check fails.
    let paper = fresh_set();
    let mut mu = read(&paper.path().join("p"), "mu-conditions-infeasible.json");
    mu["wing"] = read(&p, "w-bounds-lower.json")["wing"].clone();
    mu["weights"] = json!({"a": "0.001", "b": "2"});
    let text = serde_json::to_string_pretty(&mu).unwrap();
    std::fs::write(p.join("mu-conditions-infeasible.json"), &text).unwrap();
    edit_index(&p, |v| {
        v["certificates"].as_array_mut().unwrap().push(json!({
            "file": "mu-conditions-infeasible.json",
            "id": "mu-conditions-infeasible",
            "sha256": manifest::sha256_hex(text.as_bytes()),
        }));
        v["claims"]
            .as_array_mut()
            .unwrap()
            .push(json!({"claim": "mu-conditions", "needs": ["mu-conditions-infeasible"]}));
    });
    assert_rejected(&p, &["mu-conditions-infeasible.json", "refuted"]);
}

#[test]
fn the_omega1_enclosure_verifies_and_its_forgeries_are_refused() {
    let dir = fresh_set();
    let p = dir.path().join("p");
    let set = verify_set(&p).unwrap();
    let e = set.omega1.as_ref().expect("the set has an enclosure");
    // The verifier's own statement and the paper's ω₁ = 0.12085992204657 (tests/omega1.rs:
    // characteristic determinant) inside it.
    let fact = &set.certs.iter().find(|c| c.role.id == "omega1-enclosure").unwrap().fact;
    assert!(fact.statement.contains("≤ ω₁ ≤") && fact.statement.contains("continuous wing"), "{}", fact.statement);
    assert!(e.lower_f64() < 0.12085992204657 && 0.12085992204657 < e.upper_f64());
    assert!(set.conclusions[0].1.contains("a/b = 1 > ω̄₁: W is not positive definite for the continuous model"));
    let name = "omega1-enclosure.json";
    let cases: Vec<Forgery<'_>> = vec![
        // Λ₂ lowered below the second Galerkin eigenvalue (ω₂² ≈ 0.18 here): one negative pivot.
        (
            name,
            Box::new(|v| v["shifts"][0] = json!("0.1")),
            "Λ2 = 1.0000000000e-1: K_N − Λ2 M_N has only 1 negative pivots",
        ),
        // The test vector off the clamp: q(0) ≠ 0 is not an admissible state.
        (name, Box::new(|v| v["vector"][0] = json!("0.001")), "violates the clamp: q(0)"),
        (name, Box::new(|v| v["vector"][2] = json!("1/3")), "violates the clamp: θ(0)"),
        // A changed wing decimal: not the set's wing.
        (
            name,
            Box::new(|v| v["wing"]["ei"] = json!("0.25")),
            "wing.ei = 1/4 (≈ 2.500000e-1) but the set's config has 1/5",
        ),
        (name, Box::new(|v| v["wing"]["rho_xc"] = json!("-3.5")), "wing.rho_xc = -7/2"),
        // k and the shifts must agree; sizes and numbers are bounded before any arithmetic.
        (name, Box::new(|v| v["modes"] = json!(20)), "35 shifts, k − 1 = 19 required"),
        (name, Box::new(|v| v["modes"] = json!(1000)), "k = 1000 outside [1, 40]"),
        (name, Box::new(|v| v["inertia_elements"] = json!(4000)), "inertia_elements: 4000 outside [1, 28]"),
        (name, Box::new(|v| v["rayleigh_elements"] = json!(32)), "vector: 260 entries, 132 required"),
        (name, Box::new(|v| v["vector"] = json!(vec!["1"; 100_000])), "100000 entries, 260 required"),
        (name, Box::new(|v| v["shifts"][3] = json!("1e99999")), "exponent"),
        (name, Box::new(|v| v["shifts"][3] = json!("-2")), "Λ must be > 0"),
        // No room for a statement or the bounds themselves: the verifier derives them.
        (name, Box::new(|v| v["lower"] = json!("0.12")), "unknown field `lower`"),
        (name, Box::new(|v| v["fact"] = json!("w-lower-bound")), "expected omega1-enclosure"),
    ];
    for (file, edit, mention) in cases {
        let dir = fresh_set();
        let p = dir.path().join("p");
        forge(&p, file, edit);
        assert_rejected(&p, &[file, mention]);
    }
    // Every shift raised to 10⁶ is a true but weaker fact: it verifies, and the verifier
    // prints the weaker lower bound it implies, tr(G²)^(-1/4) (Λᵢ⁻² = 1e-12 each is negligible)
    // with tr(G²) = 11ρ²s⁸/(1680EI²) + 11(ρx_c)²s⁶/(180EI·GJ) + I_p²s⁴/(6GJ²)
    // = 4190.476… + 479.111… + 24 = 4693.5873015873 s⁴ for the paper's wing (by hand).
    let dir = fresh_set();
    let p = dir.path().join("p");
    forge(&p, name, |v| {
        for s in v["shifts"].as_array_mut().unwrap() {
            *s = json!("1000000");
        }
    });
    let weak = verify_set(&p).unwrap().omega1.unwrap();
    let trace_only = 4693.587301587302f64.powf(-0.25);
    assert!((weak.lower_f64() / trace_only - 1.0).abs() < 1e-12, "{} vs {trace_only}", weak.lower_f64());
    assert!(weak.lower < e.lower && weak.upper == e.upper);
    // The set needs its enclosure: dropped from the set and the index, the verifier's table
    // still requires it.
    let dir = fresh_set();
    let p = dir.path().join("p");
    std::fs::remove_file(p.join(name)).unwrap();
    drop_from_index(&p, "omega1-enclosure");
    assert_rejected(&p, &["does not list omega1-enclosure, which the verifier requires"]);
}
