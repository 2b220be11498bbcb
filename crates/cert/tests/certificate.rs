//! Tests for the certificate envelope, hashing, atomic writes and verification.

use std::path::Path;

use serde_json::Value;
use wingcheck_cert::certificate::{content_hash, CertError, CertKind, Certificate, Payload};
use wingcheck_cert::exact::{frac, int, parse_rational};
use wingcheck_cert::fe::ClampedMesh;
use wingcheck_cert::lp::{FarkasCertificate, LinearSystem};
use wingcheck_cert::psd::{ldlt_witness, PsdError};
use wingcheck_cert::*;

fn tridiag() -> RationalMatrix {
    // [[2,−1,0],[−1,2,−1],[0,−1,2]] is PD (pivots 2, 3/2, 4/3 by hand).
    RationalMatrix::from_fn(3, 3, |i, j| match i.abs_diff(j) {
        0 => int(2),
        1 => int(-1),
        _ => int(0),
    })
}

fn pd_cert() -> Certificate {
    Certificate {
        id: "tridiag-pd".into(),
        claim: "test claim".into(),
        statement: "The 3×3 second-difference matrix is positive definite.".into(),
        payload: Payload::positive_definite(explicit_recipe(&tridiag())),
    }
}

fn farkas_cert() -> Certificate {
    // x ≤ 1, −x ≤ −2 infeasible; y = (1, 1).
    let sys = LinearSystem {
        a: RationalMatrix::from_rows(vec![vec![int(1)], vec![int(-1)]]).unwrap(),
        b: vec![int(1), int(-2)],
        a_eq: RationalMatrix::zeros(0, 1),
        b_eq: vec![],
    };
    Certificate {
        id: "interval-infeasible".into(),
        claim: "test claim".into(),
        statement: "No x satisfies x ≤ 1 and x ≥ 2.".into(),
        payload: Payload::farkas(&sys, &FarkasCertificate { y: vec![int(1), int(1)], w: vec![] }),
    }
}

fn write(dir: &Path, name: &str, c: &Certificate) -> std::path::PathBuf {
    let p = dir.join(name);
    write_certificate(&p, c).unwrap();
    p
}

#[test]
fn round_trip_all_kinds() {
    let dir = tempfile::tempdir().unwrap();
    let singular = RationalMatrix::from_rows(vec![vec![int(1), int(1)], vec![int(1), int(1)]]).unwrap();
    let (l, d) = ldlt_witness(&singular).unwrap();
    let sys = LinearSystem {
        a: RationalMatrix::from_rows(vec![vec![int(1), int(1)]]).unwrap(),
        b: vec![int(1)],
        a_eq: RationalMatrix::zeros(0, 2),
        b_eq: vec![],
    };
    let certs = [
        pd_cert(),
        farkas_cert(),
        Certificate {
            id: "psd".into(),
            claim: "c".into(),
            statement: "[[1,1],[1,1]] is PSD.".into(),
            payload: Payload::psd_ldlt(explicit_recipe(&singular), &l, &d),
        },
        Certificate {
            id: "feas".into(),
            claim: "c".into(),
            statement: "x + y ≤ 1 has the solution (1/3, 1/2).".into(),
            payload: Payload::feasible_point(&sys, &[frac(1, 3), frac(1, 2)]),
        },
    ];
    for (k, c) in certs.iter().enumerate() {
        let p = write(dir.path(), &format!("c{k}.json"), c);
        let text = std::fs::read_to_string(&p).unwrap();
        assert_eq!(&Certificate::from_json(&text).unwrap(), c);
        let v = verify_file(&p).unwrap();
        assert_eq!(v.id, c.id);
        assert_eq!(v.kind, c.payload.kind());
    }
    // No temp files are left behind by the atomic writer.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), certs.len());
}

#[test]
fn json_shape() {
    let v = pd_cert().to_value();
    assert_eq!(v["format"], "wingcheck-certificate");
    assert_eq!(v["version"], 1);
    assert_eq!(v["kind"], "positive-definite");
    assert_eq!(v["payload"]["recipe"]["name"], "explicit");
    assert_eq!(v["payload"]["recipe"]["params"]["rows"][0][1], "-1/1");
    assert_eq!(v["sha256"].as_str().unwrap().len(), 64);
    // Reformatting (compact, different whitespace) does not change the hash.
    let compact = serde_json::to_string(&v).unwrap();
    assert!(Certificate::from_json(&compact).is_ok());
}

#[test]
fn tampered_number_is_detected_by_hash() {
    let text = pd_cert().to_json();
    // Turn the −1 off-diagonal entries into −3: [[2,−3,..]] is indefinite, but the
    // hash catches the edit first.
    let bad = text.replacen("\"-1/1\"", "\"-3/1\"", 1);
    assert_ne!(bad, text);
    let e = Certificate::from_json(&bad).unwrap_err();
    assert!(matches!(e, CertError::Tampered { .. }), "{e}");
    assert!(e.to_string().starts_with("tampered: sha256 mismatch"));
}

/// Re-hashes a JSON text after editing, as an adversary would.
fn rehash(text: &str) -> String {
    let mut v: Value = serde_json::from_str(text).unwrap();
    let h = content_hash(&v);
    v["sha256"] = Value::String(h);
    serde_json::to_string_pretty(&v).unwrap()
}

