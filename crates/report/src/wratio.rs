//! The W-bounds figure a referee asks for: the tight ratio λ2*/λ1* = min W/κ / max W/κ against
//! a/b, which passes through zero at a/b = ω₁ (where W ≻ 0 ends), beside the printed
//! λ2/λ1 = (y2 − y3)/(y1 + y3) of (27)–(28) at the configured b. Both are scale-free in the sense
//! that W is linear in (a, b): the tight ratio depends on a/b alone.

use num_traits::ToPrimitive;
use rayon::prelude::*;
use wingcheck_claims::wbounds::PrintedWing;
use wingcheck_model::Config;
use wingcheck_theory::WPencil;

use crate::chart::{tick, LineChart, LineStyle};
use crate::figure::{Caption, Chart, Figure};

/// Points of the a/b sweep (log spaced).
const POINTS: usize = 61;

/// The sweep: a/b log spaced over two decades beyond ω₁ and the configured a/b, the tight and
/// the printed λ2/λ1 at each, and where the tight one changes sign (regula falsi in log a/b,
/// [`zero_crossing`]).
struct Sweep {
    ratios: Vec<f64>,
    tight: Vec<f64>,
    printed: Vec<f64>,
    crossing: Option<f64>,
}

fn sweep(cfg: &Config, pencil: &WPencil, omega1: f64) -> Option<Sweep> {
    let b = cfg.control.b;
    let here = cfg.control.a / b;
    let (lo, hi) = (omega1.min(if here > 0.0 { here } else { omega1 }) / 100.0, omega1.max(here) * 100.0);
    let ratios: Vec<f64> = (0..POINTS).map(|k| lo * (hi / lo).powf(k as f64 / (POINTS - 1) as f64)).collect();
    // the points are independent: in parallel, collected in order
    let wing = PrintedWing::of(cfg);
    let (tight, printed): (Vec<f64>, Vec<f64>) = ratios
        .par_iter()
        .map(|&r| {
            let (l2, l1) = pencil.constants(r * b, b).ok()?;
            let p = wing.at(r * b, b);
            let (l2p, l1p) = ((&p.y2 - &p.y3).to_f64()?, (&p.y1 + &p.y3).to_f64()?);
            Some((l2 / l1, l2p / l1p))
        })
        .collect::<Option<Vec<_>>>()?
        .into_iter()
        .unzip();
    let crossing =
        ratios.windows(2).zip(tight.windows(2)).find(|(_, t)| t[0] > 0.0 && t[1] <= 0.0).and_then(|(r, t)| {
            let ratio_at = |x: f64| pencil.constants(x.exp() * b, b).ok().map(|(l2, l1)| l2 / l1);
            zero_crossing((r[0].ln(), t[0]), (r[1].ln(), t[1]), ratio_at).map(f64::exp)
        });
    Some(Sweep { ratios, tight, printed, crossing })
}

/// Bracket width (in ln a/b, so relative in a/b) at which [`zero_crossing`] stops.
const CROSSING_WIDTH: f64 = 1e-12;

/// The zero of `f` between `lo` = (x, f(x) > 0) and `hi` = (x, f(x) ≤ 0) by regula falsi with the
/// Illinois modification (superlinear: the ratio is smooth there), until the bracket is at most
/// [`CROSSING_WIDTH`] wide or f is exactly 0 (at most 100 evaluations, then the bracket's
/// midpoint); None if `f` fails.
fn zero_crossing(lo: (f64, f64), hi: (f64, f64), f: impl Fn(f64) -> Option<f64>) -> Option<f64> {
    let ((mut x0, mut f0), (mut x1, mut f1)) = (lo, hi);
    let mut kept = 0i8; // which end stayed last time (+1 the low end, −1 the high end)
    for _ in 0..100 {
        if x1 - x0 <= CROSSING_WIDTH {
            break;
        }
        let secant = (x0 * f1 - x1 * f0) / (f1 - f0);
        let m = if secant > x0 && secant < x1 { secant } else { 0.5 * (x0 + x1) };
        let fm = f(m)?;
        if fm == 0.0 {
            return Some(m);
        }
        if fm > 0.0 {
            (x0, f0) = (m, fm);
            if kept == -1 {
                f1 *= 0.5;
            }
            kept = -1;
        } else {
            (x1, f1) = (m, fm);
            if kept == 1 {
                f0 *= 0.5;
            }
            kept = 1;
        }
    }
    Some(0.5 * (x0 + x1))
}

fn chart_of(cfg: &Config, s: &Sweep, omega1: f64, elements: usize) -> LineChart {
    let (b, here) = (cfg.control.b, cfg.control.a / cfg.control.b);
    let (lo, hi) = (s.ratios[0], s.ratios[s.ratios.len() - 1]);
    let line =
        |label: String, y: &[f64]| wingcheck_claims::Line { label, x: s.ratios.clone(), y: y.to_vec(), points: false };
    let lines = vec![
        line(format!("tight λ2*/λ1* ({elements} elements)"), &s.tight),
        line(format!("printed λ2/λ1, b = {} s", tick(b)), &s.printed),
        wingcheck_claims::Line { label: "0 (W ≻ 0 above)".into(), x: vec![lo, hi], y: vec![0.0, 0.0], points: false },
    ];
    let data = wingcheck_claims::PlotData {
        name: "w-ratio".into(),
        title: "λ2/λ1 against a/b".into(),
        x_label: "a/b (1/s)".into(),
        y_label: "λ2/λ1 (dimensionless)".into(),
        log_x: true,
        log_y: false,
        lines,
    };
    let mut chart = LineChart::from(data);
    chart.styles = vec![LineStyle::Solid, LineStyle::Solid, LineStyle::Dashed];
    chart.vlines.push((omega1, format!("a/b = ω₁ = {} 1/s", tick(omega1))));
    if here > 0.0 {
        chart.vlines.push((here, format!("configured a/b = {} 1/s", tick(here))));
    }
    chart
}

