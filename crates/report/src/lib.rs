//! `wingcheck report`: one self-contained, offline HTML report (index.html + one SVG and one
//! CSV per figure) with
//!
//! - the claim ledger of [`wingcheck_claims::check_all`] at the top, colour-coded by verdict,
//!   each row linking to its section (evidence, assumptions, the row's own plots);
//! - the paper's Figures 3–20 reproduced from simulations (no control, FTDO, DOBC), with
//!   captions whose numbers are computed from the runs;
//! - FTDO-vs-DOBC overlays, and an accuracy section (tip error vs grid, FD and FE);
//! - assumptions (values the paper leaves out) and provenance (tool, platform, config and its
//!   SHA-256, wall time per stage).
//!
//! The page is rendered from a template (`templates/index.html`, minijinja) with a serde
//! context; it is well-formed XHTML, has no JavaScript and no external resources. Output is
//! atomic ([`atomic`]) and deterministic: the same config gives byte-identical files except
//! the wall times, which appear only between `<!-- walltime:begin -->` and
//! `<!-- walltime:end -->` in index.html.

#![forbid(unsafe_code)]

mod accuracy;
pub mod atomic;
use wingcheck_chart as chart;
mod context;
mod error;
mod estimate;
mod figure;
mod lines;
mod links;
mod paper;
mod progress;
mod provenance;
mod region;
mod runs;
mod statements;
mod stats;
mod top;
mod wratio;

use std::path::Path;
use std::time::Instant;

use rayon::prelude::*;
use wingcheck_claims::certify::DecidingSet;
use wingcheck_claims::{check_all_cancellable, config_sha256, seconds, CheckSettings, Ledger, Study};
use wingcheck_model::Config;

pub use atomic::MARKER;
pub use error::ReportError;
pub use estimate::report_estimate;
pub use progress::{Overall, Progress};
pub use runs::GRIDS;
pub use stats::fmt_num;
pub use top::command_text;

use crate::context::{
    assumptions, basis_tally, row_assumptions, row_ctx, tally, Build, FigCtx, GroupCtx, Page, RowLinks, Timing,
};
use crate::figure::{claim_anchor, safe_name, Caption, Chart, Figure};
use crate::progress::{report, Tracker};

/// The page template.
const TEMPLATE: &str = include_str!("../templates/index.html");

/// The model as simulated: the repository's `docs/model.md`, copied into every report.
const MODEL_MD: &str = include_str!("../../../docs/model.md");

/// Options of [`write_report`] that do not change its content.
#[derive(Default, Clone, Copy)]
pub struct ReportOptions<'a> {
    /// Called as work completes (possibly from worker threads), per stage.
    pub progress: Option<&'a (dyn Fn(Progress) + Sync)>,
    /// Called as work completes with the overall, monotone fraction.
    pub overall: Option<&'a (dyn Fn(Overall) + Sync)>,
    /// The command line that asked for the report (shown in the provenance section).
    pub command_line: Option<&'a str>,
    /// Read by every simulation, every region-map point and between the stages: once set, the
    /// report stops with [`ReportError::Cancelled`] before anything is moved into place.
    pub cancel: Option<&'a wingcheck_model::Cancel>,
}

/// Wall time of one stage.
#[derive(Debug, Clone, PartialEq)]
pub struct StageTiming {
    /// Stage name.
    pub name: String,
    /// Wall time (s). `ledger` runs concurrently with `simulations`, `region map` and
    /// `certificates`, and with `run charts` after them.
    pub seconds: f64,
}

/// What [`write_report`] did.
#[derive(Debug, Clone)]
pub struct ReportSummary {
    /// The report directory.
    pub out_dir: std::path::PathBuf,
    /// Wall time per stage, in order.
    pub timings: Vec<StageTiming>,
    /// Files written (names relative to `out_dir`, sorted; includes the marker).
    pub files: Vec<String>,
    /// The claim ledger shown in the report.
    pub ledger: Ledger,
}

