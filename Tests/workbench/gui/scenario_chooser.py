"""GUI scenario: the luminaire chooser. From the Start page the user builds the office example,
selects a ceiling luminaire, opens "Choose luminaire data" from the Lighting toolbar, picks a
shipped file, reads its summary and polar diagram, and presses Assign: the luminaire becomes
photometric with that file and its lumens, in one undo step. A user folder with a malformed
file lists it with its error, and Assign stays disabled for it. Double-clicking a luminaire
opens the chooser too."""
import os
import sys
import tempfile

from guilib import (STATUS, expect, grab_window, log, main_window, pump, scenario,
                    visible_in_window, wait_until)

REPO = os.environ.get("LIGHTING_SOURCE_DIR", os.path.dirname(os.path.dirname(
    os.path.dirname(os.path.dirname(os.path.abspath(__file__))))))
MALFORMED_IES = ("IESNA:LM-63-2002\n[MANUFAC] Test\nTILT=NONE\n1 1000 1 3 2 1 2 0.1 0.1 0\n"
                 "1 1 10\n0 45 banana\n0 180\n100 50 0\n100 50 0\n")


def build_office():
    """The office example in a new document (a 3D view exists before Arch recomputes)."""
    import FreeCAD
    import FreeCADGui

    sys.path.insert(0, os.path.join(REPO, "Examples"))
    import office_model

    doc = FreeCAD.newDocument("Office")
    pump(0.3)
    office_model.build_office(doc, photons=20000)
    FreeCADGui.activateWorkbench("LightingWorkbench")
    # Look into the room through a see-through ceiling (a viewing choice only).
    doc.getObjectsByLabel("Ceiling")[0].ViewObject.Transparency = 80
    view = FreeCADGui.getDocument(doc.Name).ActiveView
    view.viewIsometric()
    view.fitAll()
    pump(0.5)
    return doc


def toolbar_action(text):
    from PySide import QtGui

    for bar in main_window().findChildren(QtGui.QToolBar):
        for action in bar.actions():
            if action.text().replace("&", "") == text and bar.isVisible():
                return bar.windowTitle(), action
    return None, None


def painted_pixels(widget):
    """(non-white, reddish, bluish) pixel counts of the widget as drawn on screen."""
    image = widget.grab().toImage()
    counts = [0, 0, 0]
    for y in range(0, image.height(), 2):
        for x in range(0, image.width(), 2):
            c = image.pixelColor(x, y)
            r, g, b = c.red(), c.green(), c.blue()
            if min(r, g, b) < 235:
                counts[0] += 1
            if r > 150 and g < 90 and b < 90:
                counts[1] += 1
            if b > 150 and r < 90 and g < 120:
                counts[2] += 1
    return counts


def check_fits(panel):
    """Nothing of the panel is cut at the combo view's width; Assign and Close are visible."""
    from PySide import QtCore

    box = panel.button_box
    assign = box.button(box.Apply)
    close = box.button(box.Close)
    STATUS["assign_visible"] = visible_in_window(assign)
    expect(visible_in_window(assign) and visible_in_window(close),
           "Assign/Close buttons not fully visible")
    expect(assign.text() == "Assign", f"Apply button reads {assign.text()!r}")
    form = panel.form
    needed, shown = form.minimumSizeHint().width(), form.width()
    STATUS["form_width"] = [needed, shown]
    expect(needed <= shown, f"chooser needs {needed} px, has {shown} px")
    for widget in (panel.tree, panel.summary, panel.polar, panel.keep_flux):
        right = widget.mapTo(form, QtCore.QPoint(widget.width(), 0)).x()
        expect(right <= form.width(), f"{type(widget).__name__} cut at the right ({right} px)")


