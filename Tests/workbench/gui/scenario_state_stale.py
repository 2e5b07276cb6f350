"""GUI scenario: the model state is always true (issue 12, items 1, 3, 10).

From the Start page the user opens the example office (built by Examples/office.py without
solving), picks the Lighting workbench and runs the analysis; hides the ceiling to look into
the room and runs again: Em is bit-identical (hidden is not excluded) and the second run adds
no undo step; the status bar shows one short line. Then the user doubles a luminaire's flux
in the property editor: the panel and the legend say the results are out of date
(screenshot for the docs); Undo makes them current again. Finally "Exclude from lighting" on the ceiling: Check lists it as
left out, and the results are stale."""

from guilib import (build_example_file, STATUS, expect, grab_window, log, main_window, pump,
                    run_from_toolbar, scenario, wait_until)

PHOTONS = 100000


def build_example() -> str:
    return build_example_file(PHOTONS)


def workplane_em(doc):
    from lighting.objects import results as results_obj

    found = results_obj.of_analysis(doc.getObject("LightingAnalysis"))
    return results_obj.mean_lux(found, "Workplane") if found is not None else None


def last_report_line() -> str:
    """The last line of FreeCAD's report view (the message the status bar shows)."""
    from PySide import QtGui

    pump(0.3)
    for dock in main_window().findChildren(QtGui.QDockWidget):
        if dock.objectName() == "Report view":
            edits = dock.findChildren(QtGui.QTextEdit)
            if edits:
                lines = [ln for ln in edits[0].toPlainText().splitlines() if ln.strip()]
                return lines[-1] if lines else ""
    return ""


def combo_tab(title: str) -> None:
    """Show the Combo View's tab ``title`` ("Model" or "Tasks"), as a click on it does."""
    from PySide import QtGui

    for dock in main_window().findChildren(QtGui.QDockWidget):
        if dock.objectName() == "Combo View":
            for tabs in dock.findChildren(QtGui.QTabWidget):
                for i in range(tabs.count()):
                    if tabs.tabText(i) == title:
                        tabs.setCurrentIndex(i)
    pump(0.2)


def edit_in_property_editor(obj, shown_name: str, value: float) -> bool:
    """Select ``obj``, click the value cell of the property ``shown_name`` in the property
    editor (Model tab, Data), type ``value`` and press Return: what a user does, with the
    property editor's own undo step."""
    import FreeCADGui
    from PySide import QtCore, QtGui

    combo_tab("Model")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(obj)
    pump(0.4)
    cell = None
    for editor in main_window().findChildren(QtGui.QTreeView):
        if "PropertyEditor" not in editor.metaObject().className() or not editor.isVisible():
            continue
        model = editor.model()
        for row in range(model.rowCount()):
            group = model.index(row, 0)
            for child in range(model.rowCount(group)):
                if model.data(model.index(child, 0, group)) == shown_name:
                    cell = (editor, model.index(child, 1, group))
    if not expect(cell is not None, f"property '{shown_name}' not in the property editor"):
        return False
    editor, index = cell
    editor.scrollTo(index)
    pump(0.1)
    centre = QtCore.QPointF(editor.visualRect(index).center())
    for kind in (QtCore.QEvent.MouseButtonPress, QtCore.QEvent.MouseButtonRelease):
        QtGui.QApplication.sendEvent(editor.viewport(), QtGui.QMouseEvent(
            kind, centre, QtCore.Qt.LeftButton, QtCore.Qt.LeftButton, QtCore.Qt.NoModifier))
    pump(0.3)
    field = QtGui.QApplication.focusWidget()
    if not expect(hasattr(field, "setValue"), f"no value editor opened: {field}"):
        return False
    field.setValue(value)
    QtGui.QApplication.sendEvent(field, QtGui.QKeyEvent(QtCore.QEvent.KeyPress,
                                                        QtCore.Qt.Key_Return,
                                                        QtCore.Qt.NoModifier))
    pump(0.3)
    return True


def legend_stale(doc) -> bool:
    proxy = doc.getObject("LightingAnalysis").ViewObject.Proxy
    return bool(proxy.legend_holder.getNumChildren()) and proxy.results_stale()


