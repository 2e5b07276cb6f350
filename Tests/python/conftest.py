"""Shared fixtures: where the built module, the CLI and the sources are (set by ctest)."""
import os
import sys
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("LIGHTSOLVER_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BUILD_DIR = SOURCE_DIR / "build"
if "LIGHTSOLVER_CLI" not in os.environ:  # running pytest by hand after a default build
    sys.path.insert(0, str(BUILD_DIR / "NativeSolver" / "python"))
    os.environ["LIGHTSOLVER_CLI"] = str(BUILD_DIR / "NativeSolver" / "cli" / "lightsolver")


@pytest.fixture(scope="session")
def cli() -> str:
    """Path of the lightsolver executable."""
    return os.environ["LIGHTSOLVER_CLI"]


@pytest.fixture(scope="session")
def room_scene() -> Path:
    """The README's main example scene."""
    return SOURCE_DIR / "Examples" / "room" / "room.json"
