"""The typed results: :class:`Run`, :class:`Ledger` (rows, verdicts, decisive quantities),
:class:`SearchResult`, :class:`Modes`, :class:`ReportResult`, :class:`VerifiedSet`."""

from __future__ import annotations

import csv
import json
import os
from dataclasses import dataclass, field
from enum import Enum
from typing import Any, Dict, List, Mapping, Optional, Tuple

import numpy as np

from ._config import Config

__all__ = [
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
]


def _pandas() -> Any:
    import importlib

    try:
        return importlib.import_module("pandas")
    except ImportError as e:  # pragma: no cover - exercised only without pandas
        raise ImportError("to_pandas() needs pandas: pip install pandas") from e


def exact_floats(pd: Any) -> Dict[str, str]:
    """``read_csv`` options that read every float back to the float64 it was written from:
    pandas < 3 needs ``float_precision="round_trip"``; pandas 3 does it by default (and
    deprecates the option)."""
    major = int(str(pd.__version__).split(".")[0])
    return {"float_precision": "round_trip"} if major < 3 else {}


@dataclass(frozen=True)
class Peak:
    """A full-rate peak max |x| over the run (every integrator step, the initial layer resolved)."""

    name: str
    value: float
    """max |x| (in :attr:`unit`)."""
    t: float
    """When it occurs (s)."""
    unit: str
    error: Optional[float] = None
    """Its estimated error (same unit), with ``error_estimate=True``; else None."""


# the peaks of `simulate --json` and their units
_PEAK_UNITS = {
    "q_tip": "m",
    "theta_tip": "rad",
    "q_tip_rate": "m/s",
    "theta_tip_rate": "rad/s",
    "tau1": "N",
    "tau2": "N m",
    "g1_error": "N",
    "g2_error": "N m",
}


class Run:
    """One closed-loop run of :func:`wingcheck.simulate`.

    ``run["q_tip_m"]`` (or ``run.columns["q_tip_m"]``) is a float64 array of run.csv's column,
    bit for bit; :attr:`units` maps each column to its unit; :attr:`summary` is the
    ``simulate --json`` document (settings, cost, tip values at the sample times, peaks,
    provenance).
    """

    def __init__(self, raw: Mapping[str, Any]) -> None:
        self.columns: Dict[str, np.ndarray] = dict(raw["columns"])
        self.units: Dict[str, str] = dict(raw["units"])
        self.summary: Dict[str, Any] = json.loads(raw["summary"])
        self.config = Config(raw["config"])
        f = raw.get("fields")
        self.fields: Optional[Dict[str, np.ndarray]] = None if f is None else dict(f)

    def __getitem__(self, column: str) -> np.ndarray:
        return self.columns[column]

    @property
    def t(self) -> np.ndarray:
        """Output times t (s)."""
        return self.columns["t_s"]

    @property
    def provenance(self) -> Dict[str, Any]:
        """Tool build and configuration hash."""
        p: Dict[str, Any] = self.summary["provenance"]
        return p

    @property
    def peaks(self) -> Dict[str, Peak]:
        """Full-rate peaks, with their ± under ``error_estimate=True``."""
        raw = self.summary["peaks"]
        est = (self.summary.get("error_estimate") or {}).get("peaks", {})
        out = {}
        for name, p in raw.items():
            if not isinstance(p, dict) or "abs_max" not in p:
                continue
            e = est.get(name)
            value = p["abs_max"]
            error = None
            if isinstance(e, dict):
                am = e.get("abs_max")
                if isinstance(am, dict):
                    value, error = am.get("value", value), am.get("error")
            out[name] = Peak(name, value, p.get("t", float("nan")), _PEAK_UNITS.get(name, ""), error)
        return out

    def to_pandas(self) -> Any:
        """The columns as a DataFrame; ``attrs["units"]`` and ``attrs["provenance"]`` hold the
        units and provenance."""
        pd = _pandas()
        df = pd.DataFrame(self.columns)
        df.attrs["units"] = dict(self.units)
        df.attrs["provenance"] = self.provenance
        return df

    def __repr__(self) -> str:
        s = self.summary["settings"]
        return f"Run({s['controller']}, {s['method']} {s['elements']}, dt={s['dt']} s, T={s['t_end']} s, {len(self.t)} samples)"


class Verdict(str, Enum):
    """A claim's verdict."""

    HOLDS = "holds"
    FAILS = "fails"
    HOLDS_AFTER_CORRECTION = "holds-after-correction"
    VACUOUS = "vacuous"
    TRIVIALLY_TRUE = "trivially-true"
    PARTLY_REPRODUCED = "partly-reproduced"
    INCONCLUSIVE = "inconclusive"


class Basis(str, Enum):
    """What a verdict rests on: a certificate re-checked exactly is proof, a float solve evidence."""

    EXACT_CERTIFICATE = "exact-certificate"
    ANALYTIC = "analytic"
    FLOAT_SOLVER = "float-solver"
    COMPUTATION = "computation"
    SIMULATION = "simulation"


@dataclass(frozen=True)
class Quantity:
    """A decisive number with its unit and its error or basis."""

    label: str
    value: float
    unit: str
    error: Optional[float] = None
    """Its error bar (same unit), if it has one."""
    basis: Optional[str] = None
    """Why it has no error bar (``exact``, ``configured``, ``lower bound``, …)."""
    covers: Tuple[str, ...] = ()
    """The error sources the bar covers."""


@dataclass(frozen=True)
class ClaimRow:
    """One claim of the paper with its verdict and evidence."""

    id: str
    equation: str
    claim: str
    verdict: Verdict
    basis: Basis
    finding: List[str]
    decisive: List[Quantity]
    details: List[str]
    correction: Optional[str]
    assumptions: List[str]
    certificates: List[str]
    evidence: Any = field(repr=False)


