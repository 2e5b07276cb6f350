"""The report's daylight (issue 26; docs/report.md, "Daylight"): a page per daylight-factor
grid with its statistics and intervals, the sky and outside illuminance, the EN 17037
requirements and verdicts; skies and suns in a daylight schedule of their own (not luminaires:
no lumens, watts, MF, plan marks, installed power or LENI); sunlight exposure; the HTML of the
side-lit room byte for byte against its golden file.

Fixture: Tests/python/fixtures/report_daylight (make_scene.py writes the scene,
make_fixture.py the results, traced by the solver: its daylight factors, EN 17037 verdicts and
sunlight exposure). After a deliberate change,
regenerate the golden with LIGHTSOLVER_REPORT_UPDATE=1 (as test_report.py)."""
import copy
import html as htmllib
import json
import math
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from lightsolver_report import build, fmt, render_html, write_pdf

from test_report import DATE, UPDATE

DATA = Path(__file__).resolve().parent / "fixtures" / "report_daylight"
SCENE = DATA / "side_lit_room.scene.json"
GOLDEN = DATA / "side_lit_room.report.html"
#: EN 17037:2018 Table A.1, (E_T, E_TM) in lx.
EN17037 = {"minimum": (300, 100), "medium": (500, 300), "high": (750, 500)}


def results():
    return json.loads((DATA / "side_lit_room.results.json").read_text(encoding="utf-8"))


def scene():
    return json.loads(SCENE.read_text(encoding="utf-8"))


def visible_text(page: str) -> str:
    """The words a reader sees, without tags, styles and the inline pictures; any run of
    white space (no-break and thin spaces too) as one space."""
    page = re.sub(r"<style>.*?</style>|<svg.*?</svg>", " ", page, flags=re.S)
    return re.sub(r"\s+", " ", htmllib.unescape(re.sub(r"<[^>]+>", " ", page)))


def section(page: str, start: str, end: str) -> str:
    i = page.index(start)
    return page[i:page.index(end, i)]


@pytest.fixture(scope="module")
def page():
    return render_html(SCENE, results(), date=DATE)


def test_daylight_html_is_byte_identical_to_the_golden(page):
    if UPDATE:
        GOLDEN.write_text(page, encoding="utf-8")
    assert page == GOLDEN.read_text(encoding="utf-8"), (
        "the daylight report changed; if deliberately, regenerate with "
        "LIGHTSOLVER_REPORT_UPDATE=1 (test_report.py's docstring)")
    assert render_html(SCENE, results(), date=DATE) == page


def test_each_df_grid_has_its_page_with_statistics_in_their_intervals(page):
    res = results()
    labels = scene()["metadata"]["labels"]
    text = visible_text(page)
    for n, target in enumerate(res["targets"], start=1):
        df = target["daylight_factor"]
        label = labels[target["name"]]
        part = section(page, f"4.{n} Daylight factor: {label}", "</figure>")
        for stem in ("mean", "p50", "p95", "min"):
            key = "" if stem == "mean" else f"{stem}_"
            value = df[f"{key}percent" if key else "mean_percent"]
            low = df[f"{key}ci_low_percent" if key else "ci_low_percent"]
            high = df[f"{key}ci_high_percent" if key else "ci_high_percent"]
            assert low <= value <= high
            assert f"{fmt.df(value)}</td>" in part
            assert f"[{fmt.df(low)}, {fmt.df(high)}]" in part
        assert "10\u202f000&nbsp;lx on an unobstructed horizontal plane" in part
        assert "traditional CIE overcast sky (Moon &amp; Spencer)" in part
        assert "reflectance 0.20" in part and "τ<sub>v</sub>&nbsp;0.70" in part
        assert 'id="dfplan' in part and "D [%]" in part  # the plan in percent, its legend
        # Every verdict on the page as the results give it, with the requirement.
        for key, verdict in target["verdicts"].items():
            share = "50" if key == "df_target" else "95"
            assert (f"D ≥ {fmt.df(verdict['required'])}&nbsp;% over {share}&nbsp;% of the area"
                    in part)
        words = re.findall(r'badge v-(\w+)', section(part, "<tbody>", "</tbody>"))
        # Printed D_50 % before D_95 %, whatever the order of the results' keys.
        order = [k for k in ("df_target", "df_minimum") if k in target["verdicts"]]
        assert words == [target["verdicts"][k]["verdict"] for k in order]
        assert f"Verdict for {label}: <span class=\"badge v-{target['verdict']}\"" in part
    # The undecided one says what deciding it takes.
    undecided = res["targets"][0]["verdicts"]["df_minimum"]
    assert undecided["verdict"] == "undecided"
    assert f"about {fmt.sci(undecided['to_decide']['photons'])} light paths" in page
    assert "already" not in text and "alone is still undecided" in text
    assert "Daylight at a glance" in text and "Overall verdict" in text
    # On the cover, a failed grid is not "decided after" more light paths: it is decided.
    compliance = section(page, '<table class="grid summary">', "</table>")
    row = section(compliance, "<td>Reference plane", "</tr>")
    assert "badge v-fail" in row and "decided after" not in row


