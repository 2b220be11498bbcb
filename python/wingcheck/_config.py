"""Configurations: a ``Config`` object, a dict (complete or partial, merged over the paper's
default), JSON text, or a path to a JSON file — validated by the same Rust code as the
command line's ``--config``/``--set`` (same messages)."""

from __future__ import annotations

import json
import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Union

from . import _wingcheck

__all__ = ["Config", "ConfigLike", "Overrides"]

ConfigLike = Union[None, "Config", Mapping[str, Any], str, "os.PathLike[str]"]
Overrides = Union[None, Mapping[str, Any], Sequence[str]]


def _override_list(set: Overrides) -> List[str]:
    """``{"control.a": 0.05}`` or ``["control.a=0.05"]`` → ``["control.a=0.05"]``."""
    if set is None:
        return []
    if isinstance(set, Mapping):
        out = []
        for k, v in set.items():
            text = v if isinstance(v, str) else json.dumps(v)
            out.append(f"{k}={text}")
        return out
    if isinstance(set, str):
        return [set]
    return [str(s) for s in set]


def source(config: ConfigLike, set: Overrides = None) -> Dict[str, Any]:
    """The keyword arguments naming a configuration for the extension."""
    args: Dict[str, Any] = {"set": _override_list(set)}
    if config is None:
        pass
    elif isinstance(config, Config):
        args["config_text"] = config.json
    elif isinstance(config, Mapping):
        args["config_text"] = json.dumps(config)
    elif isinstance(config, str) and config.lstrip().startswith("{"):
        args["config_text"] = config
    elif isinstance(config, (str, os.PathLike)):
        args["config_path"] = os.fspath(config)
    else:
        from .errors import ConfigError

        raise ConfigError(
            f"config: expected a Config, a dict, JSON text or a path, not {type(config).__name__}"
        )
    return args


class Config:
    """A validated configuration (the paper's default merged with ``config`` and ``set``).

    ``Config()`` is the paper's configuration (configs/paper.json). ``set`` overrides keys as
    ``--set`` does: ``Config(set={"control.a": 0.05})``.
    """

    json: str
    """The effective configuration as pretty JSON (every key)."""
    sha256: str
    """SHA-256 of its compact JSON: the hash every output records."""

    def __init__(self, config: ConfigLike = None, set: Overrides = None) -> None:
        text, sha = _wingcheck.load_config(**source(config, set))
        self.json = text
        self.sha256 = sha

    def to_dict(self) -> Dict[str, Any]:
        """The configuration as nested dicts (sections ``wing``, ``control``, …)."""
        result: Dict[str, Any] = json.loads(self.json)
        return result

    def __getitem__(self, section: str) -> Any:
        return self.to_dict()[section]

    def with_overrides(self, set: Overrides) -> "Config":
        """A copy with more overrides applied."""
        return Config(self, set)

    def __repr__(self) -> str:
        return f"Config(sha256={self.sha256[:12]}…)"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Config) and other.sha256 == self.sha256

    def __hash__(self) -> int:
        return hash(self.sha256)


def optional_config(config: Optional[str]) -> Optional[Config]:
    """A Config from the compact JSON the extension returns."""
    return None if config is None else Config(config)
