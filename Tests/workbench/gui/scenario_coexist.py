"""GUI scenario: the panels show the document's state and coexist with the commands (issue 25
items 1 and 2). The user builds the office and opens the analysis panel:
- runs twice, then Edit > Undo ("Lighting results") with the panel open: the panel's table
  (numbers and verdicts), the legend's verdict markers and the document's results agree;
- turns the mouse wheel over every spin box and combo box of the analysis, Optimize, chooser
  and layout panels without clicking them first: no value changes (a clicked one does);
- opens Optimize placement, then Run analysis: the analysis panel replaces it and runs;
- Edit > Delete of the results, then of the analysis, with the analysis panel open: both are
  deleted, the panel follows (no results), then closes."""
import os
import sys

from guilib import (OUT, STATUS, expect, grab_window, log, main_window, pump, scenario,
                    wait_until)

sys.path.insert(0, os.path.join(os.environ.get("LIGHTING_SOURCE_DIR", "."), "Examples"))


def shown(panel) -> bool:
    """Whether the panel's widgets are in the task view (FreeCAD sets a closed dialog's
    ``form`` to None and deletes its widgets)."""
    import FreeCADGui

    form = getattr(panel, "form", None) if panel is not None else None
    try:
        return form is not None and FreeCADGui.Control.activeDialog() \
            and form.parentWidget() is not None
    except RuntimeError:
        return False


def answer_dialogs() -> object:
    """Answer a modal question (Delete's dependency check) with Yes, noting its text."""
    from PySide import QtCore, QtGui

    timer = QtCore.QTimer()
    timer.setInterval(200)

    def look() -> None:
        box = QtGui.QApplication.activeModalWidget()
        if isinstance(box, QtGui.QMessageBox):
            STATUS.setdefault("dialogs", []).append(box.text())
            button = box.button(QtGui.QMessageBox.Yes) or box.defaultButton()
            if button is not None:
                button.click()
            else:
                box.accept()

    timer.timeout.connect(look)
    timer.start()
    return timer


def wait_for_run(analysis_panel, previous) -> object:
    ok = wait_until(lambda: analysis_panel.last_run() is not None
                    and analysis_panel.last_run() is not previous
                    and analysis_panel.last_run().finished, 120.0)
    expect(ok, "the run did not finish")
    pump(1.0)
    job = analysis_panel.last_run()
    expect(job is not None and job.stage == "done", f"run: {getattr(job, 'stage', None)}")
    return job


def panel_rows(panel) -> dict:
    """Target -> (Em text, verdict) as the panel's table shows them."""
    table = panel.table
    last = table.columnCount() - 1
    return {table.item(r, 0).text(): (table.item(r, 2).text(), table.item(r, last).text())
            for r in range(table.rowCount())}


def document_rows(analysis) -> dict:
    """Target -> (Em text, verdict) of the document's results object."""
    from lighting.solver import store

    result = store.load_from_document(analysis)
    return {t.label: (f"{t.mean_lux:.1f}", t.verdict_text()) for t in result.targets
            if t.kind != "glare" and not t.is_glare}


def legend_texts(analysis) -> list:
    """The strings drawn in the 3D legend (title, ticks, verdict markers)."""
    holder = analysis.ViewObject.Proxy.legend_holder
    found = []

    def walk(node) -> None:
        name = node.getTypeId().getName().getString()
        if name in ("Text2", "AsciiText", "Text3"):
            found.extend(str(s) for s in node.string.getValues())
        if hasattr(node, "getNumChildren"):
            for i in range(node.getNumChildren()):
                walk(node.getChild(i))

    walk(holder)
    return found