def check_ugr_table(panel):
    """'UGR table...' opens the file's full CIE 190 table in its own window: 19 rooms, ten
    values each, the 4H x 8H row equal to the headline, nothing scrolled out of view."""
    from guilib import OUT
    from lighting import luminaire_library as library

    dialog = panel.show_ugr_table()
    pump(0.5)
    expect(dialog is not None and dialog.isVisible(), "the UGR table window did not open")
    if dialog is None:
        return
    texts = dialog.texts()
    STATUS["ugr_table_rows"] = len(texts)
    expect(len(texts) == 20, f"UGR table has {len(texts)} rows, expected 1 + 19")
    row, x = None, ""
    for t in texts[1:]:
        x = t[0] or x  # X is printed on the first row of its group only
        if (x, t[1]) == ("4H", "8H"):
            row = t
    head = library.headline_ugr(panel.current_entry().path)
    expect(row is not None and row[2] == f"{head[0]:.1f}" and row[7] == f"{head[1]:.1f}",
           f"4H x 8H row {row} against the headline {head}")
    grid = dialog.grid
    expect(grid.horizontalScrollBar().maximum() == 0 and grid.verticalScrollBar().maximum() == 0,
           "the UGR table window scrolls")
    path = os.path.join(OUT, "chooser_ugr_table.png")
    dialog.grab().save(path)
    STATUS["images"]["chooser_ugr_table"] = path
    STATUS["docs_images"]["chooser_ugr_table"] = "chooser-ugr-table.png"
    log(f"screenshot {path}")
    dialog.close()


