"""What the report refuses (lightsolver_report.guard, docs/report.md "What the report refuses"):
results that are truncated, garbled, break the schema, hold no targets or are a cancelled run's
(unless asked for), an output folder that does not exist, another suffix, unknown sign-off
fields, a picture that is no PNG. Each is refused with a message naming the file or field, and
leaves nothing behind: no file, no folder, no temporary file. The same scene and results are
accepted, by the library and by both command lines; a failure while writing leaves the old
report as it was."""
import functools
import json
import shutil
import os
import subprocess
import sys
from pathlib import Path

import lightsolver
import pytest

import lightsolver_report
from lightsolver_report import ReportError, build, guard, render_html

# The room fixture is results no solver wrote (make_fixtures.py: no provenance), so every
# render() here allows unverified results; results of another scene stay refused
# (test_provenance.py), and the other refusals do not depend on it.
render = functools.partial(lightsolver_report.render, allow_unverified=True)

FIXTURES = Path(__file__).resolve().parent / "fixtures" / "report"
DATE = "2026-01-01"
SCENE = FIXTURES / "room.scene.json"
RESULTS = FIXTURES / "room.results.json"


def tree(root):
    """Every path under ``root`` (files and folders), to compare before and after."""
    return sorted(str(p.relative_to(root)) for p in Path(root).rglob("*"))


def results_dict():
    return json.loads(RESULTS.read_text())


def refused(tmp_path, results, match, out_name="report.html", **kwargs):
    """render() raises ReportError matching ``match`` and leaves ``tmp_path`` as it was."""
    before = tree(tmp_path)
    with pytest.raises(ReportError, match=match) as caught:
        render(SCENE, results, tmp_path / out_name, date=DATE, **kwargs)
    assert tree(tmp_path) == before, "a refused report left something behind"
    return str(caught.value)