fn caption_of(s: &Sweep, omega1: f64, elements: usize, chart: &LineChart, rescaled: bool) -> Caption {
    let mut cap = Caption::default().t(format!(
        "The tight ratio λ2*/λ1* = min W/κ / max W/κ on {elements} Galerkin elements against a/b (W is linear in a and b, so the ratio depends on a/b alone), and the printed λ2/λ1 = (y2 − y3)/(y1 + y3) of (27)–(28) at the configured b. W ≻ 0 exactly where the tight ratio is positive: "
    ));
    cap = match s.crossing {
        Some(x) => cap
            .t("it crosses zero at a/b = ")
            .n("w-ratio.crossing", x)
            .t(format!(" 1/s (to 10⁻¹² relative; ω₁ of the {elements}-element space, an upper bound of ω₁), against the converged ω₁ = "))
            .n("w-ratio.omega1", omega1)
            .t(" 1/s."),
        None => cap.t("it does not change sign on this sweep."),
    };
    let negative = s.printed.iter().filter(|v| **v < 0.0).count();
    cap = cap
        .t(" The printed ratio is negative at ")
        .count("w-ratio.printed_negative", negative)
        .t(format!(" of {POINTS} points: the printed λ2 = y2 − y3 gives no bound where the tight one does."));
    if let Some(sl) = chart.symlog_y {
        cap = cap
            .t(" The y axis is symmetric-logarithmic (the small positive ratios would read as 0 on a linear one): linear for |y| ≤ ")
            .n("w-ratio.symlog_threshold", sl.threshold)
            .t(", logarithmic beyond.");
    } else if rescaled {
        cap = cap.t(" The y axis is logarithmic.");
    }
    cap
}

/// The figure, or None when the pencil cannot be set up or b is not positive.
pub fn w_ratio_figure(cfg: &Config, omega1: f64, elements: usize) -> Option<Figure> {
    if !(cfg.control.b > 0.0 && omega1 > 0.0 && omega1.is_finite()) {
        return None;
    }
    let pencil = WPencil::new(cfg, elements).ok()?;
    let s = sweep(cfg, &pencil, omega1)?;
    let (chart, rescaled) = crate::readable_y_axis(chart_of(cfg, &s, omega1, elements));
    let cap = caption_of(&s, omega1, elements, &chart, rescaled);
    Some(Figure {
        file: "w-ratio".into(),
        label: "W-bounds, λ2/λ1 against a/b".into(),
        title: "λ2/λ1 against a/b: tight and printed".into(),
        caption: cap.0,
        chart: Chart::Line(chart),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sweep's zero crossing is ω₁ of the Galerkin space, which the W-bounds row computes
    /// another way (`a_over_b_max`: −1/μ_min of the pencil (W(1, 0), W(0, 1)), one generalized
    /// eigenproblem instead of a root search over λ2/λ1); measured agreement 3.7e-12 at the
    /// paper's wing, 2.6e-13 at the SI-scale one (the crossing's width 1e-12 plus the two
    /// eigen-solves' round-off), checked to 1e-11, at the paper's wing and two others.
    #[test]
    fn the_crossing_is_the_galerkin_omega1() {
        let si = |c: &mut Config| {
            (c.wing.span, c.wing.ei, c.wing.gj, c.wing.rho, c.wing.ip) = (6.0, 1e7, 1e6, 100.0, 10.0);
            (c.control.a, c.control.b) = (2.0, 50.0);
        };
        // a/b alone sets the ratio, so another b would land on the same crossing: another wing
        let other_wing = |c: &mut Config| (c.wing.rho_xc, c.wing.gj, c.wing.xi) = (1.0, 2.0, 0.1);
        let paper = |_: &mut Config| {};
        let cases: [&dyn Fn(&mut Config); 3] = [&paper, &other_wing, &si];
        for set in cases {
            let mut cfg = Config::paper();
            set(&mut cfg);
            let elements = 16;
            let reference = wingcheck_theory::lyapunov::a_over_b_max(
                &cfg,
                wingcheck_theory::lyapunov::Coupling::Corrected,
                elements,
            )
            .unwrap();
            let omega1 = wingcheck_theory::w_threshold(&cfg).unwrap().value;
            let s = sweep(&cfg, &WPencil::new(&cfg, elements).unwrap(), omega1).unwrap();
            let x = s.crossing.expect("the sweep spans ω₁");
            assert!((x / reference - 1.0).abs() < 1e-11, "crossing {x} against ω₁ of the space {reference}");
        }
    }

    #[test]
    fn regula_falsi_finds_a_known_root() {
        // Reference: x³ − 2 has its real root at 2^(1/3) (f decreasing here: 2 − x³).
        let root = zero_crossing((1.0, 1.0), (2.0, -6.0), |x| Some(2.0 - x * x * x)).unwrap();
        assert!((root - 2f64.cbrt()).abs() < 2.0 * CROSSING_WIDTH, "{root}");
        // a failing evaluation is no crossing
        assert_eq!(zero_crossing((1.0, 1.0), (2.0, -6.0), |_| None), None);
    }
}