def check_undo(doc, analysis, analysis_panel) -> None:
    import FreeCADGui

    panel = analysis_panel.last_panel()
    # Fixed photon counts (no accuracy goal, no deciding): the two runs differ.
    panel.accuracy.setValue(0.0)
    panel.decide.setChecked(False)
    panel.photons.setValue(30000)
    panel.buttons["run"].click()
    first = wait_for_run(analysis_panel, None)
    first_rows = panel_rows(panel)
    panel.photons.setValue(90000)
    panel.buttons["run"].click()
    wait_for_run(analysis_panel, first)
    second_rows = panel_rows(panel)
    STATUS["runs"] = [first_rows, second_rows]
    expect(first_rows != second_rows, f"the two runs show the same table: {first_rows}")
    expect(doc.UndoNames and doc.UndoNames[0] == "Lighting results",
           f"the last undo step is not the results: {doc.UndoNames[:3]}")
    FreeCADGui.runCommand("Std_Undo")  # Edit > Undo, the panel open
    pump(1.5)
    shown, stored = panel_rows(panel), document_rows(analysis)
    STATUS["after_undo"] = {"panel": shown, "document": stored}
    expect({k: shown.get(k) for k in stored} == stored,
           f"after Undo the panel shows {shown}, the document holds {stored}")
    expect(shown == first_rows, f"after Undo the panel does not show the first run: {shown}")
    texts = legend_texts(analysis)
    STATUS["legend_after_undo"] = texts
    for label, (_, verdict) in stored.items():
        word = verdict.split(" ")[0]
        if word in ("pass", "FAIL", "undecided"):
            expect(any(label in t and word in t for t in texts),
                   f"the legend does not say {label}: {word}: {texts}")
    grab_window("coexist_undo")
    FreeCADGui.runCommand("Std_Redo")
    wait_until(lambda: panel_rows(panel) == second_rows, 10.0)
    expect(panel_rows(panel) == second_rows, "after Redo the panel does not show the 2nd run")


class XPointer:
    """The X server's pointer and wheel (XTest, as a real mouse): Qt gets spontaneous wheel
    events under the cursor, with its own focus and propagation rules."""

    def __init__(self) -> None:
        import ctypes

        self.x11 = ctypes.cdll.LoadLibrary("libX11.so.6")
        self.xtst = ctypes.cdll.LoadLibrary("libXtst.so.6")
        self.x11.XOpenDisplay.restype = ctypes.c_void_p
        self.x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
        self.x11.XFlush.argtypes = [ctypes.c_void_p]
        self.xtst.XTestFakeMotionEvent.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int,
                                                   ctypes.c_int, ctypes.c_ulong]
        self.xtst.XTestFakeButtonEvent.argtypes = [ctypes.c_void_p, ctypes.c_uint,
                                                   ctypes.c_int, ctypes.c_ulong]
        self.display = self.x11.XOpenDisplay(None)
        if not self.display:
            raise RuntimeError("cannot open the X display")

    def wheel_over(self, widget, notches: int = 3) -> None:
        """Move the pointer over the widget's centre and turn the wheel down ``notches``.
        ``last`` says where the pointer went and whether it is over the widget."""
        from PySide import QtGui

        centre = widget.mapToGlobal(widget.rect().center())
        ratio = widget.devicePixelRatioF()  # Qt's coordinates are scaled on this screen
        x, y = round(centre.x() * ratio), round(centre.y() * ratio)
        for _ in range(3):  # correct the scaling's rounding from where the pointer lands
            self.xtst.XTestFakeMotionEvent(self.display, -1, x, y, 0)
            self.x11.XFlush(self.display)
            pump(0.1)
            cursor = QtGui.QCursor.pos()
            if cursor == centre:
                break
            x += round((centre.x() - cursor.x()) * ratio)
            y += round((centre.y() - cursor.y()) * ratio)
        under = QtGui.QApplication.widgetAt(cursor)
        self.last = [(centre.x(), centre.y()), (cursor.x(), cursor.y()),
                     type(under).__name__ if under is not None else None,
                     under is widget or (under is not None and widget.isAncestorOf(under))]
        for _ in range(notches):
            self.xtst.XTestFakeButtonEvent(self.display, 5, 1, 0)  # button 5: wheel down
            self.xtst.XTestFakeButtonEvent(self.display, 5, 0, 0)
            self.x11.XFlush(self.display)
            pump(0.05)
        pump(0.1)