def write_results(tmp_path, text, name="results.json"):
    path = tmp_path / "in" / name
    path.parent.mkdir(exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


# --- results ----------------------------------------------------------------------------------

def test_a_file_holding_only_the_format_is_refused_for_having_no_targets(tmp_path):
    path = write_results(tmp_path, '{"format": "lightsolver.results/1"}')
    message = refused(tmp_path, path, "no targets")
    assert str(path) in message  # names the file
    assert "no targets" in refused(tmp_path, {"format": "lightsolver.results/1"}, "the results")


def test_an_empty_targets_list_is_refused(tmp_path):
    path = write_results(tmp_path, json.dumps(dict(results_dict(), targets=[])))
    assert "empty targets list" in refused(tmp_path, path, "no targets")


@pytest.mark.parametrize("cut", [0.5, 0.99])
def test_a_truncated_results_file_is_refused(tmp_path, cut):
    text = RESULTS.read_text()
    path = write_results(tmp_path, text[:int(len(text) * cut)])
    message = refused(tmp_path, path, "cannot read the results")
    assert str(path) in message


def test_garbled_results_are_refused(tmp_path):
    path = write_results(tmp_path, "\x00\x01 not json at all")
    refused(tmp_path, path, "cannot read the results")
    path = write_results(tmp_path, "[1, 2, 3]", "list.json")
    refused(tmp_path, path, "not a JSON object")
    path = write_results(tmp_path, json.dumps(dict(results_dict(), format="other/1")), "o.json")
    refused(tmp_path, path, "format")


@pytest.mark.parametrize("field, value", [("photons", "many"), ("seed", -1),
                                          ("stop_reason", "boredom"), ("confidence", 1.5)])
def test_results_that_break_the_schema_are_refused_naming_the_field(tmp_path, field, value):
    pytest.importorskip("jsonschema")
    results = results_dict()
    results[field] = value
    assert field in refused(tmp_path, results, "schema")


def test_a_target_that_breaks_the_schema_is_refused(tmp_path):
    pytest.importorskip("jsonschema")
    results = results_dict()
    del results["targets"][1]["mean_lux"]
    assert "mean_lux" in refused(tmp_path, results, "schema")
    results = results_dict()
    results["targets"][0] = "workplane"
    assert "targets 0: not an object" in refused(tmp_path, results, "malformed")


# --- partial (cancelled) results --------------------------------------------------------------

def partial_results():
    return dict(results_dict(), partial=True, stop_reason="cancelled", photons=1000)


def test_partial_results_are_refused_unless_asked_for(tmp_path):
    message = refused(tmp_path, partial_results(), "partial results")
    assert "1,000 of" in message and "allow_partial" in message and "--allow-partial" in message
    # stop_reason alone says so too (a reader must not depend on one of the two fields).
    refused(tmp_path, dict(results_dict(), stop_reason="cancelled"), "cancelled")
    out = render(SCENE, partial_results(), tmp_path / "partial.html", date=DATE,
                 allow_partial=True)
    assert "Partial results" in out.read_text(encoding="utf-8")
    assert build(SCENE, partial_results(), date=DATE).partial is True
    assert build(SCENE, results_dict(), date=DATE).partial is False


def test_a_cancelled_run_of_the_cli_is_refused_unless_asked_for(cli, tmp_path, room_scene):
    # A real cancel: lightsolver run interrupted (SIGINT) writes the photons traced so far,
    # marked partial (exit status 130).
    import signal
    import time

    results = tmp_path / "in" / "cancelled.json"
    results.parent.mkdir()
    run = subprocess.Popen([cli, "run", str(room_scene), "--photons", "10000000000000",
                            "--threads", "1", "-q", "--out", str(results)],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(1.5)
    run.send_signal(signal.SIGINT)
    _, err = run.communicate(timeout=120)
    assert run.returncode == 130 and results.is_file(), err
    doc = json.loads(results.read_text())
    assert doc["partial"] is True and doc["stop_reason"] == "cancelled"
    before = tree(tmp_path)
    with pytest.raises(ReportError, match="partial results: the run was cancelled after"):
        render(room_scene, results, tmp_path / "r.pdf", date=DATE)
    assert tree(tmp_path) == before
    out = render(room_scene, results, tmp_path / "r.html", date=DATE, allow_partial=True)
    assert "Partial results" in out.read_text(encoding="utf-8")


# --- where it goes ----------------------------------------------------------------------------

@pytest.mark.parametrize("sub", ["nonexistent/x.pdf", "a/b/c/x.html", "nonexistent/x.html"])
def test_a_missing_output_folder_is_an_error_and_is_not_created(tmp_path, sub):
    message = refused(tmp_path, RESULTS, "does not exist", out_name=sub)
    assert str((tmp_path / sub).parent) in message
    assert not (tmp_path / sub.split("/")[0]).exists()


def test_an_output_folder_that_is_a_file_or_an_output_that_is_a_folder(tmp_path):
    (tmp_path / "file").write_text("x")
    (tmp_path / "dir.html").mkdir()
    refused(tmp_path, RESULTS, "is not a folder", out_name="file/x.html")
    refused(tmp_path, RESULTS, "is a folder", out_name="dir.html")


@pytest.mark.parametrize("name", ["report.docx", "report", "report.pdf.txt"])
def test_another_suffix_is_refused(tmp_path, name):
    refused(tmp_path, RESULTS, r"\.html or \.pdf", out_name=name)


def test_the_output_is_checked_before_the_results(tmp_path):
    # A wrong place is said first, even for results that would be refused too.
    refused(tmp_path, {"format": "lightsolver.results/1"}, "does not exist",
            out_name="gone/r.html")


# --- what the caller adds ---------------------------------------------------------------------

def test_signoff_fields_are_passed_to_the_model_and_unknown_ones_refused(tmp_path):
    refused(tmp_path, RESULTS, "checked_by", signoff={"checkedby": "K. Lux"})
    report = build(SCENE, results_dict(), date=DATE,
                   signoff={"project": "Office 3", "checked_by": " K. Lux "})
    assert report.signoff == {"project": "Office 3", "author": "", "checked_by": "K. Lux"}
    assert build(SCENE, results_dict(), date=DATE).signoff == {
        "project": "", "author": "", "checked_by": ""}
    named = build(SCENE, results_dict(), date=DATE, signoff={"client": " Müller AG ",
                                                            "project_number": ""})
    assert named.signoff == {"project": "", "author": "", "checked_by": "", "client": "Müller AG"}


def test_the_view_picture_must_be_a_png(tmp_path):
    fake = tmp_path / "in" / "view.png"
    fake.parent.mkdir()
    fake.write_bytes(b"GIF89a not a png")
    refused(tmp_path, RESULTS, "not a PNG", view_png=fake)
    refused(tmp_path, RESULTS, "cannot read", view_png=tmp_path / "in" / "none.png")
    real = fake.with_name("real.png")
    real.write_bytes(guard.PNG_MAGIC + b"\0" * 16)
    report = build(SCENE, results_dict(), date=DATE, view_png=real)
    assert report.view_png == str(real) and os.path.isabs(report.view_png)
    assert build(SCENE, results_dict(), date=DATE).view_png is None


# --- do they belong to the scene (the provenance module's check, where present) ---------------

def test_render_asks_the_provenance_check_and_refuses_what_it_refuses(tmp_path, monkeypatch):
    calls = []

    def check(scene_path, results, allow_unverified=False):
        calls.append((str(scene_path), results["seed"], allow_unverified))
        if results["seed"] != results_dict()["seed"]:
            raise ReportError("the results were traced from another scene")

    monkeypatch.setattr(guard, "_provenance_check", lambda: check)
    other = dict(results_dict(), seed=99)
    refused(tmp_path, other, "another scene", allow_unverified=False)
    refused(tmp_path, other, "another scene", allow_unverified=True)
    assert calls == [(str(SCENE), 99, False), (str(SCENE), 99, True)]
    assert lightsolver_report.render(SCENE, RESULTS, tmp_path / "ok.html", date=DATE).is_file()


def test_without_a_provenance_module_nothing_is_compared():
    from importlib.util import find_spec

    present = find_spec("lightsolver_report.provenance") is not None
    assert (guard._provenance_check() is not None) == present


# --- accepted, and written whole or not at all --------------------------------------------------

@pytest.mark.parametrize("name", ["room", "office"])
def test_the_same_scene_and_results_are_accepted(tmp_path, name):
    scene = FIXTURES / f"{name}.scene.json"
    results = FIXTURES / f"{name}.results.json"
    out = render(scene, results, tmp_path / "r.html", date=DATE)
    assert out == tmp_path / "r.html"
    assert out.read_text(encoding="utf-8") == render_html(
        scene, json.loads(results.read_text()), date=DATE)
    assert tree(tmp_path) == ["r.html"]  # no temporary file left


def test_a_failure_while_writing_leaves_the_old_report(tmp_path, monkeypatch):
    out = tmp_path / "report.pdf"
    out.write_bytes(b"%PDF- the old report")
    (tmp_path / "keep.txt").write_text("x")

    def failing_pdf(html, path):
        Path(path).write_bytes(b"%PDF- half")
        raise RuntimeError("WeasyPrint failed")

    monkeypatch.setattr(lightsolver_report, "write_pdf", failing_pdf)
    with pytest.raises(RuntimeError, match="WeasyPrint failed"):
        render(SCENE, RESULTS, out, date=DATE)
    assert out.read_bytes() == b"%PDF- the old report"
    assert tree(tmp_path) == ["keep.txt", "report.pdf"]

    def interrupted(html, path):
        Path(path).write_bytes(b"%PDF- half")
        raise KeyboardInterrupt

    monkeypatch.setattr(lightsolver_report, "write_pdf", interrupted)
    with pytest.raises(KeyboardInterrupt):
        render(SCENE, RESULTS, out, date=DATE)
    assert out.read_bytes() == b"%PDF- the old report"
    assert tree(tmp_path) == ["keep.txt", "report.pdf"]


def test_weasyprint_raising_inside_leaves_nothing(tmp_path, monkeypatch):
    weasyprint = pytest.importorskip("weasyprint")

    def broken(self, target=None, **kwargs):
        with open(target, "wb") as stream:
            stream.write(b"%PDF-1.7 partial")
        raise ValueError("font subsetting failed")

    monkeypatch.setattr(weasyprint.HTML, "write_pdf", broken)
    with pytest.raises(ValueError, match="font subsetting"):
        render(SCENE, RESULTS, tmp_path / "new.pdf", date=DATE)
    assert tree(tmp_path) == []


def test_an_unwritable_folder_is_a_report_error(tmp_path):
    if os.geteuid() == 0:
        pytest.skip("root writes into read-only folders")
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o500)
    try:
        with pytest.raises(ReportError, match="cannot write"):
            render(SCENE, RESULTS, folder / "r.html", date=DATE)
        assert tree(folder) == []
    finally:
        folder.chmod(0o700)


def test_the_written_file_has_the_usual_permissions(tmp_path):
    mask = os.umask(0o022)
    try:
        out = render(SCENE, RESULTS, tmp_path / "r.html", date=DATE)
    finally:
        os.umask(mask)
    assert out.stat().st_mode & 0o777 == 0o644


# --- the command lines ------------------------------------------------------------------------

def _pythonpath():
    return os.pathsep.join([str(Path(lightsolver.__file__).parent),
                            str(Path(lightsolver_report.__file__).parent.parent)])


def python_m(*args):
    return subprocess.run([sys.executable, "-m", "lightsolver_report", *map(str, args)],
                          capture_output=True, text=True, timeout=300,
                          env={**os.environ, "PYTHONPATH": _pythonpath()})


def test_python_m_refuses_and_accepts(tmp_path):
    partial = write_results(tmp_path, json.dumps(partial_results()), "partial.json")
    empty = write_results(tmp_path, '{"format": "lightsolver.results/1"}', "empty.json")
    before = tree(tmp_path)
    r = python_m(SCENE, "--results", empty, "--out", tmp_path / "r.html")
    assert r.returncode == 1 and "no targets" in r.stderr and str(empty) in r.stderr, r.stderr
    r = python_m(SCENE, "--results", RESULTS, "--out", tmp_path / "gone" / "r.pdf")
    assert r.returncode == 1 and "does not exist" in r.stderr, r.stderr
    r = python_m(SCENE, "--results", partial, "--allow-unverified", "--out", tmp_path / "r.html")
    assert r.returncode == 1 and "--allow-partial" in r.stderr, r.stderr
    # --save-results into a missing folder: refused before tracing.
    r = python_m(SCENE, "--save-results", tmp_path / "gone" / "r.json", "--out",
                 tmp_path / "r.html")
    assert r.returncode == 1 and "does not exist" in r.stderr, r.stderr
    assert tree(tmp_path) == before
    r = python_m(SCENE, "--results", partial, "--allow-partial", "--allow-unverified",
                 "--date", DATE, "--project",
                 "Office 3", "--author", "A. Writer", "--checked-by", "K. Lux", "--out",
                 tmp_path / "r.html")
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "r.html").read_text(encoding="utf-8") == render_html(
        SCENE, partial_results(), date=DATE,
        signoff={"project": "Office 3", "author": "A. Writer", "checked_by": "K. Lux"})


