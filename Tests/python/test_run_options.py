"""The run options table (NativeSolver/include/lightsolver/run_options.hpp) describes every run
option once. Walking it: each row is the CLI flag, Python keyword, scene-file setting, Scene
property and results field it says, with the same default; a value out of its range is refused
by every front end with the same message naming the field its way; the docs list every row."""
import copy
import json
import re
import subprocess

import lightsolver
import pytest

from conftest import SOURCE_DIR

OPTIONS = lightsolver.run_options()
ROWS = {o["name"]: o for o in OPTIONS}

SCENE = {
    "format": lightsolver.SCENE_FORMAT,
    "materials": {"white": {"type": "diffuse", "reflectance": 0.5}},
    "meshes": [{"name": "floor", "material": "white",
                "vertices": [[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0]],
                "triangles": [[0, 1, 2], [0, 2, 3]]}],
    "luminaires": [{"name": "lamp", "type": "point", "flux_lm": 1000, "position": [1, 1, 2]}],
    "targets": [{"name": "floor", "type": "surface", "mesh": "floor",
                 "requirements": {"em_lux": 10}}],
    "settings": {"photons": 2000},
}


def scene_text(**settings):
    doc = copy.deepcopy(SCENE)
    doc["settings"].update(settings)
    return json.dumps(doc)


def cli_run(cli, tmp_path, *args):
    path = tmp_path / "scene.json"
    if not path.exists():
        path.write_text(scene_text())
    return subprocess.run([cli, "run", str(path), "--quiet", *args], capture_output=True,
                          text=True, timeout=120)


def test_the_table_is_well_formed():
    assert len(ROWS) == len(OPTIONS)  # one row per name
    for o in OPTIONS:
        assert o["help"] and o["type"] in {"bool", "int", "uint", "float", "str"}, o
        assert o["scene_key"] or o["cli_flag"] or o["python_keyword"], o
        if o["result_key"]:
            assert o["echoed_when"] is not None, o
        if o["range"]:
            assert o["min"] < o["max"] and o["type"] in {"int", "uint", "float"}, o
    # The options of today, so a row lost by mistake is noticed.
    assert {"photons", "seed", "confidence", "threads", "backend", "target_accuracy",
            "accuracy_per_cell", "max_seconds", "decide", "contributions",
            "max_bounces"} <= set(ROWS)


def value_text(value):
    """A default as help texts and the docs write it: none, true, 1000000, 0.95, auto."""
    if value is None:
        return "none"
    if isinstance(value, bool):
        return "true" if value else "false"
    return value if isinstance(value, str) else f"{value:.15g}"


def default_note(o):
    """Where the option's default comes from, as the CLI help and the docstrings say it."""
    if o["scene_key"]:
        return f"(default: settings.{o['scene_key']} = {value_text(o['default'])})"
    return "" if o["default"] is None else f"(default: {value_text(o['default'])})"


def test_every_flag_is_in_the_cli_help_with_its_help_range_and_default(cli):
    run_help = subprocess.run([cli, "run", "--help"], capture_output=True, text=True).stdout
    cost_help = subprocess.run([cli, "cost", "--help"], capture_output=True, text=True).stdout
    study_help = subprocess.run([cli, "study", "--help"], capture_output=True, text=True).stdout
    for o in OPTIONS:
        if not o["cli_flag"]:
            assert o["scene_key"] and f"--{o['scene_key'].replace('_', '-')}" not in run_help
            continue
        assert re.search(rf"^\s+{re.escape(o['cli_flag'])}\b", run_help, re.M), o["cli_flag"]
        if o["name"] != "backend":  # its help lists the backends built (backend_option.hpp)
            assert f"{o['help']} {default_note(o)}".strip() in run_help, o["name"]
        if o["range"]:
            assert f"{o['cli_flag']} " in run_help and o["range"] in run_help, o["name"]
        for text in (cost_help, study_help):  # checkpointed runs take their rows only
            assert (re.search(rf"^\s+{re.escape(o['cli_flag'])}\b", text, re.M) is not None) == \
                o["cost_and_study"], o["name"]


