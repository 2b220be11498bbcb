//! The paper's Figures 3–20 reproduced from the runs (each field as a map and as a 3-D surface),
//! and the DOBC − FTDO difference maps.
//! Every number in a caption is computed here from the series it describes.

use wingcheck_model::Config;
use wingcheck_sim::SimOutput;

use crate::chart::Heatmap;
use crate::figure::{Caption, Chart, Figure};
use crate::lines::{paired, FiniteTimeMarks, Frame, RunView};
use crate::runs::{Runs, TipErrors};
use crate::stats::{diff, fmt_num, max_abs};

/// The colour scale of the field maps is set by the samples with t ≥ this (s), so that the
/// residual motion is visible rather than the initial condition (at most half the horizon).
pub const FIELD_SCALE_FROM_S: f64 = 2.0;

/// Start of the field maps' colour-scale window for a horizon `t_end` (s).
pub fn field_scale_from(t_end: f64) -> f64 {
    FIELD_SCALE_FROM_S.min(0.5 * t_end)
}

/// A group of figures under one heading.
pub struct Group {
    /// Anchor id.
    pub id: &'static str,
    /// Heading.
    pub title: String,
    /// Introductory sentence.
    pub intro: String,
    /// The figures.
    pub figures: Vec<Figure>,
}

#[derive(Clone, Copy)]
enum Field {
    Q,
    Theta,
}

impl Field {
    fn sym(self) -> &'static str {
        match self {
            Field::Q => "q",
            Field::Theta => "θ",
        }
    }
    fn unit(self) -> &'static str {
        match self {
            Field::Q => "m",
            Field::Theta => "rad",
        }
    }
    fn what(self) -> &'static str {
        match self {
            Field::Q => "Bending displacement",
            Field::Theta => "Twist",
        }
    }
}

struct Ctx {
    t_half: f64,
    t_end: f64,
}

fn field_values(out: &SimOutput, f: Field) -> (&[f64], &[f64], &Vec<Vec<f64>>) {
    let fields = out.fields.as_ref().expect("runs of paper figures record fields");
    let v = match f {
        Field::Q => &fields.q,
        Field::Theta => &fields.theta,
    };
    (&out.series.t, &fields.z, v)
}

/// "colour scale ±X u, set by t ≥ t0 s …" caption text.
fn scale_caption(cap: Caption, key: String, h: &Heatmap, unit: &str) -> Caption {
    cap.t(" Colour scale ±").n(key, h.scale()).t(format!(
        " {unit}, set by t ≥ {} s (dashed line); larger values before it saturate.",
        crate::chart::tick(h.scale_from)
    ))
}

/// The field of paper Figure `n` on its (t, z) grid, colour scale from t ≥ [`field_scale_from`]
/// (or `vmax`, the scale a pair of maps shares).
fn field_map(n: u32, f: Field, out: &SimOutput, c: &Ctx, vmax: Option<f64>) -> Heatmap {
    let (t, z, values) = field_values(out, f);
    Heatmap {
        name: format!("fig{n}"),
        t: t.to_vec(),
        z: z.to_vec(),
        values: values.clone(),
        value_label: format!("{} ({})", f.sym(), f.unit()),
        scale_from: field_scale_from(c.t_end),
        vmax,
    }
}

/// The colour scale a pair of maps of field `f` shares: the larger of their own scales.
fn shared_scale(f: Field, a: &SimOutput, b: &SimOutput, c: &Ctx) -> f64 {
    field_map(0, f, a, c, None).own_scale().max(field_map(0, f, b, c, None).own_scale())
}

/// File stem of paper Figure `n`'s field map (`fig05-q-ftdo`).
fn field_file(n: u32, f: Field, run: &str) -> String {
    format!("fig{n:02}-{}-{run}", if matches!(f, Field::Q) { "q" } else { "theta" })
}