def body() -> None:
    import FreeCAD
    import FreeCADGui

    expect(STATUS["start_workbench"] == "StartWorkbench",
           f"FreeCAD did not start on the Start page: {STATUS['start_workbench']}")
    doc = build_office()
    lum = doc.getObject("Luminaire01")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(lum)
    bar, action = toolbar_action("Choose luminaire data")
    STATUS["toolbar"] = bar
    expect(action is not None and action.isEnabled(), "no enabled 'Choose luminaire data' tool")
    FreeCADGui.runCommand("Lighting_ChooseLuminaire")
    from lighting.taskpanels import luminaire_chooser

    expect(wait_until(lambda: luminaire_chooser.last_panel() is not None
                      and FreeCADGui.Control.activeDialog(), 5.0), "the chooser did not open")
    panel = luminaire_chooser.last_panel()
    pump(0.5)
    names = [e.name for e in panel.entries]
    STATUS["entries"] = names
    expect(len(names) == 8, f"expected the 8 shipped files, got {names}")
    expect("Luminaire01" in panel.targets.text(), f"targets: {panel.targets.text()!r}")

    entry = panel.select("batwing_panel.ldt")
    pump(0.5)
    summary = panel.summary.text()
    STATUS["summary"] = summary
    for part in ("3600 lm", "4 lamps", "Beam angle: C0-C180 56.4", "Field angle", "Symmetry",
                 "EULUMDAT", "Maker: Lighting project", "290 cd/klm"):
        expect(part in summary, f"summary lacks {part!r}")
    pixels = painted_pixels(panel.polar)
    STATUS["polar_pixels"] = pixels
    expect(pixels[0] > 500 and pixels[1] > 50 and pixels[2] > 50,
           f"polar diagram looks blank (non-white, red, blue samples: {pixels})")
    expect("cd/klm" in panel.caption.text(), f"caption {panel.caption.text()!r}")
    expect("UGR (4H\u00d78H, 0.7/0.5/0.2, CIE 190): 25.8 crosswise, 22.9 endwise" in summary,
           "summary lacks the data-sheet UGR")
    check_fits(panel)
    expect(visible_in_window(panel.ugr_button) and panel.ugr_button.isEnabled(),
           "'UGR table...' button not visible or disabled")
    grab_window("chooser", docs_name="chooser.png")
    check_ugr_table(panel)

    steps = list(FreeCAD.ActiveDocument.UndoNames)
    panel.button_box.button(panel.button_box.Apply).click()
    pump(0.5)
    STATUS["after_assign"] = [lum.LuminaireType, lum.PhotometricFile, lum.FluxLumen]
    expect(lum.LuminaireType == "Photometric", f"type {lum.LuminaireType}")
    expect(os.path.realpath(lum.PhotometricFile) == os.path.realpath(entry.path),
           f"file {lum.PhotometricFile!r}")
    expect(lum.FluxLumen == 3600.0, f"flux {lum.FluxLumen}")
    undo = list(doc.UndoNames)
    expect(len(undo) == len(steps) + 1 and undo[0] == "Assign luminaire data",
           f"undo steps before {steps[:3]}, after {undo[:3]}")
    expect(doc.getObject("Luminaire02").LuminaireType == "Area", "an unselected luminaire changed")

    # A user folder with a malformed file: listed in red with its error, not assignable.
    folder = tempfile.mkdtemp(prefix="chooser-user-")
    with open(os.path.join(folder, "broken.ies"), "w", encoding="ascii") as stream:
        stream.write(MALFORMED_IES)
    panel.set_folder(folder)
    pump(0.3)
    broken = panel.select("broken.ies")
    pump(0.3)
    expect(not broken.ok and "line 6" in panel.summary.text(),
           f"malformed file summary: {panel.summary.text()!r}")
    expect(not panel.button_box.button(panel.button_box.Apply).isEnabled(),
           "Assign enabled for a malformed file")
    grab_window("chooser_malformed")
    panel.set_folder("")

    # A ceiling face selected, no luminaire: Assign makes a new one 5 cm under the face's
    # centre, aimed down, with the file's lumens, in one undo step; it is then selected.
    import office_model

    ceiling = doc.getObjectsByLabel("Ceiling")[0]
    face = office_model.find_face(ceiling.Shape, FreeCAD.Vector(0, 0, -1),
                                  FreeCAD.Vector(0, 0, office_model.ROOM_Z_MM))
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(ceiling, face)
    pump(0.3)
    expect("creates a new one at the selected face" in panel.targets.text(),
           f"targets: {panel.targets.text()!r}")
    panel.select("downlight.ies")
    before, steps = len(doc.Objects), len(doc.UndoNames)
    panel.button_box.button(panel.button_box.Apply).click()
    pump(0.5)
    made = [o for o in FreeCADGui.Selection.getSelection()]
    expect(len(doc.Objects) == before + 1 and len(made) == 1, "no new luminaire selected")
    if made:
        new = made[0]
        base = new.Placement.Base
        STATUS["created"] = [new.Label, new.LuminaireType, new.FluxLumen, list(base)]
        expect(new.LuminaireType == "Photometric" and new.FluxLumen == 1500.0,
               f"new luminaire {new.LuminaireType} {new.FluxLumen}")
        expect(abs(base.x - 2500) < 1 and abs(base.y - 2000) < 1 and abs(base.z - 2950) < 1,
               f"new luminaire at {base}")
        expect(abs(new.AimDirection.z + 1.0) < 1e-9, f"aim {new.AimDirection}")
        expect(new in doc.getObject("LightingAnalysis").Group, "new luminaire not in the analysis")
        expect(len(doc.UndoNames) == steps + 1, f"undo {doc.UndoNames[:3]}")
        expect(f"Assign to: {new.Label}" in panel.targets.text(), panel.targets.text())

    # Double-click (edit) of a luminaire opens the chooser for it.
    panel.reject()
    pump(0.3)
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.ActiveDocument.setEdit("Luminaire03")
    pump(0.5)
    again = luminaire_chooser.last_panel()
    expect(again is not panel and FreeCADGui.Control.activeDialog(),
           "editing a luminaire did not open the chooser")
    expect("Luminaire03" in again.targets.text(), f"targets: {again.targets.text()!r}")
    again.select("wallwasher.ldt")
    steps = list(doc.UndoNames)
    again.button_box.button(again.button_box.Apply).click()
    pump(0.3)
    again.reject()
    pump(0.3)
    lum3 = doc.getObject("Luminaire03")
    STATUS["edit_assign"] = [lum3.LuminaireType, lum3.FluxLumen, list(doc.UndoNames)[:3]]
    expect(lum3.LuminaireType == "Photometric" and lum3.FluxLumen == 2000.0,
           f"assign from the edit chooser: {lum3.LuminaireType} {lum3.FluxLumen}")
    expect(len(doc.UndoNames) == len(steps) + 1, f"undo steps {steps[:3]} -> {doc.UndoNames[:3]}")
    doc.undo()
    pump(0.3)
    expect(lum3.LuminaireType == "Area" and lum3.FluxLumen == 5200.0,
           f"undo of the edit chooser's assign: {lum3.LuminaireType} {lum3.FluxLumen}")
    log("chooser scenario done")


scenario(body)
