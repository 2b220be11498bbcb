//! The paper's time-series figures of a controlled run — τ1, τ2 (Figs 7–8, 15–16), the tips
//! (9–10, 17–18), |g̃1|, |g̃2| (11–12, 19–20) — drawn in FTDO/DOBC pairs on common axes:
//!
//! - τ and g̃ as the full-rate range per output interval (the simulator's envelope: every
//!   integrator step and both sides of every sample's jump) with the output samples as a line,
//!   because a signal that chatters at the observer's sample rate aliases in the samples;
//! - the tips with the estimated error of the configured grid as a band (the `--error-estimate`
//!   machinery) and the uncontrolled tip for comparison; an axis that would magnify a small
//!   change includes 0;
//! - |g̃| with the measured t_reach and, for the FTDO, the bound t_f of (38)/(39).

use wingcheck_sim::metrics::{envelope_abs_max, envelope_abs_min, envelope_of, settle_time, GTILDE_THRESHOLD};
use wingcheck_sim::SimOutput;

use crate::chart::{padded_range, tick, Band, LineChart};
use crate::figure::{line_plot, Caption, Chart, Digits, Figure};
use crate::runs::TipErrors;
use crate::stats::{max_abs, rms};

/// One controlled run as the figures need it.
pub struct RunView<'a> {
    /// File-name tag (`ftdo`, `dobc`).
    pub tag: &'a str,
    /// Words after the quantity ("with DOBC").
    pub desc: &'a str,
    /// Paper figure number of its τ1 figure (7 or 15).
    pub first: u32,
    /// The run.
    pub out: &'a SimOutput,
    /// Its tip errors.
    pub err: &'a TipErrors,
    /// The bounds t_f1, t_f2 of (38)/(39) to mark (the FTDO's), if any.
    pub bounds: [Option<f64>; 2],
}

/// The horizon, the late window and the uncontrolled run.
pub struct Frame<'a> {
    /// t_end (s).
    pub t_end: f64,
    /// Output interval (s).
    pub every: f64,
    /// The run without control.
    pub none: &'a SimOutput,
}

fn unit(ch: u8) -> &'static str {
    if ch == 1 {
        "N"
    } else {
        "N m"
    }
}

/// The caption's sentence on the data file's digits (absolute error `err` in `unit`).
fn data_note(err: f64, unit: &str) -> Option<crate::figure::Part> {
    wingcheck_model::quantity::resolution_of(err).map(|r| crate::figure::Part {
        text: format!(
            " The data file has the digits of the estimated error {} {unit} (to {}).",
            wingcheck_model::quantity::format_error(err),
            tick(r)
        ),
        key: None,
    })
}

/// The same y range on both charts: the padded range of both charts' values.
fn share_y(a: &mut LineChart, b: &mut LineChart, log: bool) {
    let r = padded_range(a.y_values().into_iter().chain(b.y_values()), log);
    a.y_range = Some(r);
    b.y_range = Some(r);
}

fn band_label(every: f64) -> String {
    format!("full-rate range per {} s", tick(every))
}

/// τ of channel `ch`: the samples as a line, the full-rate range per output interval as a band.
fn tau_chart(r: &RunView, ch: u8, f: &Frame) -> LineChart {
    let s = &r.out.series;
    let v = if ch == 1 { &s.tau1 } else { &s.tau2 };
    let env = envelope_of(r.out, usize::from(ch - 1));
    let n = r.first + u32::from(ch - 1);
    let mut c: LineChart = line_plot(
        &format!("fig{n}"),
        &format!("τ{ch}(t) {}", r.desc),
        &format!("τ{ch} ({})", unit(ch)),
        vec![("samples".into(), &s.t, v.clone())],
    )
    .into();
    c.bands.push(Band {
        line: 0,
        lo: env.iter().map(|e| e.0).collect(),
        hi: env.iter().map(|e| e.1).collect(),
        label: band_label(f.every),
    });
    c
}

