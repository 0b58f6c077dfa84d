"""Shared fixtures: where the source and the build are, and the command-line tools to compare
the module with (set by tests/python/CMakeLists.txt)."""
import os
import pathlib
import subprocess

import pytest

SOURCE = pathlib.Path(os.environ.get("ECM_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BUILD = pathlib.Path(os.environ.get("ECM_BUILD_DIR", SOURCE / "build"))


@pytest.fixture
def source():
    return SOURCE


def tool(name):
    folder = {"ecm-point": "driver", "ecm-calibrate": "calibration", "ecm-mpm": "mpm"}[name]
    return str(BUILD / folder / name)


def run_tool(name, *args):
    """Runs a tool of this build; returns (exit status, stderr)."""
    p = subprocess.run([tool(name), *map(str, args)], capture_output=True, text=True, check=False)
    return p.returncode, p.stderr
