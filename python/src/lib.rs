//! `wingcheck._wingcheck`: the Python extension. Every function parses its arguments, calls
//! the same library function as the command line (`wingcheck_app`) on a worker thread with
//! the GIL released ([`blocking::run`]: Ctrl-C and the progress callback are served from the
//! calling thread), and returns plain values (numpy arrays, JSON text, dicts) that the pure
//! Python layer (`wingcheck/`) wraps in typed objects. Errors become the exception classes of
//! `wingcheck.errors` ([`errors::to_py`]); a panic becomes `InternalError`, never
//! `PanicException`. The extension never tunes the host's allocator (the CLI's
//! `wingcheck_io::tune_allocator` is not called here).

mod blocking;
mod errors;
mod functions;
mod proofs;

use pyo3::prelude::*;

#[pymodule]
fn _wingcheck(m: &Bound<'_, PyModule>) -> PyResult<()> {
    wingcheck_app::register_build();
    m.add_function(wrap_pyfunction!(functions::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(functions::check, m)?)?;
    m.add_function(wrap_pyfunction!(functions::search, m)?)?;
    m.add_function(wrap_pyfunction!(functions::report, m)?)?;
    m.add_function(wrap_pyfunction!(functions::modes, m)?)?;
    m.add_function(wrap_pyfunction!(functions::load_config, m)?)?;
    m.add_function(wrap_pyfunction!(functions::build_info, m)?)?;
    m.add_function(wrap_pyfunction!(proofs::certify, m)?)?;
    m.add_function(wrap_pyfunction!(proofs::verify, m)?)?;
    m.add_function(wrap_pyfunction!(blocking::join_stopped, m)?)?;
    Ok(())
}
