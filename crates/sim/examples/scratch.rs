use wingcheck_model::*;
use wingcheck_sim::*;
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let base = Config::paper();
    let cfg = apply_overrides(&base, &args).unwrap();
    let t = std::time::Instant::now();
    let out = simulate(&cfg, RunOptions::default()).unwrap();
    let el = t.elapsed().as_secs_f64();
    let s = &out.series;
    for &tt in &[1.0, 5.0, 10.0, 20.0] {
        println!(
            "t={tt} q={:.9} th={:.9} g1t={:.3e} g2t={:.3e} E={:.6e}",
            s.at(&s.q_tip, tt),
            s.at(&s.theta_tip, tt),
            s.at(&s.g1, tt) - s.at(&s.g1_hat, tt),
            s.at(&s.g2, tt) - s.at(&s.g2_hat, tt),
            s.at(&s.energy, tt)
        );
    }
    println!("time {el:.4}s stats {:?}", out.stats);
}
