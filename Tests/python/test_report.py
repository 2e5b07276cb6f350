"""The calculation report (lightsolver_report, docs/report.md): the HTML of the committed
fixtures against golden files, byte for byte; the numbers it prints are the results' and lie in
their intervals; verdicts coloured as the results decide them; the PDF typeset, non-blank,
its text holding the verdicts and Em values; tracing when no results are given.

Golden files: Tests/python/fixtures/report/<name>.report.html. After a deliberate change of the
report, regenerate them with
    LIGHTSOLVER_REPORT_UPDATE=1 /usr/bin/python3 -m pytest -q Tests/python/test_report.py
(with the PYTHONPATH of docs/testing.md) and look at the diff."""
import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import lightsolver
import pytest

import lightsolver_report
from lightsolver_report import ReportError, build, render, render_html
from lightsolver_report import fmt

from conftest import SOURCE_DIR

FIXTURES = Path(__file__).resolve().parent / "fixtures" / "report"
DATE = "2026-01-01"
UPDATE = os.environ.get("LIGHTSOLVER_REPORT_UPDATE") == "1"
#: room: requirements giving every verdict, 29 W panels; office: the golden office scene with
#: EN 12464-1 office figures; workbench: the office as the workbench exports it (IES panels
#: with their file's power, observers, light scenes, energy and sign-off inputs): together
#: every section of the report.
NAMES = ("room", "office", "workbench")


def fixture(name):
    scene = FIXTURES / f"{name}.scene.json"
    return scene, json.loads((FIXTURES / f"{name}.results.json").read_text())


def golden_html(name):
    scene, results = fixture(name)
    return render_html(scene, results, date=DATE)


@pytest.mark.parametrize("name", NAMES)
def test_html_is_byte_identical_to_the_golden(name):
    html = golden_html(name)
    golden = FIXTURES / f"{name}.report.html"
    if UPDATE:
        golden.write_text(html, encoding="utf-8")
    assert html == golden.read_text(encoding="utf-8"), (
        f"the report of {name} changed; if deliberately, regenerate with "
        "LIGHTSOLVER_REPORT_UPDATE=1 (see this file's docstring)")
    assert golden_html(name) == html  # and the same inputs give the same text again


@pytest.mark.parametrize("name", NAMES)
def test_printed_numbers_are_the_results_and_lie_in_their_intervals(name):
    scene, results = fixture(name)
    report = build(scene, results, date=DATE)
    html = (FIXTURES / f"{name}.report.html").read_text(encoding="utf-8")
    assert len(report.areas) == len(results["targets"])
    for area, target in zip(report.areas, results["targets"]):
        assert area.em.value == target["mean_lux"]
        if area.is_glare:  # an eye: its UGR and background luminance, not an illuminance
            assert f"{fmt.ugr(target['ugr'])}</td>" in html
            assert f"{fmt.number(target['background_luminance_cd_m2'], 3)}</td>" in html
        else:
            assert f"{fmt.lux(target['mean_lux'])}" in html
        stats = [area.em, area.emin, area.emax, area.u0, area.ud]
        for stat in (s for s in stats if s is not None and s.has_interval):
            assert stat.low <= stat.value <= stat.high
        # Every grid prints its statistics' intervals (judged or not), each holding its value.
        for key, stat in area.stats:
            if area.type == "grid":
                assert stat.has_interval, (area.name, key)
                shown = fmt.lux if key in ("em", "emin", "emax") else fmt.ratio
                assert f"[{shown(stat.low)}, {shown(stat.high)}]" in html
        for verdict in area.verdicts:
            raw = target["verdicts"][verdict.key]
            assert (verdict.verdict, verdict.value, verdict.low, verdict.high) == (
                raw["verdict"], raw["value"], raw["ci_low"], raw["ci_high"])
            if verdict.value is not None:
                assert verdict.low <= verdict.value <= verdict.high
            shown = fmt.lux if verdict.is_lux else fmt.ugr if verdict.key == "ugr" else fmt.ratio
            assert f"[{shown(raw['ci_low'])}, {shown(raw['ci_high'])}]" in html
    # Every verdict of the results appears once in the area's table, coloured by its class.
    for kind in ("pass", "fail", "undecided"):
        expected = sum(v["verdict"] == kind for t in results["targets"]
                       for v in t.get("verdicts", {}).values())
        details = html[re.search(r"<h2>\d+ Calculation areas</h2>", html).start():]
        assert details.count(f'<tr class="row-{kind}">') == expected