class Ledger:
    """The claim ledger of :func:`wingcheck.check`: :attr:`rows` in the paper's order;
    :meth:`to_json` is ``wingcheck check --json``'s text."""

    def __init__(self, text: str) -> None:
        self._text = text
        doc = json.loads(text)
        self.document: Dict[str, Any] = doc
        self.config_sha256: str = doc["config_sha256"]
        self.tool: str = doc["tool"]
        self.settings: Dict[str, Any] = doc["settings"]
        self.rows: List[ClaimRow] = [_row(r) for r in doc["rows"]]

    def to_json(self) -> str:
        """The ledger as ``wingcheck check --json`` prints it (with its final newline)."""
        return self._text + "\n"

    def __getitem__(self, claim_id: str) -> ClaimRow:
        for r in self.rows:
            if r.id == claim_id:
                return r
        raise KeyError(claim_id)

    def to_pandas(self) -> Any:
        """One row per claim: id, equation, verdict, basis, claim, finding."""
        pd = _pandas()
        return pd.DataFrame(
            {
                "id": [r.id for r in self.rows],
                "equation": [r.equation for r in self.rows],
                "verdict": [r.verdict.value for r in self.rows],
                "basis": [r.basis.value for r in self.rows],
                "claim": [r.claim for r in self.rows],
                "finding": [" ".join(r.finding) for r in self.rows],
            }
        ).set_index("id")

    def __repr__(self) -> str:
        return "Ledger(" + ", ".join(f"{r.id}: {r.verdict.value}" for r in self.rows) + ")"


def _row(r: Mapping[str, Any]) -> ClaimRow:
    decisive = [
        Quantity(
            q["label"], q["value"], q.get("unit", ""), q.get("error"), q.get("basis"), tuple(q.get("covers", ()))
        )
        for q in r["decisive"]
    ]
    return ClaimRow(
        id=r["id"],
        equation=r["equation"],
        claim=r["claim"],
        verdict=Verdict(r["verdict"]),
        basis=Basis(r["basis"]),
        finding=list(r["finding"]),
        decisive=decisive,
        details=list(r["details"]),
        correction=r.get("correction"),
        assumptions=list(r["assumptions"]),
        certificates=list(r["certificates"]),
        evidence=r["evidence"],
    )


class SearchResult:
    """A finished search: :attr:`summary` (points, failures, wall time), the output directory,
    :meth:`to_pandas` (results.csv exactly: every number reads back to the same float64) and
    :attr:`best` (best.json's points)."""

    def __init__(self, summary_text: str) -> None:
        self.summary: Dict[str, Any] = json.loads(summary_text)
        self.out_dir: str = self.summary["out_dir"]
        self.complete: bool = self.summary["complete"]
        self.files: List[str] = list(self.summary["files"])

    @property
    def results_csv(self) -> str:
        """Path of results.csv."""
        return os.path.join(self.out_dir, "results.csv")

    @property
    def best(self) -> List[Dict[str, Any]]:
        """The best points (best.json, ranked by the search's ``best`` metric)."""
        with open(os.path.join(self.out_dir, "best.json"), encoding="utf-8") as f:
            doc = json.load(f)
        points: List[Dict[str, Any]] = doc.get("points", doc.get("best", []))
        return points

    def columns(self) -> Dict[str, np.ndarray]:
        """results.csv as arrays (float64 where every entry is a number, else str), no pandas."""
        with open(self.results_csv, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
        header, body = rows[0], rows[1:]
        out: Dict[str, np.ndarray] = {}
        for i, name in enumerate(header):
            col = [row[i] for row in body]
            try:
                out[name] = np.array([float(x) for x in col], dtype=np.float64)
            except ValueError:
                out[name] = np.array(col, dtype=object)
        return out

    def to_pandas(self) -> Any:
        """results.csv as a DataFrame (round-trip float parsing: the exact float64 values)."""
        pd = _pandas()
        return pd.read_csv(self.results_csv, **exact_floats(pd))

    def __repr__(self) -> str:
        s = self.summary
        return f"SearchResult({s['points_total']} points, {s['failed']} failed, {self.out_dir})"


@dataclass(frozen=True)
class Modes:
    """Natural frequencies of the undamped, uncontrolled wing (rad/s), ``modes --json``."""

    document: Dict[str, Any]

    @property
    def coupled(self) -> np.ndarray:
        """Coupled ω_n (rad/s), Romberg-extrapolated."""
        return np.array(self.document["coupled_rad_s"])

    @property
    def errors(self) -> np.ndarray:
        """Bounds on |ω_n − ω_exact| (rad/s)."""
        return np.array(self.document["coupled_error_rad_s"])

    @property
    def uncoupled(self) -> np.ndarray:
        """Uncoupled analytic ω_n (rad/s) (ρx_c = 0)."""
        return np.array(self.document["uncoupled_analytic_rad_s"])


@dataclass(frozen=True)
class ReportResult:
    """A report written by :func:`wingcheck.report`."""

    out_dir: str
    files: List[str]
    timings: List[Tuple[str, float]]
    ledger: Ledger

    @property
    def index_html(self) -> str:
        """The page."""
        return os.path.join(self.out_dir, "index.html")


@dataclass(frozen=True)
class Certificate:
    """One verified certificate: its id, the kind of fact and the verifier's own statement."""

    id: str
    kind: str
    statement: str


@dataclass(frozen=True)
class VerifiedSet:
    """A certificate set re-checked in exact rational arithmetic by :func:`wingcheck.verify`."""

    config: Config
    config_sha256: str
    certificates: List[Certificate]
    conclusions: List[Tuple[str, str]]
    pinned: bool
    """Whether the set was required to be made for the configuration given."""
