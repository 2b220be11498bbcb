//! Integration tests of `write_report`: rendered into temp dirs on a short horizon (4 s) to
//! stay cheap; every reference value is computed independently in the test (comments say how).

use std::path::{Path, PathBuf};

use wingcheck_model::{apply_overrides, Config};
use wingcheck_report::{write_report, ReportError, ReportOptions, MARKER};
use wingcheck_sim::{simulate, RunOptions};

/// The paper's configuration on a 4-s horizon (the report's content does not depend on T
/// beyond the numbers, and the tests only need it to be small).
fn small_cfg(extra: &[&str]) -> Config {
    let mut sets = vec!["horizon.t_end=4".to_string()];
    sets.extend(extra.iter().map(|s| s.to_string()));
    apply_overrides(&Config::paper(), &sets).expect("valid overrides")
}

fn render(cfg: &Config, out: &Path) -> wingcheck_report::ReportSummary {
    write_report(cfg, out, &ReportOptions::default()).expect("report renders")
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("read {}: {e}", p.display()))
}

/// Names in `dir` other than `keep` (to detect leftover temp / old directories).
fn others(dir: &Path, keep: &[&str]) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .filter(|n| !keep.contains(&n.as_str()))
        .collect()
}

/// Parse as XML, allowing the `<!DOCTYPE html>` declaration.
fn parse_xml(text: &str) -> Result<roxmltree::Document<'_>, roxmltree::Error> {
    roxmltree::Document::parse_with_options(text, roxmltree::ParsingOptions { allow_dtd: true, ..Default::default() })
}

/// Text content of a node and its descendants.
fn text(n: roxmltree::Node) -> String {
    n.descendants().filter(|d| d.is_text()).map(|d| d.text().unwrap_or("")).collect()
}

fn has_class(n: &roxmltree::Node, c: &str) -> bool {
    n.attribute("class").is_some_and(|a| a.split_whitespace().any(|x| x == c))
}

/// Caption number with key `key` in index.html.
fn caption_number(html: &str, key: &str) -> f64 {
    let doc = parse_xml(html).expect("index.html is well-formed XML");
    let n = doc
        .descendants()
        .find(|n| n.attribute("data-key") == Some(key))
        .unwrap_or_else(|| panic!("no caption number {key}"));
    text(n).parse().unwrap_or_else(|e| panic!("{key}: {e}"))
}

