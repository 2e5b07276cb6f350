"""GUI scenario: a designer lays out luminaires. From the Start page: the office model (without
its four luminaires and its placement domain), the ceiling's underside selected, "Luminaire
layout", the panel filled in (3 columns x 2 rows, 1 m margins to the walls) at the default
combo-view width, OK (one undo step), the analysis run with few photons. Then a slip: the
same ceiling face clicked twice with "Luminaire", and Check warns about the two luminaires at
one point."""

from guilib import STATUS, expect, fits_width, grab_window, log, main_window, \
    office_without_luminaires, pump, scenario, visible_in_window, wait_until

def _office():
    """The office in a new document (a 3D view exists), without its luminaires."""
    import FreeCAD
    import FreeCADGui

    doc, office_model = office_without_luminaires()
    doc.recompute()
    view = FreeCADGui.ActiveDocument.ActiveView
    view.viewIsometric()
    # Look into the room: the ceiling and the south wall would hide the layout.
    ceiling = doc.getObject(office_model.OBJECTS["ceiling"])
    ceiling.ViewObject.Transparency = 80
    doc.getObject(office_model.OBJECTS["walls"]).ViewObject.Transparency = 60
    view.fitAll()
    pump(0.5)
    face = office_model.find_face(ceiling.Shape, FreeCAD.Vector(0, 0, -1),
                                  FreeCAD.Vector(0, 0, 3000))
    return doc, ceiling, face


def _select(doc, obj, face):
    import FreeCADGui

    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(doc.Name, obj.Name, face)
    pump(0.2)


def _ok_button():
    """The task dialog's OK button, as the user sees it."""
    from PySide import QtGui

    for box in main_window().findChildren(QtGui.QDialogButtonBox):
        button = box.button(QtGui.QDialogButtonBox.Ok)
        if button is not None and button.isVisible():
            return button
    return None


def _layout_from_panel(doc, ceiling, face):
    import FreeCADGui

    from lighting.objects import luminaire_layout as layout_mod
    from lighting.objects.base import objects_of_type
    from lighting.taskpanels import layout_panel

    _select(doc, ceiling, face)
    undo_before = doc.UndoCount
    FreeCADGui.runCommand("Lighting_LuminaireLayout")
    pump(0.5)
    panel = layout_panel.last_panel()
    expect(panel is not None, "the Luminaire layout command opened no panel")
    panel.columns.setValue(3)
    panel.rows.setValue(2)
    panel.margin_x.setValue(1.0)
    panel.margin_y.setValue(1.0)
    panel.flux.setValue(4000.0)
    pump(0.3)
    combo_width = panel.form.parentWidget().width() if panel.form.parentWidget() else 0
    STATUS["panel_width"] = [panel.form.width(), combo_width]
    for name in ("field_label", "columns", "rows", "margin_x", "offset", "kind", "flux",
                 "file", "summary"):
        expect(fits_width(getattr(panel, name)),
               f"layout panel field {name} is cut off at the default combo-view width")
    ok = _ok_button()
    expect(ok is not None and visible_in_window(ok), "the panel's OK button is not visible")
    expect("6 luminaires" in panel.summary.text(), f"summary: {panel.summary.text()!r}")
    grab_window("layout_panel", docs_name="layout-panel.png")
    ok.click()
    pump(0.5)
    layouts = objects_of_type(doc, layout_mod.TYPE)
    expect(len(layouts) == 1, f"{len(layouts)} layouts after OK")
    layout = layouts[0]
    expect((layout.Columns, layout.Rows, layout.MemberCount) == (3, 2, 6),
           f"layout {layout.Columns} x {layout.Rows}, {layout.MemberCount} members")
    expect(doc.UndoCount == undo_before + 1,
           f"creating the layout made {doc.UndoCount - undo_before} undo steps, not 1")
    expect(not FreeCADGui.Control.activeDialog(), "the layout panel stayed open after OK")
    positions = sorted((round(p.Base.x), round(p.Base.y), round(p.Base.z))
                       for _, _, p in layout_mod.layout_placements(layout))
    STATUS["positions_mm"] = positions
    expect(positions == sorted((x, y, 2950) for x in (1000, 2500, 4000) for y in (1000, 3000)),
           f"members at {positions}")
    return layout


