//! Axis parsing and validation: bad axes fail with a clear error naming the axis, before any
//! work (no output directory is created: `Search::new` is pure).

use proptest::prelude::*;
use wingcheck_model::Config;
use wingcheck_search::{Axis, Grid, Search, SearchError, SearchOptions, Spacing};

fn err(specs: &[&str]) -> String {
    let specs: Vec<String> = specs.iter().map(|s| s.to_string()).collect();
    match Search::new(Config::paper(), &specs, SearchOptions::default()) {
        Err(e @ SearchError::Axis { .. }) => e.to_string(),
        Err(e) => panic!("expected an axis error, got {e}"),
        Ok(_) => panic!("{specs:?} accepted"),
    }
}

#[test]
fn bad_axes_are_refused_with_the_axis_named() {
    let e = err(&["control.a=1e-4..10:log:8", "control.zeta=1..2:lin:3"]);
    assert!(e.contains("control.zeta") && e.contains("unknown key"), "{e}");
    let e = err(&["control.a=1..1:log:5"]);
    assert!(e.contains("control.a") && e.contains("empty range"), "{e}");
    let e = err(&["control.a=1..2:log:0"]);
    assert!(e.contains("empty range"), "{e}");
    let e = err(&["control.b="]);
    assert!(e.contains("empty range"), "{e}");
    let e = err(&["control.a=0..10:log:8"]);
    assert!(e.contains("control.a") && e.contains("positive"), "{e}");
    let e = err(&["control.b=-1..10:log:8"]);
    assert!(e.contains("positive"), "{e}");
    let e = err(&["control.a=10..1:lin:4"]);
    assert!(e.contains("lower bound 10 > upper bound 1"), "{e}");
    let e = err(&["control.a=1..2:cubic:4"]);
    assert!(e.contains("unknown spacing"), "{e}");
    let e = err(&["control.a=1,2", "control.a=3"]);
    assert!(e.contains("swept twice"), "{e}");
    // a value outside the model's range (control.a ≥ 0 in wingcheck_model::validate)
    let e = err(&["control.a=-1..1:lin:3"]);
    assert!(e.contains("control.a") && e.contains("out of range"), "{e}");
    // a corner that is invalid only in combination: ρ·I_p = 15 must exceed (ρx_c)²
    // (paper I_p = 1.5): each end is valid with the other axis at its first value
    // (ρx_c = 3.8, ρ = 10: 15 > 14.44; ρx_c = 1, ρ = 5: 7.5 > 1), the corner is not
    // (ρx_c = 3.8, ρ = 5: 7.5 < 14.44)
    let e = err(&["wing.rho_xc=1..3.8:lin:2", "wing.rho=10,5"]);
    assert!(e.contains("corner") && e.contains("mass matrix"), "{e}");
    let e = err(&["discretisation.method=fd,spectral"]);
    assert!(e.contains("spectral"), "{e}");
}

#[test]
fn integer_keys_get_integer_values() {
    // discretisation.elements is a usize in wingcheck_model::Discretisation
    let s = Search::new(Config::paper(), &["discretisation.elements=8..32:lin:4".into()], SearchOptions::default())
        .unwrap();
    let texts: Vec<String> = (0..4).map(|p| s.grid.texts(p)[0].clone()).collect();
    assert_eq!(texts, ["8", "16", "24", "32"]);
    let s = Search::new(Config::paper(), &["discretisation.elements=8..16:log:3".into()], SearchOptions::default())
        .unwrap();
    assert_eq!(s.grid.texts(1)[0], "11"); // √(8·16) = 11.31
    let e = err(&["discretisation.elements=8..9:lin:4"]);
    assert!(e.contains("repeats"), "{e}");
}

#[test]
fn grids_have_exact_endpoints_and_list_values() {
    let a = Axis::parse("control.a=1e-4..10:log:48").unwrap();
    assert_eq!(a.len(), 48);
    assert_eq!(a.numeric(0), Some(1e-4));
    assert_eq!(a.numeric(47), Some(10.0));
    // 48 points over 5 decades: ratio 10^(5/47) between neighbours
    let r = a.numeric(1).unwrap() / a.numeric(0).unwrap();
    assert!((r - 10f64.powf(5.0 / 47.0)).abs() < 1e-12);
    let l = Axis::parse("discretisation.method=fd,fe").unwrap();
    assert_eq!(l.spacing, Spacing::List { values: vec!["fd".into(), "fe".into()] });
    assert_eq!(l.override_expr(1), "discretisation.method=fe");
    // FD refuses a graded grid: a method axis needs a uniform base grid
    let mut uniform = Config::paper();
    uniform.discretisation.grading = 0.0;
    assert!(Search::new(uniform, &["discretisation.method=fd,fe".into()], SearchOptions::default()).is_ok());
}

proptest! {
    #[test]
    fn spec_round_trips(lo in 1e-6f64..1e3, f in 1.0001f64..1e3, n in 1usize..200, log in any::<bool>()) {
        let kind = if log { "log" } else { "lin" };
        let a = Axis::parse(&format!("control.b={lo}..{}:{kind}:{n}", lo * f)).unwrap();
        prop_assert_eq!(Axis::parse(&a.spec()).unwrap(), a.clone());
        for i in 0..n {
            let x = a.numeric(i).unwrap();
            prop_assert!(x >= lo && x <= lo * f);
            prop_assert_eq!(a.text(i).parse::<f64>().unwrap(), x);
        }
    }

    #[test]
    fn grid_index_round_trips(d0 in 1usize..6, d1 in 1usize..6, d2 in 1usize..6) {
        let axes = vec![
            Axis::parse(&format!("control.a=1..2:lin:{d0}")).unwrap_or_else(|_| Axis::parse("control.a=1").unwrap()),
            Axis::parse(&format!("control.b=1..2:lin:{d1}")).unwrap_or_else(|_| Axis::parse("control.b=1").unwrap()),
            Axis::parse(&format!("control.k1=1..2:lin:{d2}")).unwrap_or_else(|_| Axis::parse("control.k1=1").unwrap()),
        ];
        let g = Grid::new(axes);
        for p in 0..g.len() {
            prop_assert_eq!(g.index(&g.multi(p)), p);
        }
        // first axis slowest
        if g.len() > 1 && g.dims()[2] > 1 {
            prop_assert_eq!(g.multi(1)[2], 1);
        }
    }
}
