//! The paper's Figures 3–20 reproduced from the runs, and the FTDO-vs-DOBC overlays.
//! Every number in a caption is computed here from the series it describes.

use wingcheck_model::Config;
use wingcheck_sim::SimOutput;

use crate::chart::Heatmap;
use crate::figure::{line_plot, Caption, Chart, Figure};
use crate::runs::Runs;
use crate::stats::{diff, max_abs, rms, settling_time};

/// Threshold for the settling time of the disturbance estimation errors (N or N m).
pub const G_EPS: f64 = 1e-3;

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
    none: &'a SimOutput,
}

fn heat(n: u32, run: &str, desc: &str, f: Field, out: &SimOutput, c: &Ctx) -> Figure {
    let fields = out.fields.as_ref().expect("runs of paper figures record fields");
    let values = match f {
        Field::Q => fields.q.clone(),
        Field::Theta => fields.theta.clone(),
    };
    let t = &out.series.t;
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
    Figure {
        file: format!("fig{n:02}-{}-{run}", if matches!(f, Field::Q) { "q" } else { "theta" }),
        label: format!("Figure {n}"),
        title: format!("{} {s}(z,t) {desc}", f.what()),
        caption: caption.0,
        chart: Chart::Heat(Heatmap {
            name: format!("fig{n}"),
            t: t.clone(),
            z: fields.z.clone(),
            values,
            value_label: format!("{s} ({u})"),
        }),
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
        chart: Chart::Line(line_plot(
            &format!("fig{n}"),
            &format!("τ{ch}(t) {desc}"),
            &format!("τ{ch} ({unit})"),
            vec![(format!("τ{ch}"), &s.t, v.clone())],
        )),
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
        chart: Chart::Line(line_plot(
            &format!("fig{n}"),
            &format!("{s}(s,t) {desc}"),
            &format!("{s}(s,t) ({u})"),
            vec![(format!("{s}(s,t)"), t, v)],
        )),
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

fn settle_caption(cap: Caption, key: String, t: &[f64], v: &[f64], unit: &str) -> Caption {
    match settling_time(t, v, G_EPS) {
        Some(ts) => cap.t(format!("; |g̃| ≤ {G_EPS} {unit} from t = ")).n(key, ts).t(" s on."),
        None => cap.t(format!("; |g̃| still exceeds {G_EPS} {unit} at the end of the run.")),
    }
}

fn gerr(n: u32, run: &str, desc: &str, ch: u8, out: &SimOutput, c: &Ctx) -> Figure {
    let v = g_tilde(out, ch);
    let t = &out.series.t;
    let unit = if ch == 1 { "N" } else { "N m" };
    let cap = Caption::default()
        .t(format!("Disturbance estimation error g̃{ch}(t) = g{ch} − ĝ{ch} {desc} (paper Figure {n}). max |g̃{ch}| over [{}, {}] s: ", c.t_half, c.t_end))
        .n(format!("fig{n}.max_abs_late"), max_abs(t, &v, c.t_half, c.t_end))
        .t(format!(" {unit}"));
    let cap = settle_caption(cap, format!("fig{n}.settle_time"), t, &v, unit);
    Figure {
        file: format!("fig{n:02}-gtilde{ch}-{run}"),
        label: format!("Figure {n}"),
        title: format!("g̃{ch}(t) {desc}"),
        caption: cap.0,
        chart: Chart::Line(line_plot(
            &format!("fig{n}"),
            &format!("g̃{ch}(t) {desc}"),
            &format!("g̃{ch} ({unit})"),
            vec![(format!("g̃{ch}"), t, v)],
        )),
    }
}

/// Figures 3–20 in three groups (no control, FTDO, DOBC).
pub fn paper_figures(cfg: &Config, runs: &Runs) -> Vec<Group> {
    let t_end = cfg.horizon.t_end;
    let c = Ctx { t_half: t_end / 2.0, t_end, none: &runs.none };
    let (none, ftdo, dobc) = (&runs.none, &runs.ftdo, &runs.dobc);
    let wo = "without control";
    let pf = "with the proposed control (FTDO)";
    let db = "with DOBC";
    vec![
        Group {
            id: "paper-none",
            title: "Without control (paper Figures 3–4)".into(),
            intro: "τ1 = τ2 = 0; the disturbances (56) act.".into(),
            figures: vec![heat(3, "none", wo, Field::Q, none, &c), heat(4, "none", wo, Field::Theta, none, &c)],
        },
        Group {
            id: "paper-ftdo",
            title: "Proposed control: law (15) with the finite-time disturbance observer (paper Figures 5–12)".into(),
            intro: "Gains of Section 4; the values the paper leaves out are listed under Assumptions.".into(),
            figures: vec![
                heat(5, "ftdo", pf, Field::Q, ftdo, &c),
                heat(6, "ftdo", pf, Field::Theta, ftdo, &c),
                tau(7, "ftdo", pf, 1, ftdo, &c),
                tau(8, "ftdo", pf, 2, ftdo, &c),
                tip(9, "ftdo", pf, Field::Q, ftdo, &c),
                tip(10, "ftdo", pf, Field::Theta, ftdo, &c),
                gerr(11, "ftdo", pf, 1, ftdo, &c),
                gerr(12, "ftdo", pf, 2, ftdo, &c),
            ],
        },
        Group {
            id: "paper-dobc",
            title: "Comparison: DOBC (57), corrected (paper Figures 13–20)".into(),
            intro: "Same law (15) and gains, with the linear disturbance observer of (57).".into(),
            figures: vec![
                heat(13, "dobc", db, Field::Q, dobc, &c),
                heat(14, "dobc", db, Field::Theta, dobc, &c),
                tau(15, "dobc", db, 1, dobc, &c),
                tau(16, "dobc", db, 2, dobc, &c),
                tip(17, "dobc", db, Field::Q, dobc, &c),
                tip(18, "dobc", db, Field::Theta, dobc, &c),
                gerr(19, "dobc", db, 1, dobc, &c),
                gerr(20, "dobc", db, 2, dobc, &c),
            ],
        },
    ]
}

/// FTDO-vs-DOBC overlays: tip q, tip θ (with the uncontrolled wing), |g̃1|, |g̃2| (log scale).
pub fn comparison_figures(cfg: &Config, runs: &Runs) -> Vec<Figure> {
    let (t0, t1) = (cfg.horizon.t_end / 2.0, cfg.horizon.t_end);
    let t = &runs.ftdo.series.t;
    let mut figs = Vec::new();
    for (i, f) in [Field::Q, Field::Theta].into_iter().enumerate() {
        let pick = |o: &SimOutput| match f {
            Field::Q => o.series.q_tip.clone(),
            Field::Theta => o.series.theta_tip.clone(),
        };
        let (s, u) = (f.sym(), f.unit());
        let (a, b, z) = (pick(&runs.ftdo), pick(&runs.dobc), pick(&runs.none));
        let (ra, rb) = (rms(t, &a, t0, t1), rms(&runs.dobc.series.t, &b, t0, t1));
        let key = format!("cmp.{}", if i == 0 { "q" } else { "theta" });
        let cap = Caption::default()
            .t(format!(
                "Tip {} {s}(s,t): FTDO, DOBC and no control. RMS over [{t0}, {t1}] s: FTDO ",
                f.what().to_lowercase()
            ))
            .n(format!("{key}.rms_ftdo"), ra)
            .t(format!(" {u}, DOBC "))
            .n(format!("{key}.rms_dobc"), rb)
            .t(format!(" {u}, no control "))
            .n(format!("{key}.rms_none"), rms(&runs.none.series.t, &z, t0, t1))
            .t(format!(" {u}; DOBC/FTDO ratio "))
            .n(format!("{key}.ratio"), rb / ra)
            .t(".");
        figs.push(Figure {
            file: format!("cmp-{}-tip", if i == 0 { "q" } else { "theta" }),
            label: format!("Evidence E{}", i + 1),
            title: format!("{s}(s,t): FTDO vs DOBC"),
            caption: cap.0,
            chart: Chart::Line(line_plot(
                &format!("cmp-{s}"),
                &format!("{s}(s,t): FTDO vs DOBC"),
                &format!("{s}(s,t) ({u})"),
                vec![
                    ("FTDO".into(), t, a),
                    ("DOBC".into(), &runs.dobc.series.t, b),
                    ("no control".into(), &runs.none.series.t, z),
                ],
            )),
        });
    }
    for ch in [1u8, 2] {
        let unit = if ch == 1 { "N" } else { "N m" };
        let a: Vec<f64> = g_tilde(&runs.ftdo, ch).iter().map(|v| v.abs()).collect();
        let b: Vec<f64> = g_tilde(&runs.dobc, ch).iter().map(|v| v.abs()).collect();
        let cap = Caption::default()
            .t(format!(
                "|g̃{ch}(t)| on a log scale, FTDO vs DOBC (zero values are not drawn). max over [{t0}, {t1}] s: FTDO "
            ))
            .n(format!("cmp.g{ch}.max_ftdo"), max_abs(t, &a, t0, t1))
            .t(format!(" {unit}, DOBC "))
            .n(format!("cmp.g{ch}.max_dobc"), max_abs(&runs.dobc.series.t, &b, t0, t1))
            .t(format!(" {unit}."));
        let mut pd = line_plot(
            &format!("cmp-g{ch}"),
            &format!("|g̃{ch}|: FTDO vs DOBC"),
            &format!("|g̃{ch}| ({unit})"),
            vec![("FTDO".into(), t, a), ("DOBC".into(), &runs.dobc.series.t, b)],
        );
        pd.log_y = true;
        figs.push(Figure {
            file: format!("cmp-gtilde{ch}"),
            label: format!("Evidence E{}", ch + 2),
            title: format!("|g̃{ch}|: FTDO vs DOBC"),
            caption: cap.0,
            chart: Chart::Line(pd),
        });
    }
    figs
}
