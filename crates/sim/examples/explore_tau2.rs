use wingcheck_model::{apply_overrides, Config};
use wingcheck_sim::{simulate, RunOptions};
fn rms(t: &[f64], v: &[f64], t0: f64) -> f64 {
    let xs: Vec<f64> = t.iter().zip(v).filter(|(t, _)| **t >= t0).map(|(_, v)| v * v).collect();
    (xs.iter().sum::<f64>() / xs.len() as f64).sqrt()
}
fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let period: f64 = a[0].parse().unwrap();
    for scheme in ["trapezoid", "trbdf2"] {
        let mut line = format!("{scheme} T={period}:");
        for div in [1.0, 2.0, 4.0, 10.0, 20.0] {
            let sets = vec![
                format!("discretisation.stepper={scheme}"),
                "observer.rule=explicit".to_string(),
                format!("observer.sample_period={period}"),
                format!("discretisation.dt={}", period / div),
                "horizon.sample_every=0.01".to_string(),
            ];
            let cfg = apply_overrides(&Config::paper(), &sets).unwrap();
            let o = simulate(&cfg, RunOptions::default()).unwrap();
            let s = &o.series;
            line += &format!(
                " /{div}: {:.5} {:.5} pk {:.4}",
                rms(&s.t, &s.tau1, 5.0),
                rms(&s.t, &s.tau2, 5.0),
                o.peaks.tau1.abs_max
            );
        }
        println!("{line}");
    }
}
