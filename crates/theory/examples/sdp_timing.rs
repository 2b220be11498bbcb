//! Times `max_generalized_lambda` on random dense problems.
//! Usage: `cargo run -p wingcheck-theory --release --example sdp_timing -- 20 60 120`

use wingcheck_theory::sdp::problem::max_generalized_lambda;

fn main() {
    let sizes: Vec<usize> = std::env::args().skip(1).filter_map(|s| s.parse().ok()).collect();
    let sizes = if sizes.is_empty() { vec![20, 60, 120] } else { sizes };
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    };
    for n in sizes {
        let g: Vec<Vec<f64>> = (0..n).map(|_| (0..n).map(|_| next()).collect()).collect();
        let h: Vec<Vec<f64>> = (0..n).map(|_| (0..n).map(|_| next()).collect()).collect();
        let a: Vec<Vec<f64>> = (0..n).map(|i| (0..n).map(|j| 0.5 * (h[i][j] + h[j][i])).collect()).collect();
        let b: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| (0..n).map(|k| g[i][k] * g[j][k]).sum::<f64>() / n as f64 + f64::from(u8::from(i == j)))
                    .collect()
            })
            .collect();
        let t = std::time::Instant::now();
        let out = max_generalized_lambda(&a, &b).expect("solve");
        println!(
            "n={n:4} status={:?} lambda={:?} iterations={} clarabel_solve_time={:.3}s wall={:.3}s",
            out.status,
            out.lambda,
            out.iterations,
            out.solve_time,
            t.elapsed().as_secs_f64()
        );
    }
}