/// The region map's stage: ω1 (the converged value the ledger uses), r* in closed form, then
/// the search.
fn region_stage(
    cfg: &Config,
    progress: Option<&(dyn Fn(Progress) + Sync)>,
    cancel: &wingcheck_model::Cancel,
) -> Result<Option<region::RegionMap>, ReportError> {
    let Some(omega1) = paper::omega1(cfg) else { return Ok(None) };
    let r_star = wingcheck_theory::MuData::closed_form_ratio(cfg);
    if !(r_star.is_finite() && r_star > 0.0) {
        return Ok(None);
    }
    region::region_map(cfg, omega1, r_star, progress, cancel).map(Some)
}

/// The page's timings: the report's stages, then the ledger's own wall times.
fn page_timings(timings: &[StageTiming], ledger: &Ledger) -> Vec<Timing> {
    timings
        .iter()
        .map(|s| (s.name.clone(), s.seconds))
        .chain(ledger.wall_seconds.iter().map(|w| (format!("ledger: {}", w.what), w.seconds)))
        .map(|(name, seconds)| Timing { name, seconds: format!("{seconds:.3}") })
        .collect()
}

/// The files beside the page: the model as simulated, the configuration, the ledger and the
/// provenance record with every data file's columns.
fn write_side_files(
    cfg: &Config,
    ledger: &Ledger,
    config_sha256: &str,
    csv_records: Vec<wingcheck_io::FileRecord>,
    staging: &atomic::Staging,
    files: &mut Vec<String>,
) -> Result<(), ReportError> {
    // The model as simulated (docs/model.md of the repository), so the report is self-contained.
    files.push(staging.write("model.md", MODEL_MD.as_bytes())?);
    // The canonical compact JSON, so that `sha256sum config.json` equals the hash shown.
    files.push(staging.write("config.json", serde_json::to_string(cfg).expect("config serialises").as_bytes())?);
    files.push(staging.write("ledger.json", ledger.to_json().as_bytes())?);
    // Where the data came from, and what each data file's columns hold (docs/outputs.md).
    let provenance = wingcheck_io::Provenance::new(config_sha256, csv_records);
    files.push(staging.write("provenance.json", provenance.to_json().as_bytes())?);
    Ok(())
}

