"""Shared fixtures: where the built module, the CLI and the sources are (set by ctest)."""
import os
import sys
from pathlib import Path

import pytest

#: Provenance fields that differ between two runs of the same scene with the same options on one
#: machine: when it ran, where, and how it was started (docs/scene-format.md, "Provenance").
PROVENANCE_RUN_FACTS = ("started_utc", "finished_utc", "host", "command")

SOURCE_DIR = Path(os.environ.get("LIGHTSOLVER_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BUILD_DIR = SOURCE_DIR / "build"
if "LIGHTSOLVER_CLI" not in os.environ:  # running pytest by hand after a default build
    sys.path.insert(0, str(BUILD_DIR / "NativeSolver" / "python"))
    os.environ["LIGHTSOLVER_CLI"] = str(BUILD_DIR / "NativeSolver" / "cli" / "lightsolver")


def without_run_facts(results: dict, also=()) -> dict:
    """A copy of a results document without its provenance's run facts (and `also`, further
    provenance keys), for comparing two runs that should agree in everything else."""
    import lightsolver_results

    return lightsolver_results.without_run_facts(
        results, top_level=(), fields=PROVENANCE_RUN_FACTS + tuple(also))


@pytest.fixture(scope="session")
def cli() -> str:
    """Path of the lightsolver executable."""
    return os.environ["LIGHTSOLVER_CLI"]


@pytest.fixture(scope="session")
def room_scene() -> Path:
    """The README's main example scene."""
    return SOURCE_DIR / "Examples" / "room" / "room.json"