#[test]
fn report_is_well_formed_complete_and_matches_the_ledger() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("paper");
    let cfg = small_cfg(&[]);
    let summary = render(&cfg, &out);
    assert_eq!(others(tmp.path(), &["paper"]), Vec::<String>::new(), "no temp dir left beside the report");
    assert!(out.join(MARKER).is_file());
    for f in &summary.files {
        assert!(out.join(f).is_file(), "summary lists {f}, which must exist");
    }
    let stages: Vec<&str> = summary.timings.iter().map(|t| t.name.as_str()).collect();
    assert!(stages.contains(&"simulations") && stages.contains(&"charts"), "{stages:?}");

    let html = read(&out.join("index.html"));
    let doc = parse_xml(&html).expect("index.html is well-formed XML");
    assert!(!html.contains("<script"), "no JavaScript");
    // Offline: no external resources (the only URLs are XML namespaces).
    for a in doc.descendants().filter_map(|n| n.attribute("src").or(n.attribute("href"))) {
        assert!(!a.contains("://"), "external resource {a}");
    }

    // Every image is a non-empty, well-formed SVG; every figure links its CSV.
    let figures: Vec<_> = doc.descendants().filter(|n| n.has_tag_name("figure")).collect();
    // 18 paper figures (3–20) + a 3-D view of each of the 6 field figures (3–6, 13–14) + the
    // zooms of τ1 and τ2 of each controlled run + 2 DOBC − FTDO difference maps + 1 accuracy
    // figure + the region map + the W-bounds row's λ2/λ1 against a/b + the ledger's own plots.
    let ledger_plots: usize = summary.ledger.rows.iter().map(|r| r.plots.len()).sum();
    assert_eq!(figures.len(), 18 + 6 + 4 + 2 + 1 + 1 + 1 + ledger_plots);
    let ledger_json: serde_json::Value = serde_json::from_str(&read(&out.join("ledger.json"))).unwrap();
    // The FTDO and DOBC q and θ fields have a 3-D view, with its axes labelled with units.
    for f in ["fig05-q-ftdo", "fig06-theta-ftdo", "fig13-q-dobc", "fig14-theta-dobc"] {
        let texts = svg_texts(&read(&out.join(format!("{f}-surface.svg"))));
        let unit = if f.contains("theta") { "θ (rad)" } else { "q (m)" };
        for label in ["t (s)", "z (m)", unit] {
            assert!(texts.iter().any(|t| t == label), "{f}-surface: axis label {label}: {texts:?}");
        }
    }
    for f in &figures {
        let img = f.descendants().find(|n| n.has_tag_name("img")).expect("figure has an image");
        let src = img.attribute("src").unwrap();
        assert!(src.ends_with(".svg") && !src.contains('/'), "local SVG: {src}");
        let svg = read(&out.join(src));
        let sdoc = parse_xml(&svg).unwrap_or_else(|e| panic!("{src} is not XML: {e}"));
        assert_eq!(sdoc.root_element().tag_name().name(), "svg");
        assert!(sdoc.root_element().children().filter(|n| n.is_element()).count() > 3, "{src} has content");
        let link = f
            .descendants()
            .filter(|n| n.has_tag_name("a"))
            .find(|a| {
                a.attribute("href").is_some_and(|h| h.ends_with(".csv") || h.ends_with(".csv.gz") || h == "ledger.json")
            })
            .unwrap_or_else(|| panic!("figure {src} links no data"));
        let href = link.attribute("href").unwrap();
        if href == "ledger.json" {
            // a ledger row's plot: the link's data-path names rows[i].plots[j], which holds its
            // lines; its text is for people (no "rows[")
            let t = text(link);
            assert!(!t.contains("rows["), "{src}: data link text {t}");
            let path = link.attribute("data-path").unwrap_or_else(|| panic!("{src}: no data-path on {t}"));
            let (i, j) = path
                .strip_prefix("rows[")
                .and_then(|r| r.split_once("].plots["))
                .and_then(|(i, r)| Some((i.parse::<usize>().ok()?, r.trim_end_matches(']').parse::<usize>().ok()?)))
                .unwrap_or_else(|| panic!("{src}: data path {path}"));
            assert!(
                ledger_json["rows"][i]["plots"][j]["lines"].as_array().is_some_and(|l| !l.is_empty()),
                "{src}: {t}"
            );
            continue;
        }
        let bytes = std::fs::read(out.join(href)).unwrap();
        let data = if href.ends_with(".gz") {
            use std::io::Read;
            let mut s = String::new();
            flate2::read::GzDecoder::new(&bytes[..]).read_to_string(&mut s).unwrap();
            s
        } else {
            String::from_utf8(bytes).unwrap()
        };
        assert!(data.lines().count() > 1, "{href} has a header and data");
    }
    // All local links resolve.
    for a in doc.descendants().filter(|n| n.has_tag_name("a")) {
        let href = a.attribute("href").unwrap();
        if let Some(anchor) = href.strip_prefix('#') {
            assert!(doc.descendants().any(|n| n.attribute("id") == Some(anchor)), "dangling anchor #{anchor}");
        } else {
            assert!(out.join(href).is_file(), "dangling link {href}");
        }
    }

    // The ledger table equals check_all's rows (computed independently here), in order, the
    // verdict and basis in their words (their Display texts; check prints the kebab tokens).
    let expected = wingcheck_claims::check_all(&cfg).unwrap();
    let table = doc.descendants().find(|n| n.attribute("id") == Some("ledger-table")).unwrap();
    let tbody = table.children().find(|n| n.has_tag_name("tbody")).unwrap();
    let rows: Vec<(String, String, String)> = tbody
        .children()
        .filter(|n| n.has_tag_name("tr"))
        .map(|tr| {
            let td = |c: &str| tr.children().find(|td| has_class(td, c)).unwrap();
            let cell = |c: &str| text(td(c)).trim().to_string();
            let id = td("id").descendants().find(|n| n.has_tag_name("a")).map(text).unwrap_or_default();
            (id, cell("verdict"), cell("basis"))
        })
        .collect();
    let want: Vec<(String, String, String)> =
        expected.rows.iter().map(|r| (r.id.to_string(), r.verdict.to_string(), r.basis.to_string())).collect();
    assert_eq!(rows, want);

    // List-of-record evidence (the SDP cross-check per N, the (a, b) sweep) is a table with one
    // row per record, never a compact "{…}" dump in an evidence cell.
    let captions: Vec<String> =
        doc.descendants().filter(|n| n.has_tag_name("caption")).map(|n| text(n).trim().to_string()).collect();
    let w = expected.row(wingcheck_claims::ClaimId::WBounds).unwrap();
    let wingcheck_claims::Evidence::WBounds(we) = &w.evidence else { panic!("W-bounds evidence") };
    let c = expected.row(wingcheck_claims::ClaimId::FtdoVsDobc).unwrap();
    let wingcheck_claims::Evidence::Comparison(ce) = &c.evidence else { panic!("comparison evidence") };
    for label in [&we.sdp_cross_check.label, &ce.ab_sweep.label] {
        assert!(captions.iter().any(|c| c == label), "no table for {label}: {captions:?}");
    }
    let sdp_rows = we.sdp_cross_check.rows.len();
    let caption =
        doc.descendants().find(|n| n.has_tag_name("caption") && text(*n).trim() == we.sdp_cross_check.label).unwrap();
    let table_rows = caption.parent().unwrap().descendants().filter(|n| n.has_tag_name("tr")).count();
    assert_eq!(table_rows, sdp_rows + 1, "header + one row per N");
    for td in doc.descendants().filter(|n| n.has_tag_name("td") && has_class(n, "num")) {
        assert!(!text(td).trim_start().starts_with('{'), "compact object in an evidence cell: {}", text(td));
    }

    // Provenance: the SHA-256 shown is the config's, and config.json hashes to it.
    assert!(html.contains(&wingcheck_claims::config_sha256(&cfg)));
    assert_eq!(read(&out.join("config.json")), serde_json::to_string(&cfg).unwrap());
}