_pointer = None


def pointer() -> XPointer:
    global _pointer
    if _pointer is None:
        _pointer = XPointer()
    return _pointer


def value_of(widget):
    from PySide import QtGui

    return widget.currentIndex() if isinstance(widget, QtGui.QComboBox) else widget.value()


def bring_into_view(widget) -> None:
    """Scroll every scroll area above the widget (the panel's, the task view) to show it."""
    from PySide import QtGui

    parent = widget.parentWidget()
    while parent is not None:
        if isinstance(parent, QtGui.QScrollArea):
            parent.ensureWidgetVisible(widget)
        parent = parent.parentWidget()
    pump(0.1)


def check_wheel(name: str, form) -> None:
    """The wheel over every field of ``form`` that has no focus: no value changes (the panel
    scrolls); then over a focused spin box: it changes (the guard leaves clicked fields)."""
    from PySide import QtGui

    main_window().activateWindow()
    main_window().setFocus()
    pump(0.2)
    fields = [w for w in form.findChildren(QtGui.QWidget)
              if isinstance(w, (QtGui.QAbstractSpinBox, QtGui.QComboBox)) and w.isEnabled()
              and w.isVisible()]
    values = {id(f): value_of(f) for f in fields}
    changed = []
    missed = []
    for field in fields:
        bring_into_view(field)
        pointer().wheel_over(field)
        if not pointer().last[3]:
            missed.append(pointer().last)
    expect(not missed, f"{name}: the pointer was not over these fields: {missed}")
    for field in fields:
        if value_of(field) != values[id(field)]:
            changed.append(f"{type(field).__name__} {values[id(field)]} -> {value_of(field)}")
    STATUS.setdefault("wheel", {})[name] = {"fields": len(fields), "changed": changed}
    expect(not changed, f"{name}: the wheel changed unfocused fields: {changed}")
    spins = [f for f in fields if isinstance(f, QtGui.QAbstractSpinBox) and not f.isReadOnly()
             and f.maximum() > f.minimum() + 2]
    # The control: a real wheel reaches the fields, and a focused (clicked) one follows it.
    tries = []
    for spin in spins:
        bring_into_view(spin)
        centre = spin.mapToGlobal(spin.rect().center())
        under = QtGui.QApplication.widgetAt(centre)
        if under is not spin and (under is None or not spin.isAncestorOf(under)):
            continue  # covered or scrolled out of the viewport: try the next one
        spin.setValue(spin.minimum() + 2 * spin.singleStep())
        spin.setFocus()
        pump(0.2)
        start = spin.value()
        pointer().wheel_over(spin, 1)
        tries.append([spin.hasFocus(), start, spin.value(), pointer().last])
        moved = spin.value() != start
        spin.setValue(values[id(spin)])
        main_window().setFocus()
        if moved:
            break
    STATUS["wheel"][name]["focused"] = tries
    expect(not spins or (tries and tries[-1][1] != tries[-1][2]),
           f"{name}: no focused spin box followed the wheel: {tries}")
    log(f"wheel {name}: {STATUS['wheel'][name]}")


def check_wheel_everywhere(doc, objects) -> None:
    import FreeCADGui

    from lighting.taskpanels import (analysis_panel, layout_panel, luminaire_chooser,
                                     optimize_panel)

    panel = analysis_panel.last_panel()
    panel.all_columns.setChecked(False)
    check_wheel("analysis", panel.form)
    grab_window("coexist_wheel_analysis")
    FreeCADGui.runCommand("Lighting_Optimize")
    pump(1.0)
    check_wheel("optimize", optimize_panel.last_panel().form)
    grab_window("coexist_wheel_optimize")
    FreeCADGui.runCommand("Lighting_ChooseLuminaire")
    pump(1.5)
    check_wheel("chooser", luminaire_chooser.last_panel().form)  # no fields today: recorded
    luminaire_chooser.last_panel().reject()
    pump(0.5)
    FreeCADGui.runCommand("Lighting_LuminaireLayout")
    pump(1.5)
    check_wheel("layout", layout_panel.last_panel().form)
    grab_window("coexist_wheel_layout")
    layout_panel.last_panel().reject()
    pump(0.5)