def test_the_room_fixture_shows_every_verdict_and_the_cost_of_deciding():
    scene, results = fixture("room")
    html = golden_html("room")
    assert results["verdict"] == "fail"
    assert 'Overall verdict <span class="badge v-fail">✗ FAIL</span>' in html
    undecided = results["targets"][1]["verdicts"]["emin"]
    assert undecided["verdict"] == "undecided"
    assert f"about {fmt.sci(undecided['to_decide']['photons'])} light paths" in html
    assert "29" in html and "W/m² per 100 lx" in html  # power_w of the fixture's panels
    assert "from the photometric file" not in html  # the scene states it
    # The 29 W panels over the 15 m² workplane.
    report = build(scene, results, date=DATE)
    workplane = report.areas[1]
    assert workplane.power_density_w_m2 == pytest.approx(4 * 29 / 15.0)
    assert report.total_power_w == 4 * 29 and report.total_flux_lm == 4 * 3400


def test_the_office_fixture_shows_maintenance_factor_and_labels():
    scene, results = fixture("office")
    report = build(scene, results, date=DATE)
    (row,) = report.luminaires
    assert row.count == 4 and row.maintenance_factor == 0.8
    assert row.initial_flux_lm == pytest.approx(5200, rel=1e-12)
    assert row.flux_lm == 4160 and report.total_power_w is None
    assert [a.label for a in report.areas] == ["Workplane", "Desk top", "North wall"]
    assert report.title == "Office" and report.verdict == "pass"
    walls = next(m for m in report.materials if m.name == "default_wall")
    assert walls.reflectance == 0.5 and "North wall" in walls.used_by


def test_svg_ids_are_unique_and_the_html_has_no_date_or_absolute_path():
    html = golden_html("room")
    ids = re.findall(r'\sid="([^"]+)"', html)
    assert ids and len(ids) == len(set(ids))
    assert "<dc:date>" not in html and "Matplotlib v" not in html
    assert str(SOURCE_DIR) not in html and str(FIXTURES) not in html
    # the floor plan, the picture of the model, the workplane's plan and value chart
    assert html.count("<svg") == 4


def _older(results):
    """Results as a solver before issue 24 wrote them without requirements: the grids'
    statistics without intervals."""
    grid_intervals = ("min_ci_", "max_ci_", "uniformity_ci_", "ud")
    for target in results["targets"]:
        for key in [k for k in target if k.startswith(grid_intervals)]:
            del target[key]
    return results


def test_results_without_the_new_fields_still_render():
    # An older solver: no requirements, verdicts or statistics' intervals.
    scene = SOURCE_DIR / "Examples" / "room" / "room.json"
    results = _older(json.loads(
        (SOURCE_DIR / "Tests" / "golden" / "room.results.json").read_text()))
    html = render_html(scene, results, date=DATE)
    assert "No requirements are stated" in html
    assert "badge v-" not in html.split('<section class="guide">')[0]
    report = build(scene, results, date=DATE)
    grid = report.areas[1]
    assert grid.emin.value == results["targets"][1]["min_lux"] and not grid.emin.has_interval
    assert grid.ud.value == pytest.approx(grid.emin.value / grid.emax.value)
    # Requirements stated in the scene, not evaluated by the solver, are shown as such.
    scene_dict = json.loads(scene.read_text())
    scene_dict["targets"][1]["requirements"] = {"em_lux": 500, "u0": 0.6}
    html = render_html(scene_dict, results, scene_path=scene, date=DATE)
    assert "not evaluated by this solver" in html