/// index.html without the wall-time block.
fn strip_walltime(html: &str) -> String {
    let a = html.find("<!-- walltime:begin -->").expect("walltime block");
    let b = html.find("<!-- walltime:end -->").expect("walltime block");
    format!("{}{}", &html[..a], &html[b..])
}

#[test]
fn same_config_gives_identical_files_except_wall_times() {
    let tmp = tempfile::tempdir().unwrap();
    let cfg = small_cfg(&[]);
    let s1 = render(&cfg, &tmp.path().join("a"));
    let s2 = render(&cfg, &tmp.path().join("b"));
    assert_eq!(s1.files, s2.files);
    for f in &s1.files {
        let (x, y) = (
            std::fs::read(tmp.path().join("a").join(f)).unwrap(),
            std::fs::read(tmp.path().join("b").join(f)).unwrap(),
        );
        if f == "index.html" {
            let (x, y) = (String::from_utf8(x).unwrap(), String::from_utf8(y).unwrap());
            assert_eq!(strip_walltime(&x), strip_walltime(&y), "index.html differs outside the wall-time block");
        } else {
            assert!(x == y, "{f} differs between two renders of the same config");
        }
    }
}

#[test]
fn caption_numbers_come_from_the_run() {
    let tmp = tempfile::tempdir().unwrap();
    let base = small_cfg(&[]);
    let stiff = small_cfg(&["control.k1=6"]);
    let mut seen = Vec::new();
    for (name, cfg) in [("base", &base), ("k1", &stiff)] {
        let out = tmp.path().join(name);
        render(cfg, &out);
        let html = read(&out.join("index.html"));
        // Reference: max |q(s,t)| over [T/2, T] of an independent FTDO run of the same config.
        let ftdo = apply_overrides(cfg, &["control.kind=ftdo".to_string()]).unwrap();
        let s = simulate(&ftdo, RunOptions::default()).unwrap().series;
        let t_half = cfg.horizon.t_end / 2.0;
        let want = s.t.iter().zip(&s.q_tip).filter(|(t, _)| **t >= t_half).map(|(_, q)| q.abs()).fold(0.0, f64::max);
        let got = caption_number(&html, "fig9.max_abs_late");
        // Captions print 4 significant digits: relative rounding error ≤ 5e-4.
        assert!((got - want).abs() <= 5e-4 * want, "{name}: caption {got} vs run {want}");
        // Reference: max |τ1| over [0, T] of the same run.
        let tau = s.tau1.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let got_tau = caption_number(&html, "fig7.max_abs");
        assert!((got_tau - tau).abs() <= 5e-4 * tau, "{name}: τ1 caption {got_tau} vs run {tau}");
        seen.push(got);
    }
    assert!((seen[0] - seen[1]).abs() > 1e-3 * seen[0], "changing k1 must change the caption: {seen:?}");
}