def body() -> None:
    import FreeCAD
    import FreeCADGui

    from lighting.taskpanels import analysis_panel

    path = build_example()
    FreeCADGui.activateWorkbench("LightingWorkbench")
    doc = FreeCAD.openDocument(path)
    pump(1.0)
    FreeCADGui.ActiveDocument.ActiveView.viewIsometric()
    FreeCADGui.SendMsgToActiveView("ViewFit")
    analysis = doc.getObject("LightingAnalysis")
    ceiling = doc.getObjectsByLabel("Ceiling")[0]

    # 1. Run with everything shown, then with the ceiling hidden: the same Em.
    run_from_toolbar(doc)
    shown = workplane_em(doc)
    # The status bar shows the last console message, squashed to one line (under Xvfb the 3D
    # view's preselection clears it at once, so read the report view's last line instead).
    message = last_report_line()
    STATUS["last_message"] = message
    expect("Lighting: done: Workplane Em" in message and len(message) < 220,
           f"the run's last message is not one short summary line: {message!r}")
    FreeCADGui.Control.closeDialog()
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(ceiling)
    FreeCADGui.runCommand("Std_ToggleVisibility")
    pump(0.3)
    expect(not ceiling.ViewObject.Visibility, "the ceiling is still shown")
    undo_hidden = doc.UndoCount
    run_from_toolbar(doc)
    hidden = workplane_em(doc)
    STATUS["em"] = {"shown": shown, "hidden": hidden}
    log(f"Em shown {shown}, ceiling hidden {hidden}")
    expect(shown is not None and hidden == shown,
           f"hiding the ceiling changed Em: {shown} -> {hidden}")
    expect(doc.UndoCount == undo_hidden,
           f"a second run of an unchanged model added undo steps: {doc.UndoNames[:3]}")
    STATUS["undo_names"] = list(doc.UndoNames[:5])
    expect("Lighting settings" not in doc.UndoNames,
           f"empty 'Lighting settings' undo step: {doc.UndoNames}")
    panel = analysis_panel.last_panel()
    expect("up to date" in panel.state_label.text(),
           f"panel state after the run: {panel.state_label.text()!r}")

    # 2. Double a flux in the property editor: stale everywhere.
    lum = doc.getObject("Luminaire01")
    flux = lum.FluxLumen
    undo_before = doc.UndoCount
    edit_in_property_editor(lum, "Flux Lumen", 2 * flux)
    expect(lum.FluxLumen == 2 * flux, f"the property editor did not set the flux: {lum.FluxLumen}")
    expect(doc.UndoCount == undo_before + 1, f"flux edit undo steps: {doc.UndoNames[:3]}")
    combo_tab("Tasks")
    ok = wait_until(lambda: "out of date" in panel.state_label.text(), 5)
    STATUS["state_after_flux"] = panel.state_label.text()
    expect(ok and "Luminaire01" in panel.state_label.text(),
           f"the panel does not say the results are stale: {panel.state_label.text()!r}")
    expect(wait_until(lambda: legend_stale(doc), 5), "the legend is not marked stale")
    expect(analysis.Status == "done", f"Status changed by an edit: {analysis.Status}")
    grab_window("state_stale", docs_name="state-stale.png")
    FreeCADGui.runCommand("Std_Undo")
    expect(lum.FluxLumen == flux, f"Undo did not restore the flux: {lum.FluxLumen}")
    ok = wait_until(lambda: "up to date" in panel.state_label.text(), 5)
    expect(ok, f"after Undo the results are not current again: {panel.state_label.text()!r}")
    expect(wait_until(lambda: not legend_stale(doc), 5), "the legend stays stale after Undo")

    # 3. Exclude the ceiling with the command: Check lists it, the results are stale.
    FreeCADGui.Control.closeDialog()
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(ceiling)
    undo_before = doc.UndoCount
    FreeCADGui.runCommand("Lighting_Exclude")
    pump(0.3)
    expect(bool(getattr(ceiling, "LightingExclude", False)), "Exclude from lighting did nothing")
    expect(doc.UndoCount == undo_before + 1 and doc.UndoNames[0] == "Exclude from lighting",
           f"exclusion is not one undo step: {doc.UndoNames[:3]}")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.runCommand("Lighting_Check")
    pump(0.5)
    panel = analysis_panel.last_panel()
    text = panel.log_view.toPlainText()
    STATUS["check_log_tail"] = text[-600:]
    expect("'Ceiling' is left out of the lighting model: excluded" in text,
           "Check does not list the excluded ceiling")
    expect(doc.UndoCount == undo_before + 1, f"Check added an undo step: {doc.UndoNames[:3]}")
    expect(wait_until(lambda: "'Ceiling' left out" in panel.state_label.text(), 5),
           f"excluding did not make the results stale: {panel.state_label.text()!r}")
    grab_window("state_excluded")
    FreeCADGui.Control.closeDialog()


scenario(body)