/// Render the report for `cfg` into `out_dir` (created, or an earlier report there replaced).
///
/// Refuses an existing `out_dir` that is neither a report (marker file [`MARKER`]) nor an
/// empty directory. Everything is written into a temporary directory beside `out_dir` and
/// renamed into place at the end; on error the temporary directory is removed.
pub fn write_report(cfg: &Config, out_dir: &Path, opts: &ReportOptions) -> Result<ReportSummary, ReportError> {
    atomic::check_replaceable(out_dir)?;
    let staging = atomic::Staging::new(out_dir)?;
    let started = Instant::now();
    let tracker = Tracker::new(opts);
    let on_progress = |p: Progress| tracker.update(p);
    let progress: Option<&(dyn Fn(Progress) + Sync)> = Some(&on_progress);
    let cancel = opts.cancel.cloned().unwrap_or_default();
    let (Computed { ledger, runs, proofs, early }, mut timings) = compute(cfg, &staging, progress, &cancel)?;
    cancel.check()?;
    let Early {
        fields,
        comparison,
        accuracy: (acc_fig, acc_rows),
        region_fig,
        w_ratio,
        mut files,
        records: mut csv_records,
    } = early;

    // The figures that need the ledger, side by side.
    let t = Instant::now();
    let (series, mut row_figs) = rayon::join(
        || paper::series_figures(cfg, &runs, paper::ftdo_marks(&ledger), ledger.settings.gtilde_threshold),
        || ledger.rows.iter().enumerate().map(|(i, r)| claim_figures(i, r)).collect::<Vec<_>>(),
    );
    timings.push(StageTiming { name: "figure data".into(), seconds: t.elapsed().as_secs_f64() });

    // SVG + CSV of each of them, in parallel.
    let t = Instant::now();
    let late: Vec<&Figure> = series.0.iter().chain(&series.1).chain(row_figs.iter().flatten()).collect();
    let (late_files, late_records) = render_charts("charts", &late, &staging, progress)?;
    files.extend(late_files);
    csv_records.extend(late_records);
    csv_records.sort_by(|a, b| a.file.cmp(&b.file));
    let groups = paper::paper_groups(cfg, fields, series);
    // the W-bounds row's λ2/λ1 against a/b (drawn early: it needs no ledger)
    if let Some(i) = ledger.rows.iter().position(|r| r.id == wingcheck_claims::ClaimId::WBounds) {
        row_figs[i].extend(w_ratio);
    }
    // the certificate set for the configured point (re-checkable with `wingcheck verify proofs`)
    let coarser_enclosure = proofs.as_ref().is_ok_and(|s| s.coarser_enclosure);
    let proofs = write_proofs(proofs, &staging, &mut files)?;
    timings.push(StageTiming { name: "charts".into(), seconds: t.elapsed().as_secs_f64() });
    cancel.check()?;

    // The page.
    let t = Instant::now();
    let figures = PageFigures {
        region: region_fig.as_ref(),
        groups: &groups,
        comparison: &comparison,
        accuracy: (&acc_fig, acc_rows),
        rows: &row_figs,
        proofs,
        coarser_enclosure,
    };
    let mut page = page(cfg, opts, &ledger, figures)?;
    page.timings = page_timings(&timings, &ledger);
    page.build.total_seconds = format!("{:.3}", started.elapsed().as_secs_f64());
    page.build.machine = Some(provenance::machine());
    let html = render_html(&page)?;
    files.push(staging.write("index.html", html.as_bytes())?);
    write_side_files(cfg, &ledger, &page.config_sha256, csv_records, &staging, &mut files)?;
    timings.push(StageTiming { name: "html".into(), seconds: t.elapsed().as_secs_f64() });
    report(progress, "html", 1, 1);

    let t = Instant::now();
    // the gate: once the front end's cancel has returned, the directory never appears
    cancel.commit(|| staging.commit(&format!("{}\nconfig sha256 {}\n", ledger.tool, page.config_sha256)))?;
    files.push(MARKER.to_string());
    files.sort();
    timings.push(StageTiming { name: "write".into(), seconds: t.elapsed().as_secs_f64() });
    report(progress, "write", 1, 1);
    Ok(ReportSummary { out_dir: out_dir.to_path_buf(), timings, files, ledger })
}

/// The report's certificate directory: `wingcheck certify`'s set for the configured point, with
/// the ω₁ enclosure the W-bounds row quotes (the coarsest that decides the configured a/b,
/// [`wingcheck_claims::certify::render_deciding_set`]) instead of the tightest.
pub const PROOFS: &str = "proofs";

/// The certificate set into `proofs/` of the staging directory (names appended to `files`);
/// the set's file names, or why `certify` could not make it.
fn write_proofs(
    set: Result<DecidingSet, wingcheck_claims::certify::CertifyError>,
    staging: &atomic::Staging,
    files: &mut Vec<String>,
) -> Result<Result<Vec<String>, wingcheck_claims::certify::CertifyError>, ReportError> {
    match set {
        Ok(set) => {
            let mut names = Vec::new();
            for (name, text) in &set.files {
                files.push(staging.write(&format!("{PROOFS}/{name}"), text.as_bytes())?);
                names.push(name.clone());
            }
            Ok(Ok(names))
        }
        Err(e) => Ok(Err(e)),
    }
}