def check_run_with_optimize(analysis, analysis_panel) -> None:
    import FreeCADGui

    from lighting.taskpanels import optimize_panel

    FreeCADGui.runCommand("Lighting_Optimize")
    wait_until(lambda: shown(optimize_panel.last_panel()), 10.0)
    expect(shown(optimize_panel.last_panel()), "the Optimize panel did not open")
    previous = analysis_panel.last_run()
    old_panel = analysis_panel.last_panel()
    FreeCADGui.runCommand("Lighting_Run")  # used to fail: 'NoneType' ... 'parentWidget'
    wait_until(lambda: analysis_panel.last_panel() is not old_panel
               and shown(analysis_panel.last_panel())
               and not shown(optimize_panel.last_panel()), 10.0)
    panel = analysis_panel.last_panel()
    expect(panel is not old_panel and shown(panel),
           "Run analysis did not open the analysis panel over Optimize")
    expect(not shown(optimize_panel.last_panel()), "the Optimize panel is still open")
    wait_for_run(analysis_panel, previous)
    grab_window("coexist_run_over_optimize")


def check_delete(doc, analysis, analysis_panel) -> None:
    import FreeCADGui

    from lighting.objects import results

    analysis.ViewObject.Proxy.doubleClicked(analysis.ViewObject)  # a double-click in the tree
    pump(1.0)
    panel = analysis_panel.last_panel()
    expect(shown(panel), "double-click did not open the analysis panel")
    STATUS["in_edit_after_double_click"] = str(FreeCADGui.ActiveDocument.getInEdit())
    found = results.of_analysis(analysis)
    expect(found is not None, "no results to delete")
    name, results_name = analysis.Name, found.Name
    timer = answer_dialogs()
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(found)
    FreeCADGui.runCommand("Std_Delete")  # Edit > Delete
    wait_until(lambda: doc.getObject(results_name) is None and shown(panel)
               and panel.table.rowCount() == 0, 10.0)
    expect(doc.getObject(results_name) is None, "Delete did not delete the results")
    expect(shown(panel) and panel.table.rowCount() == 0,
           f"the panel does not follow the deleted results: {panel.table.rowCount()} rows")
    grab_window("coexist_delete_results")
    members = [o.Name for o in analysis.Group]
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(analysis)
    FreeCADGui.runCommand("Std_Delete")
    wait_until(lambda: doc.getObject(name) is None and not shown(panel), 10.0)
    timer.stop()
    expect(doc.getObject(name) is None, "Delete did not delete the analysis with its panel open")
    expect(not shown(panel), "the deleted analysis' panel is still open")
    expect(all(doc.getObject(m) is not None for m in members), "the analysis' members were lost")
    grab_window("coexist_delete_analysis")
    FreeCADGui.runCommand("Std_Undo")  # the analysis comes back
    wait_until(lambda: doc.getObject(name) is not None, 10.0)
    expect(doc.getObject(name) is not None, "Undo did not bring the analysis back")


def body() -> None:
    import FreeCAD

    import office_model
    from lighting.taskpanels import analysis_panel

    doc = office_model.build_office(photons=30000)
    office_model.show_in_gui(doc)
    pump(0.5)
    analysis = doc.getObject(office_model.OBJECTS["analysis"])
    analysis.ViewObject.Proxy.doubleClicked(analysis.ViewObject)
    pump(1.0)
    expect(analysis_panel.last_panel() is not None, "no analysis panel")
    check_undo(doc, analysis, analysis_panel)
    check_wheel_everywhere(doc, office_model.OBJECTS)
    check_run_with_optimize(analysis, analysis_panel)
    check_delete(doc, analysis, analysis_panel)
    FreeCAD.closeDocument(doc.Name)


scenario(body)