#[test]
fn refuses_to_overwrite_a_directory_that_is_not_a_report() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("precious");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("thesis.tex"), "do not delete").unwrap();
    let err = write_report(&small_cfg(&[]), &out, &ReportOptions::default()).unwrap_err();
    assert!(matches!(err, ReportError::NotAReport { .. }), "{err}");
    assert!(err.to_string().contains(&out.display().to_string()), "error names the path: {err}");
    assert_eq!(read(&out.join("thesis.tex")), "do not delete");
    assert_eq!(others(tmp.path(), &["precious"]), Vec::<String>::new(), "no temp dir left on error");

    // A plain file is refused too, before any work (wingcheck_io::check_output_dir), untouched.
    let file = tmp.path().join("notes.txt");
    std::fs::write(&file, "x").unwrap();
    let err = write_report(&small_cfg(&[]), &file, &ReportOptions::default()).unwrap_err();
    assert!(matches!(err, ReportError::Output(wingcheck_io::IoError::BadOutput { .. })), "{err}");
    assert!(err.to_string().contains("exists and is a regular file, not a directory"), "{err}");
    assert_eq!(read(&file), "x");
}

#[test]
fn replaces_an_earlier_report_by_swap_and_leaves_nothing_behind() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("r");
    render(&small_cfg(&[]), &out);
    render(&small_cfg(&["control.a=0.5"]), &out);
    assert!(out.join("index.html").is_file());
    // A file the tool did not write is never deleted: the replacement is refused, naming it.
    std::fs::write(out.join("stale.txt"), "a user's notes").unwrap();
    let err = write_report(&small_cfg(&[]), &out, &ReportOptions::default()).unwrap_err();
    assert!(err.to_string().contains("stale.txt") && err.to_string().contains("did not write"), "{err}");
    assert_eq!(std::fs::read_to_string(out.join("stale.txt")).unwrap(), "a user's notes");
    assert!(out.join("index.html").is_file(), "the old report is intact");
    assert_eq!(others(tmp.path(), &["r"]), Vec::<String>::new());
}

#[test]
fn unwritable_output_is_a_clear_error_and_an_interrupted_run_leaves_no_temp_dir() {
    let tmp = tempfile::tempdir().unwrap();
    // Parent is a regular file: cannot create the directory; the error names the path.
    let blocker = tmp.path().join("blocker");
    std::fs::write(&blocker, "").unwrap();
    let out: PathBuf = blocker.join("report");
    let err = write_report(&small_cfg(&[]), &out, &ReportOptions::default()).unwrap_err();
    assert!(matches!(err, ReportError::Output(wingcheck_io::IoError::BadOutput { .. })), "{err}");
    assert!(err.to_string().contains(&format!("{} is a regular file, not a directory", blocker.display())), "{err}");

    // A run interrupted mid-way (a panicking progress callback while charts are written)
    // removes its staging directory and creates no report.
    let out = tmp.path().join("interrupted");
    let panicky = |p: wingcheck_report::Progress| {
        if p.stage == "charts" {
            panic!("interrupted");
        }
    };
    let r = std::panic::catch_unwind(|| {
        write_report(&small_cfg(&[]), &out, &ReportOptions { progress: Some(&panicky), ..Default::default() })
    });
    assert!(r.is_err());
    assert!(!out.exists());
    assert_eq!(others(tmp.path(), &["blocker"]), Vec::<String>::new(), "no temp dir left after interruption");
}

