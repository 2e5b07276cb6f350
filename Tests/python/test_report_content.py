"""What a signed report holds (issue 24, item 4): power from the photometric file, installed
power per area and LENI by their formulas, surfaces listed by part, every light scene's
results as the solver rescales them, the partial mark on every page, the provenance and
sign-off block, and client wording (no file names or internal keys, remarks reworded).

The fixtures are Tests/python/fixtures/report (make_fixtures.py); the golden HTML of each is
checked in test_report.py."""
import json
import re
import shutil
import subprocess

import lightsolver
import pytest

import lightsolver_report
from lightsolver_report import ReportError, build, fmt, render_html
from lightsolver_report.energy import EnergyInputError, read_inputs

from conftest import SOURCE_DIR
from test_report import DATE, FIXTURES, fixture

PARTIAL_MARK = "Partial results — calculation was stopped early"


def page(report):
    """The HTML page of a report object changed after build() (as render's callers set
    ``signoff`` and ``partial``), through the package's templates and filters."""
    import jinja2

    env = jinja2.Environment(loader=jinja2.FileSystemLoader(str(lightsolver_report.TEMPLATES)),
                             autoescape=True, undefined=jinja2.StrictUndefined, trim_blocks=True,
                             lstrip_blocks=True, keep_trailing_newline=True)
    env.filters.update(fmt.FILTERS)
    css = (lightsolver_report.TEMPLATES / "report.css").read_text(encoding="utf-8")
    return env.get_template("report.html.j2").render(report=report, css=css)


# --- power and energy -------------------------------------------------------------------------

def test_power_comes_from_the_photometric_file_when_the_scene_gives_none():
    scene, results = fixture("workbench")
    report = build(scene, results, date=DATE)
    (row,) = report.luminaires
    summary = lightsolver.photometry_summary(str(FIXTURES / row.files[0]))
    assert summary["input_watts"] == 36.0 and row.power_w == 36.0 and row.power_from_file
    assert report.total_power_w == 6 * 36.0
    html = render_html(scene, results, date=DATE)
    assert "Power from the photometric file" in html and "36<sup>*</sup>" in html
    # The scene's power_w wins over the file's and is not marked.
    data = json.loads(scene.read_text())
    for lum in data["luminaires"]:
        lum["power_w"] = 30.0
    row = build(data, results, scene_path=scene, date=DATE).luminaires[0]
    assert row.power_w == 30.0 and not row.power_from_file


def test_eulumdat_wattage_is_the_files_input_watts():
    lum_dir = SOURCE_DIR / "Resources" / "luminaires"
    assert lightsolver.photometry_summary(str(lum_dir / "batwing_panel.ldt"))["input_watts"] \
        == 36.0  # field 26f, wattage including ballast
    assert lightsolver.photometry_summary(str(lum_dir / "batwing_panel.ies"))["input_watts"] \
        == 36.0


def test_installed_power_per_area_and_leni_follow_their_formulas():
    scene, results = fixture("workbench")
    report = build(scene, results, date=DATE)
    workplane = next(a for a in report.areas if a.name == "Workplane")
    assert workplane.power_density_w_m2 == pytest.approx(216.0 / workplane.area_m2, rel=1e-12)
    assert workplane.power_density_w_m2_100lx == pytest.approx(
        workplane.power_density_w_m2 / (workplane.em.value / 100.0), rel=1e-12)
    given = json.loads(scene.read_text())["metadata"]["report"]["energy"]
    leni = report.leni
    lighting = 216.0 * given["constant_illuminance_factor"] * given["occupancy_factor"] * (
        given["daylight_hours"] * given["daylight_dependency_factor"] + given["night_hours"]) / 1000
    assert leni.lighting_kwh == pytest.approx(lighting, rel=1e-12)
    assert leni.leni_kwh_m2 == pytest.approx(
        (lighting + given["parasitic_kwh_m2"] * given["area_m2"]) / given["area_m2"], rel=1e-12)
    html = render_html(scene, results, date=DATE)
    assert f"{fmt.number(leni.leni_kwh_m2, 3)} kWh/(m²·a)" in html
    # No energy inputs, no LENI section; inputs but no power: said why.
    room_scene, room_results = fixture("room")
    assert "Energy estimate" not in render_html(room_scene, room_results, date=DATE)
    office_scene, office_results = fixture("office")
    data = json.loads(office_scene.read_text())
    data["metadata"]["report"] = {"energy": {"daylight_hours": 2000, "night_hours": 500}}
    office = build(data, office_results, scene_path=office_scene, date=DATE)
    assert office.leni is None and "power of every luminaire" in office.leni_missing


