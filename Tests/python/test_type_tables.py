"""The solver's type tables as Python sees them (lightsolver.luminaire_types(),
lightsolver.target_types()), and the Python layers' conformance to them: every type's effect,
name and result fields are in the results schema; every type the workbench exports is one the
solver has, and every solver type is exported by the workbench or listed here as not offered
there (with the reason); the report has a branch for every target type with result fields of
its own."""
import json
import re
from typing import Dict, List, Set

import pytest

import lightsolver
from conftest import SOURCE_DIR

SCHEMA = json.loads((SOURCE_DIR / "docs" / "schemas" / "results.schema.json").read_text())
WORKBENCH = SOURCE_DIR / "Workbench" / "lighting"
REPORT_MODEL = SOURCE_DIR / "NativeSolver" / "python" / "lightsolver_report" / "areas.py"

#: Solver luminaire types the workbench offers no object for, and why.
NOT_IN_WORKBENCH: Dict[str, str] = {
    "directional": "a parallel beam: the workbench's Sky offers the sun (with its disc) instead",
}

LUMINAIRES: List[dict] = lightsolver.luminaire_types()
TARGETS: List[dict] = lightsolver.target_types()


def quoted_types(text: str) -> Set[str]:
    """The scene ``type`` values a Python source writes (``"type": "grid"``)."""
    return set(re.findall(r'"type":\s*"([a-z_]+)"', text))


def test_the_tables_list_every_type_once_with_their_fields():
    names = [t["name"] for t in LUMINAIRES]
    assert names == ["point", "spot", "area", "directional", "photometric", "sun", "sky"]
    assert [t["name"] for t in TARGETS] == ["surface", "grid", "observer", "observer_grid"]
    for t in LUMINAIRES:
        assert {"name", "type"} <= set(t["keys"])
        assert t["effect"] == t["name"] + "_emission"
        # A glare source, or a reason it is none.
        assert (t["glare_source"] is None) == bool(t["not_glare_because"]), t
    for t in TARGETS:
        assert {"name", "type"} <= set(t["keys"])
        assert t["requirements"], t["name"]
        assert t["tally"] in ("mesh_bin", "grid_rows")
    by_name = {t["name"]: t for t in TARGETS}
    assert by_name["grid"]["cells"] and not by_name["grid"]["eyes"]
    assert by_name["observer_grid"]["eyes"] and by_name["observer"]["eyes"]
    assert by_name["surface"]["tally"] == "mesh_bin"
    assert by_name["observer"]["requirements"] == ["ugr_max"]


def test_the_tables_agree_with_what_the_solver_reads(tmp_path):
    # Each type's keys are the ones the reader accepts: an extra key is refused with the list.
    scene = {"format": "lightsolver.scene/1", "materials": {"m": {"type": "diffuse",
                                                                  "reflectance": 0.5}},
             "meshes": [], "targets": [],
             "luminaires": [{"name": "l", "type": "point", "flux_lm": 1, "position": [0, 0, 0],
                             "colour": "red"}]}
    path = tmp_path / "s.json"
    path.write_text(json.dumps(scene))
    with pytest.raises(Exception) as e:
        lightsolver.load_scene(str(path))
    point = next(t for t in LUMINAIRES if t["name"] == "point")
    assert "allowed here: " + ", ".join(point["keys"]) in str(e.value)


def test_every_type_is_in_the_results_schema():
    effects = set(SCHEMA["properties"]["effects"]["properties"]["simulated"]["items"]["enum"])
    target = SCHEMA["$defs"]["target"]
    for t in LUMINAIRES:
        assert t["effect"] in effects, t["name"]
    assert [t["name"] for t in TARGETS] == target["properties"]["type"]["enum"]
    for t in TARGETS:
        missing = set(t["result_fields"]) - set(target["properties"])
        assert not missing, (t["name"], missing)


def test_the_workbench_exports_only_solver_types_and_every_one_it_offers():
    luminaire_py = (WORKBENCH / "objects" / "luminaire.py").read_text()
    offered = set(re.findall(r'LuminaireKind\("([a-z_]+)"', luminaire_py))
    # The daylight types: the Sky object's rows (objects/sky.py).
    sky_py = (WORKBENCH / "objects" / "sky.py").read_text()
    offered |= set(re.findall(r'DaylightKind\("([a-z_]+)"', sky_py))
    solver = {t["name"] for t in LUMINAIRES}
    assert offered and offered <= solver
    assert solver - offered == set(NOT_IN_WORKBENCH), "offer it in the workbench or list why not"
    exported: Set[str] = set()
    for path in WORKBENCH.rglob("*.py"):
        exported |= quoted_types(path.read_text())
    for t in TARGETS:
        assert t["name"] in exported, f"the workbench never exports a {t['name']} target"


@pytest.mark.parametrize("target", TARGETS, ids=lambda t: t["name"])
def test_the_one_results_reader_reads_every_target_type(target):
    """The workbench and the report read results through lightsolver_results, which reads each
    target type once (READ_TYPES); a type it does not know is only noted, never laid out."""
    import lightsolver_results
    assert target["name"] in lightsolver_results.READ_TYPES


def test_the_report_lays_out_observer_grids_as_observer_grids():
    """The one type with a layout of its own in the report (max UGR over its points)."""
    assert '"observer_grid"' in REPORT_MODEL.read_text()
