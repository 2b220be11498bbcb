"""wingcheck from Python: simulate the coupled bending–torsion wing of "Vibration Suppression of
a Coupled Aircraft Wing with Finite-Time Convergence" under boundary control, check the paper's
claims, map the gain region, write the report and the exact certificates.

Every function takes a configuration as a :class:`Config`, a dict (complete or partial, merged
over the paper's default), JSON text or a path, plus ``set=`` overrides (``{"control.a": 0.05}``),
validated by the same Rust code as the command line (same messages). Long calls release the GIL,
honour Ctrl-C (``KeyboardInterrupt`` within 0.1 s, nothing written) and take ``progress=True`` (tqdm when installed)
or a callable ``progress(fraction, stage)`` that may return ``False`` to stop.
"""

from __future__ import annotations

import atexit
import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from . import _progress, _wingcheck, errors
from ._config import Config, ConfigLike, Overrides, source
from ._control import Comparison, Continuous, Tip, Wing, check_callable, continuous_of
from ._progress import ProgressArg
from ._results import (
    Basis,
    Certificate,
    ClaimRow,
    Ledger,
    Modes,
    Peak,
    Quantity,
    ReportResult,
    Run,
    SearchResult,
    Verdict,
    VerifiedSet,
)
# a report or certify stopped by Ctrl-C returns at once; its worker removes its staging
# directory at its next checkpoint, and the interpreter waits for that before it exits
atexit.register(_wingcheck.join_stopped)

from .errors import (
    Cancelled,
    ConfigError,
    ControllerError,
    DivergedError,
    InputError,
    InternalError,
    NumericalError,
    OutputError,
    SearchError,
    VerificationError,
    WingcheckError,
    WorkLimitError,
)

__all__ = [
    "simulate",
    "check",
    "search",
    "report",
    "modes",
    "certify",
    "verify",
    "build_info",
    "Config",
    "Run",
    "Peak",
    "Ledger",
    "ClaimRow",
    "Quantity",
    "Verdict",
    "Basis",
    "SearchResult",
    "Modes",
    "ReportResult",
    "VerifiedSet",
    "Certificate",
    "errors",
    "WingcheckError",
    "ConfigError",
    "WorkLimitError",
    "NumericalError",
    "DivergedError",
    "SearchError",
    "InputError",
    "OutputError",
    "VerificationError",
    "InternalError",
    "Cancelled",
    "ControllerError",
    "Tip",
    "Continuous",
    "ControllerLike",
    "compare",
    "Comparison",
    "Wing",
]

#: A controller: a built-in one by name, or your own (see :mod:`wingcheck._control`).
ControllerLike = Union[str, Callable[[float, Tip], Any]]

__version__: str = _wingcheck.build_info()["version"]

PathLike = Union[str, "os.PathLike[str]"]


def _path(p: Optional[PathLike]) -> Optional[str]:
    return None if p is None else os.fspath(p)


def _with_progress(progress: ProgressArg, what: str, call: Any, **kwargs: Any) -> Any:
    p = _progress.make(progress, what)
    try:
        return call(progress=p, **kwargs)
    finally:
        _progress.close(p)


