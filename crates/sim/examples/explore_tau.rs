use wingcheck_model::{apply_overrides, Config};
use wingcheck_sim::{simulate, RunOptions};
fn rms(t: &[f64], v: &[f64], t0: f64) -> f64 {
    let xs: Vec<f64> = t.iter().zip(v).filter(|(t, _)| **t >= t0).map(|(_, v)| v * v).collect();
    (xs.iter().sum::<f64>() / xs.len() as f64).sqrt()
}
fn main() {
    for scheme in ["trapezoid", "trbdf2"] {
        for rule in ["explicit", "implicit"] {
            for period in [1e-3, 1e-2] {
                let mut res = vec![];
                for div in [1.0, 10.0] {
                    let sets = vec![
                        format!("discretisation.stepper={scheme}"),
                        format!("observer.rule={rule}"),
                        format!("observer.sample_period={period}"),
                        format!("discretisation.dt={}", period / div),
                    ];
                    let cfg = apply_overrides(&Config::paper(), &sets).unwrap();
                    let t = std::time::Instant::now();
                    let o = simulate(&cfg, RunOptions::default()).unwrap();
                    let el = t.elapsed().as_secs_f64();
                    let s = &o.series;
                    res.push((rms(&s.t, &s.tau1, 5.0), rms(&s.t, &s.tau2, 5.0), o.peaks.tau1.abs_max, el));
                }
                println!("{scheme} {rule} T={period}: rms τ1 {:.5} vs {:.5} ({:+.2}%), rms τ2 {:.5} vs {:.5} ({:+.2}%), peak τ1 {:.3} vs {:.3}; {:.1} ms",
                    res[0].0, res[1].0, 100.0*(res[0].0/res[1].0-1.0), res[0].1, res[1].1, 100.0*(res[0].1/res[1].1-1.0), res[0].2, res[1].2, res[0].3*1e3);
            }
        }
    }
}