/// Text of every `<text>` element of an SVG.
fn svg_texts(svg: &str) -> Vec<String> {
    let doc = parse_xml(svg).expect("SVG is XML");
    doc.descendants().filter(|n| n.has_tag_name("text")).map(|n| text(n).trim().to_string()).collect()
}

/// An axis label with a unit: ends in `(unit)` with a non-empty unit.
fn has_unit(label: &str) -> bool {
    label.ends_with(')') && label.rfind('(').is_some_and(|i| label.len() - i > 2)
}

#[test]
fn ledger_digest_charts_sizes_links_and_provenance() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("paper");
    let cfg = small_cfg(&[]);
    let summary = render(&cfg, &out);
    let html = read(&out.join("index.html"));
    let doc = parse_xml(&html).expect("well-formed");

    // No raw evidence identifier in the ledger table: no evidence key of any row (keys are
    // snake_case / dotted identifiers) appears in its finding or numbers cells.
    let table = doc.descendants().find(|n| n.attribute("id") == Some("ledger-table")).unwrap();
    let cells: String = table
        .descendants()
        .filter(|n| has_class(n, "finding") || has_class(n, "numbers"))
        .map(text)
        .collect::<Vec<_>>()
        .join(" ");
    fn keys(v: &serde_json::Value, out: &mut Vec<String>) {
        if let Some(m) = v.as_object() {
            for (k, x) in m {
                out.push(k.clone());
                keys(x, out);
            }
        } else if let Some(a) = v.as_array() {
            a.iter().for_each(|x| keys(x, out));
        }
    }
    for r in &summary.ledger.rows {
        let mut all = Vec::new();
        keys(&r.evidence_json(), &mut all);
        for key in all.iter().filter(|k| k.contains('_') || k.contains('.')) {
            assert!(!cells.contains(key.as_str()), "ledger shows the raw evidence key {key}");
        }
        assert!(!r.finding.is_empty());
    }
    // Every ledger line states what decides its verdict; every row's section has a finding of
    // whole sentences and at least two decisive numbers.
    for tr in table.descendants().filter(|n| n.has_tag_name("tr") && n.attribute("id").is_some()) {
        let deciding = tr.children().find(|c| has_class(c, "deciding")).map(text).unwrap_or_default();
        assert!(!deciding.trim().is_empty(), "{:?}: nothing decides", tr.attribute("id"));
        let section_id = tr.attribute("id").unwrap().trim_start_matches("ledger-");
        let section = doc.descendants().find(|n| n.attribute("id") == Some(section_id)).unwrap();
        let finding = section.descendants().find(|p| p.has_tag_name("p") && text(*p).starts_with("Finding:")).map(text);
        assert!(finding.is_some_and(|f| f.trim().ends_with('.')), "{section_id}: finding is a sentence");
        let numbers = section
            .descendants()
            .filter(|n| n.has_tag_name("ul") && has_class(n, "decisive"))
            .flat_map(|ul| ul.children().filter(|li| li.has_tag_name("li")))
            .count();
        assert!(numbers >= 2, "{section_id}: {numbers} decisive numbers");
    }

    // Every chart — the report's own (paper figures, difference maps, accuracy, region map) and
    // the claims' evidence plots — has x and y axis labels with units.
    let mut total_svg = 0usize;
    let claim_charts = summary.files.iter().filter(|f| f.starts_with("claim-") && f.ends_with(".svg")).count();
    assert!(claim_charts > 0, "the claims' evidence plots are among the charts checked");
    // A claim plot's axes are labelled as the ledger's plot data says (a dimensional axis with
    // its unit in brackets, a dimensionless one — elements N, a ratio — without a "(1)").
    let claim_axes: Vec<(String, String, String)> = summary
        .ledger
        .rows
        .iter()
        .flat_map(|r| {
            r.plots.iter().map(move |p| (format!("{}-{}", r.id, p.name), p.x_label.clone(), p.y_label.clone()))
        })
        .collect();
    for f in summary.files.iter().filter(|f| f.ends_with(".svg")) {
        let svg = read(&out.join(f));
        total_svg += svg.len();
        let texts = svg_texts(&svg);
        if let Some((_, x, y)) = claim_axes.iter().find(|(name, _, _)| f == &format!("claim-{name}.svg")) {
            for label in [x, y] {
                assert!(texts.contains(label), "{f}: axis label {label} missing: {texts:?}");
                assert!(!label.ends_with("(1)"), "{f}: dimensionless axis labelled (1): {label}");
            }
            continue;
        }
        let labels: Vec<String> = texts.into_iter().filter(|t| has_unit(t)).collect();
        assert!(labels.len() >= 2, "{f}: axis labels with units, found {labels:?}");
    }
    // The mu-conditions plot (sup λ3/b ≈ 1e-5 below r*, down to ≈ −40 above) has a symmetric-log
    // y axis: 0 and signed decades as tick labels, and the linear threshold stated.
    let mu =
        summary.files.iter().find(|f| f.contains("mu-lambda3") && f.ends_with(".svg")).expect("the mu-conditions plot");
    let texts = svg_texts(&read(&out.join(mu)));
    assert!(texts.iter().any(|t| t.starts_with("linear for |y| ≤ 10")), "{mu}: threshold stated: {texts:?}");
    assert!(texts.iter().any(|t| t == "0") && texts.iter().any(|t| t.starts_with("−10")), "{mu}: {texts:?}");
    assert!(html.contains("symmetric-logarithmic"), "the caption says the axis is symmetric-log");
    // Total SVG within the page budget (1.5 MB; heatmaps are PNG rasters inside the SVGs).
    assert!(total_svg <= 1_500_000, "total SVG {total_svg} bytes");

    // No link or resource outside the report: relative, no parent directory, no scheme; and
    // no mention of material outside the repository.
    for a in doc.descendants().filter_map(|n| n.attribute("src").or(n.attribute("href"))) {
        assert!(!a.contains("://") && !a.starts_with('/') && !a.contains(".."), "link outside the report: {a}");
    }
    assert!(!html.contains("shared/"), "the report cites a path outside the repository");
    assert_eq!(
        read(&out.join("model.md")),
        read(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/model.md").as_path())
    );

    // The library on its own has no build facts (the wingcheck binary registers them; its test
    // tests/report_cli.rs checks the commit against git): the provenance says `unknown`.
    let commit = doc.descendants().find(|n| n.attribute("id") == Some("git-commit")).map(text).unwrap();
    assert_eq!(commit, "unknown");
}

