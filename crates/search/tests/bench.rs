//! `wingcheck bench --what search` on a small grid: every repeat it promises is run, and the
//! ratios are formed from the medians and pairs it reports (recomputed here from the
//! published fields), finite and positive.

use wingcheck_model::Config;
use wingcheck_search::bench::{bench_search, RULE_ROUNDS, SEARCH_REPEATS};
use wingcheck_sim::bench::median;

#[test]
fn the_search_bench_runs_its_repeats_and_forms_its_ratios_from_them() {
    let b = bench_search(&Config::paper(), 3, &[1, 2]).unwrap();
    assert_eq!(b.points, 9);
    assert_eq!(b.runs.len(), 2);
    assert!(b.runs.iter().all(|r| r.failed == 0 && r.wall_seconds > 0.0));
    // the repeats with the most threads, each with the simulate timings around it; the ratio
    // is the median of the runs' own ratios
    assert_eq!(b.most_threads_wall_seconds.len(), SEARCH_REPEATS);
    assert_eq!(b.simulate_around_seconds.len(), SEARCH_REPEATS);
    assert!(b.simulate_around_seconds.iter().all(|s| *s > 0.0));
    let ratios: Vec<f64> = b
        .most_threads_wall_seconds
        .iter()
        .zip(&b.simulate_around_seconds)
        .map(|(w, s)| w / (b.points as f64 * s))
        .collect();
    let ratio = median(ratios);
    assert!((b.wall_over_simulate_runs - ratio).abs() <= 1e-12 * ratio, "{} vs {ratio}", b.wall_over_simulate_runs);
    // the load-independent ratio from CPU times, formed the same way from its own fields
    #[cfg(target_os = "linux")]
    {
        let cpu: Vec<f64> = b
            .most_threads_cpu_seconds
            .iter()
            .zip(&b.simulate_around_cpu_seconds)
            .map(|(w, s)| w.unwrap() / (b.points as f64 * s.unwrap()))
            .collect();
        let cpu_ratio = median(cpu);
        let got = b.cpu_over_simulate_runs.unwrap();
        assert!((got - cpu_ratio).abs() <= 1e-12 * cpu_ratio, "{got} vs {cpu_ratio}");
        // the machine line: cores and the load at both ends
        assert!(b.machine.load_average_end.is_some() && b.machine.cores >= 1);
    }
    // both observer rules on the 8 × 8 grid, their pairs' median ratio positive and finite
    assert_eq!(b.rules.len(), 2);
    assert!(b.rules.iter().all(|r| r.points == 64 && r.wall_seconds_per_point > 0.0));
    assert_eq!((b.rules[0].rule.as_str(), b.rules[1].rule.as_str()), ("implicit", "explicit"));
    assert_eq!(b.rules[1].scheme, "exponential");
    assert!(b.explicit_over_implicit_wall.is_finite() && b.explicit_over_implicit_wall > 0.0);
    // the median of the RULE_ROUNDS paired ratios and the ratio of the two rules' medians
    // measure the same thing: of the same order however loaded the machine
    let of_medians = b.rules[1].wall_seconds_per_point / b.rules[0].wall_seconds_per_point;
    assert!(RULE_ROUNDS >= 3 && (0.2..5.0).contains(&(b.explicit_over_implicit_wall / of_medians)));
    // on Linux every optional timing (load average, CPU times) is measured: no null in the JSON
    #[cfg(target_os = "linux")]
    assert!(!serde_json::to_string(&b).unwrap().contains("null"));
}