def test_every_keyword_is_in_the_docstrings_with_its_default():
    for o in OPTIONS:
        if not o["python_keyword"]:
            continue
        entry = f"{o['python_keyword']}={o['python_default']!r}: {o['help']}"
        assert entry in lightsolver.solve.__doc__, entry
        assert (entry in lightsolver.cost.__doc__) == o["cost_and_study"], o["name"]
        assert (entry in lightsolver.study.__doc__) == o["cost_and_study"], o["name"]
        assert (entry in lightsolver.Simulation.run.__doc__) != o["per_backend"], o["name"]
        # A scene setting's keyword defaults to the scene's value (None), others to their own.
        if o["scene_key"]:
            assert o["python_default"] is None
            assert default_note(o) in lightsolver.solve.__doc__, o["name"]
        else:
            assert o["python_default"] == o["default"]


def test_every_scene_setting_is_a_scene_property_with_its_help_and_default():
    for o in OPTIONS:
        if o["scene_key"]:
            doc = getattr(lightsolver.Scene, o["scene_key"]).__doc__
            assert f"{o['help']} {default_note(o)}" in doc, o["name"]


def test_unknown_keywords_are_refused_by_name():
    scene = lightsolver.scene_from_json(scene_text())
    with pytest.raises(TypeError, match="solve\\(\\) got an unexpected keyword argument 'photon'"):
        lightsolver.solve(scene, photon=10)
    with pytest.raises(TypeError, match="max_bounces"):  # a scene setting only
        lightsolver.solve(scene, max_bounces=3)
    with pytest.raises(TypeError, match="'photons'"):  # not an option of cost
        lightsolver.cost(scene, photons=10)


def test_every_scene_setting_is_read_with_the_tables_default():
    scene = lightsolver.Scene()
    keys = [o["scene_key"] for o in OPTIONS if o["scene_key"]]
    for o in OPTIONS:
        if o["scene_key"]:
            # A new Scene and a scene file without the key have the default ...
            assert getattr(scene, o["scene_key"]) == o["default"], o["name"]
            # ... and a scene file giving the default reads the same.
            doc = json.loads(scene_text())
            doc["settings"] = {o["scene_key"]: o["default"]}
            if o["default"] is not None:
                read = lightsolver.scene_from_json(json.dumps(doc))
                assert getattr(read, o["scene_key"]) == o["default"], o["name"]
    # The reader knows exactly the table's keys.
    with pytest.raises(lightsolver.InputError) as e:
        lightsolver.scene_from_json(scene_text(threads=2))
    assert "settings.threads: unknown key (allowed here: " + ", ".join(keys) + ")" in str(e.value)


def out_of_range(o):
    """Values just outside the row's range that its type can hold."""
    values = []
    if o["min"] is not None and o["min"] > float("-inf"):
        below = o["min"] if o["min_open"] else o["min"] - 1
        if not (o["type"] == "uint" and below < 0):
            values.append(below)
    if o["max"] is not None and o["max"] < float("inf"):
        values.append(o["max"] if o["max_open"] else o["max"] + 1)
    return [int(v) if o["type"] in {"int", "uint"} else float(v) for v in values]


RANGED = [(o["name"], v) for o in OPTIONS if o["range"] for v in out_of_range(o)]


def message_after(field, text):
    """What an error says about `field` ("must ... (got V)"), from a longer message."""
    m = re.search(re.escape(field) + r": (must [^\n]*\(got [^)]*\))", text)
    assert m, f"{field} not named in: {text}"
    return m.group(1)


@pytest.mark.parametrize("name,value", RANGED)
def test_out_of_range_values_are_refused_alike_by_every_front_end(name, value, cli, tmp_path):
    o = ROWS[name]
    messages = []
    if o["cli_flag"]:
        r = cli_run(cli, tmp_path, o["cli_flag"], str(value))
        assert r.returncode != 0 and "photons," not in r.stdout
        messages.append(message_after(o["cli_flag"], r.stderr))
    if o["python_keyword"]:
        with pytest.raises(lightsolver.InputError) as e:
            lightsolver.solve(lightsolver.scene_from_json(scene_text()),
                              **{o["python_keyword"]: value})
        messages.append(message_after(o["python_keyword"], str(e.value)))
    if o["scene_key"]:
        with pytest.raises(lightsolver.InputError) as e:
            lightsolver.scene_from_json(scene_text(**{o["scene_key"]: value}))
        messages.append(message_after("settings." + o["scene_key"], str(e.value)))
        with pytest.raises(lightsolver.InputError) as e:
            setattr(lightsolver.Scene(), o["scene_key"], value)
        messages.append(message_after(o["scene_key"], str(e.value)))
    assert len(messages) >= 2 and len(set(messages)) == 1, messages
    assert "(got " in messages[0]


