"""A year of daylight in the report (issue 27; docs/report.md, "A year of daylight"): the annual
schema against a file the CLI writes now; the section, given only with annual results, with the
weather file's name, place, source and hash, each grid's sDA, ASE, DA, UDI and EN 17037 values
with the intervals and verdicts of annual.json, the undecided cells counted and marked on the
plan; client wording; annual results of another model refused before anything is written; the
HTML of the fixture byte for byte against its golden file; the PDF.

Fixture: Tests/python/fixtures/report_annual (make_fixture.py: the example side-lit room traced
by the solver, and `lightsolver annual` of it with the Chicago weather file). After a deliberate
change, regenerate the golden with LIGHTSOLVER_REPORT_UPDATE=1 (as test_report.py)."""
import copy
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import lightsolver_report
import lightsolver_results
from lightsolver_report import ReportError, build, render_html, write_pdf
from lightsolver_report.annual import SHORT_HASH, fraction_text, percent_text

from conftest import SOURCE_DIR
from test_report import DATE, UPDATE
from test_report_daylight import section, visible_text

DATA = Path(__file__).resolve().parent / "fixtures" / "report_annual"
SCENE = DATA / "side_lit_room.scene.json"
RESULTS = DATA / "side_lit_room.results.json"
ANNUAL = DATA / "annual.json"
GOLDEN = DATA / "side_lit_room.report.html"
CHICAGO = SOURCE_DIR / "Tests/native/sun/data/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw"
SCHEMA = SOURCE_DIR / "docs/schemas/annual.schema.json"


def annual():
    return json.loads(ANNUAL.read_text(encoding="utf-8"))


