"""The Python module: same scenes and numbers as the CLI, numpy in and out, progress,
cancellation, GIL release and clear errors."""
import json
import math
import threading
import time

import numpy as np
import pytest

import lightsolver


def unit_room(reflectance: float = 0.0) -> "lightsolver.Scene":
    """A 2 m cube (inward faces) with a central point source and a floor grid."""
    s = lightsolver.Scene()
    s.add_material("grey", reflectance=reflectance)
    v = np.array([[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0],
                  [0, 0, 2], [2, 0, 2], [2, 2, 2], [0, 2, 2]], dtype=float)
    # Fronts point into the cube.
    t = np.array([[0, 1, 2], [0, 2, 3], [4, 6, 5], [4, 7, 6], [0, 4, 5], [0, 5, 1],
                  [3, 2, 6], [3, 6, 7], [0, 3, 7], [0, 7, 4], [1, 5, 6], [1, 6, 2]])
    s.add_mesh("cube", v, t, "grey")
    s.add_light("lamp", "point", position=[1, 1, 1], flux_lm=1000.0)
    s.add_target("walls", "surface", mesh="cube")
    s.add_target("floor grid", "grid", corner=[0, 0, 0], edge1=[2, 0, 0], edge2=[0, 2, 0],
                 cells=[4, 3])
    return s


def test_version_and_format():
    assert lightsolver.__version__.count(".") == 2
    assert lightsolver.SCENE_FORMAT == "lightsolver.scene/1"


def test_numpy_scene_conserves_flux_and_shapes_cells():
    # Photon counts (every photon lands once): direct light by photons, not shadow rays.
    r = lightsolver.solve(unit_room(), photons=200_000, seed=3, next_event="off")
    walls, grid = r["targets"]
    assert walls["hits"] == r["photons"] == 200_000  # closed black room: every photon lands once
    assert math.isclose(walls["mean_lux"] * walls["area_m2"], 1000.0, rel_tol=1e-9)
    assert grid["cells_lux"].shape == (3, 4)
    assert grid["cells_hits"].dtype == np.uint64
    assert np.all(grid["cells_ci_low_lux"] <= grid["cells_lux"])
    assert np.all(grid["cells_lux"] <= grid["cells_ci_high_lux"])
    assert grid["min_lux"] == pytest.approx(grid["cells_lux"].min())


def test_json_and_numpy_scenes_give_identical_numbers(tmp_path):
    scene = {
        "format": "lightsolver.scene/1",
        "materials": {"grey": {"type": "diffuse", "reflectance": 0.6}},
        "meshes": [{"name": "floor", "material": "grey",
                    "vertices": [[0, 0, 0], [3, 0, 0], [3, 3, 0], [0, 3, 0]],
                    "triangles": [[0, 1, 2], [0, 2, 3]]}],
        "luminaires": [{"name": "lamp", "type": "point", "flux_lm": 500, "position": [1, 1, 2]}],
        "targets": [{"name": "floor", "type": "surface", "mesh": "floor"}],
    }
    path = tmp_path / "s.json"
    path.write_text(json.dumps(scene))
    from_file = lightsolver.solve(lightsolver.load_scene(str(path)), photons=50_000, seed=9)
    s = lightsolver.Scene()
    s.add_material("grey", reflectance=0.6)
    s.add_mesh("floor", np.array(scene["meshes"][0]["vertices"], float),
               np.array(scene["meshes"][0]["triangles"]), "grey")
    s.add_light("lamp", "point", position=[1, 1, 2], flux_lm=500)
    s.add_target("floor", "surface", mesh="floor")
    from_numpy = lightsolver.solve(s, photons=50_000, seed=9)
    assert from_file["targets"] == from_numpy["targets"]


def test_progress_callback_reports_and_can_cancel():
    calls = []
    r = lightsolver.solve(unit_room(), photons=2_000_000, progress=lambda d, t: calls.append((d, t)))
    assert calls and calls[-1] == (2_000_000, 2_000_000)
    assert not r["partial"]
    # Batches grow to ~0.2 s each (at most 2^25 photons): a budget far beyond two batches is
    # still unfinished when the callback asks to stop, however fast the machine.
    r = lightsolver.solve(unit_room(), photons=1_000_000_000, progress=lambda d, t: d < 100_000)
    assert r["partial"] and 0 < r["photons"] < 1_000_000_000
    assert any("stopped early" in w for w in r["warnings"])


def test_cancel_token_from_another_thread_and_gil_released():
    token = lightsolver.CancelToken()
    ticks = []

    def other_thread():
        for _ in range(20):  # runs only if solve() released the GIL
            ticks.append(time.monotonic())
            time.sleep(0.01)
        token.cancel()

    worker = threading.Thread(target=other_thread)
    worker.start()
    r = lightsolver.solve(unit_room(0.95), photons=500_000_000, cancel=token)
    worker.join()
    assert token.cancelled
    assert r["partial"] and r["photons"] < 500_000_000
    assert len(ticks) == 20


def test_callback_exception_propagates():
    def boom(done, total):
        raise RuntimeError("from callback")

    with pytest.raises(RuntimeError, match="from callback"):
        lightsolver.solve(unit_room(), photons=1_000_000, progress=boom)