def test_en17037_requirements_are_derived_and_said(page):
    res = results()
    reference, window = res["targets"]
    req = reference["requirements"]
    e_t, e_tm = EN17037[req["en17037"]]
    median = req["median_diffuse_lx"]
    assert req["df_target_percent"] == pytest.approx(e_t / median * 100, rel=1e-12)
    assert req["df_minimum_percent"] == pytest.approx(e_tm / median * 100, rel=1e-12)
    text = visible_text(section(page, "4.1 Daylight factor", "4.2 Daylight factor"))
    assert "level minimum" in text and "E T = 300 lx over 50 %" in text
    assert "E v,d,med = 14 800 lx" in text
    assert f"D T = E T / E v,d,med = {fmt.df(req['df_target_percent'])} %" in text
    # The window zone's targets are the designer's own, not a level's.
    text = visible_text(section(page, "4.2 Daylight factor", "</figure>"))
    assert "Requirements set by the designer" in text and "EN 17037:2018, daylight" not in text
    assert window["requirements"] == {"df_target_percent": 2.0, "df_minimum_percent": 1.0}


def test_the_fixture_df_follows_from_the_traced_cells():
    """The daylight factors are the sky's part of each cell over E_out (docs/scene-format.md, "Targets"), the
    order statistics and their intervals consistent with the cells, as the solver wrote them."""
    res = results()
    sky = next(lum for lum in scene()["luminaires"] if lum["type"] == "sky")
    for target in res["targets"]:
        df = target["daylight_factor"]
        assert df["sky"] == sky["name"]
        assert df["outside_illuminance_lx"] == sky["diffuse_horizontal_lx"]
        part = target["contributions"][sky["group"]]
        e_out = df["outside_illuminance_lx"]
        cells = df["cells"]
        assert len(cells) == math.prod(target["cells_uv"])
        for c, lux in zip(cells, part["cells"]):
            assert c["percent"] == pytest.approx(lux["lux"] / e_out * 100, rel=1e-6)
            assert c["ci_low_percent"] <= c["percent"] <= c["ci_high_percent"]
        assert df["mean_percent"] == pytest.approx(part["illuminance_lux"] / e_out * 100,
                                                   rel=1e-6)
        values = sorted((c["percent"] for c in cells), reverse=True)
        for stem, share in (("p50", 0.5), ("p95", 0.95)):
            k = math.ceil(share * len(values))
            # Reached or exceeded over the share: at least k cells at or above it.
            assert sum(v >= df[f"{stem}_percent"] for v in values) >= k
            assert df[f"{stem}_ci_low_percent"] <= df[f"{stem}_percent"] \
                <= df[f"{stem}_ci_high_percent"]
        assert df["min_percent"] == pytest.approx(values[-1], rel=1e-9)
        # The grid's lux stays all light (sky, sun and the panel): more than the sky's part.
        assert target["mean_lux"] > part["illuminance_lux"]