def results():
    return json.loads(RESULTS.read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def page():
    return render_html(SCENE, results(), date=DATE, annual=ANNUAL)


def grid_part(page: str) -> str:
    return section(page, "5.1 Work plane", "</figure>")


# --- the schema ---------------------------------------------------------------------------------

def test_the_schema_holds_a_file_the_cli_writes_now(tmp_path):
    jsonschema = pytest.importorskip("jsonschema")
    schema = json.loads(SCHEMA.read_text(encoding="utf-8"))
    jsonschema.Draft202012Validator.check_schema(schema)
    out = tmp_path / "out"
    r = subprocess.run([os.environ["LIGHTSOLVER_CLI"], "annual", str(SCENE), "--weather",
                        str(CHICAGO), "--photons", "50000", "--out-dir", str(out)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    doc = json.loads((out / "annual.json").read_text())
    jsonschema.validate(doc, schema, cls=jsonschema.Draft202012Validator)
    assert lightsolver_results.check_annual(doc) == []
    jsonschema.validate(annual(), schema, cls=jsonschema.Draft202012Validator)  # the fixture


@pytest.mark.parametrize("change, field", [
    (lambda d: d["weather"].pop("sha256"), "sha256"),
    (lambda d: d["weather"].update(sha256="3cc3"), "sha256"),
    (lambda d: d["grids"][0]["metrics"].update(ase_verdict="undecided"), "ase_verdict"),
    (lambda d: d["grids"][0]["metrics"]["sda_percent"].update(high=101.0), "sda_percent"),
    (lambda d: d["grids"][0]["metrics"]["cells"]["sda_verdict"].__setitem__(0, "maybe"),
     "sda_verdict"),
    (lambda d: d.update(grids=[]), "grids"),
    (lambda d: d["trace"].update(photons=-1), "photons")])
def test_the_reader_refuses_what_breaks_the_schema_naming_the_field(change, field):
    pytest.importorskip("jsonschema")
    doc = annual()
    change(doc)
    with pytest.raises(lightsolver_results.ResultsError, match=field):
        lightsolver_results.read_annual(doc)
    lightsolver_results.read_annual(doc, check_schema=False)  # the view itself reads it


def test_without_a_sun_ase_is_null_in_the_schema_and_the_view():
    pytest.importorskip("jsonschema")
    doc = annual()
    m = doc["grids"][0]["metrics"]
    m.update(ase_percent=None, ase_verdict=None)
    m["cells"]["ase_hours"] = None
    view = lightsolver_results.read_annual(doc)
    assert view.grids[0].ase_percent is None and view.grids[0].cell_ase_hours == []


# --- the section --------------------------------------------------------------------------------

def test_annual_html_is_byte_identical_to_the_golden(page):
    if UPDATE:
        GOLDEN.write_text(page, encoding="utf-8")
    assert page == GOLDEN.read_text(encoding="utf-8"), (
        "the annual report changed; if deliberately, regenerate with "
        "LIGHTSOLVER_REPORT_UPDATE=1 (test_report.py's docstring)")
    assert render_html(SCENE, results(), date=DATE, annual=annual()) == page


def test_the_section_appears_only_when_given(page):
    plain = render_html(SCENE, results(), date=DATE)
    assert "A year of daylight" not in plain and "Weather data" not in plain
    assert "5 A year of daylight" in page
    assert build(SCENE, results(), date=DATE).annual is None
    # Everything else on the page is as without it (the section and its lines only).
    assert visible_text(plain).split(" 4 Daylight ")[1].split(" 5 How to read")[0] \
        in visible_text(page)


def test_the_weather_file_its_place_source_and_hash(page):
    w = annual()["weather"]
    part = section(page, "5 A year of daylight", "5.1 Work plane")
    text = visible_text(part)
    assert w["file"] in text and "Chicago Ohare Intl Ap, IL, USA" in text
    assert "41.98° N, 87.92° W, local standard time UTC−6 h" in text
    assert "source: TMY3" in text and "8 760 hours, of which 4 414 with daylight" in text
    # The hash shortened visibly, in full in small print, and in the provenance block.
    assert f"<code>{w['sha256'][:SHORT_HASH]}…</code>" in part
    assert f'<span class="small fingerprint">SHA-256 of the weather file: <code>{w["sha256"]}' \
        in part
    prov = section(page, "Provenance and sign-off", "</table>")
    assert f"<code>{w['sha256']}</code>" in prov and w["file"] in prov
    assert "Perez all-weather sky" in text and "145 patches" in text
    assert "IES LM-83: every day 8:00–18:00 local standard time: 3 650 hours" in text
    assert "4 380 hours (EN 17037" in text


def test_each_metric_with_its_interval_and_verdict(page):
    g = annual()["grids"][0]
    m = g["metrics"]
    part = grid_part(page)
    text = visible_text(part)
    sda = m["sda_percent"]
    assert sda["low"] <= sda["estimate"] <= sda["high"]
    assert f"[{percent_text(sda['low'])}, {percent_text(sda['high'])}]" in part
    rows = section(part, '<table class="grid stats annual-lm83">', "</table>")
    badges = re.findall(r"badge v-(\w+)", rows)
    assert badges == [m["sda_nominal_verdict"], m["sda_preferred_verdict"], m["ase_verdict"]]
    assert f">{percent_text(m['ase_percent'])}</td>" in rows and "exact (no interval)" in rows
    da = m["da_fraction"]
    assert f">{fraction_text(da['estimate'])}</td>" in rows
    assert f"[{fraction_text(da['low'])}, {fraction_text(da['high'])}]" in rows
    udi = section(part, '<table class="grid stats annual-udi">', "</table>")
    for key in ("udi_below_fraction", "udi_useful_fraction", "udi_above_fraction",
                "udi_useful_alt_fraction", "udi_above_alt_fraction"):
        s = m[key]
        assert s["low"] <= s["estimate"] <= s["high"]
        assert f"{fraction_text(s['estimate'])}</td>" in udi
        assert f"[{fraction_text(s['low'])}, {fraction_text(s['high'])}]" in udi, key
    en = section(part, '<table class="grid stats annual-en17037"', "</table>")
    expected = []
    for level in m["en17037"]:
        for which in ("target", "minimum"):
            c = level[which]
            f = c["hours_fraction"]
            assert f"[{fraction_text(f['low'])}, {fraction_text(f['high'])}]" in en
            expected.append(c["verdict"])
            if which == "target":
                expected.append(level["verdict"])
    assert re.findall(r"badge v-(\w+)", en) == expected
    # The fixture shows every kind of verdict.
    assert {"pass", "fail", "undecided"} <= set(re.findall(r"badge v-(\w+)", part))
    assert "sDA 300/50%" in text and "ASE 1000,250h" in text and "mean DA 300" in text


def test_undecided_cells_are_counted_and_marked_on_the_plan(page):
    cells = annual()["grids"][0]["metrics"]["cells"]
    undecided = cells["sda_verdict"].count("undecided")
    passing = cells["sda_verdict"].count("pass")
    assert undecided > 0  # the fixture's few photons leave some
    text = visible_text(grid_part(page))
    assert f"{passing} of 60 cells surely reach DA 300 ≥ 50 %, {undecided} are undecided" in text
    da_plan = section(page, 'id="daplan0', "</svg>")
    assert da_plan.count(">?<") == undecided
    assert "DA300 [%]" in da_plan and "50 %" in da_plan
    over = sum(h > 250 for h in cells["ase_hours"])
    assert f"{over} of 60 cells get direct sun above 1000 lx for more than 250" in text
    assert 'id="aseplan0' in page and "250 h" in section(page, 'id="aseplan0', "</svg>")
    assert "neither counted nor dropped" in visible_text(page)


def test_no_sun_no_ase_plan_and_the_page_says_so():
    doc = annual()
    m = doc["grids"][0]["metrics"]
    m.update(ase_percent=None, ase_verdict=None)
    m["cells"]["ase_hours"] = None
    page = render_html(SCENE, results(), date=DATE, annual=doc)
    assert "no sun in this calculation" in page and 'id="aseplan0' not in page
    assert 'id="daplan0' in page


def test_the_trace_facts_in_the_appendix(page):
    doc = annual()
    part = section(page, "<h3>A year of daylight</h3>", "</table>")
    text = visible_text(part)
    assert "100 000 traced once for the 145 sky patches" in text
    assert f"Seed {doc['trace']['seed']}" in text and "embree" in text
    assert "Traced until decided no" in text


def test_the_annual_traces_remarks_are_worded_for_the_client():
    doc = annual()
    doc["warnings"] = ['target "work plane": 3 cells received no photon']
    page = render_html(SCENE, results(), date=DATE, annual=doc)
    notes = section(page, '<table class="facts run tech annual-trace">', "</ul>")
    assert "Target “Work plane”: 3 cells received no photon" in notes
    assert "work plane" not in notes


def test_no_internal_keys_or_file_names_other_than_the_weathers(page):
    body = visible_text(page[:page.index("Appendix: technical notes")])
    for word in ("sda_percent", "udi_", "en17037", "annual.json", "annual.npz", ".json",
                 "side_lit_room", "ase_hours", "work plane", "lightsolver.annual", "None"):
        assert word not in body, word
    assert not re.search(r"\b(nan|inf)\b", body, re.I)
    assert annual()["weather"]["file"] in body


# --- refused --------------------------------------------------------------------------------------

def _tree(root):
    return sorted(str(p.relative_to(root)) for p in Path(root).rglob("*"))


@pytest.mark.parametrize("change, match", [
    (lambda d: d["grids"][0].update(name="office"), "'office' is not a grid of the scene"),
    (lambda d: d["grids"][0].update(nu=20, nv=15, cells=300), "20 × 15 cells"),
    (lambda d: d.update(format="lightsolver.results/1"), "lightsolver.annual/1")])
def test_annual_results_of_another_model_are_refused_writing_nothing(tmp_path, change, match):
    doc = annual()
    change(doc)
    path = tmp_path / "in" / "annual.json"
    path.parent.mkdir()
    path.write_text(json.dumps(doc))
    before = _tree(tmp_path)
    with pytest.raises(ReportError, match=match) as caught:
        lightsolver_report.render(SCENE, RESULTS, tmp_path / "r.html", date=DATE,
                                  annual=path)
    assert str(path) in str(caught.value)
    assert _tree(tmp_path) == before


def test_an_unreadable_annual_file_is_refused_by_python_m(tmp_path):
    broken = tmp_path / "annual.json"
    broken.write_text(ANNUAL.read_text()[:5000])
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(Path(lightsolver_report.__file__).parent.parent)] + sys.path)}
    r = subprocess.run([sys.executable, "-m", "lightsolver_report", str(SCENE), "--results",
                        str(RESULTS), "--annual", str(broken), "--out", str(tmp_path / "r.html")],
                       capture_output=True, text=True, timeout=300, env=env)
    assert r.returncode == 1 and str(broken) in r.stderr, r.stderr
    assert not (tmp_path / "r.html").exists()
    r = subprocess.run([sys.executable, "-m", "lightsolver_report", str(SCENE), "--results",
                        str(RESULTS), "--annual", str(ANNUAL), "--date", DATE, "--out",
                        str(tmp_path / "r.html")], capture_output=True, text=True, timeout=300,
                       env=env)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "r.html").read_text(encoding="utf-8") == render_html(
        SCENE, results(), date=DATE, annual=ANNUAL)


