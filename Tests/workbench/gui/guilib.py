"""Shared helpers of the GUI scenarios (macros that ``run_scenario.py`` starts in a real
FreeCAD under Xvfb; do not run them alone).

A scenario is a user's session: FreeCAD starts with a fresh user folder (so the default
window size and the Start page), the scenario drives it through commands, task panels and
macros as a user would, records what it saw in ``STATUS`` and adds every failed expectation
to ``STATUS["errors"]``. ``finish()`` writes ``status.json`` and ends the process: FreeCAD's
GUI cannot report a failure through its exit status."""
import json
import os
import threading
import time
import traceback
from typing import Any, Callable, Dict, Optional, Tuple

OUT = os.environ.get("LIGHTING_GUI_OUT", os.getcwd())
#: The repository (the scenarios' examples and the workbench's sources).
REPO = os.environ.get("LIGHTING_SOURCE_DIR") or os.path.dirname(os.path.dirname(
    os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
STATUS: Dict[str, Any] = {"errors": [], "log": [], "images": {}, "docs_images": {}}


def log(text: str) -> None:
    """A line of the scenario's log (kept in status.json)."""
    STATUS["log"].append(f"{time.monotonic():.2f} {text}")


def expect(ok: bool, problem: str) -> bool:
    """Record ``problem`` as a failure unless ``ok``."""
    if not ok:
        STATUS["errors"].append(problem)
    return ok


def finish(code: int = 0) -> None:
    """Write status.json and end FreeCAD at once (no save dialogs)."""
    STATUS["passed"] = code == 0 and not STATUS["errors"]
    with open(os.path.join(OUT, "status.json"), "w", encoding="utf-8") as stream:
        json.dump(STATUS, stream, indent=1, default=str)
    os._exit(code)


def start_watchdog(seconds: Optional[float] = None) -> None:
    """End the scenario as failed when it hangs (a modal dialog nobody closes, a lost loop)."""
    limit = float(seconds or os.environ.get("LIGHTING_GUI_TIMEOUT", "300"))
    timer = threading.Timer(limit, lambda: (expect(False, f"watchdog: timed out after {limit} s"),
                                            finish(3)))
    timer.daemon = True
    timer.start()


def pump(seconds: float = 0.3) -> None:
    """Let the event loop run (repaints, queued signals, timers)."""
    from PySide import QtGui

    end = time.monotonic() + seconds
    while time.monotonic() < end:
        QtGui.QApplication.processEvents()
        time.sleep(0.01)


def wait_until(condition: Callable[[], bool], timeout_s: float, step_s: float = 0.05) -> bool:
    """Pump events until ``condition()`` is true; False after ``timeout_s``."""
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        if condition():
            return True
        pump(step_s)
    return bool(condition())


def main_window():
    import FreeCADGui

    return FreeCADGui.getMainWindow()


def grab_window(name: str, docs_name: Optional[str] = None) -> str:
    """Screenshot of the whole main window as the user sees it (panels, tree, 3D view)."""
    pump(0.3)
    path = os.path.join(OUT, f"{name}.png")
    picture = main_window().grab()
    _paint_3d_views(picture)
    picture.save(path)
    STATUS["images"][name] = path
    if docs_name:
        STATUS["docs_images"][name] = docs_name
    log(f"screenshot {path}")
    return path


def _paint_3d_views(picture) -> None:
    """Paint the shown 3D view into ``picture`` (a grab of the main window): a widget grab
    leaves FreeCAD 0.20's OpenGL view blank, so it is rendered offscreen (saveImage) at its
    size and drawn where it is on screen."""
    import tempfile

    import FreeCADGui
    from PySide import QtCore, QtGui

    window = main_window()
    shown = [w for w in window.findChildren(QtGui.QWidget) if _shown_3d_view(w)]
    view = FreeCADGui.activeView() if FreeCADGui.ActiveDocument is not None else None
    if len(shown) != 1 or view is None or "View3DInventor" not in str(type(view)):
        return  # MDI tabs show one view at a time; none shown: nothing to paint
    widget = shown[0]
    with tempfile.TemporaryDirectory() as folder:
        image = os.path.join(folder, "view.png")
        view.saveImage(image, widget.width(), widget.height(), "Current")
        painter = QtGui.QPainter(picture)
        painter.drawImage(widget.mapTo(window, QtCore.QPoint(0, 0)), QtGui.QImage(image))
        painter.end()


def _shown_3d_view(widget) -> bool:
    """Whether ``widget`` is a shown 3D view. A widget can be deleted while the window's
    children are walked (a closing task panel's, when the garbage collector takes the Python
    object that owned it: the coexist scenario met "Internal C++ object already deleted"):
    that one is not a view."""
    try:
        return widget.metaObject().className() == "Gui::View3DInventor" and widget.isVisible()
    except RuntimeError:
        return False


def visible_in_window(widget) -> bool:
    """True when ``widget`` is shown and its whole rectangle lies inside every scroll viewport
    and parent that contains it, and inside the main window: a user can see and click it."""
    from PySide import QtCore

    if widget is None or not widget.isVisible() or widget.width() <= 0:
        return False
    window = main_window()
    top_left = widget.mapTo(window, QtCore.QPoint(0, 0))
    rect = QtCore.QRect(top_left, widget.size())
    parent = widget.parentWidget()
    while parent is not None and parent is not window:
        origin = parent.mapTo(window, QtCore.QPoint(0, 0))
        if not QtCore.QRect(origin, parent.size()).contains(rect):
            return False
        parent = parent.parentWidget()
    return window.rect().contains(rect)


def fits_width(widget) -> bool:
    """True when the widget's left and right edges lie inside every parent and the window:
    nothing is cut off sideways (a tall panel may still scroll vertically)."""
    from PySide import QtCore

    window = main_window()
    left = widget.mapTo(window, QtCore.QPoint(0, 0)).x()
    right = left + widget.width()
    parent = widget.parentWidget()
    while parent is not None and parent is not window:
        origin = parent.mapTo(window, QtCore.QPoint(0, 0)).x()
        if left < origin or right > origin + parent.width():
            return False
        parent = parent.parentWidget()
    return widget.isVisible() and 0 <= left and right <= window.width()


def toolbar_enabled(command: str) -> bool:
    """Whether the command's toolbar button is enabled, as the user sees it: FreeCAD updates
    its actions on a timer from Command::testActive, which also asks the open task dialog
    (FreeCADGui.isCommandActive asks only the command's IsActive)."""
    from PySide import QtGui

    pump(1.0)  # the action update timer runs every few hundred ms
    actions = [a for a in main_window().findChildren(QtGui.QAction) if a.objectName() == command]
    expect(bool(actions), f"no toolbar action {command}")
    return bool(actions) and all(a.isEnabled() for a in actions)


def build_example_file(photons: int) -> str:
    """The example office as a user has it: a file written by Examples/office.py (freecadcmd,
    build only), in the scenario's output folder."""
    import subprocess

    repo = os.environ["LIGHTING_SOURCE_DIR"]
    out = os.path.join(OUT, "office.FCStd")
    env = dict(os.environ, LIGHTING_OUT=out, LIGHTING_BUILD_ONLY="1",
               LIGHTING_PHOTONS=str(photons))
    proc = subprocess.run(["freecadcmd", os.path.join(repo, "Examples", "office.py")], env=env,
                          capture_output=True, text=True, timeout=240)
    expect(proc.returncode == 0 and os.path.exists(out),
           f"Examples/office.py failed: {proc.stdout[-800:]} {proc.stderr[-800:]}")
    return out


def office_without_luminaires() -> Tuple[object, object]:
    """The example office (Examples/office_model.py, 20 000 photons, seed 1) in a new document
    with a 3D view, its four luminaires and their placement domain deleted (one undo step), so
    a scenario lays out its own. Returns the document and the office_model module."""
    import sys

    import FreeCAD
    import FreeCADGui

    sys.path.insert(0, os.path.join(REPO, "Examples"))
    import office_model

    FreeCADGui.activateWorkbench("LightingWorkbench")
    doc = FreeCAD.newDocument("Office")
    office_model.build_office(doc, photons=20000, seed=1)
    doc.openTransaction("Delete luminaires")
    for name in ("CeilingDomain", "Luminaire01", "Luminaire02", "Luminaire03", "Luminaire04"):
        doc.removeObject(name)
    doc.commitTransaction()
    return doc, office_model


def run_macro_file(path: str, globals_: Optional[dict] = None) -> None:
    """Execute a macro file the way FreeCAD's Macro dialog does (in the GUI's interpreter, with
    ``__name__ == '__main__'``)."""
    with open(path, encoding="utf-8") as stream:
        code = compile(stream.read(), path, "exec")
    exec(code, dict(globals_ or {}, __name__="__main__", __file__=path))


def run_from_toolbar(doc) -> object:
    """Lighting_Run as from the toolbar; waits for this run to finish and returns it."""
    import FreeCADGui

    from lighting.taskpanels import analysis_panel

    before = analysis_panel.last_run()
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.runCommand("Lighting_Run")
    wait_until(lambda: analysis_panel.last_run() is not before and
               analysis_panel.last_run().stage in ("done", "failed", "cancelled"), 180)
    job = analysis_panel.last_run()
    expect(job is not before and job.stage == "done",
           f"run did not finish: {job.stage if job else None} {job.error if job else ''}")
    pump(0.5)
    return job


def run_and_read_rows(analysis, timeout_s: float) -> Tuple[object, Dict[str, Tuple[str, str]]]:
    """Select ``analysis`` alone, run it as from the toolbar and wait until the run ends; then
    read its panel's results table as the user does: {row label: (third column, verdict)}
    (also kept in STATUS["rows"]). Returns the panel and the rows."""
    import FreeCADGui

    from lighting.taskpanels import analysis_panel

    before = analysis_panel.last_run()  # a finished earlier run is not this one
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(analysis)
    FreeCADGui.runCommand("Lighting_Run")
    ok = wait_until(lambda: analysis_panel.last_run() is not None
                    and analysis_panel.last_run() is not before
                    and analysis_panel.last_run().finished, timeout_s)
    expect(ok, "the run did not finish")
    pump(0.5)
    panel = analysis_panel.last_panel()
    last = panel.table.columnCount() - 1
    rows = {panel.table.item(r, 0).text(): (panel.table.item(r, 2).text(),
                                            panel.table.item(r, last).text())
            for r in range(panel.table.rowCount())}
    STATUS["rows"] = rows
    log(f"rows {rows}")
    return panel, rows


def scenario(body: Callable[[], None], delay_ms: int = 1500) -> None:
    """Run ``body`` once FreeCAD's event loop is up (the Start page shown), then finish.
    Exceptions become failures with their traceback.

    Only the scenario FreeCAD was started with runs (run_scenario.py names it in
    LIGHTING_GUI_SCENARIO): a scenario module imported by another for a helper must not
    schedule its own session too (it did: toolbar_legend, importing state_stale, ran
    state_stale's session as well, whose opened example was the second document)."""
    from PySide import QtCore

    wanted = os.environ.get("LIGHTING_GUI_SCENARIO")
    mine = os.path.basename(body.__code__.co_filename)
    if wanted and mine != f"scenario_{wanted}.py":
        return
    start_watchdog()

    def run() -> None:
        try:
            import FreeCADGui

            STATUS["start_workbench"] = FreeCADGui.activeWorkbench().name()
            STATUS["window_size"] = [main_window().width(), main_window().height()]
            body()
        except Exception:  # noqa: BLE001 - every failure must reach status.json
            expect(False, traceback.format_exc())
        finish(0)

    QtCore.QTimer.singleShot(delay_ms, run)