def test_the_command_line_flags_reach_render(monkeypatch, tmp_path):
    from lightsolver_report import __main__ as cmd

    seen = {}
    monkeypatch.setattr(cmd, "render", lambda *a, **k: seen.update(k) or Path(a[2]))
    assert cmd.main([str(SCENE), "--results", str(RESULTS), "--out", str(tmp_path / "r.pdf"),
                     "--allow-partial", "--allow-unverified", "--author", "A. Writer",
                     "--checked-by", "K. Lux"]) == 0
    assert seen["allow_partial"] and seen["allow_unverified"]
    assert seen["signoff"] == {"project": None, "author": "A. Writer", "checked_by": "K. Lux",
                               "project_number": None, "client": None}
    seen.clear()
    assert cmd.main([str(SCENE), "--results", str(RESULTS), "--out", str(tmp_path / "r.pdf")]) == 0
    assert not seen["allow_partial"] and not seen["allow_unverified"]


def test_lightsolver_report_refuses_a_missing_folder_and_empty_results(cli, tmp_path):
    empty = write_results(tmp_path, '{"format": "lightsolver.results/1"}')
    before = tree(tmp_path)
    r = subprocess.run([cli, "report", str(SCENE), "--results", str(RESULTS), "--out",
                        "/nonexistent-lighting-report/x.pdf"], capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 1 and "/nonexistent-lighting-report" in r.stderr, r.stderr
    assert not os.path.exists("/nonexistent-lighting-report")
    r = subprocess.run([cli, "report", str(SCENE), "--results", str(empty), "--out",
                        str(tmp_path / "x.pdf")], capture_output=True, text=True, timeout=300)
    assert r.returncode == 1 and "no targets" in r.stderr, r.stderr
    assert tree(tmp_path) == before
    # The flags reach the report: the same page as the library's.
    partial = write_results(tmp_path, json.dumps(partial_results()), "partial.json")
    r = subprocess.run([cli, "report", str(SCENE), "--results", str(partial), "--date", DATE,
                        "--allow-partial", "--allow-unverified", "--project", "Office 3",
                        "--author", "A. Writer", "--checked-by", "K. Lux", "--project-number",
                        "2026-014", "--client", "Müller AG", "--out",
                        str(tmp_path / "r.html")], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    page = (tmp_path / "r.html").read_text(encoding="utf-8")
    assert page == render_html(
        SCENE, partial_results(), date=DATE,
        signoff={"project": "Office 3", "author": "A. Writer", "checked_by": "K. Lux",
                 "project_number": "2026-014", "client": "Müller AG"})
    assert "<th>Client</th><td>Müller AG</td>" in page


def test_stale_results_of_a_changed_model_are_refused_unless_allowed_and_then_said(tmp_path):
    """Results traced from the workbench fixture's scene, the scene changed since: refused;
    with allow_stale (the workbench, the user asked) written, what differs on the page."""
    shutil.copytree(FIXTURES / "photometry", tmp_path / "photometry")
    scene = json.loads((FIXTURES / "workbench.scene.json").read_text())
    scene["luminaires"][0]["flux_lm"] = scene["luminaires"][0]["flux_lm"] * 1.1
    changed = tmp_path / "workbench.scene.json"
    changed.write_text(json.dumps(scene, indent=1))
    results = json.loads((FIXTURES / "workbench.results.json").read_text())
    with pytest.raises(ReportError, match="scene's content differs"):
        lightsolver_report.render(changed, results, tmp_path / "r.html", date=DATE)
    assert not (tmp_path / "r.html").exists()
    out = lightsolver_report.render(changed, results, tmp_path / "r.html", date=DATE,
                                    allow_stale=True)
    assert "earlier state of the model" in out.read_text(encoding="utf-8")
