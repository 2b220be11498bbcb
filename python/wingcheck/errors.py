"""The exceptions of wingcheck.

Every error of the library is a :class:`WingcheckError`; bad input is also a :class:`ValueError`,
and unreadable inputs and unwritable outputs are also :class:`OSError`. A computation stopped by
Ctrl-C raises the interpreter's own :class:`KeyboardInterrupt` (from the SIGINT handler); one
stopped by a progress callback that returned ``False`` raises :class:`Cancelled`, a
``KeyboardInterrupt`` too. Either way nothing was written. A bug inside the Rust library (a
panic) is raised as :class:`InternalError`, never as pyo3's ``PanicException``.
"""

from __future__ import annotations

from typing import Optional

__all__ = [
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
]


class WingcheckError(Exception):
    """Base class of every wingcheck error."""


class ConfigError(WingcheckError, ValueError):
    """The configuration, an override or an argument is invalid; the message names the field
    (``wing.ei``, ``control.a``, ``sample_times``…) and the allowed range."""


class WorkLimitError(WingcheckError):
    """The estimated work is above the limits (10 min of computing, 4 GiB of memory, 1 GiB of
    output; a search: 1e6 points or 2 core-hours). The message names the estimate and
    ``allow_large=True``, which runs it anyway."""

    #: Estimated computing time (s), when known.
    estimated_seconds: Optional[float] = None
    #: Estimated peak memory (bytes), when known.
    estimated_memory_bytes: Optional[float] = None
    #: Estimated output size (bytes), when known.
    estimated_output_bytes: Optional[float] = None
    #: Estimated integrator steps, when known.
    estimated_steps: Optional[float] = None


class NumericalError(WingcheckError):
    """A numerical step failed (a factorisation, an eigen-solve, a refinement that cannot run)."""


class DivergedError(NumericalError):
    """The closed loop diverged: a state became non-finite or the energy exceeded
    1e12 × (1 + E(0)). :attr:`t` is the time of detection (s)."""

    #: Time of detection (s).
    t: float = float("nan")


class SearchError(WingcheckError):
    """A search is malformed (an axis, a metric, a window) or its directory holds another search."""


class InputError(WingcheckError, OSError):
    """An input file or directory (a configuration, a certificate set) cannot be read."""


class OutputError(WingcheckError, OSError):
    """An output cannot be written (missing or read-only directory, a directory that is not a
    wingcheck output, a bad file extension); nothing was written."""


class VerificationError(WingcheckError):
    """A certificate set was rejected by the exact verifier."""


class InternalError(WingcheckError):
    """A bug inside wingcheck (a Rust panic, caught); please report it."""


class Cancelled(KeyboardInterrupt):
    """The computation was stopped by its progress callback (which returned ``False``);
    nothing was written."""
