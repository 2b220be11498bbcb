//! The paper's Figures 3–20 reproduced from the runs (each field as a map and as a 3-D surface),
//! and the DOBC − FTDO difference maps.
//! Every number in a caption is computed here from the series it describes.

use wingcheck_model::Config;
use wingcheck_sim::metrics::{settle_time, GTILDE_THRESHOLD};
use wingcheck_sim::SimOutput;

use crate::chart::{Heatmap, LineChart};
use crate::figure::{line_plot, Caption, Chart, Figure};
use crate::runs::Runs;
use crate::stats::{diff, fmt_num, max_abs, rms};

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

struct Ctx<'a> {
    t_half: f64,
    t_end: f64,
    sample_every: f64,
    none: &'a SimOutput,
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

/// The field of paper Figure `n` on its (t, z) grid, colour scale from t ≥ [`field_scale_from`].
fn field_map(n: u32, f: Field, out: &SimOutput, c: &Ctx) -> Heatmap {
    let (t, z, values) = field_values(out, f);
    Heatmap {
        name: format!("fig{n}"),
        t: t.to_vec(),
        z: z.to_vec(),
        values: values.clone(),
        value_label: format!("{} ({})", f.sym(), f.unit()),
        scale_from: field_scale_from(c.t_end),
    }
}

/// File stem of paper Figure `n`'s field map (`fig05-q-ftdo`).
fn field_file(n: u32, f: Field, run: &str) -> String {
    format!("fig{n:02}-{}-{run}", if matches!(f, Field::Q) { "q" } else { "theta" })
}

fn heat(n: u32, run: &str, desc: &str, f: Field, out: &SimOutput, c: &Ctx) -> Figure {
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
    let h = field_map(n, f, out, c);
    let caption = scale_caption(caption, format!("fig{n}.scale"), &h, u)
        .t(" The map is the quantitative view (read values off the colour bar); the 3-D view below shows the shape of the motion, as the paper draws it.");
    Figure {
        file: field_file(n, f, run),
        label: format!("Figure {n}"),
        title: format!("{} {s}(z,t) {desc}", f.what()),
        caption: caption.0,
        chart: Chart::Heat(h),
    }
}