/// The map of paper Figure `n`; its data file has the digits of `error` (the run's estimated
/// tip error of this field, [`crate::runs::TipErrors`]).
#[allow(clippy::too_many_arguments)]
fn heat(
    n: u32,
    run: &str,
    desc: &str,
    f: Field,
    out: &SimOutput,
    c: &Ctx,
    pair: Option<(f64, u32)>,
    error: f64,
) -> Figure {
    let (t, _, values) = field_values(out, f);
    let row_max = |k: usize| values[k].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let per_t: Vec<f64> = (0..t.len()).map(row_max).collect();
    let late = max_abs(t, &per_t, c.t_half, c.t_end);
    let end = per_t.last().copied().unwrap_or(f64::NAN);
    let (s, u) = (f.sym(), f.unit());
    let caption = Caption::default()
        .t(format!(
            "{} {s}(z,t) of the wing {desc} (paper Figure {n}). max |{s}(z,t)| over the span for t ∈ [{}, {}] s: ",
            f.what(),
            c.t_half,
            c.t_end
        ))
        .n(format!("fig{n}.max_abs_late"), late)
        .t(format!(" {u}; at t = {} s: ", c.t_end))
        .n(format!("fig{n}.max_abs_end"), end)
        .t(format!(" {u}."));
    let h = field_map(n, f, out, c, pair.map(|p| p.0));
    let mut caption = scale_caption(caption, format!("fig{n}.scale"), &h, u);
    if let Some((_, twin)) = pair {
        caption = caption.t(format!(" One colour scale with Figure {twin}."));
    }
    let caption = caption.t(format!(
        " The map is the quantitative view (read values off the colour bar); the 3-D view below shows the shape of the motion, as the paper draws it. The data file (gzip-compressed CSV) has the digits of the estimated error of the configured grid, {} {u} at the tip.",
        crate::chart::tick(error)
    ));
    Figure {
        file: field_file(n, f, run),
        label: format!("Figure {n}"),
        title: format!("{} {s}(z,t) {desc}", f.what()),
        caption: caption.0,
        chart: Chart::Heat { map: h, resolution: wingcheck_model::quantity::resolution_of(error) },
    }
}

/// The field of paper Figure `n` as a 3-D surface, beside its map: the view of the paper's
/// figure (the shape of the motion); the map is the quantitative view.
fn surface(n: u32, run: &str, desc: &str, f: Field, out: &SimOutput, c: &Ctx, vmax: Option<f64>) -> Figure {
    let (s, u) = (f.sym(), f.unit());
    let sf = Heatmap { name: format!("fig{n}-surface"), ..field_map(n, f, out, c, vmax) };
    let caption = Caption::default()
        .t(format!(
            "{} {s}(z,t) {desc} as a 3-D surface, the view of the paper's Figure {n}: height to scale over the whole run, so it shows the shape of the motion (the initial shape and what follows it); colour as in the map above (±",
            f.what()
        ))
        .n(format!("fig{n}.surface_scale"), sf.scale())
        .t(format!(
            " {u}, set by t ≥ {} s; larger values saturate), so the residual motion that is flat at this height still shows. Read values off the map.",
            crate::chart::tick(sf.scale_from)
        ));
    Figure {
        file: format!("{}-surface", field_file(n, f, run)),
        label: format!("Figure {n}, 3-D view"),
        title: format!("{} {s}(z,t) {desc}, 3-D view", f.what()),
        caption: caption.0,
        chart: Chart::Surface(sf),
    }
}

/// The field figures of a controlled run (q, θ: map and 3-D view, on the colour scales the
/// pair shares, `pair` = (q scale, θ scale, the twin's first figure)); the caller appends its
/// time-series figures.
fn controlled(
    n: u32,
    run: &str,
    desc: &str,
    out: &SimOutput,
    c: &Ctx,
    pair: (f64, f64, u32),
    err: &TipErrors,
) -> Vec<Figure> {
    let (sq, st, twin) = pair;
    vec![
        heat(n, run, desc, Field::Q, out, c, Some((sq, twin)), err.max_q),
        surface(n, run, desc, Field::Q, out, c, Some(sq)),
        heat(n + 1, run, desc, Field::Theta, out, c, Some((st, twin + 1)), err.max_theta),
        surface(n + 1, run, desc, Field::Theta, out, c, Some(st)),
    ]
}

/// The field figures of Figures 3–6 and 13–14 (map and 3-D view of q and θ per run): they need
/// only the runs, so the report draws them while the ledger is still being checked.
pub struct FieldFigures {
    /// Figures 3–4, no control.
    none: Vec<Figure>,
    /// Figures 5–6, FTDO.
    ftdo: Vec<Figure>,
    /// Figures 13–14, DOBC.
    dobc: Vec<Figure>,
}

impl FieldFigures {
    /// Every figure, in page order.
    pub fn all(&self) -> impl Iterator<Item = &Figure> {
        self.none.iter().chain(&self.ftdo).chain(&self.dobc)
    }
}

