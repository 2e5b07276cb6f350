"""GUI scenario: a user's first start. FreeCAD comes up on its Start page at its default
window size; the user picks the Lighting workbench from the workbench list, and its toolbars
and menu are there."""
from guilib import STATUS, expect, grab_window, log, main_window, pump, scenario


def body() -> None:
    import FreeCADGui

    expect(STATUS["start_workbench"] == "StartWorkbench",
           f"FreeCAD did not start on the Start page: {STATUS['start_workbench']}")
    FreeCADGui.activateWorkbench("LightingWorkbench")
    pump(0.5)
    from PySide import QtGui

    bars = [b.windowTitle() for b in main_window().findChildren(QtGui.QToolBar)
            if b.isVisible()]
    STATUS["toolbars"] = bars
    log(f"toolbars {bars}")
    expect("Lighting model" in bars and "Lighting analysis" in bars,
           f"Lighting toolbars not shown: {bars}")
    grab_window("lighting_workbench")


scenario(body)