# --- the PDF ------------------------------------------------------------------------------------

def test_pdf_of_the_annual_report(tmp_path, page):
    if not (shutil.which("pdftoppm") and shutil.which("pdftotext")):
        pytest.skip("poppler-utils (pdftoppm, pdftotext) not installed")
    pdf = tmp_path / "annual.pdf"
    write_pdf(page, pdf)
    text = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], check=True,
                          capture_output=True, text=True).stdout
    for words in ("5 A year of daylight", "5.1 Work plane", "Useful daylight illuminance",
                  "✗ FAIL", "? UNDECIDED", "✓ PASS", annual()["weather"]["sha256"]):
        assert words in text, words
    pages = text.split("\f")
    page_no = next(i for i, p in enumerate(pages, 1) if "5.1 Work plane" in p)
    subprocess.run(["pdftoppm", "-r", "40", "-gray", "-f", str(page_no), "-l", str(page_no),
                    str(pdf), str(tmp_path / "an")], check=True)
    from test_report import _ink_fraction

    (pgm,) = tmp_path.glob("an-*.pgm")
    assert 0.02 < _ink_fraction(pgm) < 0.6
    # The plans' page: drawn, not empty.
    plans = next(i for i, p in enumerate(pages, 1) if "Direct sunlight on Work plane" in p)
    subprocess.run(["pdftoppm", "-r", "40", "-gray", "-f", str(plans), "-l", str(plans),
                    str(pdf), str(tmp_path / "plans")], check=True)
    (pgm,) = tmp_path.glob("plans-*.pgm")
    assert _ink_fraction(pgm) > 0.1