/// What the report's first stage computes.
struct Computed {
    ledger: Ledger,
    runs: runs::Runs,
    /// The certificate set for the configured point ([`PROOFS`]), or why it could not be made.
    proofs: Result<DecidingSet, wingcheck_claims::certify::CertifyError>,
    early: Early,
}

/// The figures that need no ledger, drawn and written while the ledger is being checked.
struct Early {
    fields: paper::FieldFigures,
    comparison: Vec<Figure>,
    accuracy: (Figure, Vec<accuracy::AccuracyRow>),
    /// The region map's figure.
    region_fig: Option<Figure>,
    /// The W-bounds row's λ2/λ1 against a/b, through zero at ω₁ ([`wratio`]).
    w_ratio: Option<Figure>,
    /// The files written.
    files: Vec<String>,
    /// Their CSVs' records for provenance.json.
    records: Vec<wingcheck_io::FileRecord>,
}

/// The figures of the runs and the region map (data, then SVG and CSV), in parallel.
fn early_figures(
    cfg: &Config,
    runs: &runs::Runs,
    region: Option<&region::RegionMap>,
    staging: &atomic::Staging,
    progress: Option<&(dyn Fn(Progress) + Sync)>,
) -> Result<Early, ReportError> {
    let omega1 = region.map(|r| r.omega1).or_else(|| paper::omega1(cfg));
    let elements = CheckSettings::default().uub_lambda2_elements;
    let ((region_fig, fields), ((comparison, accuracy), w_ratio)) = rayon::join(
        || (region.map(|r| r.figure()), paper::field_figures(cfg, runs)),
        || {
            rayon::join(
                || (paper::comparison_figures(cfg, runs), accuracy::accuracy(&runs.accuracy)),
                || omega1.and_then(|w| wratio::w_ratio_figure(cfg, w, elements)),
            )
        },
    );
    let all: Vec<&Figure> = fields
        .all()
        .chain(&comparison)
        .chain(std::iter::once(&accuracy.0))
        .chain(region_fig.iter())
        .chain(w_ratio.iter())
        .collect();
    let (files, records) = render_charts("run charts", &all, staging, progress)?;
    Ok(Early { fields, comparison, accuracy, region_fig, w_ratio, files, records })
}

/// The ledger, the simulations, the region map and the certificate set, concurrently; the
/// ledger and the figures share one study, so every simulation runs once, and the set's ω₁
/// enclosure is the ledger's (cached per wing and plan; computed twice only when the two ask at
/// the same instant, which costs time, never a different file). (The ledger's SDP
/// cross-check is bounded by an iteration budget, not by wall time, so sharing the threads
/// changes no result.)
fn compute(
    cfg: &Config,
    staging: &atomic::Staging,
    progress: Option<&(dyn Fn(Progress) + Sync)>,
    cancel: &wingcheck_model::Cancel,
) -> Result<(Computed, Vec<StageTiming>), ReportError> {
    let study = Study::with_cancel(cancel.clone());
    let settings = CheckSettings::default();
    let ((ledger, lt), ((runs, st), (region, rt), (proofs, pt), early)) = rayon::join(
        || {
            report(progress, "ledger", 0, 1);
            let l = seconds(|| check_all_cancellable(cfg, &study, &settings).map_err(ReportError::from));
            report(progress, "ledger", 1, 1);
            l
        },
        || {
            let (((runs, st), (region, rt)), (proofs, pt)) = rayon::join(
                || {
                    rayon::join(
                        || seconds(|| runs::run_all(cfg, &study, progress)),
                        || seconds(|| region_stage(cfg, progress, cancel)),
                    )
                },
                || seconds(|| wingcheck_claims::certify::render_deciding_set(cfg)),
            );
            report(progress, "region map", 1, 1);
            // the figures that need no ledger, while the ledger's longest chain still runs
            let early = match (&runs, &region) {
                (Ok(r), Ok(m)) => Some(seconds(|| early_figures(cfg, r, m.as_ref(), staging, progress))),
                _ => None,
            };
            ((runs, st), (region, rt), (proofs, pt), early)
        },
    );
    cancel.check()?;
    let (ledger, runs) = (ledger?, runs?);
    region?;
    let (early, et) = early.expect("drawn whenever the runs and the region map succeeded");
    let timings = vec![
        StageTiming { name: "ledger".into(), seconds: lt },
        StageTiming { name: "simulations".into(), seconds: st },
        StageTiming { name: "region map".into(), seconds: rt },
        StageTiming { name: "certificates".into(), seconds: pt },
        StageTiming { name: "run charts".into(), seconds: et },
    ];
    Ok((Computed { ledger, runs, proofs, early: early? }, timings))
}