#[test]
fn adversary_with_valid_hash_is_refuted_by_maths() {
    let dir = tempfile::tempdir().unwrap();
    // PD: the symmetric edit −1 → −3 in both (0,1) and (1,0) makes pivot 1 = 2 − 9/2 = −5/2.
    let text = pd_cert().to_json().replace("\"-1/1\"", "\"-3/1\"");
    let p = dir.path().join("pd.json");
    std::fs::write(&p, rehash(&text)).unwrap();
    match verify_file(&p) {
        Err(CertError::Psd(PsdError::PivotNotPositive { index: 1, value })) => {
            assert_eq!(value, frac(-5, 2))
        }
        other => panic!("expected pivot failure, got {other:?}"),
    }
    // Farkas: multiplier y = (1, 1) → (1, 2) leaves combination 1 − 2 = −1 at column 0.
    let mut v = farkas_cert().to_value();
    v["payload"]["y"][1] = Value::String("2/1".into());
    let p = dir.path().join("farkas.json");
    std::fs::write(&p, rehash(&v.to_string())).unwrap();
    let e = verify_file(&p).unwrap_err();
    assert!(e.to_string().contains("Farkas combination nonzero at column 0"), "{e}");
}

#[test]
fn truncated_and_malformed_files() {
    let dir = tempfile::tempdir().unwrap();
    let text = pd_cert().to_json();
    let p = dir.path().join("t.json");
    std::fs::write(&p, &text[..text.len() / 2]).unwrap();
    let e = verify_file(&p).unwrap_err();
    assert!(matches!(e, CertError::Truncated { .. }), "{e}");
    std::fs::write(&p, "{\"format\": wingcheck}").unwrap();
    let e = verify_file(&p).unwrap_err();
    assert!(matches!(e, CertError::Malformed { line: 1, .. }), "{e}");
    let e = verify_file(&dir.path().join("missing.json")).unwrap_err();
    assert!(e.to_string().starts_with("unreadable file"), "{e}");
    // Wrong format / version.
    let mut v = pd_cert().to_value();
    v["version"] = 2.into();
    assert!(matches!(Certificate::from_json(&v.to_string()), Err(CertError::UnsupportedVersion(_))));
    v["format"] = "something-else".into();
    assert!(matches!(Certificate::from_json(&v.to_string()), Err(CertError::WrongFormat(_))));
}

#[test]
fn directory_with_mixed_files() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "a_good.json", &pd_cert());
    write(dir.path(), "b_good.json", &farkas_cert());
    let text = pd_cert().to_json();
    std::fs::write(dir.path().join("c_tampered.json"), text.replacen("\"2/1\"", "\"3/1\"", 1)).unwrap();
    std::fs::write(dir.path().join("d_truncated.json"), &text[..40]).unwrap();
    std::fs::write(dir.path().join("notes.txt"), "ignored").unwrap();
    let out = verify_dir(dir.path());
    let names: Vec<_> = out.iter().map(|(p, _)| p.file_name().unwrap().to_string_lossy().into_owned()).collect();
    assert_eq!(names, ["a_good.json", "b_good.json", "c_tampered.json", "d_truncated.json"]);
    assert!(out[0].1.is_ok() && out[1].1.is_ok());
    assert!(matches!(out[2].1, Err(CertError::Tampered { .. })));
    assert!(matches!(out[3].1, Err(CertError::Truncated { .. })));
    // A missing directory is reported as one I/O failure.
    let missing = verify_dir(&dir.path().join("nope"));
    assert_eq!(missing.len(), 1);
    assert!(matches!(missing[0].1, Err(CertError::Io { .. })));
}

/// Caller-side recipe: clamped Hermite bending stiffness from `{length, elements}`.
fn hermite_stiffness_recipe(params: &Value) -> Result<RationalMatrix, String> {
    let length =
        parse_rational(params["length"].as_str().ok_or("length must be a string")?).map_err(|e| e.to_string())?;
    let n = params["elements"].as_u64().ok_or("elements must be an integer")? as usize;
    if n == 0 || length <= int(0) {
        return Err("need length > 0 and elements ≥ 1".into());
    }
    Ok(ClampedMesh::new(length, n).hermite_stiffness())
}

#[test]
fn custom_recipe_rebuilds_matrix() {
    let mut reg = RecipeRegistry::new();
    reg.register(Box::new(FnRecipe { name: "hermite-stiffness", build: hermite_stiffness_recipe })).unwrap();
    assert!(matches!(
        reg.register(Box::new(FnRecipe { name: "explicit", build: hermite_stiffness_recipe })),
        Err(CertError::DuplicateRecipe(_))
    ));
    let recipe =
        RecipeRef { name: "hermite-stiffness".into(), params: serde_json::json!({"length": "7/2", "elements": 60}) };
    let cert = Certificate {
        id: "beam-k-pd".into(),
        claim: "clamped beam stiffness is coercive".into(),
        statement: "The 120×120 clamped Hermite bending stiffness on [0, 7/2] is positive definite.".into(),
        payload: Payload::positive_definite(recipe),
    };
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "k.json", &cert);
    let v = verify_file_with(&p, &reg).unwrap();
    assert_eq!(v.kind, CertKind::PositiveDefinite);
    assert!(v.detail.contains("120×120"), "{}", v.detail);
    // Without the registration the verifier refuses rather than trusting the file.
    assert!(matches!(verify_file(&p), Err(CertError::UnknownRecipe(_))));
    // A broken parameter is reported by the recipe.
    let mut bad = cert.clone();
    bad.payload = Payload::positive_definite(RecipeRef {
        name: "hermite-stiffness".into(),
        params: serde_json::json!({"length": "-1", "elements": 3}),
    });
    assert!(matches!(verify_certificate(&bad, &reg), Err(CertError::Recipe { .. })));
}