@pytest.mark.parametrize("energy, field", [
    ({"daylight_hours": -5, "night_hours": 250}, "daylight_hours"),
    ({"daylight_hours": 2250}, "night_hours"),
    ({"daylight_hours": 8000, "night_hours": 1000}, "must not exceed 8760"),
    ({"daylight_hours": 2250, "night_hours": 250, "occupancy": 0.9}, "occupancy"),
    ({"daylight_hours": 2250, "night_hours": 250, "occupancy_factor": 1.5}, "occupancy_factor"),
    ({"daylight_hours": 2250, "night_hours": float("nan")}, "night_hours"),
])
def test_unusable_energy_inputs_are_refused_naming_the_field(energy, field):
    with pytest.raises(EnergyInputError, match=field):
        read_inputs(energy)
    scene, results = fixture("workbench")
    data = json.loads(scene.read_text())
    data["metadata"]["report"]["energy"] = energy
    with pytest.raises(ReportError, match=f"metadata.report.energy.*{field}"):
        build(data, results, scene_path=scene, date=DATE)


# --- surfaces ---------------------------------------------------------------------------------

def test_surfaces_are_listed_by_part_as_the_model_assigns_materials():
    """The office's slabs carry three materials each: a table by material would read
    "floor material: Floor, Ceiling"; by surface, the ceiling slab's top has the floor
    material and its underside (the room's ceiling) the ceiling material."""
    scene, results = fixture("office")
    report = build(scene, results, date=DATE)
    parts = {s.label: {p.faces: p.material.name for p in s.parts} for s in report.surfaces}
    assert parts["Ceiling"] == {"sides": "default_wall", "underside": "default_ceiling",
                                "top": "default_floor"}
    assert parts["Floor"]["top"] == "default_floor"
    assert parts["Walls"] == {"all faces": "default_wall"}
    desk_top = next(s for s in report.surfaces if s.label == "Desk top")
    assert desk_top.calculation
    html = render_html(scene, results, date=DATE)
    table = html[html.index("Surfaces and reflectances</h2>"):]
    table = table[:table.index("</table>")]
    assert re.search(r"<td>Ceiling</td><td class=\"small\">sides</td><td>default_wall</td>",
                     table)


# --- light scenes -----------------------------------------------------------------------------

def test_each_light_scene_is_the_solvers_rescale_of_the_run():
    scene, results = fixture("workbench")
    report = build(scene, results, date=DATE)
    levels = {s["name"]: s["levels"] for s in json.loads(scene.read_text())["metadata"][
        "light_scenes"]}
    assert [s.name for s in report.light_scenes] == list(levels)
    html = render_html(scene, results, date=DATE)
    for light in report.light_scenes:
        expected = lightsolver.rescale(results, levels[light.name])
        assert light.verdict == expected["verdict"]
        for area, target in zip(light.areas, expected["targets"]):
            assert (area.em.value, area.em.low, area.em.high) == (
                target["mean_lux"], target["ci_low_lux"], target["ci_high_lux"])
            if area.is_glare:
                assert area.ugr.value == target["ugr"]
        assert f"<h3>{light.name}</h3>" in html
    assert "Window row off, Back row 30 %" in html


def test_results_that_are_a_light_scene_say_so_and_rescale_from_it():
    scene, results = fixture("workbench")
    traced = build(scene, results, date=DATE)
    evening = lightsolver.rescale(results, {"Window row": 0.5})
    shown = build(scene, evening, date=DATE)
    assert shown.shown_scene == "light scene Evening (Window row 50 %)"
    # The cover states the installation at full output, whatever the results show.
    assert shown.installed_flux_lm == pytest.approx(results["total_flux_lm"], rel=1e-12)
    assert shown.total_flux_lm == pytest.approx(evening["total_flux_lm"], rel=1e-12)
    assert shown.total_flux_lm < 0.8 * shown.installed_flux_lm
    for mine, theirs in zip(shown.light_scenes, traced.light_scenes):
        for a, b in zip(mine.areas, theirs.areas):
            assert a.em.value == pytest.approx(b.em.value, rel=1e-12)
    # W/m² per 100 lx stays that of the installation at full output.
    full = next(a for a in traced.areas if a.name == "Workplane")
    dimmed = next(a for a in shown.areas if a.name == "Workplane")
    assert dimmed.power_density_w_m2_100lx == pytest.approx(full.power_density_w_m2_100lx,
                                                            rel=1e-12)
    # A group off in the given results cannot be lit again from them.
    off = build(scene, lightsolver.rescale(results, {"Window row": 0.0}), date=DATE)
    evening_view = next(s for s in off.light_scenes if s.name == "Evening")
    assert evening_view.results is None and "Window row is off" in evening_view.missing
    assert off.areas[0].power_density_w_m2_100lx is None