#[test]
fn overall_progress_never_goes_back_and_ends_at_one() {
    let tmp = tempfile::tempdir().unwrap();
    let seen = std::sync::Mutex::new(Vec::new());
    let on = |p: wingcheck_report::Overall| seen.lock().unwrap().push(p.fraction);
    write_report(&small_cfg(&[]), &tmp.path().join("r"), &ReportOptions { overall: Some(&on), ..Default::default() })
        .unwrap();
    let v = seen.into_inner().unwrap();
    assert!(v.len() > 10, "{} updates", v.len());
    assert!(v.windows(2).all(|w| w[1] >= w[0]), "the overall fraction went back: {v:?}");
    assert!((v.last().unwrap() - 1.0).abs() < 1e-12, "ends at {}", v.last().unwrap());
}

/// The page says the set's ω₁ enclosure is coarser than `certify`'s only when it is: at the
/// paper's point (a/b = 1, far above ω₁ ≈ 0.12 1/s) the coarsest plan decides (4 modes in the
/// file); with b = 0 nothing is placed, so the set carries the tightest enclosure (36 modes,
/// `certify`'s), and the sentence is absent.
#[test]
fn the_enclosure_sentence_matches_the_sets_plan() {
    let tmp = tempfile::tempdir().unwrap();
    let sentence = "the coarsest that decides where the configured a/b lies";
    for (name, sets, coarser) in [("paper", &[][..], true), ("b0", &["control.b=0"][..], false)] {
        let out = tmp.path().join(name);
        render(&small_cfg(sets), &out);
        let html = read(&out.join("index.html"));
        let cert: serde_json::Value = serde_json::from_str(&read(&out.join("proofs/omega1-enclosure.json"))).unwrap();
        let modes = cert["modes"].as_u64().unwrap() as usize;
        assert_eq!(modes < wingcheck_claims::certify::omega1::PLAN.modes, coarser, "{name}: {modes} modes");
        assert_eq!(html.contains(sentence), coarser, "{name}");
    }
}