#: A valid value other than the default for every echoed option, and what else it needs.
ECHO = {
    "photons": (3000, {}),
    "seed": (7, {}),
    "confidence": (0.9, {}),
    "backend": ("embree", {}),
    "target_accuracy": (0.5, {"photons": 3000}),
    "accuracy_per_cell": (True, {"target_accuracy": 0.5, "photons": 3000}),
    "max_seconds": (100.0, {}),
    "decide": (True, {"photons": 3000}),
}


def cli_args(values):
    args = []
    for name, value in values.items():
        flag = ROWS[name]["cli_flag"]
        args += [flag] if value is True else [flag, str(value)]
    return args


def test_every_echoed_option_is_echoed_by_every_front_end(cli, tmp_path):
    echoed = [o for o in OPTIONS if o["result_key"]]
    assert {o["name"] for o in echoed} == set(ECHO)
    for o in echoed:
        value, context = ECHO[o["name"]]
        given = dict(context, **{o["name"]: value})
        assert value != o["default"], o["name"]
        py = lightsolver.solve(lightsolver.scene_from_json(scene_text()),
                               **{ROWS[k]["python_keyword"]: v for k, v in given.items()})
        assert py[o["result_key"]] == value, o["name"]
        out = tmp_path / f"{o['name']}.json"
        r = cli_run(cli, tmp_path, *cli_args(given), "--out", str(out))
        assert r.returncode == 0, r.stderr
        assert json.loads(out.read_text())[o["result_key"]] == value, o["name"]
        if o["scene_key"] and all(ROWS[k]["scene_key"] for k in given):
            # The same from the scene's settings (photons given there: max_seconds applies).
            from_file = lightsolver.solve(lightsolver.scene_from_json(
                scene_text(**{ROWS[k]["scene_key"]: v for k, v in given.items()})))
            assert from_file[o["result_key"]] == value, o["name"]
    # Defaults echo as the table says (no time limit and no goal: their keys are left out).
    plain = lightsolver.solve(lightsolver.scene_from_json(scene_text()))
    assert plain["seed"] == ROWS["seed"]["default"]
    assert plain["confidence"] == ROWS["confidence"]["default"]
    assert "max_seconds" not in plain and "target_accuracy" not in plain


def documented_settings():
    """{key: default text} from docs/scene-format.md's "Settings" table."""
    text = (SOURCE_DIR / "docs" / "scene-format.md").read_text()
    section = text.split("\n## Settings\n", 1)[1].split("\n## ", 1)[0]
    return dict(re.findall(r"^\| `(\w+)` \| ([^|]*?) \|", section, re.M))


def default_text(o):
    return "none" if o["default"] is None else json.dumps(o["default"])


def test_the_scene_format_lists_every_setting_with_its_default():
    documented = documented_settings()
    assert set(documented) == {o["scene_key"] for o in OPTIONS if o["scene_key"]}
    for o in OPTIONS:
        if o["scene_key"]:
            assert documented[o["scene_key"]] == default_text(o), o["name"]


def test_the_readme_lists_every_flag_and_keyword():
    readme = (SOURCE_DIR / "README.md").read_text()
    command_line = readme.split("\n## Command line\n", 1)[1].split("\n## ", 1)[0]
    python = readme.split("\n## Python\n", 1)[1].split("\n## ", 1)[0]
    for o in OPTIONS:
        if o["cli_flag"]:
            assert o["cli_flag"] in command_line, o["cli_flag"]
        if o["python_keyword"]:
            assert f"`{o['python_keyword']}`" in python, o["python_keyword"]