def _run(doc):
    import FreeCADGui

    from lighting.taskpanels import analysis_panel

    doc.getObject("LightingAnalysis").Photons = 20000
    before = analysis_panel.last_run()  # a finished earlier run is not this one
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.runCommand("Lighting_Run")
    done = wait_until(lambda: analysis_panel.last_run() is not None
                      and analysis_panel.last_run() is not before
                      and analysis_panel.last_run().stage in ("done", "failed", "cancelled"), 240)
    pump(1.0)
    run = analysis_panel.last_run()
    expect(done and run.stage == "done", f"run ended as {run.stage if run else None}")
    import lighting

    result = lighting.results(doc)
    if result is not None:
        STATUS["workplane_em_lux"] = result["Workplane"].mean_lux
        log(result.table())
    expect(result is not None and result["Workplane"].mean_lux > 100.0,
           "no workplane illuminance after the run")
    FreeCADGui.ActiveDocument.ActiveView.fitAll()
    grab_window("layout_3x2", docs_name="layout-3x2.png")
    FreeCADGui.Control.closeDialog()
    pump(0.3)


def _edit_later(doc, layout):
    """Double click (setEdit) opens the panel on the layout: Cancel restores it, OK with 3 rows
    gives 9 luminaires in one undo step, Undo brings back the 3 x 2."""
    import FreeCADGui

    from lighting.taskpanels import layout_panel

    def edit_rows(rows, button):
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.ActiveDocument.setEdit(layout.Name)
        pump(0.5)
        panel = layout_panel.last_panel()
        expect(panel is not None and panel.layout == layout, "double click opened no layout panel")
        panel.rows.setValue(rows)
        pump(0.3)
        expect(layout.MemberCount == 3 * rows, f"live preview: {layout.MemberCount} members")
        from PySide import QtGui

        for box in main_window().findChildren(QtGui.QDialogButtonBox):
            found = box.button(button)
            if found is not None and found.isVisible():
                found.click()
                break
        pump(0.5)

    undo_before = doc.UndoCount
    edit_rows(4, _standard_button("Cancel"))
    expect((layout.Rows, layout.MemberCount) == (2, 6),
           f"Cancel left {layout.Rows} rows, {layout.MemberCount} members")
    expect(doc.UndoCount == undo_before, "Cancel left an undo step")
    edit_rows(3, _standard_button("Ok"))
    expect((layout.Rows, layout.MemberCount) == (3, 9),
           f"OK left {layout.Rows} rows, {layout.MemberCount} members")
    expect(doc.UndoCount == undo_before + 1,
           f"editing made {doc.UndoCount - undo_before} undo steps, not 1")
    FreeCADGui.runCommand("Std_Undo")
    pump(0.5)
    doc.recompute()
    expect((layout.Rows, layout.MemberCount) == (2, 6),
           f"Undo left {layout.Rows} rows, {layout.MemberCount} members")


def _standard_button(name):
    """A QDialogButtonBox standard button by name ("Ok", "Cancel")."""
    from PySide import QtGui

    return getattr(QtGui.QDialogButtonBox, name)


def _double_click_slip(doc, ceiling, face):
    import FreeCADGui

    from lighting.taskpanels import analysis_panel

    for _ in range(2):
        _select(doc, ceiling, face)
        FreeCADGui.runCommand("Lighting_Luminaire")
        pump(0.3)
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.runCommand("Lighting_Check")
    pump(1.0)
    panel = analysis_panel.last_panel()
    text = panel.log_view.toPlainText() if panel is not None else ""
    STATUS["check_log"] = text
    warned = [line for line in text.splitlines() if "same point" in line]
    expect(len(warned) == 1 and "'Luminaire'" in warned[0] and "'Luminaire001'" in warned[0],
           f"Check did not warn about the coincident luminaires: {text!r}")
    if panel is not None:  # the user scrolls the log up to the first warning
        panel.log_view.verticalScrollBar().setValue(0)
    grab_window("layout_coincident_check", docs_name="layout-coincident.png")


def _luminaire_with_nothing_selected(doc):
    """Nothing selected: the luminaire goes under the ceiling at the room's centre."""
    import FreeCADGui

    FreeCADGui.Control.closeDialog()
    FreeCADGui.Selection.clearSelection()
    before = {o.Name for o in doc.Objects}
    FreeCADGui.runCommand("Lighting_Luminaire")
    pump(0.3)
    new = [doc.getObject(n) for n in {o.Name for o in doc.Objects} - before]
    expect(len(new) == 1, f"Luminaire with nothing selected made {len(new)} objects")
    if new:
        p = new[0].Placement.Base
        STATUS["default_luminaire_mm"] = [p.x, p.y, p.z]
        expect((p - type(p)(2500, 2000, 2950)).Length < 1e-6,
               f"luminaire with nothing selected at {p}, not the room's centre under the ceiling")


def body() -> None:
    expect(STATUS["start_workbench"] == "StartWorkbench",
           f"FreeCAD did not start on the Start page: {STATUS['start_workbench']}")
    doc, ceiling, face = _office()
    layout = _layout_from_panel(doc, ceiling, face)
    _run(doc)
    _edit_later(doc, layout)
    _double_click_slip(doc, ceiling, face)
    _luminaire_with_nothing_selected(doc)


scenario(body)