def simulate(
    config: ConfigLike = None,
    *,
    set: Overrides = None,
    controller: Optional[ControllerLike] = None,
    observer: Optional[str] = None,
    method: Optional[str] = None,
    sample_every: Optional[float] = None,
    error_estimate: bool = False,
    fields: bool = False,
    sample_times: Optional[Sequence[float]] = None,
    out: Optional[PathLike] = None,
    allow_large: bool = False,
    progress: ProgressArg = None,
) -> Run:
    """Run the closed loop (paper eq. (9)–(10) as corrected, control law (15), observer
    (16)–(21) or DOBC (57), disturbances (56)) over [0, horizon.t_end] s.

    ``controller``: ``"none"``, ``"pd"``, ``"ftdo"``, ``"dobc"`` (``control.kind``), or a
    controller of your own: a callable ``f(t, tip) -> (tau1, tau2)`` called once per
    ``observer.sample_period`` with a :class:`Tip`, or an object with ``__call__``,
    ``continuous`` (k1, k2, a, b) and ``reset()`` (see :mod:`wingcheck._control`; it runs in
    the basis the configuration resolves to, as the built-ins do, holding the GIL only for its
    calls). An exception inside it propagates
    as raised; a NaN, inf or non-pair output raises :class:`ControllerError` naming the time;
    ``observer``: ``"implicit"`` or ``"explicit"``; ``method``: ``"fe"`` or ``"fd"`` (``fd``
    implies ``discretisation.grading=0`` unless ``set`` gives the grading); ``sample_every``:
    output interval (s); ``error_estimate``: also estimate the discretisation error of every tip
    value and peak (one refinement in h and one in dt, Richardson order 2; ≈ 5× the work);
    ``fields``: record q(z,t) (m) and θ(z,t) (rad) on the output grid; ``sample_times``: times
    (s) of the summary's tip values; ``out``: also write ``.csv`` or ``.json`` as
    ``wingcheck simulate --out`` does (atomically). Returns a :class:`Run` whose columns equal
    run.csv's bit for bit.
    """
    own: Dict[str, Any] = {}
    if controller is not None and not isinstance(controller, str):
        check_callable(controller)
        own = {"controller_object": controller, "continuous": continuous_of(controller)}
        controller = None
    raw = _with_progress(
        progress,
        "simulate",
        _wingcheck.simulate,
        controller=controller,
        **own,
        observer=observer,
        method=method,
        sample_every=sample_every,
        error_estimate=error_estimate,
        fields=fields,
        sample_times=None if sample_times is None else [float(t) for t in sample_times],
        out=_path(out),
        allow_large=allow_large,
        **source(config, set),
    )
    return Run(raw)


def compare(
    config: ConfigLike = None,
    controllers: Optional[Mapping[str, ControllerLike]] = None,
    *,
    set: Overrides = None,
    allow_large: bool = False,
    progress: ProgressArg = None,
) -> Comparison:
    """Controllers side by side on the same wing, disturbances and metrics:
    ``compare(cfg, {"mine": f, "FTDO": "ftdo", "DOBC": "dobc"})``. Each row is a run plus the
    two ``error_estimate`` refinements (≈ 5 runs of work); each metric (RMS and peak of q and θ,
    settling times, RMS and peak |τ1|, |τ2| at full rate, E(t_end)/E(0)) carries its error.
    Every row steps in the basis the configuration resolves to; a built-in row's runs are
    ``check``'s."""
    if not controllers:
        controllers = {"FTDO": "ftdo", "DOBC": "dobc"}
    entrants: List[Tuple[str, Optional[str], Any, Optional[Tuple[float, float, float, float]]]] = []
    for name, c in controllers.items():
        if isinstance(c, str):
            entrants.append((str(name), c, None, None))
        else:
            check_callable(c)
            entrants.append((str(name), None, c, continuous_of(c)))
    text = _with_progress(
        progress, "compare", _wingcheck.compare, entrants=entrants, allow_large=allow_large, **source(config, set)
    )
    return Comparison(text)


def check(
    config: ConfigLike = None, *, set: Overrides = None, allow_large: bool = False, progress: ProgressArg = None
) -> Ledger:
    """The claim ledger: one verdict per claim of the paper (W-bounds (22)–(28), the mu
    conditions (29)–(32), UUB (33)–(37), finite time (38)–(39), Lemmas 1–3 (11)–(14), FTDO vs
    DOBC (57)), with evidence, assumptions and certificates; :meth:`Ledger.to_json` equals
    ``wingcheck check --json``."""
    text = _with_progress(progress, "check", _wingcheck.check, allow_large=allow_large, **source(config, set))
    return Ledger(text)