@pytest.mark.parametrize("name", NAMES)
def test_pdf_is_typeset_non_blank_and_holds_verdicts_and_values(name, tmp_path):
    if not (shutil.which("pdftoppm") and shutil.which("pdftotext")):
        pytest.skip("poppler-utils (pdftoppm, pdftotext) not installed")
    scene, results = fixture(name)
    # The room and office fixtures are results no solver wrote (make_fixtures.py): unverified.
    pdf = render(scene, results, tmp_path / f"{name}.pdf", date=DATE, allow_unverified=True)
    assert pdf.read_bytes().startswith(b"%PDF")
    subprocess.run(["pdftoppm", "-r", "40", "-gray", "-f", "1", "-l", "3", str(pdf),
                    str(tmp_path / "page")], check=True)
    pages = sorted(tmp_path.glob("page-*.pgm"))
    assert len(pages) == 3
    for page in pages:
        ink = _ink_fraction(page)
        assert 0.01 < ink < 0.6, f"{page.name}: {ink:.3f} of the page inked"
    text = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], check=True,
                          capture_output=True, text=True).stdout
    words = {"pass": "PASS", "fail": "FAIL", "undecided": "UNDECIDED"}
    lines = text.splitlines()
    # The overall verdict, and each area's verdict on the line of its compliance row.
    assert any("Overall verdict" in ln and words[results["verdict"]] in ln for ln in lines)
    report = build(scene, results, date=DATE)
    for area in report.areas_with_requirements:
        row = [ln for ln in lines if ln.lstrip().startswith(area.label)]
        assert row and words[area.verdict] in row[0].split()[-1], (area.label, row[:1])
    for target in results["targets"]:
        assert (fmt.ugr(target["ugr"]) if target["type"] in ("observer", "observer_grid")
                else fmt.lux(target["mean_lux"])) in text
    assert re.search(r"Page 1 of \d", text)


def _ink_fraction(pgm: Path) -> float:
    """Share of pixels darker than near-white in a binary PGM (pdftoppm -gray)."""
    import numpy as np

    data = pgm.read_bytes()
    fields = data.split(maxsplit=4)  # P5, width, height, maxval, pixels
    width, height = int(fields[1]), int(fields[2])
    pixels = np.frombuffer(fields[4][-width * height:], dtype=np.uint8)
    return float(np.mean(pixels < 200))


def test_traces_with_the_scenes_settings_when_no_results_are_given(tmp_path, room_scene):
    # Examples/room's settings (2e6 photons, seed 1) on embree give Tests/golden/room.results.json
    # bit for bit, so its report is the traced one's, but for the tracing time (and the
    # results' fingerprint, which covers it).
    out = render(room_scene, None, tmp_path / "room.html", date=DATE, backend="embree")
    golden = json.loads((SOURCE_DIR / "Tests" / "golden" / "room.results.json").read_text())
    expected = render_html(room_scene, golden, date=DATE)
    timed = re.compile(r'<td class="run-seconds">[^<]*</td>|<code>[0-9a-f]{64}</code>'
                       r'|\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ|commit [0-9a-f]+')
    assert timed.sub("", out.read_text(encoding="utf-8")) == timed.sub("", expected)