def test_the_scene_fixture_is_the_example_room():
    example = json.loads((SOURCE_DIR / "Examples/daylight/annual_side_lit_room.scene.json")
                         .read_text())
    scene = json.loads(SCENE.read_text())
    assert scene["meshes"] == example["meshes"] and scene["materials"] == example["materials"]
    assert copy.deepcopy(scene["luminaires"]) == example["luminaires"]


def test_lightsolver_report_passes_annual_on(cli, tmp_path):
    out = tmp_path / "r.html"
    r = subprocess.run([cli, "report", str(SCENE), "--results", str(RESULTS), "--annual",
                        str(ANNUAL), "--date", DATE, "--out", str(out)], capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert out.read_text(encoding="utf-8") == render_html(SCENE, results(), date=DATE,
                                                          annual=ANNUAL)
    r = subprocess.run([cli, "report", str(SCENE), "--results", str(RESULTS), "--annual",
                        str(tmp_path / "none.json"), "--out", str(tmp_path / "s.html")],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode != 0 and "none.json" in r.stderr and not (tmp_path / "s.html").exists()


def test_electric_light_beside_daylight_when_the_run_has_it():
    doc = annual()
    doc["grids"][0]["electric"] = {
        "target_lx": 500.0, "occupied_hours": 3650, "critical_value_hour": 4.5,
        "electric_lx": {"estimate": 612.0, "low": 598.0, "high": 626.0},
        "hours_below_target": {"estimate": 1234.0, "low": 1180.0, "high": 1301.0},
        "mean_output_fraction": {"estimate": 0.183, "low": 0.171, "high": 0.197}}
    page = render_html(SCENE, results(), date=DATE, annual=doc)
    assert "Electric light beside daylight" in page
    assert "1234" in page and "[1180, 1301]" in page and "of 3650" in page
    assert "18.3" in page
    assert "Electric light beside daylight" not in render_html(SCENE, results(), date=DATE,
                                                              annual=annual())
