"""Shared fixtures: the repository root and the built CLI the tests compare against."""

import json
import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def repo():
    return REPO


@pytest.fixture(scope="session")
def cli():
    """Runs the built `quadtri` (QUADTRI_CLI, set by CTest; else build/src/cli/quadtri)."""
    path = os.environ.get("QUADTRI_CLI") or str(REPO / "build" / "src" / "cli" / "quadtri")
    if not os.access(path, os.X_OK):
        pytest.skip(f"no quadtri CLI at {path} (set QUADTRI_CLI)")

    def run(*args, check=True):
        result = subprocess.run([path, *map(str, args)], capture_output=True, text=True)
        if check and result.returncode != 0:
            raise AssertionError(f"quadtri {' '.join(map(str, args))}: {result.stderr}")
        return result

    run.json = lambda *args: json.loads(run(*args).stdout)
    return run


def cli_error(result):
    """The message after "quadtri: error: " on the CLI's stderr."""
    assert result.returncode == 1, result.stderr
    prefix = "quadtri: error: "
    line = result.stderr.strip().splitlines()[-1]
    assert line.startswith(prefix), result.stderr
    return line[len(prefix):]