fn tau_figure(r: &RunView, ch: u8, f: &Frame, chart: LineChart, twin: u32) -> Figure {
    let s = &r.out.series;
    let n = r.first + u32::from(ch - 1);
    let peak = envelope_abs_max(envelope_of(r.out, usize::from(ch - 1)));
    let u = unit(ch);
    let inside = if r.out.stats.sub_step_probes[0] > 0 {
        ", and inside the first step after each jump (the exponential scheme's sub-step probe)"
    } else {
        ""
    };
    let caption = Caption::default()
        .t(format!(
            "Control command τ{ch}(t) {} (paper Figure {n}). Shaded: the full-rate range of τ{ch} over each output interval (every integrator step, both sides of every sample's jump{inside}); line: the output samples, which alias a command that chatters at the observer's sample rate. Full-rate max |τ{ch}| over [0, {}] s: ",
            r.desc,
            tick(f.t_end)
        ))
        .n(format!("fig{n}.max_abs"), max_abs(&s.t, &peak, 0.0, f.t_end))
        .t(format!(" {u}; over [{}, {}] s: ", tick(f.t_end / 2.0), tick(f.t_end)))
        .n(format!("fig{n}.max_abs_late"), max_abs(&s.t, &peak, f.t_end / 2.0, f.t_end))
        .t(format!(" {u}. Same axes as Figure {twin}."));
    let err = r.err.tau[usize::from(ch - 1)];
    Figure {
        file: format!("fig{n:02}-tau{ch}-{}", r.tag),
        label: format!("Figure {n}"),
        title: format!("τ{ch}(t) {}", r.desc),
        caption: caption.0.into_iter().chain(data_note(err, u)).collect(),
        chart: Chart::Measured { chart, digits: Digits::absolute(err) },
    }
}

/// Both commands over the first 0.2 s (where the peaks are), full-rate range per interval.
fn tau_zoom(r: &RunView, f: &Frame) -> Figure {
    let s = &r.out.series;
    let zoom = 0.2_f64.min(f.t_end);
    // the zoom's samples only (the whole run is in Figures 7–8's data)
    let m = s.t.partition_point(|t| *t <= zoom * (1.0 + 1e-12));
    let mut c: LineChart = line_plot(
        &format!("tau-zoom-{}", r.tag),
        &format!("τ1, τ2 over the first {} s {}", tick(zoom), r.desc),
        "τ1 (N), τ2 (N m)",
        vec![("τ1 (N)".into(), &s.t[..m], s.tau1[..m].to_vec()), ("τ2 (N m)".into(), &s.t[..m], s.tau2[..m].to_vec())],
    )
    .into();
    for (i, env) in [envelope_of(r.out, 0), envelope_of(r.out, 1)].into_iter().enumerate() {
        c.bands.push(Band {
            line: i,
            lo: env[..m].iter().map(|e| e.0).collect(),
            hi: env[..m].iter().map(|e| e.1).collect(),
            label: if i == 0 { band_label(f.every) } else { String::new() },
        });
    }
    c.bands.retain(|b| !b.label.is_empty() || b.line == 1);
    c.x_range = Some((0.0, zoom));
    let caption = Caption::default().t(format!(
        "Zoom of Figures {}–{} on [0, {}] s, where the commands peak: output samples as lines, the full-rate range per {}-s output interval shaded. Full-rate peaks over the run: |τ1| ",
        r.first,
        r.first + 1,
        tick(zoom),
        tick(f.every)
    ))
    .n(format!("tau-zoom-{}.peak1", r.tag), r.out.peaks.tau1.abs_max)
    .t(" N at t = ")
    .n(format!("tau-zoom-{}.t1", r.tag), r.out.peaks.tau1.t)
    .t(" s, |τ2| ")
    .n(format!("tau-zoom-{}.peak2", r.tag), r.out.peaks.tau2.abs_max)
    .t(" N m at t = ")
    .n(format!("tau-zoom-{}.t2", r.tag), r.out.peaks.tau2.t)
    .t(" s.");
    let err = r.err.tau[0].min(r.err.tau[1]);
    Figure {
        file: format!("tau-zoom-{}", r.tag),
        label: format!("Figures {}–{}, zoom", r.first, r.first + 1),
        title: format!("τ1, τ2 over the first {} s {}", tick(zoom), r.desc),
        caption: caption.0.into_iter().chain(data_note(err, "N or N m")).collect(),
        chart: Chart::Measured { chart: c, digits: Digits::absolute(err) },
    }
}

