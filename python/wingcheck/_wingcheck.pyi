"""The compiled extension (Rust, pyo3). Internal: use the functions of :mod:`wingcheck`."""

from os import PathLike
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union, final

__all__ = [
    "WingLoop",
    "build_info",
    "certify",
    "check",
    "compare",
    "join_stopped",
    "load_config",
    "modes",
    "report",
    "search",
    "simulate",
    "verify",
]

_Progress = Optional[Callable[[float, str], Optional[bool]]]
_Path = Union[str, PathLike[str]]

def simulate(
    config_text: Optional[str] = None,
    config_path: Optional[_Path] = None,
    set: Sequence[str] = ...,
    controller: Optional[str] = None,
    observer: Optional[str] = None,
    method: Optional[str] = None,
    sample_every: Optional[float] = None,
    error_estimate: bool = False,
    fields: bool = False,
    sample_times: Optional[Sequence[float]] = None,
    out: Optional[_Path] = None,
    allow_large: bool = False,
    progress: _Progress = None,
    controller_object: Optional[Callable[..., Any]] = None,
    continuous: Optional[Sequence[float]] = None,
) -> Dict[str, Any]: ...
def compare(
    entrants: Sequence[Tuple[str, Optional[str], Optional[Callable[..., Any]], Optional[Sequence[float]]]],
    config_text: Optional[str] = None,
    config_path: Optional[_Path] = None,
    set: Sequence[str] = ...,
    allow_large: bool = False,
    progress: _Progress = None,
) -> str: ...

_Obs = Tuple[float, float, float, float, float, float, float, float, float, float, float]

@final
class WingLoop:
    def __new__(
        cls,
        continuous: Sequence[float],
        config_text: Optional[str] = None,
        config_path: Optional[_Path] = None,
        set: Sequence[str] = ...,
    ) -> "WingLoop": ...
    def reset(self) -> _Obs: ...
    def step(self, tau1: float, tau2: float) -> Tuple[_Obs, float, float]: ...
    def timing(self) -> Tuple[float, float]: ...
def check(
    config_text: Optional[str] = None,
    config_path: Optional[_Path] = None,
    set: Sequence[str] = ...,
    allow_large: bool = False,
    progress: _Progress = None,
) -> str: ...
def search(
    over: Sequence[str],
    out: _Path,
    config_text: Optional[str] = None,
    config_path: Optional[_Path] = None,
    set: Sequence[str] = ...,
    threads: Optional[int] = None,
    refine: Optional[float] = None,
    best: Optional[str] = None,
    window: Optional[Tuple[float, float]] = None,
    chunk_size: int = 32,
    allow_large: bool = False,
    progress: _Progress = None,
    controller_object: Optional[Callable[..., Any]] = None,
    continuous: Optional[Sequence[float]] = None,
    controller_name: Optional[str] = None,
) -> str: ...
def report(
    out: _Path,
    config_text: Optional[str] = None,
    config_path: Optional[_Path] = None,
    set: Sequence[str] = ...,
    allow_large: bool = False,
    progress: _Progress = None,
) -> Tuple[str, List[str], List[Tuple[str, float]], str]: ...
def modes(
    config_text: Optional[str] = None,
    config_path: Optional[_Path] = None,
    set: Sequence[str] = ...,
    count: int = 5,
    method: Optional[str] = None,
    tol: Optional[float] = None,
) -> str: ...
def load_config(
    config_text: Optional[str] = None,
    config_path: Optional[_Path] = None,
    set: Sequence[str] = ...,
) -> Tuple[str, str]: ...
def build_info() -> Dict[str, str]: ...
def certify(
    out: _Path,
    config_text: Optional[str] = None,
    config_path: Optional[_Path] = None,
    set: Sequence[str] = ...,
) -> Tuple[List[str], List[str]]: ...
def verify(
    path: _Path,
    pinned: bool = False,
    config_text: Optional[str] = None,
    config_path: Optional[_Path] = None,
    set: Sequence[str] = ...,
) -> Dict[str, Any]: ...
def join_stopped() -> None: ...