def test_photometric_luminaires_say_what_their_files_say(tmp_path):
    lum_dir = SOURCE_DIR / "Resources" / "luminaires"
    scene = {
        "format": "lightsolver.scene/1",
        "materials": {"floor": {"type": "diffuse", "reflectance": 0.2}},
        "meshes": [{"name": "floor", "material": "floor",
                    "vertices": [[0, 0, 0], [4, 0, 0], [4, 4, 0], [0, 4, 0]],
                    "triangles": [[0, 1, 2], [0, 2, 3]]}],
        "luminaires": [
            {"name": f"dl{i}", "type": "photometric",
             "file": "copy of downlight.ies" if i == 2 else "downlight.ies",
             "position": [1 + 2 * (i % 2), 1 + 2 * (i // 2), 3], "flux_lm": 1000}
            for i in range(3)] + [
            {"name": "ldt", "type": "photometric", "file": "downlight.ldt",
             "position": [3, 3, 3]}],
        # As the workbench writes them: no maintenance factor reaches a file's own flux.
        "metadata": {"project": "Downlights",
                     "luminaires": {n: {"maintenance_factor": 0.8, "flux_lm_initial": 0.0}
                                    for n in ("dl0", "dl1", "dl2", "ldt")}},
        "targets": [{"name": "floor grid", "type": "grid", "corner": [0, 0, 0],
                     "edge1": [4, 0, 0], "edge2": [0, 4, 0], "cells": [4, 4]}],
        "settings": {"photons": 20000, "seed": 3}}
    for f in ("downlight.ies", "downlight.ldt"):
        shutil.copy(lum_dir / f, tmp_path / f)
    shutil.copy(lum_dir / "downlight.ies", tmp_path / "copy of downlight.ies")  # one type
    path = tmp_path / "downlights.json"
    path.write_text(json.dumps(scene))
    results = lightsolver_report.trace(path)
    report = build(path, results, date=DATE)
    ies, ldt = report.luminaires
    summary = lightsolver.photometry_summary(str(lum_dir / "downlight.ies"))
    assert ("LUMCAT", "LS-DL-150") in [tuple(k) for k in summary["keywords"]]
    assert ies.count == 3 and ies.files == ["downlight.ies", "copy of downlight.ies"]
    assert (ies.maker, ies.catalogue, ies.lamp) == (
        "Lighting project", "LS-DL-150", "LED module 1500 lm")
    assert ies.flux_lm == pytest.approx(summary["integrated_lumens_lm"] * 1000 / 1500)
    assert ldt.count == 1 and ldt.catalogue == "LS-DL-150" and ldt.maintenance_factor is None
    assert ies.maintenance_factor == 0.8  # flux_lm given: the workbench applied it
    assert ldt.flux_lm == pytest.approx(
        lightsolver.photometry_summary(str(lum_dir / "downlight.ldt"))["integrated_lumens_lm"])
    # The solver traced what the schedule says is emitted.
    assert report.total_flux_lm == pytest.approx(results["total_flux_lm"], rel=1e-9)
    html = render_html(path, results, date=DATE)
    assert "cat. no. LS-DL-150" in html and "Lighting project" in html
    # The client reads what the data describes, not the files' names.
    assert "downlight.ies" not in html and "downlight.ldt" not in html
    assert str(tmp_path) not in html
    # The data-sheet UGR of each file is the solver's CIE 190 table at 4H x 8H, 0.7/0.5/0.2.
    table = lightsolver.ugr_table(str(lum_dir / "downlight.ldt"))
    row = next(r for r in table["rows"] if (r["x_h"], r["y_h"]) == (4.0, 8.0))
    assert ldt.ugr_4h8h == (row["crosswise"][0], row["endwise"][0])
    assert "UGR (CIE 190, room 4H × 8H, 0.7/0.5/0.2)" in html



def test_each_photometric_file_gets_its_full_ugr_table(tmp_path):
    """The data-sheet UGR table (CIE 190, 19 rooms x 5 reflectances, crosswise and endwise)
    of each photometric file, once per file, every value the solver's to one decimal."""
    lum_dir = SOURCE_DIR / "Resources" / "luminaires"
    shutil.copy(lum_dir / "batwing_panel.ldt", tmp_path / "batwing_panel.ldt")
    scene = {
        "format": "lightsolver.scene/1",
        "materials": {"floor": {"type": "diffuse", "reflectance": 0.2}},
        "meshes": [{"name": "floor", "material": "floor",
                    "vertices": [[0, 0, 0], [4, 0, 0], [4, 4, 0], [0, 4, 0]],
                    "triangles": [[0, 1, 2], [0, 2, 3]]}],
        # Two schedule rows (two fluxes) of one file: one table.
        "luminaires": [{"name": "a", "type": "photometric", "file": "batwing_panel.ldt",
                        "position": [1, 1, 3]},
                       {"name": "b", "type": "photometric", "file": "batwing_panel.ldt",
                        "position": [3, 3, 3], "flux_lm": 2000},
                       {"name": "c", "type": "point", "position": [2, 2, 3], "flux_lm": 100}],
        "targets": [{"name": "floor grid", "type": "grid", "corner": [0, 0, 0],
                     "edge1": [4, 0, 0], "edge2": [0, 4, 0], "cells": [2, 2]}],
        "settings": {"photons": 20000, "seed": 3}}
    path = tmp_path / "panels.json"
    path.write_text(json.dumps(scene))
    results = lightsolver_report.trace(path)
    report = build(path, results, date=DATE)
    assert len(report.luminaires) == 3 and len(report.ugr_tables) == 1
    html = render_html(path, results, date=DATE)
    heading = f"UGR table: {report.ugr_tables[0].title}"
    assert html.count(heading) == 1 and "batwing_panel.ldt" not in html
    assert "S = 0.25 H. Corrections for other spacings are not given." in html
    expected = lightsolver.ugr_table(str(lum_dir / "batwing_panel.ldt"))
    block = html.split(heading, 1)[1].split("</table>", 1)[0]
    body = block.split("<tbody>", 1)[1]
    printed = [re.findall(r'<td class="r[^"]*">([^<]*)</td>', row)
               for row in re.findall(r"<tr[^>]*>(.*?)</tr>", body, re.S)]
    assert len(printed) == 19
    for row, cells in zip(expected["rows"], printed):
        assert cells == [f"{v:.1f}" for v in row["crosswise"] + row["endwise"]]
    assert [r.x_h for r in report.ugr_tables[0].ugr_table.rows][:7] == [2.0] * 6 + [4.0]
    # The headline in the schedule is the table's 4H x 8H, 0.7/0.5/0.2 entry.
    row = next(r for r in expected["rows"] if (r["x_h"], r["y_h"]) == (4.0, 8.0))
    assert report.luminaires[0].ugr_4h8h == (row["crosswise"][0], row["endwise"][0])

def test_large_grids_print_every_kth_value():
    import numpy as np

    from lightsolver_report.model import GridData
    from lightsolver_report.plots import chart_svg

    lux = np.arange(60 * 50, dtype=float).reshape(50, 60) + 100.0
    svg, note = chart_svg(GridData(lux, 12.0, 10.0), "big")
    assert note == "every 3rd column and every 2nd row (and the Emin and Emax cells)"
    assert svg.count("<text") < 20 * 25 + 2 + 40  # values (+ the extremes) and axis labels
    assert chart_svg(GridData(lux, 12.0, 10.0), "big") == (svg, note)


def test_dates_and_bad_output_names(tmp_path, monkeypatch):
    assert lightsolver_report.report_date("2025-03-04") == "2025-03-04"
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    assert lightsolver_report.report_date() == "2023-11-14"
    with pytest.raises(ReportError, match="YYYY-MM-DD"):
        lightsolver_report.report_date("04.03.2025")
    scene, results = fixture("room")
    with pytest.raises(ReportError, match=r"\.html or \.pdf"):
        render(scene, results, tmp_path / "report.docx")
    assert not list(tmp_path.iterdir())


def test_missing_jinja2_is_named_with_its_package(tmp_path):
    scene = FIXTURES / "room.scene.json"
    code = ("import sys; sys.modules['jinja2'] = None\n"
            "from lightsolver_report.__main__ import main\n"
            f"sys.exit(main([{str(scene)!r}, '--results', "
            f"{str(FIXTURES / 'room.results.json')!r}, '--allow-unverified', '--out', "
            f"{str(tmp_path / 'r.html')!r}]))")
    r = subprocess.run(["/usr/bin/python3", "-c", code], capture_output=True, text=True,
                       env={**os.environ, "PYTHONPATH": os.pathsep.join(_pythonpath())})
    assert r.returncode == 1 and "python3-jinja2" in r.stderr, r.stderr


def _pythonpath():
    return [str(Path(lightsolver.__file__).parent),
            str(Path(lightsolver_report.__file__).parent.parent)]


# --- lightsolver report (the CLI) ------------------------------------------------------------

def run_cli(cli, *args, env=None):
    return subprocess.run([cli, "report", *args], capture_output=True, text=True, timeout=300,
                          env=env)


def test_cli_report_gives_the_golden_html(cli, tmp_path):
    out = tmp_path / "room.html"
    r = run_cli(cli, str(FIXTURES / "room.scene.json"), "--results",
                str(FIXTURES / "room.results.json"), "--allow-unverified", "--date", DATE,
                "--out", str(out))
    assert r.returncode == 0, r.stderr
    assert out.read_text(encoding="utf-8") == (FIXTURES / "room.report.html").read_text(
        encoding="utf-8")
    r = run_cli(cli, "--help")
    assert r.returncode == 0 and "--results" in r.stdout and "--out" in r.stdout


def test_cli_report_names_what_is_missing(cli, tmp_path):
    args = [str(FIXTURES / "room.scene.json"), "--results", str(FIXTURES / "room.results.json"),
            "--out", str(tmp_path / "r.html")]
    r = run_cli(cli, *args, env={**os.environ, "LIGHTSOLVER_PYTHON": "/nowhere/python3"})
    assert r.returncode == 1 and "needs Python 3" in r.stderr and "LIGHTSOLVER_PYTHON" in r.stderr
    r = run_cli(cli, *args, env={**os.environ, "LIGHTSOLVER_PYTHONPATH": str(tmp_path)})
    assert r.returncode == 1 and "lightsolver_report" in r.stderr
    assert "LIGHTSOLVER_PYTHONPATH" in r.stderr
    r = run_cli(cli, *args[:-1], str(tmp_path / "r.txt"))
    assert r.returncode == 1 and ".html or .pdf" in r.stderr
    assert not (tmp_path / "r.html").exists()


@pytest.mark.parametrize("shape", [(1, 5), (4, 1), (1, 1), (100, 120)])
def test_plans_of_thin_dark_and_large_grids(shape):
    import numpy as np

    from lightsolver_report.model import GridData
    from lightsolver_report.plots import chart_svg, colour_range, iso_levels, plan_svg

    nv, nu = shape
    rng = np.random.default_rng(1)
    for lux in (np.zeros(shape), 300.0 + 50.0 * rng.random(shape)):
        grid = GridData(lux, 0.1 * nu, 0.1 * nv)
        low, high = colour_range(lux)
        assert low <= lux.min() and high >= lux.max() and high > low
        assert all(lux.min() < level < lux.max() for level in iso_levels(lux))
        svg = plan_svg(grid, "p")
        assert svg.startswith("<svg") and svg == plan_svg(grid, "p")
        assert chart_svg(grid, "c")[0].startswith("<svg")


def test_names_are_escaped(tmp_path):
    scene, results = fixture("room")
    scene_dict = json.loads(scene.read_text())
    scene_dict["metadata"]["labels"] = {"workplane": "<b>work & plane</b>"}
    html = render_html(scene_dict, results, scene_path=scene, date=DATE)
    assert "&lt;b&gt;work &amp; plane&lt;/b&gt;" in html and "<b>work" not in html


def test_partial_results_are_said_on_the_cover():
    scene, results = fixture("room")
    results = dict(results, partial=True, stop_reason="cancelled", photons=1000)
    html = render_html(scene, results, date=DATE)
    cover = html[:html.index('<section class="page">')]
    assert "Partial results" in cover


@pytest.mark.parametrize("name", NAMES)
def test_fixture_results_follow_the_results_schema(name):
    # The fixtures carry issue 13's contract fields (requirements, verdicts, intervals); once
    # the schema describes them, the fixtures must validate against it exactly.
    jsonschema = pytest.importorskip("jsonschema")
    schema = json.loads((SOURCE_DIR / "docs" / "schemas" / "results.schema.json").read_text())
    if "verdicts" not in schema["$defs"]["target"]["properties"]:
        pytest.skip("the results schema does not describe verdicts yet (issue 13, item 2)")
    _, results = fixture(name)
    errors = [f"{'/'.join(map(str, e.absolute_path))}: {e.message}" for e in
              jsonschema.Draft202012Validator(schema).iter_errors(results)]
    assert not errors, errors


def test_an_unknown_cost_of_deciding_is_said():
    scene, results = fixture("room")
    results["targets"][1]["verdicts"]["emin"]["to_decide"] = {"photons": None, "seconds": None}
    html = render_html(scene, results, date=DATE)
    assert "not estimated" in html and "decided after" not in html
    results["stop_reason"], results["decide"] = "decided", True
    assert "as soon as every requirement was decided" in render_html(scene, results, date=DATE)


def test_tracing_first_leaves_no_numpy_warning(tmp_path, room_scene):
    # The tracer leaves denormals flushed on the calling thread; numpy then warns at its first
    # float-limits query unless the report settled them before tracing. A fresh interpreter,
    # warnings as errors.
    r = subprocess.run(["/usr/bin/python3", "-W", "error::UserWarning", "-m", "lightsolver_report",
                        str(room_scene), "--photons", "20000", "--date", DATE, "--out",
                        str(tmp_path / "r.html")], capture_output=True, text=True, timeout=120,
                       env={**os.environ, "PYTHONPATH": os.pathsep.join(_pythonpath())})
    assert r.returncode == 0 and "subnormal" not in r.stderr, r.stderr


def test_an_observer_is_reported_with_its_ugr_interval_and_verdict(tmp_path):
    """Observers (eyes for discomfort glare) get their own kind of area: the UGR with its
    interval and the ugr_max verdict, the eye's illuminance said to be reflected light."""
    scene = json.loads((SOURCE_DIR / "Examples" / "room" / "room.json").read_text())
    scene["targets"].append({"name": "seated eye", "type": "observer",
                             "position": [1.0, 2.0, 1.2], "view_direction": [1, 0, 0],
                             "requirements": {"ugr_max": 19}})
    path = tmp_path / "room_with_eye.json"
    path.write_text(json.dumps(scene))
    for mesh in scene.get("meshes", []):  # mesh files next to the scene, as in Examples/room
        if "file" in mesh:
            shutil.copy(SOURCE_DIR / "Examples" / "room" / mesh["file"], tmp_path / mesh["file"])
    results = lightsolver.solve(lightsolver.load_scene(str(path)), photons=200_000)
    eye = next(t for t in results["targets"] if t["name"] == "seated eye")
    html = render_html(scene, json.loads(json.dumps(results, default=lambda o: o.tolist())),
                       date=DATE)
    glare = html[html.index("Discomfort glare (UGR)</h2>"):]
    assert "seated eye" in glare and "(1.00, 2.00, 1.20)&nbsp;m" in glare and "0°" in glare
    if eye["ugr"] is not None:
        assert f"{fmt.ugr(eye['ugr'])}</td>" in glare  # the printed UGR is the results' value
    # An eye is no illuminance area: not among the results at a glance nor section 3.
    glance = html[html.index("Results at a glance"):html.index("Discomfort glare at a glance")]
    assert "seated eye" not in glance
    assert "seated eye" not in html[html.index("Calculation areas</h2>"):
                                    html.index("Discomfort glare (UGR)</h2>")]
    verdict = eye["verdicts"]["ugr"]["verdict"]
    assert {"pass": "PASS", "fail": "FAIL", "undecided": "UNDECIDED"}[verdict] in html


def _tilt_scene(tmp_path):
    """A floor lit by the parser corpus's TILT=INCLUDE lamp (type C; factor 0.90 at 45 degrees
    from straight down) aimed 45 degrees off, and a point light: the TILT changes the lamp's
    flux by 10 %."""
    lamp = "lm63_1991_tilt_include.ies"
    shutil.copy(SOURCE_DIR / "Tests" / "fuzz" / "corpus" / "ies" / lamp, tmp_path / lamp)
    scene = {
        "format": "lightsolver.scene/1",
        "materials": {"floor": {"type": "diffuse", "reflectance": 0.3}},
        "meshes": [{"name": "floor", "material": "floor",
                    "vertices": [[0, 0, 0], [4, 0, 0], [4, 4, 0], [0, 4, 0]],
                    "triangles": [[0, 1, 2], [0, 2, 3]]}],
        "luminaires": [{"name": "tilted", "type": "photometric", "file": lamp,
                        "position": [2, 2, 2.5],
                        "aim": [0.7071067811865476, 0, -0.7071067811865476]},
                       {"name": "bulb", "type": "point", "position": [1, 1, 2.5], "flux_lm": 500}],
        "targets": [{"name": "floor grid", "type": "grid", "corner": [0, 0, 0],
                     "edge1": [4, 0, 0], "edge2": [0, 4, 0], "cells": [2, 2]}],
        "settings": {"photons": 20000, "seed": 3}}
    path = tmp_path / "tilt.json"
    path.write_text(json.dumps(scene))
    return path, lamp


def test_the_schedule_prints_the_traced_flux_with_tilt(tmp_path):
    """The schedule's flux is the one the solver traced (results ``luminaires``), TILT applied;
    results without that record fall back to the scene, and the page says so."""
    from lightsolver_report import schedule

    path, lamp = _tilt_scene(tmp_path)
    results = lightsolver_report.trace(path)
    traced = {lum["name"]: lum for lum in results["luminaires"]}
    assert traced["tilted"]["tilt_factor"] == pytest.approx(0.90, abs=1e-12)
    summary = lightsolver.photometry_summary(str(tmp_path / lamp))
    untilted = schedule.scene_flux(json.loads(path.read_text())["luminaires"][0], summary)
    report = build(path, results, date=DATE)
    tilted = next(r for r in report.luminaires if r.file == lamp)
    assert tilted.flux_lm == traced["tilted"]["emitted_flux_lm"]  # the solver's number
    assert tilted.flux_lm == pytest.approx(0.90 * untilted, rel=1e-9)  # measurably not the file's
    assert tilted.tilt_factor == traced["tilted"]["tilt_factor"]
    assert report.traced_flux
    assert report.total_flux_lm == pytest.approx(results["total_flux_lm"], rel=1e-12)
    html = render_html(path, results, date=DATE)
    assert f"{fmt.number(tilted.flux_lm, 5)}<br><span class=\"ci\">TILT × 0.9</span>" in html
    assert ", as traced" in html and "derived from the model" not in html

    older = {k: v for k, v in results.items() if k != "luminaires"}  # an older solver's file
    report = build(path, older, date=DATE)
    derived = next(r for r in report.luminaires if r.file == lamp)
    assert derived.flux_lm == pytest.approx(untilted, rel=1e-12) and not report.traced_flux
    assert report.total_flux_lm != pytest.approx(results["total_flux_lm"], rel=1e-3)
    html = render_html(path, older, date=DATE)
    assert "derived from the model" in html and "TILT ×" not in html
    assert any("without a photometric TILT table" in w for w in report.warnings)


def test_an_observer_grid_is_reported_as_an_observer_grid(tmp_path, room_scene):
    """An observer grid is its own kind of area: its maximum UGR with the simultaneous
    interval, its points and where the maximum is (not "Surface")."""
    scene = json.loads(room_scene.read_text())
    scene["targets"].append({"name": "eyes", "type": "observer_grid", "corner": [0.5, 0.5, 1.2],
                             "edge1": [5.0, 0, 0], "edge2": [0, 3.0, 0], "cells": [2, 2],
                             "view_step_deg": 90, "requirements": {"ugr_max": 19}})
    path = tmp_path / "room_with_eyes.json"
    path.write_text(json.dumps(scene))
    for mesh in scene.get("meshes", []):
        if "file" in mesh:
            shutil.copy(room_scene.parent / mesh["file"], tmp_path / mesh["file"])
    results = lightsolver_report.trace(path, photons=100_000, seed=3)
    eyes = next(t for t in results["targets"] if t["name"] == "eyes")
    assert eyes["ugr"] is not None, "the room's panels give glare somewhere"
    area = next(a for a in build(path, results, date=DATE).areas if a.name == "eyes")
    assert area.type == "observer_grid" and area.ugr_name == "max UGR"
    assert (area.ugr.value, area.ugr.low, area.ugr.high) == (
        eyes["ugr"], eyes["ugr_ci_low"], eyes["ugr_ci_high"])
    assert (len(area.observer_positions), len(area.observer_directions)) == (4, 4)
    at = eyes["observer_grid"]["max_at"]
    assert area.max_at == (tuple(eyes["observer_grid"]["positions"][at["position"]]),
                           tuple(eyes["observer_grid"]["view_directions"][at["direction"]]))
    html = render_html(path, results, date=DATE)
    section = html[re.search(r"<h3>\d+\.1 eyes</h3>", html).start():]
    section = section[:section.index("</section>")]
    assert "Observer grid: 4 eye positions × 4 lines of sight" in section
    assert "Surface" not in section
    assert "%.2f, %.2f, %.2f" % area.max_at[0] in section
    assert f"{fmt.ugr(eyes['ugr'])}</td>" in section  # the maximum, as the results give it
    # Every point's UGR in the table of positions x lines of sight.
    points = section[section.index('class="grid compact points"'):]
    for row in eyes["observer_grid"]["ugr"]:
        for value in row:
            assert f'<td class="r">{fmt.ugr(value)}</td>' in points
    verdict = eyes["verdicts"]["ugr"]["verdict"]
    assert {"pass": "PASS", "fail": "FAIL", "undecided": "UNDECIDED"}[verdict] in section