/// The tip value `q` (`is_q`) or θ with its error band and the uncontrolled tip.
fn tip_chart(r: &RunView, is_q: bool, f: &Frame) -> LineChart {
    let pick = |o: &SimOutput| if is_q { o.series.q_tip.clone() } else { o.series.theta_tip.clone() };
    let (s, u) = if is_q { ("q", "m") } else { ("θ", "rad") };
    let v = pick(r.out);
    let e = if is_q { &r.err.q } else { &r.err.theta };
    let n = r.first + if is_q { 2 } else { 3 };
    let t = &r.out.series.t;
    let mut c: LineChart = line_plot(
        &format!("fig{n}"),
        &format!("{s}(s,t) {}", r.desc),
        &format!("{s}(s,t) ({u})"),
        vec![(r.tag.to_uppercase(), t, v.clone()), ("without control".into(), &f.none.series.t, pick(f.none))],
    )
    .into();
    c.bands.push(Band {
        line: 0,
        lo: v.iter().zip(e).map(|(v, e)| v - e).collect(),
        hi: v.iter().zip(e).map(|(v, e)| v + e).collect(),
        label: format!("± estimated grid error (2N = {}, dt/2 = {} s)", r.err.refined_grid, tick(r.err.refined_dt)),
    });
    c
}

/// A y range that includes 0 when the values change by less than a tenth of their size (else
/// a small drift fills the axis and reads as a large change); the relative change if so.
fn include_zero(a: &mut LineChart, b: &mut LineChart) -> Option<f64> {
    let (lo, hi) = a.y_range.unwrap_or((0.0, 0.0));
    let size = lo.abs().max(hi.abs());
    if lo <= 0.0 && hi >= 0.0 || size == 0.0 || hi - lo >= 0.1 * size {
        return None;
    }
    let vals: Vec<f64> = a.y_values().into_iter().chain(b.y_values()).collect();
    let r = padded_range(vals.iter().copied().chain(std::iter::once(0.0)), false);
    a.y_range = Some(r);
    b.y_range = Some(r);
    let (vlo, vhi) = vals.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(*v), h.max(*v)));
    Some((vhi - vlo) / size)
}