def test_light_scenes_need_each_groups_part():
    scene, results = fixture("room")
    data = json.loads(scene.read_text())
    data["metadata"]["light_scenes"] = [{"name": "Dim", "levels": {"panel 1": 0.5}}]
    html = render_html(data, results, scene_path=scene, date=DATE)
    assert "Not shown: the calculation did not keep each group" in html


# --- partial results, provenance, sign-off ----------------------------------------------------

def test_partial_results_are_marked_on_every_page(tmp_path):
    if not shutil.which("pdftotext"):
        pytest.skip("poppler-utils (pdftotext) not installed")
    scene, results = fixture("workbench")
    report = build(scene, results, date=DATE)
    assert PARTIAL_MARK not in page(report)
    report.partial = True  # as render(allow_partial=True) sets it
    html = page(report)
    assert html.count(PARTIAL_MARK) == 1  # the banner; the page margins repeat it
    pdf = tmp_path / "partial.pdf"
    lightsolver_report.write_pdf(html, pdf)
    text = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], check=True,
                          capture_output=True, text=True).stdout
    pages = [p for p in text.split("\f") if p.strip()]
    assert len(pages) > 3 and all(PARTIAL_MARK in p for p in pages)
    # Results that say they were cancelled are marked too.
    cancelled = dict(results, partial=True, stop_reason="cancelled")
    assert PARTIAL_MARK in render_html(scene, cancelled, date=DATE)


def test_the_provenance_block_shows_what_the_results_record():
    scene, results = fixture("workbench")
    ies = "photometry/LuminaireLayout_r1c1_batwing_panel.ies"
    import hashlib
    digest = hashlib.sha256((FIXTURES / ies).read_bytes()).hexdigest()
    provenance = {"scene_sha256": "a" * 64, "files": [{"path": ies, "sha256": digest}],
                  "solver_version": "0.1.0", "source_commit": "379eac7" + "0" * 33,
                  "build_type": "Release", "backend": "embree", "device": "2 CPU cores",
                  "mpi_ranks": 2, "threads": 4, "options": {"photons": 200000},
                  "started_utc": "2026-01-01T10:00:00Z", "finished_utc": "2026-01-01T10:01:05Z",
                  "host": "build-host-17", "command": "lightsolver run scene.json"}
    report = build(scene, dict(results, provenance=provenance), date=DATE)
    html = page(report)
    block = html[html.index("Provenance and sign-off</h2>"):]
    assert f"<code>{'a' * 64}</code>" in block and f"<code>{digest}</code>" in block
    assert "photometric data: Batwing office panel 600 x 600" in block
    assert "lightsolver 0.1.0 (commit 379eac700000, Release)" in block
    assert "embree, 2 CPU cores, 4 threads, 2 MPI ranks" in block
    assert "2026-01-01T10:00:00Z to 2026-01-01T10:01:05Z (UTC)" in block
    assert "build-host-17" not in html and "scene.json" not in html  # not for the client
    assert "record no provenance" not in block
    # The fingerprint is the results file's when the caller read one, else the content's.
    assert f"<code>{report.provenance.results_sha256}</code>" in block
    assert "SHA-256 of the results content (canonical JSON" in block
    from lightsolver_report.model import build_report
    filed = build_report(json.loads(scene.read_text()), results, scene_name="s", base_dir=str(
        FIXTURES), date=DATE, solver_version="x", results_sha256="b" * 64)
    assert filed.provenance.results_sha256 == "b" * 64
    assert filed.provenance.results_hash_of == "file"
    # Older results: said, and the block still renders.
    old = render_html(scene, {k: v for k, v in results.items() if k != "provenance"}, date=DATE)
    assert "record no provenance" in old


def test_signoff_given_by_the_caller_is_printed_on_the_cover_and_the_block():
    scene, results = fixture("office")
    report = build(scene, results, date=DATE)
    blank = page(report)
    assert "Prepared by · date, signature" in blank  # lines to sign on
    report.signoff = {"project": "Head office", "author": "C. Engineer", "checked_by": "D. Lead"}
    html = page(report)
    cover = html[:html.index('<section class="page">')]
    assert "C. Engineer" in cover and "D. Lead" in cover
    block = html[html.index("Provenance and sign-off</h2>"):]
    assert "<td>Head office</td>" in block and "Prepared by: C. Engineer" in block
    assert "Project no." not in html and "<th>Client</th>" not in html  # only when given
    report.signoff = dict(report.signoff, project_number="2026-014", client="Müller AG")
    block = page(report)
    block = block[block.index("Provenance and sign-off</h2>"):]
    assert "<th>Project no.</th><td>2026-014</td>" in block
    assert "<th>Client</th><td>Müller AG</td>" in block