def test_bad_input_raises_input_error_naming_the_field(tmp_path):
    s = unit_room()
    s.add_light("bad", "point", position=[0, 0, 1], flux_lm=-5.0)
    with pytest.raises(lightsolver.InputError, match=r"luminaires\[1\]\.flux_lm"):
        lightsolver.solve(s)
    nan = lightsolver.Scene()
    nan.add_material("m")
    nan.add_mesh("tri", np.array([[0, 0, 0], [1, np.nan, 0], [0, 1, 0]]), np.array([[0, 1, 2]]), "m")
    nan.add_light("p", "point", position=[0, 0, 1], flux_lm=1.0)
    nan.add_target("t", "surface", mesh="tri")
    with pytest.raises(lightsolver.InputError, match=r"meshes\[0\]\.vertices\[1\]"):
        nan.validate()
    with pytest.raises(ValueError, match="out of range"):
        nan.add_mesh("bad", np.zeros((3, 3)), np.array([[0, 1, 3]]), "m")
    with pytest.raises(ValueError, match="shape"):
        nan.add_mesh("bad", np.zeros((3, 2)), np.array([[0, 1, 2]]), "m")
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "lightsolver.scene/1",\n "materials": [}')
    with pytest.raises(lightsolver.InputError, match=r"bad\.json: line 2"):
        lightsolver.load_scene(str(bad))
    with pytest.raises(lightsolver.InputError, match="photons"):
        lightsolver.solve(unit_room(), photons=0)


def test_target_accuracy_keyword():
    r = lightsolver.solve(unit_room(0.5), photons=50_000_000, target_accuracy=0.02)
    assert r["accuracy_met"] and r["photons"] < 50_000_000
    walls = r["targets"][0]
    assert (walls["ci_high_lux"] - walls["ci_low_lux"]) / 2 <= 0.02 * walls["mean_lux"]


def test_stop_reason_and_time_limit():
    r = lightsolver.solve(unit_room(0.5), photons=100_000)
    assert r["stop_reason"] == "photons" and "max_seconds" not in r
    s = unit_room(0.5)
    s.photons = 10_000  # not a budget for an accuracy goal: only an explicit count is
    r = lightsolver.solve(s, target_accuracy=0.01)
    assert r["stop_reason"] == "accuracy" and r["accuracy_met"] and r["photons"] > 10_000
    assert r["photons_requested"] == 10_000_000_000 and r["max_seconds"] == 300
    start = time.monotonic()
    r = lightsolver.solve(s, photons=10 ** 13, max_seconds=0.5)
    assert time.monotonic() - start < 10
    assert r["stop_reason"] == "time" and not r["partial"] and r["max_seconds"] == 0.5
    assert 0 < r["photons"] < 10 ** 13 and any("time limit" in w for w in r["warnings"])
    s.max_seconds = 0.5  # the scene's limit, used when solve() gives no photon count
    s.photons = 10 ** 13
    assert s.max_seconds == 0.5
    assert lightsolver.solve(s)["stop_reason"] == "time"
    s.max_seconds = None
    assert s.max_seconds is None
    with pytest.raises(ValueError, match="max_seconds"):
        s.max_seconds = -1.0
    with pytest.raises(lightsolver.InputError, match="max_seconds"):
        lightsolver.solve(s, max_seconds=float("nan"))


def test_photometric_light_from_python():
    from conftest import SOURCE_DIR
    s = lightsolver.Scene()
    s.add_light("dl", "photometric", file=str(SOURCE_DIR / "Resources/luminaires/downlight.ies"),
                position=[0, 0, 3], flux_lm=1500.0)
    s.add_target("floor", "grid", corner=[-2, -2, 0], edge1=[4, 0, 0], edge2=[0, 4, 0],
                 cells=[4, 4])
    r = lightsolver.solve(s, photons=400_000)
    cells = r["targets"][0]["cells_lux"]
    assert cells[1:3, 1:3].min() > 2 * cells[0, 0]  # a downlight: bright under, dim in corners
    with pytest.raises(lightsolver.InputError, match="missing.ies"):
        s.add_light("x", "photometric", file="/nowhere/missing.ies", position=[0, 0, 3])


def test_backends_are_the_registry_and_each_traces_on_its_own_name():
    listed = lightsolver.backends()
    names = [b["name"] for b in listed]
    assert names[0] == "auto" and "embree" in names and len(set(names)) == len(names)
    for b in listed:
        assert set(b) == {"name", "description", "gpu", "available"} and b["description"]
    by_name = {b["name"]: b for b in listed}
    assert by_name["embree"]["available"] and not by_name["embree"]["gpu"]
    assert by_name["auto"]["available"] and not by_name["auto"]["gpu"]
    for name in names[1:]:
        if by_name[name]["available"]:
            r = lightsolver.solve(unit_room(), photons=2_000, seed=1, backend=name)
            assert r["backend"] == name
        else:  # reported missing: refused, never traced somewhere else
            with pytest.raises(RuntimeError):
                lightsolver.solve(unit_room(), photons=2_000, seed=1, backend=name)


def test_an_unknown_backend_is_refused_with_the_registry_names():
    with pytest.raises(ValueError) as err:
        lightsolver.solve(unit_room(), photons=1_000, backend="cuda")
    message = str(err.value)
    assert '"cuda"' in message
    for b in lightsolver.backends():
        assert b["name"] in message, message


def test_solve_leaves_the_callers_floating_point_modes_alone():
    """Embree's threads flush denormals to zero; the calling thread (which TBB also traces on)
    must get its modes back, or numpy and plain Python arithmetic lose subnormals after a
    solve()."""
    tiny = float("5e-324")  # the smallest subnormal double, at run time (no constant folding)
    assert tiny * 1.0 > 0.0
    s = lightsolver.Scene()
    s.add_light("lamp", "point", position=[0, 0, 1], flux_lm=100.0)
    s.add_target("g", "grid", corner=[-1, -1, 0], edge1=[2, 0, 0], edge2=[0, 2, 0], cells=[2, 2])
    lightsolver.solve(s, photons=20_000, backend="embree", threads=1)
    assert tiny * 1.0 > 0.0
    assert np.finfo(np.float64).smallest_subnormal > 0.0