/// The field figures of the three runs, the FTDO/DOBC pairs on the colour scales they share.
pub fn field_figures(cfg: &Config, runs: &Runs) -> FieldFigures {
    let c = Ctx { t_half: cfg.horizon.t_end / 2.0, t_end: cfg.horizon.t_end };
    let (none, ftdo, dobc) = (&runs.none, &runs.ftdo, &runs.dobc);
    let (sq, st) = (shared_scale(Field::Q, ftdo, dobc, &c), shared_scale(Field::Theta, ftdo, dobc, &c));
    let wo = "without control";
    FieldFigures {
        none: vec![
            heat(3, "none", wo, Field::Q, none, &c, None, runs.errors[0].max_q),
            surface(3, "none", wo, Field::Q, none, &c, None),
            heat(4, "none", wo, Field::Theta, none, &c, None, runs.errors[0].max_theta),
            surface(4, "none", wo, Field::Theta, none, &c, None),
        ],
        ftdo: controlled(5, "ftdo", PROPOSED, ftdo, &c, (sq, st, 13), &runs.errors[1]),
        dobc: controlled(13, "dobc", DOBC, dobc, &c, (sq, st, 5), &runs.errors[2]),
    }
}

const PROPOSED: &str = "with the proposed control (FTDO)";
const DOBC: &str = "with DOBC";

/// The time-series figures of Figures 7–12 and 15–20 (FTDO/DOBC pairs on common axes); `marks`
/// are the ledger's bounds t_f1, t_f2 of (38)/(39) and its reaching times t_reach, marked on the
/// FTDO's |g̃|, with the ledger's |g̃| threshold `gtilde_threshold` (N, N m).
pub fn series_figures(
    cfg: &Config,
    runs: &Runs,
    marks: [FiniteTimeMarks; 2],
    gtilde_threshold: f64,
) -> (Vec<Figure>, Vec<Figure>) {
    let frame = Frame { t_end: cfg.horizon.t_end, every: cfg.horizon.sample_every, none: &runs.none, gtilde_threshold };
    let view = |tag, desc, first, out, err, marks| RunView { tag, desc, first, out, err, marks };
    paired(
        &view("ftdo", PROPOSED, 7, &runs.ftdo, &runs.errors[1], marks),
        &view("dobc", DOBC, 15, &runs.dobc, &runs.errors[2], Default::default()),
        &frame,
    )
}

/// Figures 3–20 in three groups (no control, FTDO, DOBC): each run's field figures, then its
/// time series (`series`, from [`series_figures`]).
pub fn paper_groups(cfg: &Config, fields: FieldFigures, series: (Vec<Figure>, Vec<Figure>)) -> Vec<Group> {
    let (lf, ld) = series;
    vec![
        Group {
            id: "paper-none",
            title: "Without control (paper Figures 3–4)".into(),
            intro: format!("τ1 = τ2 = 0; the disturbances (56) act. {}", period_note(cfg)),
            figures: fields.none,
        },
        Group {
            id: "paper-ftdo",
            title: "Proposed control: law (15) with the finite-time disturbance observer (paper Figures 5–12)".into(),
            intro: "The configured gains; the values the paper leaves out are listed under Assumptions.".into(),
            figures: [fields.ftdo, lf].concat(),
        },
        Group {
            id: "paper-dobc",
            title: "Comparison: DOBC (57), corrected (paper Figures 13–20)".into(),
            intro: "Same law (15) and gains, with the linear disturbance observer of (57).".into(),
            figures: [fields.dobc, ld].concat(),
        },
    ]
}