# --- client wording ---------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["room", "office", "workbench"])
def test_the_page_holds_no_file_names_or_internal_phrasing(name):
    html = (FIXTURES / f"{name}.report.html").read_text(encoding="utf-8")
    scene, _ = fixture(name)
    data = json.loads(scene.read_text())
    for forbidden in ("docs/", ".json", "requested", "photons traced", "power_w"):
        assert forbidden not in html, forbidden
    for lum in data["luminaires"]:
        if "file" in lum:
            assert lum["file"] not in html and lum["file"].split("/")[-1] not in html
    # Names the designer gave, not the solver's: a target with a label is printed by it.
    labels = data.get("metadata", {}).get("labels", {})
    for target in data["targets"]:
        if labels.get(target["name"], target["name"]) != target["name"]:
            assert f">{target['name']}<" not in html and f"({target['name']})" not in html


#: What a solver before the coincident-contact rule (issue 25) said of the workbench office:
#: surfaces in contact (walls on the floor slab, the frame in the wall, the desk on the floor).
OLD_OVERLAPS = [
    f'meshes "{a}" (material "{ma}") and "{b}" (material "{mb}") overlap in one plane over '
    f"{area} m²: the material seen there is arbitrary" for a, ma, b, mb, area in (
        ("Wall", "default_wall", "Structure.default_floor", "default_floor", "3.76"),
        ("Wall", "default_wall", "Structure001.default_ceiling", "default_ceiling", "3.76"),
        ("Wall", "default_wall", "Window.default_frame", "default_frame", "0.27"),
        ("Structure.default_floor", "default_floor", "Desk", "Desk_material", "0.04"),
        ("Structure.default_floor", "default_floor", "Cabinet", "default_furniture", "0.32"),
        ("Window.default_frame", "default_frame", "Window.default_glass", "default_glass",
         "0.05"))]


def test_the_workbench_office_has_no_overlap_remarks_now():
    """The solver no longer warns of solids in contact: the regenerated fixture has none."""
    scene, results = fixture("workbench")
    assert not [w for w in results["warnings"] if "overlap in one plane" in w]
    report = build(scene, results, date=DATE)
    assert not [n for n in report.notes if "same plane" in n.text]


def test_overlap_remarks_are_one_note():
    scene, results = fixture("workbench")
    results["warnings"] = list(results["warnings"]) + OLD_OVERLAPS
    report = build(scene, results, date=DATE)
    (note,) = [n for n in report.notes if "same plane" in n.text]
    assert len(note.details) == 6 and "Walls and Floor: 3.76 m²" in note.details
    assert not any("overlap in one plane" in n.text for n in report.notes)


def test_every_grid_prints_its_intervals_without_requirements():
    scene = SOURCE_DIR / "Examples" / "room" / "room.json"
    results = json.loads((SOURCE_DIR / "Tests" / "golden" / "room.results.json").read_text())
    grid = results["targets"][1]
    assert "requirements" not in grid and "min_ci_low_lux" in grid
    html = render_html(scene, results, date=DATE)
    glance = html[html.index("Results at a glance"):html.index("<h2 class=\"cover-h\">Calc")]
    for low, high, show in (("min_ci_low_lux", "min_ci_high_lux", fmt.lux),
                            ("max_ci_low_lux", "max_ci_high_lux", fmt.lux),
                            ("uniformity_ci_low", "uniformity_ci_high", fmt.ratio),
                            ("ud_ci_low", "ud_ci_high", fmt.ratio)):
        assert f"[{show(grid[low])}, {show(grid[high])}]" in glance


def test_an_observer_grid_with_many_lines_of_sight_lists_each_positions_largest(tmp_path):
    """Every 15 degrees (24 lines of sight) does not fit a column each: each eye position's
    largest UGR and where it looks."""
    scene = json.loads((FIXTURES / "workbench.scene.json").read_text())
    grid = next(t for t in scene["targets"] if t["type"] == "observer_grid")
    grid["view_step_deg"] = 15
    scene["settings"].update(photons=20_000, decide=False)
    shutil.copytree(FIXTURES / "photometry", tmp_path / "photometry")
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    results = lightsolver_report.trace(path)
    entry = next(t for t in results["targets"] if t["type"] == "observer_grid")
    area = next(a for a in build(path, results, date=DATE).areas if a.type == "observer_grid")
    assert len(area.observer_directions) == 24
    for (position, top, direction), row in zip(area.point_maxima, entry["observer_grid"]["ugr"]):
        known = [u for u in row if u is not None]
        assert top == (max(known) if known else None)
        if top is not None:
            assert direction == tuple(entry["observer_grid"]["view_directions"][row.index(top)])
    html = render_html(path, results, date=DATE)
    assert "largest UGR at each eye position over its 24 lines of sight" in html
    assert "<th class=\"r\">15°</th>" not in html  # no column per line of sight