fn tip_figure(r: &RunView, is_q: bool, f: &Frame, chart: LineChart, twin: u32, small: Option<f64>) -> Figure {
    let pick = |o: &SimOutput| if is_q { o.series.q_tip.clone() } else { o.series.theta_tip.clone() };
    let (s, u, what) = if is_q { ("q", "m", "bending") } else { ("θ", "rad", "twist") };
    let n = r.first + if is_q { 2 } else { 3 };
    let (v, v0, t) = (pick(r.out), pick(f.none), &r.out.series.t);
    let (t0, t1) = (f.t_end / 2.0, f.t_end);
    let mut cap = Caption::default()
        .t(format!(
            "Boundary {what} {s}(s,t) at the tip {} (paper Figure {n}), against the tip without control. max |{s}(s,t)| over [{}, {}] s: ",
            r.desc,
            tick(t0),
            tick(t1)
        ))
        .n(format!("fig{n}.max_abs_late"), max_abs(t, &v, t0, t1))
        .t(format!(" {u} (without control: "))
        .n(format!("fig{n}.none_max_abs_late"), max_abs(&f.none.series.t, &v0, t0, t1))
        .t(format!(" {u}); RMS over the same window: "))
        .n(format!("fig{n}.rms_late"), rms(t, &v, t0, t1))
        .t(format!(" {u}. Shaded: the estimated discretisation error of the configured grid (from runs at 2N and dt/2, Richardson, safety factor 1.25), at most "))
        .n(format!("fig{n}.max_error"), if is_q { r.err.max_q } else { r.err.max_theta })
        .t(format!(" {u}. Same axes as Figure {twin}."));
    if let Some(rel) = small {
        cap = cap
            .t(" The y axis includes 0: the values change by only ")
            .n(format!("fig{n}.relative_change"), 100.0 * rel)
            .t(" % of their size over the run.");
    }
    let err = if is_q { r.err.max_q } else { r.err.max_theta };
    Figure {
        file: format!("fig{n:02}-{}-tip-{}", if is_q { "q" } else { "theta" }, r.tag),
        label: format!("Figure {n}"),
        title: format!("{s}(s,t) {}", r.desc),
        caption: cap.0.into_iter().chain(data_note(err, u)).collect(),
        chart: Chart::Measured { chart, digits: Digits::absolute(err) },
    }
}

/// |g̃| of channel `ch` on a log axis: the samples as a line, the full-rate range of |g̃| per
/// interval as a band, the threshold, t_reach (from the full-rate maximum per interval) and
/// the bound t_f of (38)/(39) when given (times > 0: the time axis is logarithmic); and t_reach.
fn gerr_chart(r: &RunView, ch: u8) -> (LineChart, Option<f64>) {
    let s = &r.out.series;
    let v: Vec<f64> = wingcheck_sim::metrics::observer_error(s, usize::from(ch - 1)).iter().map(|x| x.abs()).collect();
    let env = envelope_of(r.out, usize::from(ch + 1));
    let (lo, hi) = (envelope_abs_min(env), envelope_abs_max(env));
    let reach = settle_time(&s.t, &hi, GTILDE_THRESHOLD);
    let n = r.first + 3 + u32::from(ch);
    let mut c: LineChart = line_plot(
        &format!("fig{n}"),
        &format!("|g̃{ch}(t)| {}", r.desc),
        &format!("|g̃{ch}| ({})", unit(ch)),
        vec![("samples".into(), &s.t, v)],
    )
    .into();
    c.data.log_y = true;
    c.data.log_x = true;
    c.bands.push(Band { line: 0, lo, hi, label: band_label(r.out.series.t.get(1).copied().unwrap_or(0.0)) });
    c.hlines.push((GTILDE_THRESHOLD, format!("|g̃| = {} {}", tick(GTILDE_THRESHOLD), unit(ch))));
    // (a time 0 has no place on the log time axis; the caption states it)
    if let Some(ts) = reach.filter(|t| *t > 0.0) {
        c.vlines.push((ts, format!("t_reach ≤ {} s", tick(ts))));
    }
    if let Some(tf) = r.bounds[usize::from(ch - 1)].filter(|t| *t > 0.0) {
        c.vlines.push((tf, format!("bound t_f{ch} = {} s of ({})", tick(tf), if ch == 1 { 38 } else { 39 })));
    }
    (c, reach)
}

