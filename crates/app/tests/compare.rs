//! `compare` from Rust: a controller handed over through the interface gets the same row as the
//! built-in one it wraps; every value carries an error; the claims that do not apply are named.

use wingcheck_app::compare::{compare, Entrant, COLUMNS, NOT_APPLICABLE};
use wingcheck_app::{Front, WorkPolicy};
use wingcheck_control::{BuiltIn, Erased};
use wingcheck_model::{Cancel, Config, ControllerKind, StepBasis};
use wingcheck_sim::{BoxedController, ControllerFactory};

#[test]
fn an_own_controller_row_equals_the_built_in_it_wraps() {
    // Reference: the built-in DOBC in the nodal basis (where the interface gives a built-in's
    // bits): the same controller through it makes the same runs, so the same numbers and errors.
    let mut cfg = Config::paper();
    cfg.horizon.t_end = 4.0;
    cfg.discretisation.basis = StepBasis::Nodal;
    cfg.control.kind = ControllerKind::Dobc;
    let make = || -> BoxedController { Box::new(Erased(BuiltIn::of(&cfg))) };
    let entrants = [
        ("mine".to_string(), Entrant::Own(&make as ControllerFactory<'_>)),
        ("DOBC".to_string(), Entrant::BuiltIn(ControllerKind::Dobc)),
    ];
    let policy = WorkPolicy { allow_large: false, front: Front::Cli };
    let c = compare(&cfg, &entrants, policy, &Cancel::new()).unwrap();
    assert_eq!(c.rows.len(), 2);
    let (mine, dobc) = (&c.rows[0], &c.rows[1]);
    assert_eq!(mine.values, dobc.values);
    assert_eq!(mine.basis, "nodal");
    for (q, (label, _)) in mine.values.iter().zip(COLUMNS) {
        if let Some(q) = q {
            assert_eq!(q.label, label);
            assert!(q.value.is_finite() && q.error().is_some_and(|e| e >= 0.0), "{label}");
        }
    }
    assert_eq!(c.not_applicable.len(), NOT_APPLICABLE.len());
}
