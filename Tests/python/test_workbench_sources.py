"""Every Python file of the workbench compiles (GUI modules too, which headless tests never
import: a syntax error there would only show as a FreeCAD dialog when the workbench loads)."""
import py_compile
from pathlib import Path

import pytest

WORKBENCH = Path(__file__).resolve().parents[2] / "Workbench"
SOURCES = sorted(WORKBENCH.rglob("*.py"))


def test_the_workbench_has_sources():
    assert len(SOURCES) > 40


@pytest.mark.parametrize("path", SOURCES, ids=lambda p: str(p.relative_to(WORKBENCH)))
def test_compiles(path, tmp_path):
    py_compile.compile(str(path), cfile=str(tmp_path / "out.pyc"), doraise=True)