/// The SVG and CSV of every figure, written into the staging directory in parallel (progress
/// reported as `stage`); the file names written and each CSV's record for provenance.json
/// (sorted by file).
fn render_charts(
    stage: &str,
    all: &[&Figure],
    staging: &atomic::Staging,
    progress: Option<&(dyn Fn(Progress) + Sync)>,
) -> Result<(Vec<String>, Vec<wingcheck_io::FileRecord>), ReportError> {
    let total = all.len();
    let done = std::sync::atomic::AtomicUsize::new(0);
    Ok(all
        .par_iter()
        .map(|f| {
            let r = f.render()?;
            let mut names = vec![staging.write(&format!("{}.svg", f.file), r.svg.as_bytes())?];
            if let Some(csv) = &r.csv {
                names.push(staging.write(&f.data_file(), csv)?);
            }
            let k = done.fetch_add(1, std::sync::atomic::Ordering::SeqCst) + 1;
            report(progress, stage, k, total);
            let record =
                r.csv.is_some().then(|| wingcheck_io::FileRecord { file: f.data_file(), contents: r.contents });
            Ok::<_, ReportError>((names, record))
        })
        .collect::<Result<Vec<_>, _>>()?
        .into_iter()
        .unzip::<_, _, Vec<_>, Vec<_>>())
    .map(|(names, records)| {
        let mut records: Vec<wingcheck_io::FileRecord> = records.into_iter().flatten().collect();
        records.sort_by(|a, b| a.file.cmp(&b.file));
        (names.into_iter().flatten().collect(), records)
    })
}

/// The figures a page shows, by section.
struct PageFigures<'a> {
    region: Option<&'a Figure>,
    groups: &'a [paper::Group],
    comparison: &'a [Figure],
    accuracy: (&'a Figure, Vec<accuracy::AccuracyRow>),
    rows: &'a [Vec<Figure>],
    /// The certificate set's file names, or why `certify` could not make it.
    proofs: Result<Vec<String>, wingcheck_claims::certify::CertifyError>,
    /// Whether `proofs/`'s ω₁ enclosure is coarser than the one `wingcheck certify` writes.
    coarser_enclosure: bool,
}

