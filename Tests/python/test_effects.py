"""The effects a run simulated (docs/scene-format.md, "Effects"): listed in the results file
(schema-valid, every effect once), printed by the CLI as "no glass: refraction not simulated",
the same for both ways of running, and the general Embree kernel forced from the environment
gives the same numbers to the bit."""
import json
import os
import subprocess

import jsonschema

from conftest import SOURCE_DIR, without_run_facts

SCHEMA = json.loads((SOURCE_DIR / "docs" / "schemas" / "results.schema.json").read_text())
SMALL_ROOM = SOURCE_DIR / "Examples" / "optimization" / "small_room" / "small_room.json"
EFFECTS = SCHEMA["properties"]["effects"]["properties"]["simulated"]["items"]["enum"]


def run(cli, scene, tmp_path, env=None, name="r.json", extra=()):
    out = tmp_path / name
    r = subprocess.run([cli, "run", str(scene), "--photons", "100000", "--seed", "3",
                        "--backend", "embree", "--out", str(out), *extra],
                       capture_output=True, text=True, timeout=120,
                       env={**os.environ, **(env or {})})
    assert r.returncode == 0, r.stderr
    return r.stdout, json.loads(out.read_text())


def test_results_list_every_effect_once_and_the_cli_prints_what_was_skipped(cli, tmp_path):
    stdout, results = run(cli, SMALL_ROOM, tmp_path)
    jsonschema.Draft202012Validator(SCHEMA).validate(results)
    effects = results["effects"]
    skipped = {s["effect"]: s["reason"] for s in effects["skipped"]}
    assert sorted(effects["simulated"] + list(skipped)) == sorted(EFFECTS)
    assert {"interreflection", "diffuse_reflection", "grid_crossing"} <= set(effects["simulated"])
    assert skipped["refraction"] == "no glass"
    assert "simulated: interreflection, diffuse reflection, " in stdout
    # One line of effects: the skipped ones are counted, listed only with --effects.
    assert f"({len(skipped)} effects not needed by this scene, not simulated" in stdout
    assert "not simulated\n" not in stdout.replace("--effects lists them)\n", "")
    listed, _ = run(cli, SMALL_ROOM, tmp_path, extra=["--effects"], name="listed.json")
    assert "no glass: refraction not simulated" in listed
    assert "no observer: observer crossing not simulated" in listed


def test_the_general_kernel_gives_the_same_numbers(cli, room_scene, tmp_path):
    _, special = run(cli, room_scene, tmp_path, name="special.json")
    _, general = run(cli, room_scene, tmp_path, {"LIGHTSOLVER_EMBREE_KERNEL": "general"},
                     name="general.json")
    for doc in (special, general):
        doc.pop("seconds")
    assert without_run_facts(special) == without_run_facts(general)
    assert "refraction" in special["effects"]["simulated"]  # the room's window is glass


def test_auto_notes_which_targets_kept_shadow_rays_and_the_cli_prints_it(cli, tmp_path):
    """The materials golden's scene: its large floor goes back to the photons, its grids and
    small targets keep shadow rays (docs/statistics.md, "When shadow rays pay"); the note is
    schema-valid, read back by the results reader, and printed under the simulated line."""
    scene = SOURCE_DIR / "Tests" / "golden" / "scenes" / "materials.json"
    stdout, results = run(cli, scene, tmp_path)
    jsonschema.Draft202012Validator(SCHEMA).validate(results)
    assert "next_event_direct" in results["effects"]["simulated"]
    [note] = results["effects"]["notes"]
    assert note["effect"] == "next_event_direct"
    assert note["note"].startswith("photons where shadow rays would be wider: floor ("), note
    assert "shadow rays: under block" in note["note"]
    assert "next event direct: photons where shadow rays would be wider: floor (" in stdout