def search(
    config: ConfigLike = None,
    *,
    over: Sequence[str],
    out: PathLike,
    set: Overrides = None,
    threads: Optional[int] = None,
    refine: Optional[float] = None,
    best: Optional[str] = None,
    window: Optional[Tuple[float, float]] = None,
    chunk_size: int = 32,
    allow_large: bool = False,
    progress: ProgressArg = None,
    controller: Optional[ControllerLike] = None,
) -> SearchResult:
    """Map the gain region where the theorems' conditions hold (W ≻ 0, (32)) and how the closed
    loop performs, as ``wingcheck search`` does: ``over`` axes ``"control.a=1e-3..10:log:16"``,
    ``"key=lo..hi:lin:N"`` or ``"key=v1,v2"``; results in ``out`` (resumed if it holds this
    search; a cancelled search into a new directory leaves nothing). ``window``: metric window
    (t0, t1) in s (default: the second half of the horizon); ``best``: the ranking metric
    (``"rms_q_tip"``; ``"-lambda"`` maximises). ``controller``: your own controller (as for
    :func:`simulate`; the built-in ones are chosen with ``set={"control.kind": ...}``) run at
    every point in place of ``control.kind``, reset before each point's run, the points one at a
    time (the one object carries its state from call to call; ``threads`` > 1 is refused). Its
    gains are its own, so axes over ``control.*`` are refused (they would change the paper's law
    (15), not your object: sweep your controller's parameters in Python). Its name
    (``__name__`` or the class name) is recorded in manifest.json; an exception inside it makes
    that point an error and the search goes on. The theory columns stay the paper's (about its
    FTDO)."""
    own: Dict[str, Any] = {}
    if controller is not None:
        if isinstance(controller, str):
            raise ConfigError(
                "controller: search takes your own controller; choose a built-in one with "
                "set={'control.kind': %r}" % controller
            )
        check_callable(controller)
        swept = [axis for axis in over if axis.strip().startswith("control.")]
        if swept:
            raise ConfigError(
                "over: %s: axes over control.* do not reach your controller (its gains are its own: "
                "continuous and __call__); sweep its parameters in Python, or leave out controller= "
                "to sweep the paper's law (15)" % ", ".join(swept)
            )
        name = getattr(controller, "__name__", None) or type(controller).__name__
        own = {"controller_object": controller, "continuous": continuous_of(controller), "controller_name": name}
    text = _with_progress(
        progress,
        "search",
        _wingcheck.search,
        over=list(over),
        out=os.fspath(out),
        threads=threads,
        refine=refine,
        best=best,
        window=window,
        chunk_size=chunk_size,
        allow_large=allow_large,
        **own,
        **source(config, set),
    )
    return SearchResult(text)


def report(
    config: ConfigLike = None,
    *,
    out: PathLike,
    set: Overrides = None,
    allow_large: bool = False,
    progress: ProgressArg = None,
) -> ReportResult:
    """Write the self-contained HTML report (the ledger, Figures 3–20, the region map, accuracy,
    the certificates in ``proofs/``, provenance) into ``out``, replacing an earlier report there
    atomically."""
    out_dir, files, timings, ledger = _with_progress(
        progress, "report", _wingcheck.report, out=os.fspath(out), allow_large=allow_large, **source(config, set)
    )
    return ReportResult(os.fspath(out_dir), list(files), list(timings), Ledger(ledger))


def modes(
    config: ConfigLike = None,
    *,
    set: Overrides = None,
    count: int = 5,
    method: Optional[str] = None,
    tol: Optional[float] = None,
) -> Modes:
    """The first ``count`` (1–50) natural frequencies (rad/s) of the undamped, uncontrolled
    coupled wing, each extrapolated to the relative tolerance ``tol`` (default 1e-9, ≥ 1e-13)
    with its error bound, beside the analytic uncoupled ones (``modes --json``)."""
    import json

    text = _wingcheck.modes(count=count, method=method, tol=tol, **source(config, set))
    return Modes(json.loads(text))


def certify(config: ConfigLike = None, *, out: PathLike, set: Overrides = None) -> Tuple[list, list]:
    """Write the exact certificates of the definiteness/infeasibility facts (W-bounds' ω₁
    enclosure, the mu conditions) into ``out`` (replaced atomically); returns (files, notes)."""
    files, notes = _wingcheck.certify(out=os.fspath(out), **source(config, set))
    return [os.fspath(f) for f in files], list(notes)


def verify(path: PathLike, config: ConfigLike = None, *, set: Overrides = None) -> VerifiedSet:
    """Re-check the certificate set in ``path`` (a directory, e.g. a report's ``proofs/``) in
    exact rational arithmetic, independent of the solvers; with ``config`` (or ``set``) the set
    must have been made for exactly that configuration. Raises
    :class:`~wingcheck.errors.VerificationError` when rejected."""
    pinned = config is not None or bool(set)
    raw: Dict[str, Any] = _wingcheck.verify(os.fspath(path), pinned=pinned, **source(config, set))
    return VerifiedSet(
        config=Config(raw["config"]),
        config_sha256=raw["config_sha256"],
        certificates=[Certificate(*c) for c in raw["certificates"]],
        conclusions=[tuple(c) for c in raw["conclusions"]],
        pinned=pinned,
    )


def build_info() -> Dict[str, str]:
    """The build of the extension, as every output's provenance records it: ``version``,
    ``commit``, ``tree`` (``clean``, ``dirty`` or ``unknown``), ``describe``, ``rustc``."""
    info: Dict[str, str] = dict(_wingcheck.build_info())
    return info