/// The template's context (wall times are filled in by the caller).
fn page(cfg: &Config, opts: &ReportOptions, ledger: &Ledger, figs: PageFigures) -> Result<Page, ReportError> {
    let with_claims = |f: &Figure| FigCtx::from(f).with_claims(ledger);
    let groups: Vec<GroupCtx> = figs
        .groups
        .iter()
        .map(|g| GroupCtx {
            id: g.id.into(),
            title: g.title.clone(),
            intro: g.intro.clone(),
            figures: g.figures.iter().map(with_claims).collect(),
        })
        .collect();
    let region = figs.region.map(with_claims);
    let comparison: Vec<FigCtx> = figs.comparison.iter().map(with_claims).collect();
    // every figure a row may link to, by id
    let paper_figs: Vec<FigCtx> = groups
        .iter()
        .flat_map(|g| g.figures.iter())
        .chain(region.iter())
        .chain(comparison.iter())
        .map(|f| FigCtx { claims: Vec::new(), caption: Vec::new(), ..f.clone() })
        .collect();
    let figure_ids: Vec<String> = paper_figs.iter().map(|f| f.id.clone()).collect();
    let proof_files: Vec<String> = figs.proofs.as_ref().cloned().unwrap_or_default();
    let links = RowLinks { figure_ids: &figure_ids, figures: &paper_figs, proofs: &proof_files };
    Ok(Page {
        tool: ledger.tool.clone(),
        build: Build {
            git_commit: wingcheck_io::build().commit.clone(),
            tree: match wingcheck_io::build().tree {
                wingcheck_io::TreeState::Clean => "clean (the commit as it is)".into(),
                wingcheck_io::TreeState::Dirty => "dirty (built with uncommitted changes to tracked files)".into(),
                wingcheck_io::TreeState::Unknown => {
                    "unknown (not built from a git checkout, or the library used without the wingcheck binary)".into()
                }
            },
            rustc: wingcheck_io::build().rustc.clone(),
            date: provenance::utc_string(jiff::Timestamp::now()),
            command_line: opts.command_line.unwrap_or("(library call)").into(),
            total_seconds: String::new(),
            machine: None,
        },
        region,
        region_missing: if figs.region.is_none() {
            "The region map was not drawn: the fundamental frequency or the closed-form (32) boundary of this configuration is not a positive finite number.".into()
        } else {
            String::new()
        },
        config_sha256: config_sha256(cfg),
        config_json: cfg.to_json_pretty(),
        platform: format!("{}/{}", std::env::consts::OS, std::env::consts::ARCH),
        rows: ledger.rows.iter().zip(figs.rows).map(|(r, f)| row_ctx(r, f, &links)).collect::<Result<_, _>>()?,
        groups,
        comparison,
        accuracy_figure: FigCtx::from(figs.accuracy.0),
        accuracy_rows: figs.accuracy.1,
        grids: GRIDS.to_vec(),
        assumptions: assumptions(cfg),
        row_assumptions: row_assumptions(ledger),
        timings: Vec::new(),
        verdict_legend: wingcheck_claims::Verdict::ALL.iter().map(|v| (v.to_string(), v.meaning())).collect(),
        verdict_short: wingcheck_claims::Verdict::ALL.iter().map(|v| (v.to_string(), v.short())).collect(),
        basis_legend: wingcheck_claims::Basis::ALL.iter().map(|b| (b.to_string(), b.meaning())).collect(),
        changes: top::config_changes(cfg),
        notation: wingcheck_claims::display::notation(cfg),
        certificates: crate::links::certificates(ledger, &proof_files),
        // the page shows the set's files, or the refusal as its sentence
        proofs: figs.proofs.as_ref().cloned().map_err(ToString::to_string),
        coarser_enclosure: figs.coarser_enclosure,
        tally: tally(ledger),
        basis_tally: basis_tally(ledger),
        statements: crate::statements::statements(ledger),
    })
}

/// A ledger row's plots as figures (files `claim-<row>-<plot>`; their data is the row's `plots`
/// in ledger.json, the `index`-th row).
fn claim_figures(index: usize, r: &wingcheck_claims::ClaimRow) -> Vec<Figure> {
    r.plots
        .iter()
        .enumerate()
        .map(|(i, pd)| {
            let (chart, rescaled) = readable_y_axis(held_as_steps(pd.clone()));
            let mut caption = Caption::default().t(pd.title.clone());
            if let Some(s) = chart.symlog_y {
                caption = caption
                    .t(". The y axis is symmetric-logarithmic (on a linear one the small values would read as 0): linear for |y| ≤ ")
                    .n(format!("{}.symlog_threshold", safe_name(&pd.name)), s.threshold)
                    .t(", logarithmic beyond (ticks at 0 and ±c·10ᵏ).");
            } else if rescaled {
                caption = caption.t(". The y axis is logarithmic (on a linear one the small values would read as 0).");
            }
            Figure {
                file: format!("{}-{}", claim_anchor(&r.id.to_string()), safe_name(&pd.name)),
                label: format!("{}, plot {}", r.id, i + 1),
                title: pd.title.clone(),
                caption: caption.0,
                chart: Chart::InLedger {
                    chart,
                    path: format!("rows[{index}].plots[{i}]"),
                    what: format!("the {} row's plot {}", r.id, i + 1),
                },
            }
        })
        .collect()
}

