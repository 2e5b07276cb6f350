"""EN 17037 sunlight exposure end to end (docs/daylight.md, "Sunlight exposure (EN 17037)"):
the scene key, ``lightsolver sunlight``, the run's results and Python agree, the results
schema holds it, and bad input names its field and writes nothing."""
import copy
import json
import subprocess
from pathlib import Path

import jsonschema
import pytest

import lightsolver
from conftest import SOURCE_DIR

SCHEMA = json.loads((SOURCE_DIR / "docs" / "schemas" / "results.schema.json").read_text())
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA)

#: The room example's opening is its south wall between x = 2 and 4 m (y = 0); a point in it.
SUNLIGHT = {"site": {"latitude_deg": 48.8566, "longitude_deg": 2.3522, "utc_offset_h": 1,
                     "elevation_m": 35},
            "date": "2026-03-20", "min_elevation_deg": 11, "step_minutes": 1,
            "points": [{"name": "south window", "position": [3.0, 0.0, 1.4],
                        "normal": [0, -1, 0]},
                       {"name": "north wall", "position": [3.0, 3.9, 1.4],
                        "normal": [0, -1, 0]}]}


def write_scene(tmp_path: Path, sunlight: dict, light: bool = True) -> Path:
    """The room example with a ``sunlight_exposure`` (without luminaires and targets if not
    ``light``)."""
    scene = json.loads((SOURCE_DIR / "Examples" / "room" / "room.json").read_text())
    scene["sunlight_exposure"] = sunlight
    if not light:
        scene["luminaires"], scene["targets"] = [], []
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    return path


def run_cli(cli: str, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([cli, *args], capture_output=True, text=True, timeout=120)


def test_run_cli_and_python_agree(cli, tmp_path):
    scene = write_scene(tmp_path, SUNLIGHT)
    out = tmp_path / "r.json"
    r = run_cli(cli, "run", str(scene), "--quiet", "--photons", "20000", "--out", str(out))
    assert r.returncode == 0, r.stderr
    results = json.loads(out.read_text())
    assert [f"{e.absolute_path}: {e.message}" for e in VALIDATOR.iter_errors(results)] == []
    alone = run_cli(cli, "sunlight", str(scene), "--json")
    assert alone.returncode == 0, alone.stderr
    from_py = lightsolver.sunlight_exposure(lightsolver.load_scene(str(scene)))
    assert results["sunlight_exposure"] == json.loads(alone.stdout) == from_py
    assert lightsolver.solve(lightsolver.load_scene(str(scene)),
                             photons=20000)["sunlight_exposure"] == from_py
    south, north = from_py["points"]
    # Open to the south: from the sun's rising above 11° to its setting below, about 9.6 h
    # (the native tests hold it to NOAA's equations). A point at the far wall sees the sun
    # only through the 2 x 3 m opening 3.9 m away: a lower, nearly southern sun, if at all.
    assert 9.3 < south["hours"] < 9.9 and south["level"] == "high"
    assert len(south["periods"]) == 1
    start, end = south["periods"][0]
    assert start < "09:00" and end > "16:30"
    assert north["hours"] < south["hours"]


def test_sunlight_alone_reads_a_scene_without_light_and_writes_its_file(cli, tmp_path):
    scene = write_scene(tmp_path, SUNLIGHT, light=False)
    out = tmp_path / "sun.json"
    r = run_cli(cli, "sunlight", str(scene), "--out", str(out))
    assert r.returncode == 0, r.stderr
    assert "sunlight exposure (EN 17037) on 2026-03-20" in r.stdout
    assert "south window" in r.stdout and "high" in r.stdout
    written = json.loads(out.read_text())
    assert written == lightsolver.sunlight_exposure(str(scene))
    assert [e.message for e in VALIDATOR.iter_errors({**minimal_results(), "sunlight_exposure":
                                                      written})] == []


def minimal_results() -> dict:
    """The smallest results document the schema takes, to check one key against it."""
    return {"format": "lightsolver.results/1", "photons": 0, "photons_requested": 0,
            "partial": False, "stop_reason": "photons", "seconds": 0.0, "backend": "embree",
            "confidence": 0.95, "seed": 1, "ray_segments": 0, "capped_paths": 0,
            "cut_paths": 0, "total_flux_lm": 0.0, "warnings": [],
            "effects": {"simulated": [], "skipped": []}, "targets": []}


@pytest.mark.parametrize("key,value,field", [
    ("step_minutes", 0, "sunlight_exposure.step_minutes"),
    ("step_minutes", 7, "sunlight_exposure.step_minutes"),
    ("date", "2026-02-30", "sunlight_exposure.date"),
    ("min_elevation_deg", 95, "sunlight_exposure.min_elevation_deg"),
])
def test_bad_input_names_the_field_and_writes_nothing(cli, tmp_path, key, value, field):
    scene = write_scene(tmp_path, {**SUNLIGHT, key: value})
    out = tmp_path / "sun.json"
    r = run_cli(cli, "sunlight", str(scene), "--out", str(out))
    assert r.returncode == 1
    assert f"scene.json: {field}:" in r.stderr
    assert not out.exists()
    with pytest.raises(lightsolver.InputError, match=field):
        lightsolver.sunlight_exposure(str(scene))


def test_bad_site_and_point(cli, tmp_path):
    bad = copy.deepcopy(SUNLIGHT)
    bad["site"]["latitude_deg"] = 91
    r = run_cli(cli, "sunlight", str(write_scene(tmp_path, bad)))
    assert r.returncode == 1 and "sunlight_exposure.site.latitude_deg" in r.stderr
    bad = copy.deepcopy(SUNLIGHT)
    bad["points"][0]["normal"] = [0, 0, 0]
    r = run_cli(cli, "sunlight", str(write_scene(tmp_path, bad)))
    assert r.returncode == 1 and "sunlight_exposure.points[0].normal" in r.stderr


def test_date_outside_the_standards_span_warns(cli, tmp_path):
    scene = write_scene(tmp_path, {**SUNLIGHT, "date": "2026-06-21"})
    r = run_cli(cli, "sunlight", str(scene))
    assert r.returncode == 0, r.stderr
    assert "warning: " in r.stderr and "sunlight_exposure.date" in r.stderr
    assert "outside EN 17037's 1 February to 21 March" in r.stderr


def test_schema_rejects_a_bad_level_and_clock(tmp_path):
    good = {**minimal_results(), "sunlight_exposure": {
        "date": "2026-03-20", "step_minutes": 1, "min_elevation_deg": 11,
        "points": [{"name": "w", "hours": 3.5, "level": "medium",
                    "periods": [["09:00", "12:30"]]}]}}
    assert list(VALIDATOR.iter_errors(good)) == []
    for path, value in [(("level",), "great"), (("periods", 0, 1), "25:00"),
                        (("hours",), -1), (("periods", 0), ["09:00"])]:
        bad = copy.deepcopy(good)
        node = bad["sunlight_exposure"]["points"][0]
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = value
        assert list(VALIDATOR.iter_errors(bad)), path
