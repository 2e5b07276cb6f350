"""GUI scenario: Examples/office.py run inside FreeCAD right after it starts on its Start page
(no document, no 3D view yet), first as the Macro dialog runs a macro (Macro > Macros... >
Execute), then as a user types it into the Python console (``exec(open(...).read())``, which
defines no ``__file__`` of the script). Each run must build, analyse and save the office,
end on the Lighting workbench with the 3D view fitted and the ceiling shown transparent -
visible, and in the exported lighting model. Last, office_model builds into a document
whose 3D view the user closed (a spreadsheet of it still open): Arch's recompute asks
Draft for the active 3D view (``get_normal``) and, with none, left the walls without their
faces ("no face with normal ... through ...") before office_model gave the document an
active 3D view first."""
import contextlib
import io
import os

from guilib import STATUS, OUT, expect, grab_window, log, pump, run_macro_file, scenario

EXAMPLE = os.path.join(os.environ.get("LIGHTING_SOURCE_DIR", "."), "Examples", "office.py")


def run_captured(action) -> str:
    """Run ``action()`` with stdout/stderr captured (the example prints its table there)."""
    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer), contextlib.redirect_stderr(buffer):
        action()
    return buffer.getvalue()


def check_finished(name: str, output: str, out_file: str) -> None:
    """What the user sees after the example: results, workbench, view, ceiling."""
    import FreeCAD
    import FreeCADGui

    import lighting

    STATUS[f"{name}_output"] = output[-2500:]
    expect("Traceback" not in output and "failed" not in output,
           f"{name}: the example failed:\n{output[-2500:]}")
    expect(f"office: saved {out_file}" in output, f"{name}: the example did not finish")
    doc = FreeCAD.ActiveDocument
    expect(doc is not None and doc.FileName == out_file,
           f"{name}: the active document is not the example's ({doc and doc.FileName})")
    if doc is None:
        return
    results = lighting.results(doc)
    workplane = results["Workplane"] if results else None
    STATUS[f"{name}_workplane_lux"] = workplane.mean_lux if workplane else None
    expect(workplane is not None and workplane.mean_lux > 300.0,
           f"{name}: no plausible Workplane result: {workplane}")
    workbench = FreeCADGui.activeWorkbench().name()
    expect(workbench == "LightingWorkbench", f"{name}: workbench is {workbench}")
    ceiling = doc.getObjectsByLabel("Ceiling")[0]
    STATUS[f"{name}_ceiling"] = {"visible": ceiling.ViewObject.Visibility,
                                 "transparency": ceiling.ViewObject.Transparency}
    expect(ceiling.ViewObject.Visibility and ceiling.ViewObject.Transparency >= 50,
           f"{name}: the ceiling is not shown transparent: {STATUS[f'{name}_ceiling']}")
    # The ceiling stays in the lighting model: its material is in the exported scene.
    scene_file = doc.getObject("LightingAnalysis").SceneFile
    with open(scene_file, encoding="utf-8") as stream:
        expect("default_ceiling" in stream.read(), f"{name}: the ceiling is not in the scene")
    view = FreeCADGui.getDocument(doc.Name).mdiViewsOfType("Gui::View3DInventor")[0]
    direction = view.getViewDirection()
    STATUS[f"{name}_view_direction"] = [round(c, 3) for c in direction]
    expect(abs(abs(direction.x) - abs(direction.y)) < 1e-3
           and abs(abs(direction.x) - abs(direction.z)) < 1e-3,
           f"{name}: the view is not isometric: {direction}")


def body() -> None:
    import FreeCAD
    import FreeCADGui

    expect(STATUS["start_workbench"] == "StartWorkbench" and FreeCAD.ActiveDocument is None,
           "FreeCAD did not start on the Start page without a document")
    os.environ["LIGHTING_PHOTONS"] = "100000"  # small solve: the example reads it

    out_macro = os.path.join(OUT, "macro", "office.FCStd")
    os.environ["LIGHTING_OUT"] = out_macro
    log("running the example as the Macro dialog does")
    output = run_captured(lambda: run_macro_file(EXAMPLE))
    pump(1.0)
    check_finished("macro", output, out_macro)
    grab_window("example_office", docs_name="example-office.png")
    FreeCAD.closeDocument(FreeCAD.ActiveDocument.Name)
    pump(0.3)

    # The Python console: the line a user types there, run by the console's interpreter.
    out_console = os.path.join(OUT, "console", "office.FCStd")
    os.environ["LIGHTING_OUT"] = out_console
    log("running the example from the Python console")
    output = run_captured(lambda: FreeCADGui.doCommand(f"exec(open({EXAMPLE!r}).read())"))
    pump(1.0)
    check_finished("console", output, out_console)
    grab_window("example_office_console")
    FreeCAD.closeDocument(FreeCAD.ActiveDocument.Name)
    pump(0.3)
    build_without_view()


def build_without_view() -> None:
    """A document whose 3D view the user closed, a spreadsheet of it still open: the office
    must still build into it."""
    import sys

    import FreeCAD
    import FreeCADGui
    from PySide import QtGui

    doc = FreeCAD.newDocument("NoView")
    sheet = doc.addObject("Spreadsheet::Sheet", "Notes")
    doc.recompute()
    pump(0.3)
    mdi = FreeCADGui.getMainWindow().findChild(QtGui.QMdiArea)
    view_3d = mdi.activeSubWindow()
    sheet.ViewObject.doubleClicked()  # opens the spreadsheet's own view
    pump(0.5)
    view_3d.close()
    pump(0.5)
    views = FreeCADGui.getDocument(doc.Name).mdiViewsOfType("Gui::View3DInventor")
    STATUS["no_view"] = {"views_before": len(views),
                         "active_gui_document": str(FreeCADGui.ActiveDocument)}
    expect(not views, "the test document still has a 3D view")
    sys.path.insert(0, os.path.dirname(EXAMPLE))
    import office_model

    office_model.build_office(doc)
    ceiling = doc.getObject(office_model.OBJECTS["ceiling"])
    STATUS["no_view"]["ceiling_bounds_z"] = [ceiling.Shape.BoundBox.ZMin,
                                             ceiling.Shape.BoundBox.ZMax]
    expect(abs(ceiling.Shape.BoundBox.ZMin - office_model.ROOM_Z_MM) < 1e-6,
           f"the ceiling slab is misplaced: {STATUS['no_view']}")


scenario(body)