/// Where a linear y axis would show some of the values as 0 ([`chart::SymLog::for_values`]
/// decides from the plotted values): a logarithmic axis when every value is positive, else a
/// symmetric-log one. Returns the chart and whether its axis was changed.
pub(crate) fn readable_y_axis(mut c: chart::LineChart) -> (chart::LineChart, bool) {
    if c.data.log_y {
        return (c, false);
    }
    let ys = || c.data.lines.iter().flat_map(|l| l.y.iter().copied()).filter(|y| y.is_finite());
    match chart::SymLog::for_values(ys()) {
        Some(_) if ys().all(|y| y > 0.0) => c.data.log_y = true,
        Some(s) => c.symlog_y = Some(s),
        None => return (c, false),
    }
    (c, true)
}

/// The digital observer's outputs ĝ and the commands τ are held over a sample period (zero-order
/// hold): sampled series of them against time are drawn as steps, not as dots.
fn held_as_steps(mut pd: wingcheck_claims::PlotData) -> chart::LineChart {
    let mut styles = Vec::with_capacity(pd.lines.len());
    let over_time = pd.x_label.starts_with("t (");
    for l in &mut pd.lines {
        let held = over_time && l.points && (l.label.starts_with('ĝ') || l.label.starts_with('τ'));
        if held {
            l.points = false;
        }
        styles.push(if held { chart::LineStyle::Step } else { chart::LineStyle::Solid });
    }
    chart::LineChart { styles, ..chart::LineChart::from(pd) }
}

/// Render the page from the template.
fn render_html(page: &Page) -> Result<String, ReportError> {
    let mut env = minijinja::Environment::new();
    env.set_auto_escape_callback(|_| minijinja::AutoEscape::Html);
    // plain text as pieces for the `pieces` macro: text and caret powers raised
    env.add_filter("prose", |s: String| minijinja::Value::from_serialize(crate::top::raised(&s)));
    env.add_template("index.html", TEMPLATE)?;
    Ok(env.get_template("index.html")?.render(page)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chart_of(ys: Vec<f64>) -> chart::LineChart {
        let x = (0..ys.len()).map(|i| i as f64).collect();
        chart::LineChart::from(wingcheck_claims::PlotData {
            name: "p".into(),
            title: "p".into(),
            x_label: "x (1)".into(),
            y_label: "y (1)".into(),
            log_x: false,
            log_y: false,
            lines: vec![wingcheck_claims::Line { label: "y".into(), x, y: ys, points: false }],
        })
    }

    #[test]
    fn small_values_get_a_log_or_symmetric_log_axis() {
        // Positive, 2e-6 … 40: log axis.
        let (c, changed) = readable_y_axis(chart_of(vec![2e-6, 5e-5, 1e-2, 40.0]));
        assert!(changed && c.data.log_y && c.symlog_y.is_none());
        // Both signs, 2e-6 … 6e-5 and −7e-4 … −42 (the mu plot's shape): symmetric log.
        let (c, changed) = readable_y_axis(chart_of(vec![2e-6, 6e-5, -7e-4, -0.1, -42.0]));
        assert!(changed && !c.data.log_y && c.symlog_y.is_some());
        // A sine: unchanged, linear.
        let (c, changed) = readable_y_axis(chart_of((0..100).map(|k| (0.0628 * k as f64).sin()).collect()));
        assert!(!changed && !c.data.log_y && c.symlog_y.is_none());
    }
}
