"""lightsolver.optimize and `lightsolver optimize`: the result dict / JSON, progress, cancellation
with the GIL released, in-memory scenes and errors naming the field."""
import json
import subprocess
import threading
import time
from pathlib import Path

import pytest

import lightsolver
from conftest import SOURCE_DIR

SMALL_ROOM = SOURCE_DIR / "Examples" / "optimization" / "small_room" / "small_room.json"
CORNELL = SOURCE_DIR / "Examples" / "optimization" / "cornell" / "cornell.json"


def test_optimize_file_returns_the_documented_result() -> None:
    r = lightsolver.optimize(str(SMALL_ROOM), iterations=3, seed=2, threads=2)
    assert r["format"] == "lightsolver.optimization/1"
    assert r["goal"] == "minimize"
    assert r["variables"] == ["a.u", "a.v", "b.u", "b.v", "a+b.flux_lm"]
    assert r["counters"]["iterations"] == 3
    assert len(r["history"]) == 3
    member = r["isoc"][0]
    assert {c["verdict"] for c in member["constraints"]} == {"met"}
    flux = member["scene"]["a.flux_lm"][0]
    assert member["objective"]["mean"] == pytest.approx(2 * flux)
    assert len(member["scene"]["a"]) == 3  # world position of luminaire a


def test_same_seed_same_isoc() -> None:
    a = lightsolver.optimize(SMALL_ROOM, iterations=2, seed=5, threads=2)
    b = lightsolver.optimize(SMALL_ROOM, iterations=2, seed=5, threads=1)
    assert [m["cells"] for m in a["isoc"]] == [m["cells"] for m in b["isoc"]]
    assert a["isoc"][0]["constraints"] == b["isoc"][0]["constraints"]


def test_progress_reports_every_iteration_and_can_stop() -> None:
    seen: list[dict] = []

    def progress(s: dict) -> bool:
        seen.append(s)
        return s["event"] != "iteration" or s["iteration"] < 2

    r = lightsolver.optimize(SMALL_ROOM, iterations=10, progress=progress, threads=2)
    assert [s["iteration"] for s in seen if s["event"] == "iteration"] == [1, 2]
    assert r["stop"] == "cancelled"
    iterations = [s for s in seen if s["event"] == "iteration"]
    assert sum(s["trace_seconds"] for s in iterations) > 0 and iterations[-1]["total_photons"] > 0
    # The first report comes after the first trace, before any iteration has ended.
    assert seen[0]["event"] == "evaluation" and seen[0]["iteration"] == 0
    assert seen[0]["evaluations"] >= 1 and seen[0]["elapsed_seconds"] > 0


def test_cancel_token_stops_a_long_run_and_the_gil_is_released() -> None:
    token = lightsolver.CancelToken()
    ticks = 0

    def tick() -> None:
        nonlocal ticks
        while not token.cancelled:
            ticks += 1  # runs only if optimize() released the GIL
            time.sleep(0.01)
            if ticks == 30:
                token.cancel()

    t = threading.Thread(target=tick)
    t.start()
    start = time.monotonic()
    r = lightsolver.optimize(CORNELL, iterations=1000, confirmation_photons=2_000_000, threads=2,
                             cancel=token)
    t.join()
    assert r["stop"] == "cancelled"
    assert ticks >= 30
    assert time.monotonic() - start < 30


def test_in_memory_scene_with_a_block_dict() -> None:
    scene = lightsolver.load_scene(str(SMALL_ROOM))
    block = json.loads(SMALL_ROOM.read_text())["optimization"]
    block["intention"] = {"type": "maximize_mean_illuminance", "target": "workplane"}
    block["variables"] = block["variables"][:1]
    block["search"] = {"max_iterations": 2, "screening_photons": 0,
                       "confirmation_photons": 20000}
    r = lightsolver.optimize(scene, optimization=block, threads=2)
    assert r["goal"] == "maximize"
    assert r["variables"] == ["a.u", "a.v"]
    with pytest.raises(ValueError, match="optimization"):
        lightsolver.optimize(scene)


def test_a_file_with_a_given_block(tmp_path: Path) -> None:
    # The given block replaces the file's: the file needs none, and a broken one is not read.
    doc = json.loads(SMALL_ROOM.read_text())
    block = doc.pop("optimization")
    block["search"] = {"max_iterations": 1, "screening_photons": 0,
                       "confirmation_photons": 20000}
    plain = tmp_path / "plain.json"
    plain.write_text(json.dumps(doc))
    r = lightsolver.optimize(str(plain), optimization=block, threads=2)
    assert r["counters"]["iterations"] == 1 and r["scene_file"] == str(plain)
    doc["optimization"] = {"variables": "broken"}
    broken = tmp_path / "broken.json"
    broken.write_text(json.dumps(doc))
    assert lightsolver.optimize(str(broken), optimization=block, threads=2)["isoc"] == r["isoc"]


def test_bad_block_names_the_field(tmp_path: Path) -> None:
    doc = json.loads(SMALL_ROOM.read_text())
    doc["optimization"]["variables"][1]["cells"] = [3]
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(doc))
    with pytest.raises(lightsolver.InputError, match=r"optimization\.variables\[1\]\.cells"):
        lightsolver.optimize(str(bad))