/// The field of paper Figure `n` as a 3-D surface, beside its map: the view of the paper's
/// figure (the shape of the motion); the map is the quantitative view.
fn surface(n: u32, run: &str, desc: &str, f: Field, out: &SimOutput, c: &Ctx) -> Figure {
    let (s, u) = (f.sym(), f.unit());
    let sf = Heatmap { name: format!("fig{n}-surface"), ..field_map(n, f, out, c) };
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

fn tau(n: u32, run: &str, desc: &str, ch: u8, out: &SimOutput, c: &Ctx) -> Figure {
    let s = &out.series;
    let (v, unit) = if ch == 1 { (&s.tau1, "N") } else { (&s.tau2, "N m") };
    let caption = Caption::default()
        .t(format!("Control command τ{ch}(t) {desc} (paper Figure {n}). max |τ{ch}| over [0, {}] s: ", c.t_end))
        .n(format!("fig{n}.max_abs"), max_abs(&s.t, v, 0.0, c.t_end))
        .t(format!(" {unit}; over [{}, {}] s: ", c.t_half, c.t_end))
        .n(format!("fig{n}.max_abs_late"), max_abs(&s.t, v, c.t_half, c.t_end))
        .t(format!(" {unit}."));
    Figure {
        file: format!("fig{n:02}-tau{ch}-{run}"),
        label: format!("Figure {n}"),
        title: format!("τ{ch}(t) {desc}"),
        caption: caption.0,
        chart: Chart::Line(
            line_plot(
                &format!("fig{n}"),
                &format!("τ{ch}(t) {desc}"),
                &format!("τ{ch} ({unit})"),
                vec![(String::new(), &s.t, v.clone())],
            )
            .into(),
        ),
    }
}

fn tip(n: u32, run: &str, desc: &str, f: Field, out: &SimOutput, c: &Ctx) -> Figure {
    let pick = |o: &SimOutput| match f {
        Field::Q => o.series.q_tip.clone(),
        Field::Theta => o.series.theta_tip.clone(),
    };
    let (v, v0) = (pick(out), pick(c.none));
    let t = &out.series.t;
    let (s, u) = (f.sym(), f.unit());
    let caption = Caption::default()
        .t(format!(
            "Boundary {} {s}(s,t) at the tip {desc} (paper Figure {n}). max |{s}(s,t)| over [{}, {}] s: ",
            f.what().to_lowercase(),
            c.t_half,
            c.t_end
        ))
        .n(format!("fig{n}.max_abs_late"), max_abs(t, &v, c.t_half, c.t_end))
        .t(format!(" {u} (without control: "))
        .n(format!("fig{n}.none_max_abs_late"), max_abs(&c.none.series.t, &v0, c.t_half, c.t_end))
        .t(format!(" {u}); RMS over the same window: "))
        .n(format!("fig{n}.rms_late"), rms(t, &v, c.t_half, c.t_end))
        .t(format!(" {u}."));
    Figure {
        file: format!("fig{n:02}-{}-tip-{run}", if matches!(f, Field::Q) { "q" } else { "theta" }),
        label: format!("Figure {n}"),
        title: format!("{s}(s,t) {desc}"),
        caption: caption.0,
        chart: Chart::Line(
            line_plot(
                &format!("fig{n}"),
                &format!("{s}(s,t) {desc}"),
                &format!("{s}(s,t) ({u})"),
                vec![(String::new(), t, v)],
            )
            .into(),
        ),
    }
}

/// g̃ = g − ĝ of channel `ch` (1 or 2).
pub fn g_tilde(out: &SimOutput, ch: u8) -> Vec<f64> {
    let s = &out.series;
    if ch == 1 {
        diff(&s.g1, &s.g1_hat)
    } else {
        diff(&s.g2, &s.g2_hat)
    }
}

/// |g̃| of a channel on a log axis with the threshold [`GTILDE_THRESHOLD`] and the time from
/// which |g̃| stays below it (t_f) marked; the x axis is zoomed to [0, 4 t_f] when t_f is
/// less than a tenth of the horizon (the convergence would otherwise sit in the first pixel).
fn gerr(n: u32, run: &str, desc: &str, ch: u8, out: &SimOutput, c: &Ctx) -> Figure {
    let v = g_tilde(out, ch);
    let t = &out.series.t;
    let unit = if ch == 1 { "N" } else { "N m" };
    let thr = crate::chart::tick(GTILDE_THRESHOLD);
    let h = c.sample_every;
    let settle = settle_time(t, &v, GTILDE_THRESHOLD);
    let mut cap = Caption::default()
        .t(format!("Disturbance estimation error |g̃{ch}(t)| = |g{ch} − ĝ{ch}| {desc} (paper Figure {n}), log scale. max |g̃{ch}| over [{}, {}] s: ", c.t_half, c.t_end))
        .n(format!("fig{n}.max_abs_late"), max_abs(t, &v, c.t_half, c.t_end))
        .t(format!(" {unit}"));
    let mut chart: LineChart = line_plot(
        &format!("fig{n}"),
        &format!("|g̃{ch}(t)| {desc}"),
        &format!("|g̃{ch}| ({unit})"),
        vec![(String::new(), t, v.iter().map(|x| x.abs()).collect())],
    )
    .into();
    chart.data.log_y = true;
    chart.hlines.push((GTILDE_THRESHOLD, format!("|g̃| = {thr} {unit}")));
    match settle {
        Some(ts) => {
            cap = cap
                .t(format!("; |g̃{ch}| ≤ {thr} {unit} (the threshold used throughout) from t_f = "))
                .n(format!("fig{n}.settle_time"), ts)
                .t(format!(" s on (resolved to the output sampling, every {} s)", crate::chart::tick(h)));
            chart.vlines.push((ts, format!("t_f = {} s", crate::chart::tick(ts))));
            if ts > 0.0 && ts < 0.1 * c.t_end {
                let zoom = (4.0 * ts).max(20.0 * h);
                chart.x_range = Some((0.0, zoom));
                cap = cap.t(format!(
                    "; time axis zoomed to [0, {}] s, the whole run is in the CSV",
                    crate::chart::tick(zoom)
                ));
            }
            cap = cap.t(".");
        }
        None => {
            cap = cap.t(format!(
                "; |g̃{ch}| still exceeds {thr} {unit} (the threshold used throughout) at the end of the run."
            ))
        }
    }
    Figure {
        file: format!("fig{n:02}-gtilde{ch}-{run}"),
        label: format!("Figure {n}"),
        title: format!("|g̃{ch}(t)| {desc}"),
        caption: cap.0,
        chart: Chart::Line(chart),
    }
}

/// The eight figures of a controlled run, paper Figures n … n + 7 (fields q, θ with their 3-D
/// views, τ1, τ2, the tips, g̃1, g̃2): 5–12 for the FTDO, 13–20 for DOBC.
fn controlled(n: u32, run: &str, desc: &str, out: &SimOutput, c: &Ctx) -> Vec<Figure> {
    vec![
        heat(n, run, desc, Field::Q, out, c),
        surface(n, run, desc, Field::Q, out, c),
        heat(n + 1, run, desc, Field::Theta, out, c),
        surface(n + 1, run, desc, Field::Theta, out, c),
        tau(n + 2, run, desc, 1, out, c),
        tau(n + 3, run, desc, 2, out, c),
        tip(n + 4, run, desc, Field::Q, out, c),
        tip(n + 5, run, desc, Field::Theta, out, c),
        gerr(n + 6, run, desc, 1, out, c),
        gerr(n + 7, run, desc, 2, out, c),
    ]
}

/// Figures 3–20 in three groups (no control, FTDO, DOBC).
pub fn paper_figures(cfg: &Config, runs: &Runs) -> Vec<Group> {
    let t_end = cfg.horizon.t_end;
    let c = Ctx { t_half: t_end / 2.0, t_end, sample_every: cfg.horizon.sample_every, none: &runs.none };
    let (none, ftdo, dobc) = (&runs.none, &runs.ftdo, &runs.dobc);
    let wo = "without control";
    let pf = "with the proposed control (FTDO)";
    let db = "with DOBC";
    vec![
        Group {
            id: "paper-none",
            title: "Without control (paper Figures 3–4)".into(),
            intro: format!("τ1 = τ2 = 0; the disturbances (56) act. {}", period_note(cfg)),
            figures: vec![
                heat(3, "none", wo, Field::Q, none, &c),
                surface(3, "none", wo, Field::Q, none, &c),
                heat(4, "none", wo, Field::Theta, none, &c),
                surface(4, "none", wo, Field::Theta, none, &c),
            ],
        },
        Group {
            id: "paper-ftdo",
            title: "Proposed control: law (15) with the finite-time disturbance observer (paper Figures 5–12)".into(),
            intro: "The configured gains; the values the paper leaves out are listed under Assumptions.".into(),
            figures: controlled(5, "ftdo", pf, ftdo, &c),
        },
        Group {
            id: "paper-dobc",
            title: "Comparison: DOBC (57), corrected (paper Figures 13–20)".into(),
            intro: "Same law (15) and gains, with the linear disturbance observer of (57).".into(),
            figures: controlled(13, "dobc", db, dobc, &c),
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
        let cap = scale_caption(cap, format!("{key}.scale"), &h, u);
        figs.push(Figure {
            file: format!("cmp-d{}", if i == 0 { "q" } else { "theta" }),
            label: format!("Difference {}", if i == 0 { "Δq" } else { "Δθ" }),
            title: format!("Δ{s}(z,t) = DOBC − FTDO"),
            caption: cap.0,
            chart: Chart::Heat(h),
        });
    }
    figs
}

/// The fundamental (lowest natural) angular frequency ω1 (rad/s) of the configured wing: the
/// converged value the ledger's W ≻ 0 threshold uses ([`wingcheck_claims::theory::w_threshold`]).
pub fn omega1(cfg: &Config) -> Option<f64> {
    wingcheck_claims::theory::w_threshold(cfg).ok().map(|e| e.value).filter(|w| w.is_finite() && *w > 0.0)
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