def test_skies_and_suns_are_daylight_not_luminaires(page):
    report = build(SCENE, results(), date=DATE)
    assert [row.names for row in report.luminaires] == [["Ceiling panel"]]
    assert report.total_power_w == 25.0 and report.total_count == 1
    assert all(a.power_density_w_m2 is None for a in report.areas)  # DF grids: no W/m²
    (sky,), (sun,) = report.skies, report.suns
    assert sky.label == "Overcast sky" and sky.ground_reflectance == 0.2
    (opening,) = sky.openings
    assert opening.area_m2 == pytest.approx(3.6) and opening.facing == "south (180°)"
    assert opening.effective == pytest.approx(0.7 * 0.8 * 0.9)
    assert sun.elevation_deg == pytest.approx(37.756, abs=0.01)  # lightsolver.sun_position
    assert sun.azimuth == "south (176°)" and sun.direct_normal_lx == 70000
    schedule = section(page, "Daylight: sky, sun and openings", "</table>")
    assert "10\u202f000 lx diffuse horizontal" in schedule and "70\u202f000&nbsp;lx" in schedule
    assert "2026-03-21 12:00 (UTC+01:00), 52.52° N, 13.40° E" in schedule
    luminaires = section(page, '<table class="grid luminaires">', "</table>")
    assert "Overcast sky" not in luminaires and "Sun, 21 March" not in luminaires
    plans = section(page, "Plans and view of the model", "4 Daylight")
    assert "Overcast sky" not in visible_text(plans)  # no sky or sun marked in the room
    # The picture of the model colours the DF grids by their daylight factor (no lux grid).
    assert "Daylight-factor grids (cell by cell) in false colours by their daylight factor" \
        in plans and plans.count("D [%]") == 1
    flux = {lum["name"]: lum["emitted_flux_lm"] for lum in results()["luminaires"]}
    assert f">{fmt.number(flux['sky'], 4)}</td>" in schedule


def test_a_daylight_only_model_has_no_installation_row(tmp_path):
    data = scene()
    data["luminaires"] = [lum for lum in data["luminaires"] if lum["type"] in ("sky", "sun")]
    res = results()
    res["luminaires"] = [lum for lum in res["luminaires"] if lum["type"] in ("sky", "sun")]
    page = render_html(data, res, scene_path=SCENE, date=DATE)
    assert "No electric lighting: the model is lit by daylight only." in page
    assert "<th>Installation</th>" not in page and "<th>Daylight</th>" in page
    assert build(data, res, scene_path=SCENE, date=DATE).total_power_w is None


def test_sunlight_exposure_is_a_table_of_points(page):
    res = results()["sunlight_exposure"]
    part = section(page, "Sunlight exposure (EN 17037)", "</table>")
    text = visible_text(part)
    assert res["date"] in text and "at least 11° above the horizon" in text
    assert "52.52° N, 13.40° E, local time UTC+1 h" in text
    for point in res["points"]:
        row = section(part, f"<td>{point['name']}</td>", "</tr>")
        assert fmt.sunhours(point["hours"]) in row
        for a, b in point["periods"]:
            assert f"{a}–{b}" in row
        assert f"<strong>{point['level']}</strong>" in row
        minutes = sum(_minutes(b) - _minutes(a) for a, b in point["periods"])
        assert minutes == pytest.approx(point["hours"] * 60)  # the periods hold the hours
    changed = copy.deepcopy(results())
    changed["sunlight_exposure"]["points"][0].update(hours=1.2, level="none", periods=[])
    text = visible_text(render_html(SCENE, changed, date=DATE))
    assert "none (under 1.5 h)" in text and "1 h 12 min" in text


def _minutes(clock: str) -> int:
    hours, minutes = clock.split(":")
    return 60 * int(hours) + int(minutes)