fn gerr_figure(r: &RunView, ch: u8, f: &Frame, chart: LineChart, reach: Option<f64>, twin: u32) -> Figure {
    let s = &r.out.series;
    let n = r.first + 3 + u32::from(ch);
    let u = unit(ch);
    let thr = tick(GTILDE_THRESHOLD);
    let hi = envelope_abs_max(envelope_of(r.out, usize::from(ch + 1)));
    let mut cap = Caption::default()
        .t(format!(
            "Disturbance estimation error |g̃{ch}(t)| = |g{ch} − ĝ{ch}| {} (paper Figure {n}), log scale; shaded: its full-rate range over each output interval, line: the output samples. Full-rate max |g̃{ch}| over [{}, {}] s: ",
            r.desc,
            tick(f.t_end / 2.0),
            tick(f.t_end)
        ))
        .n(format!("fig{n}.max_abs_late"), max_abs(&s.t, &hi, f.t_end / 2.0, f.t_end))
        .t(format!(" {u}"));
    cap = match reach {
        Some(ts) => cap
            .t(format!("; at full rate |g̃{ch}| stays ≤ {thr} {u} (the threshold used throughout) from within the output interval ending at t_reach = "))
            .n(format!("fig{n}.settle_time"), ts)
            .t(format!(" s (resolved to the {} s of an output interval)", tick(f.every))),
        None => cap.t(format!("; at full rate |g̃{ch}| still exceeds {thr} {u} (the threshold used throughout) in the last output interval")),
    };
    if let Some(tf) = r.bounds[usize::from(ch - 1)] {
        cap = cap
            .t(format!("; the bound t_f{ch} of ({}) is ", if ch == 1 { 38 } else { 39 }))
            .n(format!("fig{n}.bound"), tf)
            .t(" s");
    }
    cap = cap.t(format!(
        ". The time axis is logarithmic from the first output sample ({} s), so the convergence and the late level both show; same axes as Figure {twin}.",
        tick(f.every)
    ));
    let relative = r.err.gtilde_relative[usize::from(ch - 1)];
    let digits = Digits::relative(relative);
    let note = match digits {
        Digits::Significant(k) => format!(
            " The data file has {k} significant digits, from the largest estimated relative error {} of the samples.",
            wingcheck_model::quantity::format_error(relative)
        ),
        _ => String::new(),
    };
    Figure {
        file: format!("fig{n:02}-gtilde{ch}-{}", r.tag),
        label: format!("Figure {n}"),
        title: format!("|g̃{ch}(t)| {}", r.desc),
        caption: cap.t(note).0,
        chart: Chart::Measured { chart, digits },
    }
}

/// The τ, tip and |g̃| figures of both runs, each pair on common axes: (FTDO's, DOBC's), each
/// in paper order (τ1, τ2, τ zoom, q tip, θ tip, |g̃1|, |g̃2|).
pub fn paired(a: &RunView, b: &RunView, f: &Frame) -> (Vec<Figure>, Vec<Figure>) {
    let (mut fa, mut fb) = (Vec::new(), Vec::new());
    let twin = |r: &RunView, k: u32| r.first + k;
    for ch in [1u8, 2] {
        let (mut ca, mut cb) = (tau_chart(a, ch, f), tau_chart(b, ch, f));
        share_y(&mut ca, &mut cb, false);
        let k = u32::from(ch - 1);
        fa.push(tau_figure(a, ch, f, ca, twin(b, k)));
        fb.push(tau_figure(b, ch, f, cb, twin(a, k)));
    }
    fa.push(tau_zoom(a, f));
    fb.push(tau_zoom(b, f));
    for is_q in [true, false] {
        let (mut ca, mut cb) = (tip_chart(a, is_q, f), tip_chart(b, is_q, f));
        share_y(&mut ca, &mut cb, false);
        let small = include_zero(&mut ca, &mut cb);
        let k = if is_q { 2 } else { 3 };
        fa.push(tip_figure(a, is_q, f, ca, twin(b, k), small));
        fb.push(tip_figure(b, is_q, f, cb, twin(a, k), small));
    }
    for ch in [1u8, 2] {
        let ((mut ca, ra), (mut cb, rb)) = (gerr_chart(a, ch), gerr_chart(b, ch));
        share_y(&mut ca, &mut cb, true);
        let k = 3 + u32::from(ch);
        fa.push(gerr_figure(a, ch, f, ca, ra, twin(b, k)));
        fb.push(gerr_figure(b, ch, f, cb, rb, twin(a, k)));
    }
    (fa, fb)
}
