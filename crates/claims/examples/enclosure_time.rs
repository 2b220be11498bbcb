//! Timing of the ω₁ enclosure at several plans (development aid).
use std::time::Instant;
use wingcheck_claims::certify::omega1::{compute_with, Plan};
use wingcheck_model::{apply_overrides, Config};

fn main() {
    let sets: Vec<String> = std::env::args().skip(1).collect();
    let cfg = apply_overrides(&Config::paper(), &sets).unwrap();
    for plan in [
        Plan { modes: 4, inertia_elements: 4, rayleigh_elements: 8 },
        Plan { modes: 8, inertia_elements: 8, rayleigh_elements: 16 },
        Plan { modes: 16, inertia_elements: 12, rayleigh_elements: 32 },
        wingcheck_claims::certify::omega1::PLAN,
    ] {
        let t = Instant::now();
        match compute_with(&cfg, &plan) {
            Ok(c) => println!("{plan:?}: width {:.2e}, {:.3} s", c.1.relative_width(), t.elapsed().as_secs_f64()),
            Err(e) => println!("{plan:?}: {e}"),
        }
    }
}
