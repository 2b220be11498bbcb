//! The paper's time-series figures of a controlled run — τ1, τ2 (Figs 7–8, 15–16), the tips
//! (9–10, 17–18), |g̃1|, |g̃2| (11–12, 19–20) — drawn in FTDO/DOBC pairs on common axes:
//!
//! - τ and g̃ as the full-rate range per output interval (the simulator's envelope: every
//!   integrator step and both sides of every sample's jump) with the output samples as a line,
//!   because a signal that chatters at the observer's sample rate aliases in the samples;
//! - the tips with the estimated error of the configured grid as a band (the `--error-estimate`
//!   machinery) and the uncontrolled tip for comparison; an axis that would magnify a small
//!   change includes 0;
//! - |g̃| with t_band (from when the simulated |g̃| stays below the threshold, at full rate) and,
//!   for the FTDO, the ledger's t_reach and bound t_f of (38)/(39) (one symbol, one value).

use wingcheck_sim::metrics::{envelope_abs_max, envelope_abs_min, envelope_of, gtilde_band};
use wingcheck_sim::SimOutput;

use crate::chart::{padded_range, tick, Band, BandStyle, LineChart, LineStyle};
use crate::figure::{line_plot, Caption, Chart, Digits, Figure};
use crate::runs::TipErrors;
use crate::stats::{fmt_num, max_abs, rms};

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
    /// The ledger's bound t_f and reaching time t_reach per channel to mark (the FTDO's).
    pub marks: [FiniteTimeMarks; 2],
}

/// What a finite-time row states about one observer channel, for its |g̃| figure: the bound
/// t_f of (38)/(39) and the reaching time t_reach, as the ledger prints them (one symbol, one
/// value: the figure shows the ledger's numbers).
#[derive(Debug, Clone, Default)]
pub struct FiniteTimeMarks {
    /// The bound t_f1 or t_f2.
    pub bound: Option<wingcheck_model::Quantity>,
    /// The Filippov reaching time t_reach with its error.
    pub reach: Option<wingcheck_model::Quantity>,
}

/// The horizon, the late window and the uncontrolled run.
pub struct Frame<'a> {
    /// t_end (s).
    pub t_end: f64,
    /// Output interval (s).
    pub every: f64,
    /// The run without control.
    pub none: &'a SimOutput,
    /// The ledger's |g̃| convergence threshold (N, N m; `CheckSettings::gtilde_threshold`).
    pub gtilde_threshold: f64,
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

/// Whether a full-rate envelope chatters: in more than half of the output intervals of the
/// second half of the run, the signal's full-rate range is wider than half its size there (the
/// explicit observer's τ jumps between ≈ ±3.5 N every sample; the implicit one's moves by a
/// small fraction of its value per interval). Then the envelope is the curve to read and the
/// output samples alias it.
pub fn chatters(env: &[(f64, f64)]) -> bool {
    let late = &env[env.len() / 2..];
    let wide = late.iter().filter(|(lo, hi)| hi - lo > 0.5 * lo.abs().max(hi.abs()) && hi > lo).count();
    !late.is_empty() && 2 * wide > late.len()
}

/// τ of channel `ch` over the first `m` samples: the samples as a line, the full-rate range per
/// output interval as a band; where the signal chatters the band's edges are the main curve and
/// the samples a faint dashed line. Whether it chatters is returned too.
fn tau_lines(r: &RunView, ch: u8, m: usize, name: &str, title: String, every: f64) -> (LineChart, bool) {
    let s = &r.out.series;
    let v = if ch == 1 { &s.tau1 } else { &s.tau2 };
    let env = envelope_of(r.out, usize::from(ch - 1));
    let chatter = chatters(env);
    let label = if chatter { "output samples (alias the chatter)" } else { "output samples" };
    let mut c: LineChart =
        line_plot(name, &title, &format!("τ{ch} ({})", unit(ch)), vec![(label.into(), &s.t[..m], v[..m].to_vec())])
            .into();
    c.styles = vec![if chatter { LineStyle::Faint } else { LineStyle::Solid }];
    c.bands.push(Band {
        line: 0,
        lo: env[..m].iter().map(|e| e.0).collect(),
        hi: env[..m].iter().map(|e| e.1).collect(),
        label: if chatter {
            format!("full-rate max and min per {} s (the command)", tick(every))
        } else {
            band_label(every)
        },
        style: if chatter { BandStyle::Edges } else { BandStyle::Shade },
    });
    (c, chatter)
}