def test_no_internal_keys_or_file_names_on_the_page(page):
    body = visible_text(page[:page.index("Appendix: technical notes")])
    for word in ("daylight_factor", "df_target", "df_minimum", "en17037", "cie_overcast",
                 "median_diffuse_lx", "side_lit_room", ".json", "portal", "sky luminaire"):
        assert word not in body, word
    # The results schema describes every daylight field: the reader has nothing to note.
    report = build(SCENE, results(), date=DATE)
    assert [note.text for note in report.notes] == []


def test_pdf_of_the_daylight_report(tmp_path, page):
    if not (shutil.which("pdftoppm") and shutil.which("pdftotext")):
        pytest.skip("poppler-utils (pdftoppm, pdftotext) not installed")
    pdf = tmp_path / "daylight.pdf"
    write_pdf(page, pdf)
    text = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], check=True,
                          capture_output=True, text=True).stdout
    for words in ("4.1 Daylight factor: Reference plane", "4.2 Daylight factor: Desks by the",
                  "Sunlight exposure (EN 17037)", "Daylight: sky, sun and openings",
                  "✗ FAIL", "? UNDECIDED", "✓ PASS"):
        assert words in text, words
    page_no = next(i for i, p in enumerate(text.split("\f"), 1) if "4.1 Daylight factor" in p)
    subprocess.run(["pdftoppm", "-r", "40", "-gray", "-f", str(page_no), "-l", str(page_no),
                    str(pdf), str(tmp_path / "df")], check=True)
    from test_report import _ink_fraction

    (pgm,) = tmp_path.glob("df-*.pgm")
    assert 0.02 < _ink_fraction(pgm) < 0.6


def test_incomplete_daylight_results_print_dashes_never_nan():
    res = results()
    df = res["targets"][0]["daylight_factor"]
    for key in ("p95_percent", "p95_ci_low_percent", "min_ci_high_percent"):
        del df[key]
    df["mean_percent"] = float("nan")
    df["cells"] = df["cells"][:-1]  # not the grid's shape: no plan rather than a wrong one
    page = render_html(SCENE, res, date=DATE)
    part = section(page, "4.1 Daylight factor", "4.2 Daylight factor")
    assert not re.search(r"\b(nan|inf)\b", visible_text(part), re.I)
    assert 'id="dfplan0' not in part and 'id="dfplan1' in page
    rows = section(part, "<tbody>", "</tbody>")
    assert rows.count("–") >= 3  # the missing mean, D95's value and D_min's interval


def test_a_solver_without_df_shows_the_grid_by_its_illuminance():
    res = results()
    for target in res["targets"]:
        for key in ("daylight_factor", "requirements", "verdicts", "verdict"):
            target.pop(key, None)
    res.pop("verdict"), res.pop("sunlight_exposure")
    report = build(SCENE, res, date=DATE)
    assert not report.daylight_areas and report.sunlight is None
    assert [a.label for a in report.illuminance_areas] == ["Reference plane",
                                                          "Desks by the window"]
    page = render_html(SCENE, res, date=DATE)
    assert "Daylight factor:" not in page and "Daylight: sky, sun and openings" in page


def test_a_suns_opening_faces_the_sun_whichever_way_its_edges_turn():
    data = scene()
    sun = next(lum for lum in data["luminaires"] if lum["type"] == "sun")
    sun["edge1"], sun["edge2"] = sun["edge2"], sun["edge1"]  # edge1 × edge2 now outward
    (row,) = build(data, results(), scene_path=SCENE, date=DATE).suns
    assert row.openings[0].facing == "south (180°)"
    del sun["site"], sun["time"]
    sun["direction"] = [0, 1, -1]  # from the south, 45° high
    (row,) = build(data, results(), scene_path=SCENE, date=DATE).suns
    assert row.elevation_deg == pytest.approx(45.0) and row.azimuth == "south (180°)"
    assert row.openings[0].facing == "south (180°)" and row.when == ""