/// DOBC − FTDO difference maps of q(z,t) and θ(z,t): where and when the two observers give
/// different wing motion (the tip overlays are in the ftdo-vs-dobc claim's section).
pub fn comparison_figures(cfg: &Config, runs: &Runs) -> Vec<Figure> {
    let (t0, t1) = (cfg.horizon.t_end / 2.0, cfg.horizon.t_end);
    let mut figs = Vec::new();
    for (i, f) in [Field::Q, Field::Theta].into_iter().enumerate() {
        let (t, z, a) = field_values(&runs.ftdo, f);
        let (_, _, b) = field_values(&runs.dobc, f);
        let values: Vec<Vec<f64>> = a.iter().zip(b).map(|(ra, rb)| diff(rb, ra)).collect();
        let (s, u) = (f.sym(), f.unit());
        let key = format!("cmp.d{}", if i == 0 { "q" } else { "theta" });
        let per_t: Vec<f64> = values.iter().map(|r| r.iter().fold(0.0_f64, |m, v| m.max(v.abs()))).collect();
        let (_, _, ftdo_rows) = field_values(&runs.ftdo, f);
        let ftdo_t: Vec<f64> = ftdo_rows.iter().map(|r| r.iter().fold(0.0_f64, |m, v| m.max(v.abs()))).collect();
        let h = Heatmap {
            name: format!("cmp-d{s}"),
            t: t.to_vec(),
            z: z.to_vec(),
            values,
            value_label: format!("Δ{s} ({u})"),
            scale_from: field_scale_from(t1),
            vmax: None,
        };
        let cap = Caption::default()
            .t(format!(
                "Difference of the {} fields, DOBC − FTDO, Δ{s}(z,t). max |Δ{s}| over the span and [{t0}, {t1}] s: ",
                f.what().to_lowercase()
            ))
            .n(format!("{key}.max_abs_late"), max_abs(t, &per_t, t0, t1))
            .t(format!(" {u}, against max |{s}| of the FTDO run over the same window: "))
            .n(format!("{key}.ftdo_max_abs_late"), max_abs(t, &ftdo_t, t0, t1))
            .t(format!(" {u}."));
        let cap = scale_caption(cap, format!("{key}.scale"), &h, u).t(
            " The data file (gzip-compressed CSV) has 4 significant digits of the largest |Δ|: the difference of two runs on one grid, whose discretisation errors largely cancel, has no error estimate of its own.",
        );
        let largest = per_t.iter().copied().fold(0.0_f64, f64::max);
        let resolution = (largest > 0.0).then(|| 10f64.powi(largest.log10().floor() as i32 - 3));
        figs.push(Figure {
            file: format!("cmp-d{}", if i == 0 { "q" } else { "theta" }),
            label: format!("Difference {}", if i == 0 { "Δq" } else { "Δθ" }),
            title: format!("Δ{s}(z,t) = DOBC − FTDO"),
            caption: cap.0,
            chart: Chart::Heat { map: h, resolution },
        });
    }
    figs
}

/// The bounds t_f1, t_f2 of (38)/(39) and the reaching times t_reach as the ledger's
/// finite-time rows state them (None where a row computed nothing).
pub fn ftdo_marks(ledger: &wingcheck_claims::Ledger) -> [FiniteTimeMarks; 2] {
    let mut m: [FiniteTimeMarks; 2] = Default::default();
    for r in &ledger.rows {
        if let wingcheck_claims::Evidence::FiniteTime(e) = &r.evidence {
            let i = usize::from(r.id == wingcheck_claims::ClaimId::FiniteTime2);
            m[i] = FiniteTimeMarks {
                bound: Some(e.bound_s.clone()).filter(|q| q.value.is_finite()),
                reach: e.measured_s.quantity().cloned(),
            };
        }
    }
    m
}

/// The fundamental (lowest natural) angular frequency ω1 (rad/s) of the configured wing: the
/// converged value the ledger's W ≻ 0 threshold uses ([`wingcheck_theory::w_threshold`]).
pub fn omega1(cfg: &Config) -> Option<f64> {
    wingcheck_theory::w_threshold(cfg).ok().map(|e| e.value).filter(|w| w.is_finite() && *w > 0.0)
}

/// A sentence on the fundamental period 2π/ω1 against the horizon.
pub fn period_note(cfg: &Config) -> String {
    let t_end = cfg.horizon.t_end;
    match omega1(cfg) {
        Some(w) => {
            let period = 2.0 * std::f64::consts::PI / w;
            if period > t_end {
                format!(
                    "The fundamental period 2π/ω₁ = {} s (ω₁ = {} rad/s) exceeds the horizon t_end = {} s: the wing completes {} of its slowest oscillation, so the uncontrolled \"vibration\" is a slow drift of the initial deflection, not an oscillation.",
                    fmt_num(period), fmt_num(w), crate::chart::tick(t_end), fmt_num(t_end / period)
                )
            } else {
                format!(
                    "The fundamental period 2π/ω₁ = {} s (ω₁ = {} rad/s); the horizon t_end = {} s spans {} periods.",
                    fmt_num(period),
                    fmt_num(w),
                    crate::chart::tick(t_end),
                    fmt_num(t_end / period)
                )
            }
        }
        None => "The fundamental frequency could not be computed for this configuration.".into(),
    }
}