/// τ of channel `ch` over the whole run.
fn tau_chart(r: &RunView, ch: u8, f: &Frame) -> LineChart {
    let n = r.first + u32::from(ch - 1);
    let m = r.out.series.t.len();
    tau_lines(r, ch, m, &format!("fig{n}"), format!("τ{ch}(t) {}", r.desc), f.every).0
}

/// How the τ figures' curves read, for a caption.
fn tau_reading(r: &RunView, ch: u8, inside: &str) -> String {
    if chatters(envelope_of(r.out, usize::from(ch - 1))) {
        format!("Solid lines: the full-rate max and min of τ{ch} over each output interval (every integrator step, both sides of every sample's jump{inside}) — the command chatters at the observer's sample rate, so these are the curves to read; dashed: the output samples, which alias the chatter")
    } else {
        format!("Shaded: the full-rate range of τ{ch} over each output interval (every integrator step, both sides of every sample's jump{inside}); line: the output samples")
    }
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
            "Control command τ{ch}(t) {} (paper Figure {n}). {}. Full-rate max |τ{ch}| over [0, {}] s: ",
            r.desc,
            tau_reading(r, ch, inside),
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

/// The first 0.2 s of τ of channel `ch` (where the commands peak), on its own axis (τ1 in N, τ2
/// in N m), with the full-rate peak of the whole run marked when it falls in the zoom (the
/// initial layer, resolved by finer steps, can peak between the first samples).
fn tau_zoom_chart(r: &RunView, ch: u8, f: &Frame) -> LineChart {
    let s = &r.out.series;
    let zoom = 0.2_f64.min(f.t_end);
    // the zoom's samples only (the whole run is in Figures 7–8's data)
    let m = s.t.partition_point(|t| *t <= zoom * (1.0 + 1e-12));
    let n = r.first + u32::from(ch - 1);
    let title = format!("τ{ch} over the first {} s {}", tick(zoom), r.desc);
    let (mut c, _) = tau_lines(r, ch, m, &format!("tau{ch}-zoom-{}", r.tag), title, f.every);
    let p = if ch == 1 { r.out.peaks.tau1 } else { r.out.peaks.tau2 };
    if p.t <= zoom {
        c.data.lines.push(wingcheck_claims::Line {
            label: format!("full-rate peak of Figure {n}: |τ{ch}| = {} {}", fmt_num(p.abs_max), unit(ch)),
            x: vec![p.t],
            y: vec![p.value],
            points: true,
        });
    }
    c.x_range = Some((0.0, zoom));
    c
}

fn tau_zoom_figure(r: &RunView, ch: u8, f: &Frame, chart: LineChart, twin: u32) -> Figure {
    let zoom = 0.2_f64.min(f.t_end);
    let n = r.first + u32::from(ch - 1);
    let p = if ch == 1 { r.out.peaks.tau1 } else { r.out.peaks.tau2 };
    let u = unit(ch);
    let caption = Caption::default()
        .t(format!(
            "Zoom of Figure {n} on [0, {}] s, where the command peaks. {}. Full-rate peak |τ{ch}| over the run: ",
            tick(zoom),
            tau_reading(r, ch, "")
        ))
        .n(format!("tau{ch}-zoom-{}.peak", r.tag), p.abs_max)
        .t(format!(" {u} at t = "))
        .n(format!("tau{ch}-zoom-{}.t", r.tag), p.t)
        .t(format!(" s{}. Same axes as the zoom of Figure {twin}.", if p.t <= zoom { " (the dot)" } else { "" }));
    let err = r.err.tau[usize::from(ch - 1)];
    Figure {
        file: format!("tau{ch}-zoom-{}", r.tag),
        label: format!("Figure {n}, zoom"),
        title: format!("τ{ch} over the first {} s {}", tick(zoom), r.desc),
        caption: caption.0.into_iter().chain(data_note(err, u)).collect(),
        chart: Chart::Measured { chart, digits: Digits::absolute(err) },
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
        style: BandStyle::Shade,
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

/// Hide the bands of a chart that are thinner than about two pixels of its y range (0.5 % of
/// it: the plot is ≈ 370 px tall), which would be listed in the legend but not seen (they stay
/// in the data file); true if the bands are drawn.
fn keep_visible_bands(c: &mut LineChart) -> bool {
    let (lo, hi) = c.y_range.unwrap_or((0.0, 0.0));
    let span = hi - lo;
    let thin = span > 0.0 && c.bands.iter().all(|b| b.lo.iter().zip(&b.hi).all(|(l, h)| (h - l).abs() < 0.005 * span));
    if thin {
        c.bands.iter_mut().for_each(|b| b.style = BandStyle::Hidden);
    }
    !thin
}

fn tip_figure(r: &RunView, is_q: bool, f: &Frame, chart: LineChart, twin: u32, small: Option<f64>) -> Figure {
    let mut chart = chart;
    let drawn = keep_visible_bands(&mut chart);
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
        .t(format!(
            " {u}. {} the estimated discretisation error of the configured grid (from runs at 2N and dt/2, Richardson, safety factor 1.25), at most ",
            if drawn { "Shaded:" } else { "Not drawn, because it is thinner than the line at this scale:" }
        ))
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
/// interval as a band, the ledger's threshold, t_band (the entry into its band, [`gtilde_band`]),
/// and the ledger's t_reach and bound t_f of (38)/(39) when given (times > 0: the time axis is
/// logarithmic).
fn gerr_chart(r: &RunView, ch: u8, f: &Frame) -> LineChart {
    let s = &r.out.series;
    let v: Vec<f64> = wingcheck_sim::metrics::observer_error(s, usize::from(ch - 1)).iter().map(|x| x.abs()).collect();
    let env = envelope_of(r.out, usize::from(ch + 1));
    let (lo, hi) = (envelope_abs_min(env), envelope_abs_max(env));
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
    // where g̃ chatters (the explicit rule) the full-rate max and min are the curves to read and
    // the samples alias them, as for τ
    let chatter = chatters(env);
    let every = r.out.series.t.get(1).copied().unwrap_or(0.0);
    if chatter {
        c.data.lines[0].label = "output samples (alias the chatter)".into();
        c.styles = vec![LineStyle::Faint];
    }
    c.bands.push(Band {
        line: 0,
        lo,
        hi,
        label: if chatter {
            format!("full-rate max and min of |g̃{ch}| per {} s", tick(every))
        } else {
            band_label(every)
        },
        style: if chatter { BandStyle::Edges } else { BandStyle::Shade },
    });
    c.hlines.push((f.gtilde_threshold, format!("|g̃| = {} {}", tick(f.gtilde_threshold), unit(ch))));
    let m = &r.marks[usize::from(ch - 1)];
    // (a time 0 has no place on the log time axis; the caption states it)
    if let Some(q) = m.reach.as_ref().filter(|q| q.value > 0.0) {
        c.vlines.push((q.value, format!("t_reach = {} (ledger)", q.value_text())));
    }
    if let Some(tb) = gtilde_band(r.out, f.gtilde_threshold).entry[usize::from(ch - 1)].filter(|t| *t > 0.0) {
        c.vlines.push((tb, format!("t_band = {} s", tick(tb))));
    }
    if let Some(q) = m.bound.as_ref().filter(|q| q.value > 0.0) {
        c.vlines.push((q.value, format!("bound t_f{ch} = {} of ({})", q.value_text(), if ch == 1 { 38 } else { 39 })));
    }
    c
}

fn gerr_figure(r: &RunView, ch: u8, f: &Frame, chart: LineChart, twin: u32) -> Figure {
    let s = &r.out.series;
    let n = r.first + 3 + u32::from(ch);
    let u = unit(ch);
    let thr = tick(f.gtilde_threshold);
    let band = gtilde_band(r.out, f.gtilde_threshold);
    let read = if band.full_rate {
        "at full rate (every integrator step, both sides of every sample's jump)"
    } else {
        "at the output samples"
    };
    let hi = envelope_abs_max(envelope_of(r.out, usize::from(ch + 1)));
    let mut cap = Caption::default()
        .t(format!(
            "Disturbance estimation error |g̃{ch}(t)| = |g{ch} − ĝ{ch}| {} (paper Figure {n}), log scale; {}. Full-rate max |g̃{ch}| over [{}, {}] s: ",
            r.desc,
            if chatters(envelope_of(r.out, usize::from(ch + 1))) {
                "solid lines: its full-rate max and min over each output interval — it chatters at the observer's sample rate, so these are the curves to read; dashed: the output samples, which alias the chatter"
            } else {
                "shaded: its full-rate range over each output interval, line: the output samples"
            },
            tick(f.t_end / 2.0),
            tick(f.t_end)
        ))
        .n(format!("fig{n}.max_abs_late"), max_abs(&s.t, &hi, f.t_end / 2.0, f.t_end))
        .t(format!(" {u}"));
    cap = match band.entry[usize::from(ch - 1)] {
        Some(tb) => cap
            .t(format!("; {read} |g̃{ch}| stays ≤ {thr} {u} (the threshold used throughout) from t_band = "))
            .n(format!("fig{n}.t_band"), tb)
            .t(" s"),
        None => cap.t(format!(
            "; {} |g̃{ch}| still exceeds {thr} {u} (the threshold used throughout) at the end of the run",
            if band.full_rate { "at full rate" } else { "at the output samples" }
        )),
    };
    let m = &r.marks[usize::from(ch - 1)];
    if let Some(q) = &m.reach {
        cap = cap
            .t(format!(". The finite-time-{ch} row's t_reach, when σ{ch} (and with it g̃{ch}) reaches 0 in the continuous-time (Filippov) limit, is "))
            .q(format!("fig{n}.t_reach"), q);
    }
    if let Some(q) = &m.bound {
        cap = cap
            .t(format!("; the bound t_f{ch} of ({}) is ", if ch == 1 { 38 } else { 39 }))
            .q(format!("fig{n}.bound"), q);
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
    for ch in [1u8, 2] {
        let (mut ca, mut cb) = (tau_zoom_chart(a, ch, f), tau_zoom_chart(b, ch, f));
        share_y(&mut ca, &mut cb, false);
        let k = u32::from(ch - 1);
        fa.push(tau_zoom_figure(a, ch, f, ca, twin(b, k)));
        fb.push(tau_zoom_figure(b, ch, f, cb, twin(a, k)));
    }
    for is_q in [true, false] {
        let (mut ca, mut cb) = (tip_chart(a, is_q, f), tip_chart(b, is_q, f));
        share_y(&mut ca, &mut cb, false);
        let small = include_zero(&mut ca, &mut cb);
        let k = if is_q { 2 } else { 3 };
        fa.push(tip_figure(a, is_q, f, ca, twin(b, k), small));
        fb.push(tip_figure(b, is_q, f, cb, twin(a, k), small));
    }
    for ch in [1u8, 2] {
        let (mut ca, mut cb) = (gerr_chart(a, ch, f), gerr_chart(b, ch, f));
        share_y(&mut ca, &mut cb, true);
        let k = 3 + u32::from(ch);
        fa.push(gerr_figure(a, ch, f, ca, twin(b, k)));
        fb.push(gerr_figure(b, ch, f, cb, twin(a, k)));
    }
    (fa, fb)
}
