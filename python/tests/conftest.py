"""Shared fixtures: the wingcheck command line the binding is compared with (WINGCHECK_CLI, or
`wingcheck` on PATH; missing is a failure, not a skip)."""

from __future__ import annotations

import os
import shutil
import subprocess
from typing import List

import pytest


@pytest.fixture(scope="session")
def cli() -> str:
    path = os.environ.get("WINGCHECK_CLI") or shutil.which("wingcheck")
    assert path, "set WINGCHECK_CLI to the wingcheck binary (the CLI the binding is compared with)"
    return path


def run_cli(cli: str, args: List[str], cwd: str) -> subprocess.CompletedProcess:
    return subprocess.run([cli, *args], cwd=cwd, capture_output=True, text=True, check=True)
