"""Progress display for long calls: ``progress=True`` uses ``tqdm.auto`` when installed, a plain
line on stderr otherwise; ``progress=callable`` is called as ``callable(fraction, stage)`` from
the calling thread (about every 20 ms while the fraction moves) and may return ``False`` to stop
the computation (raising :class:`wingcheck.errors.Cancelled`)."""

from __future__ import annotations

import sys
import time
from typing import Any, Callable, Optional, Union

ProgressArg = Union[None, bool, Callable[[float, str], Optional[bool]]]


class _Line:
    """A plain progress line on stderr, redrawn at most every 0.5 s."""

    def __init__(self, what: str) -> None:
        self.what = what
        self.last = 0.0

    def __call__(self, fraction: float, stage: str) -> None:
        now = time.monotonic()
        if now - self.last >= 0.5:
            self.last = now
            sys.stderr.write(f"\r{self.what}: {stage} {100.0 * fraction:5.1f} %")
            sys.stderr.flush()

    def close(self) -> None:
        sys.stderr.write("\n")
        sys.stderr.flush()


class _Tqdm:
    """A tqdm.auto bar over 1000 units."""

    def __init__(self, what: str, tqdm: Any) -> None:
        self.bar = tqdm(total=1000, desc=what, leave=False)

    def __call__(self, fraction: float, stage: str) -> None:
        self.bar.set_postfix_str(stage, refresh=False)
        self.bar.n = int(round(1000 * fraction))
        self.bar.refresh()

    def close(self) -> None:
        self.bar.close()


def make(progress: ProgressArg, what: str) -> Any:
    """The callable handed to the extension, or None."""
    if progress is None or progress is False:
        return None
    if progress is True:
        import importlib

        try:
            tqdm = importlib.import_module("tqdm.auto").tqdm
        except ImportError:
            return _Line(what)
        return _Tqdm(what, tqdm)
    if not callable(progress):
        from .errors import ConfigError

        raise ConfigError("progress: use True, False, None or a callable(fraction, stage)")
    return progress


def close(p: Any) -> None:
    """Close a display made by :func:`make` (a user's callable is left alone)."""
    if isinstance(p, (_Line, _Tqdm)):
        p.close()