def test_cli_prints_progress_and_writes_the_isoc(cli: str, tmp_path: Path) -> None:
    out = tmp_path / "isoc.json"
    p = subprocess.run([cli, "optimize", str(SMALL_ROOM), "--iterations", "2", "--seed", "3",
                        "--threads", "2", "--out", str(out)],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert lines[0].split()[0] == "1" and "isoc" in lines[0] and "trace" in lines[0]
    assert "per iteration: update" in p.stdout
    r = json.loads(out.read_text())
    assert r["counters"]["iterations"] == 2
    assert r["isoc"] and "scene" in r["isoc"][0]


def test_cli_reports_a_bad_block(cli: str, tmp_path: Path) -> None:
    doc = json.loads(SMALL_ROOM.read_text())
    doc["optimization"]["search"]["strategy"] = "guess"
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(doc))
    p = subprocess.run([cli, "optimize", str(bad)], capture_output=True, text=True, timeout=60)
    assert p.returncode == 1
    assert "optimization.search.strategy" in p.stderr


def test_backend_choice_reaches_the_search(cli: str, tmp_path: Path) -> None:
    names = [b["name"] for b in lightsolver.backends()]
    with pytest.raises(ValueError) as err:
        lightsolver.optimize(SMALL_ROOM, iterations=1, backend="cuda")
    assert all(name in str(err.value) for name in names), err.value
    r = lightsolver.optimize(SMALL_ROOM, iterations=1, seed=2, threads=2, backend="embree")
    assert r["counters"]["iterations"] == 1
    help_text = " ".join(subprocess.run([cli, "optimize", "--help"], capture_output=True,
                                        text=True, timeout=60).stdout.split())
    assert all(f"{name} (" in help_text for name in names), help_text
    if "vulkan" in names:  # without a driver, asking for vulkan must fail, not fall back
        env = {"PATH": "/usr/bin:/bin", "VK_ICD_FILENAMES": str(tmp_path / "none.json")}
        args = [cli, "optimize", str(SMALL_ROOM), "--iterations", "1", "-q", "--backend"]
        bad = subprocess.run(args + ["vulkan"], capture_output=True, text=True, timeout=120,
                             env=env)
        assert bad.returncode != 0 and "Vulkan" in bad.stderr, bad.stderr
        good = subprocess.run(args + ["auto"], capture_output=True, text=True, timeout=120,
                              env=env)
        assert good.returncode == 0, good.stderr


def test_reused_traces_save_photons_and_can_be_turned_off(cli: str, tmp_path: Path) -> None:
    """small_room's flux variable scales one trace per placement: fewer photons traced than
    requested; reuse_traces=False (--no-reuse) traces every photon of every evaluation."""
    on = lightsolver.optimize(SMALL_ROOM, iterations=3, seed=2, threads=2)
    off = lightsolver.optimize(SMALL_ROOM, iterations=3, seed=2, threads=2, reuse_traces=False)
    c_on, c_off = on["counters"], off["counters"]
    assert c_on["photons_traced"] < c_on["photons"]
    assert c_off["photons_traced"] == c_off["photons"]
    assert on["isoc"] and off["isoc"]
    out = tmp_path / "r.json"
    p = subprocess.run([cli, "optimize", str(SMALL_ROOM), "--iterations", "3", "--seed", "2",
                        "--threads", "2", "-q", "--no-reuse", "--out", str(out)],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert "traced)" in p.stdout
    assert json.loads(out.read_text())["counters"] == {
        **c_off, **{k: json.loads(out.read_text())["counters"][k] for k in
                    ("update_seconds", "trace_seconds", "other_seconds", "total_seconds")}}


def test_next_event_refine_stage_and_match_widths_keywords_reach_the_search() -> None:
    """next_event=, refine_stage_photons= and match_widths= override the scene's
    settings.next_event and search.refine_stage_photons / match_widths, as --next-event,
    --refine-stage-photons and --match-widths do; a bad value is refused naming the setting."""
    small = dict(iterations=2, seed=3, threads=2, screening_photons=2000,
                 confirmation_photons=16000)
    on = lightsolver.optimize(CORNELL, next_event="on", refine_stage_photons=4000,
                              match_widths=False, **small)
    off = lightsolver.optimize(CORNELL, next_event="off", refine_stage_photons=0, **small)
    assert on["provenance"]["options"]["next_event"] == "on"
    assert off["provenance"]["options"]["next_event"] == "off"
    assert on["next_event"]["setting"] == "on" and on["next_event"]["direct"] is True
    assert off["next_event"]["direct"] is False
    assert on["provenance"]["options"]["refine_stage_photons"] == 4000
    assert off["provenance"]["options"]["refine_stage_photons"] == 0
    assert off["counters"]["refine_stage"] == 0
    with pytest.raises(Exception, match="next_event"):
        lightsolver.optimize(CORNELL, next_event="sometimes", **small)
    # match_widths is the default (search.match_widths true): the same search as asking for it
    matched = lightsolver.optimize(CORNELL, next_event="on", **small)
    asked = lightsolver.optimize(CORNELL, next_event="on", match_widths=True, **small)
    assert asked["provenance"]["options"]["width_factor"] == \
        matched["provenance"]["options"]["width_factor"]
    options = matched["provenance"]["options"]
    assert options["match_widths"] is True and on["provenance"]["options"]["match_widths"] is False
    assert "width_factor" not in on["provenance"]["options"]
    assert 0.25 <= options["width_factor"] <= 1.0  # never below the calibration's 4000 photons
    assert options["confirmation_photons"] == round(16000 * options["width_factor"])
    assert all(m["photons"] == options["confirmation_photons"] for m in matched["isoc"])
