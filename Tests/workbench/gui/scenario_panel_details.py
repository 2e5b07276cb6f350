"""GUI scenario: the analysis panel's details at FreeCAD's default window size. The user builds
the office with an office task on the workplane and an *Observer* (UGR limit 19), runs, and:

- reads every target's name whole in the results table, each on its own line above its values
  (a name squeezed beside the value columns was elided to "D..."): the row is tall enough for
  the name wrapped to the table's width and the pixels of its band reach across the name;
  a long name, typed as the target's Label, wraps instead of being cut;
- unticks *Decide requirements*, asks for an Em just at what the workplane gets and runs: the
  Undecided summary says Decide was off (not a limit the run never tried) and offers Decide;
- ticks *All columns*: every figure with its interval (Emin, Emax, U0; the observer's UGR and
  limit) and each requirement's verdict appear one per line under the table, and neither table
  is wider than the panel (no sideways scrolling), no value cut short;
- reads the observer's row: UGR with its interval and limit, never an illuminance or an area;
- types a photon count without pressing Run, then moves a luminaire (an unrelated change the
  panel refreshes on): the typed value stays; a script setting the analysis' Photons (as Undo
  of "Lighting settings" does) is followed."""
import os
import sys

from guilib import STATUS, expect, grab_window, log, pump, scenario, wait_until

sys.path.insert(0, os.path.join(os.environ.get("LIGHTING_SOURCE_DIR", "."), "Examples"))

OFFICE = "Offices: Writing, typing, reading, data processing"


def fits(table) -> dict:
    """Whether ``table`` needs no sideways scrolling and shows every cell's text whole."""
    from PySide import QtGui

    header = table.horizontalHeader()
    metrics = QtGui.QFontMetrics(table.font())
    cut = []
    for row in range(table.rowCount()):
        for column in range(table.columnCount()):
            item = table.item(row, column)
            if item is None or table.isColumnHidden(column) or column == 0:
                continue  # the first column elides long labels by design (tooltip)
            if table.columnSpan(row, column) > 1:
                continue
            if metrics.horizontalAdvance(item.text()) + 6 > table.columnWidth(column):
                cut.append(item.text())
    return {"content_px": header.length(), "viewport_px": table.viewport().width(),
            "cut": cut, "scrollbar": table.horizontalScrollBar().isVisible()}


def names_shown(table) -> dict:
    """Whether each target's name (column 0's text) can be read whole: in a visible column
    wide enough for it, or, column 0 hidden, drawn on its row above the values: the row is as
    tall as the name wrapped to the table's width (bold, as drawn) plus a line of values, and
    the dark pixels of that band reach across the name (an elided "D..." reaches a few
    pixels)."""
    from PySide import QtCore, QtGui

    plain = QtGui.QFontMetrics(table.font())
    bold_font = QtGui.QFont(table.font())
    bold_font.setBold(True)
    bold = QtGui.QFontMetrics(bold_font)
    width = table.horizontalHeader().length()
    image = table.viewport().grab().toImage()
    scale = image.width() / max(table.viewport().width(), 1)  # 1 under Xvfb
    out = []
    for row in range(table.rowCount()):
        name = table.item(row, 0).text()
        if not table.isColumnHidden(0):
            out.append({"name": name, "ok": plain.horizontalAdvance(name) + 6
                        <= table.columnWidth(0), "column_px": table.columnWidth(0)})
            continue
        # Wrapped between words, anywhere only within a word longer than the line.
        longest = max((bold.horizontalAdvance(w) for w in name.split()), default=0)
        wrap = QtCore.Qt.TextWrapAnywhere if longest > width - 8 else QtCore.Qt.TextWordWrap
        wrapped = bold.boundingRect(QtCore.QRect(0, 0, width - 8, 100000),
                                    int(QtCore.Qt.AlignLeft | wrap), name)
        top, height = table.rowViewportPosition(row), table.rowHeight(row)
        xs = [x for y in range(top, top + wrapped.height() + 2)
              for x in range(0, width)
              if QtGui.qGray(image.pixel(int(x * scale), int(y * scale))) < 100]
        reach = (max(xs) - min(xs) + 1) if xs else 0
        wanted = 0.8 * min(bold.horizontalAdvance(name), width - 8)
        out.append({"name": name, "row_px": height, "needed_px": wrapped.height()
                    + plain.height(), "lines": round(wrapped.height() / bold.lineSpacing()),
                    "ink_px": reach, "name_px": bold.horizontalAdvance(name),
                    "ok": height >= wrapped.height() + plain.height() and reach >= wanted})
    return {"rows": out, "cut": [r["name"] for r in out if not r["ok"]]}


def check_names(panel, what: str) -> dict:
    """Every name in the table readable whole (names_shown); ``what`` names the check."""
    shown = names_shown(panel.table)
    STATUS.setdefault("names", {})[what] = shown
    expect(panel.table.rowCount() > 0 and not shown["cut"],
           f"target names cut short in the table ({what}): {shown}")
    return shown


def check_long_name(panel, doc) -> None:
    """A long Label, typed in the property editor: shown whole, wrapped over two lines."""
    target = [o for o in doc.Objects if o.Label == "Desk top"][0]
    long_name = "Desk top by the window on the north side of the office"
    target.Label = long_name
    doc.recompute()
    ok = wait_until(lambda: any(panel.table.item(r, 0).text() == long_name
                                for r in range(panel.table.rowCount())), 3.0)
    pump(0.5)
    expect(ok, f"the table does not show the new Label {long_name!r}")
    shown = check_names(panel, "long name")
    lines = [r.get("lines", 1) for r in shown["rows"] if r["name"] == long_name]
    expect(lines and lines[0] >= 2, f"the long name does not wrap: {shown}")
    panel.scroll.ensureWidgetVisible(panel.table)
    pump(0.3)
    grab_window("panel_long_name")


def check_decide_off(panel, doc) -> None:
    """A run with Decide off that leaves the workplane undecided: the summary says why."""
    from lighting.taskpanels import analysis_panel

    workplane = [o for o in doc.Objects if o.Label == "Workplane"][0]
    workplane.RequiredLux = 580.0  # about its Em: undecided after a short run
    doc.recompute()
    panel.decide.setChecked(False)  # the user unticks it, sets a short run and presses Run
    panel.photons.setValue(16384)
    before = analysis_panel.last_run()
    panel.buttons["run"].click()
    ok = wait_until(lambda: analysis_panel.last_run() is not before
                    and analysis_panel.last_run().finished, 180.0)
    expect(ok, "the run with Decide off did not finish")
    pump(0.5)
    view = panel.decide_view
    summary = view.summary.text()
    STATUS["decide_off"] = {"summary": summary, "buttons": [b.text() for b in view.buttons],
                            "items": [i.text() for i in view.items]}
    expect(any(i.target == "Workplane" and i.name == "Em" for i in view.items),
           f"the workplane's Em is not undecided: {STATUS['decide_off']}")
    expect("Decide requirements was off for this run" in summary and "Press Decide" in summary
           and "continues by itself" not in summary, f"the Decide-off summary: {summary!r}")
    expect(bool(view.buttons) and all(b.isEnabled() for b in view.buttons),
           f"no Decide offered: {STATUS['decide_off']}")
    panel.scroll.ensureWidgetVisible(panel.sections["undecided"])
    pump(0.3)
    expect_no_sideways_scrolling(panel, "Decide off")
    grab_window("panel_decide_off", docs_name="decide-off.png")


def expect_no_sideways_scrolling(panel, what: str) -> None:
    """The panel's content is no wider than its viewport (a Decide button's long text once
    pushed it sideways, cutting every line's first letters)."""
    from PySide import QtGui

    room = panel.scroll.viewport().width()
    wide = [(w.minimumSizeHint().width(), type(w).__name__, (w.text() if hasattr(w, "text")
                                                             else "")[:40])
            for w in panel.form.findChildren(QtGui.QWidget)
            if w.isVisible() and w.minimumSizeHint().width() > room]
    shift = panel.scroll.horizontalScrollBar().maximum()
    STATUS.setdefault("sideways", {})[what] = {"viewport_px": room, "scroll_px": shift,
                                               "too_wide": sorted(wide, reverse=True)[:6]}
    expect(shift == 0, f"the panel scrolls sideways ({what}): {STATUS['sideways'][what]}")


def check_all_columns(panel, eye) -> None:
    view = panel.results_view
    panel.all_columns.setChecked(True)  # the user ticks it
    pump(0.5)
    details = view.details
    expect(details.isVisible() and details.rowCount() > 0, "All columns shows no details")
    texts = [[details.item(r, c).text() if details.item(r, c) else "" for c in range(3)]
             for r in range(details.rowCount())]
    STATUS["details"] = texts
    main, more = fits(panel.table), fits(details)
    STATUS["fit"] = {"table": main, "details": more,
                     "panel_px": panel.scroll.viewport().width()}
    for name, fit in (("table", main), ("details", more)):
        expect(fit["content_px"] <= fit["viewport_px"] and not fit["scrollbar"],
               f"the {name} is wider than the panel: {fit}")
        expect(not fit["cut"], f"values cut short in the {name}: {fit['cut']}")
    expect(details.width() <= panel.scroll.viewport().width(),
           f"the details table is wider than the panel: {STATUS['fit']}")
    flat = [" | ".join(t) for t in texts]
    for wanted in ("Workplane (grid)", "Emin", "Emax", "U0", "Em >= 500 lx"):
        expect(any(wanted in line for line in flat), f"no {wanted!r} in the details: {flat}")
    eye_rows = [line for line in flat if line.startswith(eye.Label)]
    expect(bool(eye_rows), f"no details for the observer: {flat}")
    at = flat.index(eye_rows[0]) if eye_rows else 0
    mine = flat[at + 1:at + 3]
    expect(len(mine) == 2 and mine[0].startswith("UGR |") and " - " in mine[0].split(" | ")[2]
           and mine[1].startswith("UGR <= 19 |"), f"the observer's details: {mine}")
    expect(not any(" lx" in line for line in mine), f"the observer shows lux: {mine}")


def check_observer_row(panel, eye) -> None:
    table = panel.table
    row = [r for r in range(table.rowCount()) if table.item(r, 0).text() == eye.Label]
    expect(len(row) == 1, f"no row for {eye.Label}")
    if not row:
        return
    cells = [table.item(row[0], c).text() for c in range(table.columnCount())]
    tip = table.item(row[0], 2).toolTip()
    STATUS["observer_row"] = {"cells": cells, "tooltip": tip}
    expect(cells[2].startswith("UGR "), f"the observer's row: {cells}")
    expect("interval" in tip and "UGR <= 19:" in tip and " lx" not in tip and "m\u00b2" not in tip
           and "Em" not in tip, f"the observer's tooltip: {tip!r}")
    work = [r for r in range(table.rowCount()) if table.item(r, 0).text() == "Workplane"][0]
    wtip = table.item(work, 2).toolTip()
    STATUS["workplane_tooltip"] = wtip
    expect("Em >= 500 lx:" in wtip and "interval" in wtip, f"workplane tooltip: {wtip!r}")


def check_typed_value_kept(panel, doc, analysis) -> None:
    """A value being typed survives an unrelated change; a change of the value itself is
    followed."""
    from PySide import QtCore, QtGui

    box = panel.photons
    panel.scroll.ensureWidgetVisible(box)
    box.setFocus()
    box.selectAll()
    for char in "123456":  # typed key by key, as a user types
        for kind in (QtCore.QEvent.KeyPress, QtCore.QEvent.KeyRelease):
            QtGui.QApplication.sendEvent(box, QtGui.QKeyEvent(
                kind, int(getattr(QtCore.Qt, f"Key_{char}")), QtCore.Qt.NoModifier, char))
    pump(0.2)
    typed = box.value()
    lum = doc.getObject("Luminaire01")
    base = lum.Placement.Base
    lum.Placement.Base = base.add(type(base)(100.0, 0.0, 0.0))  # the property editor's move
    doc.recompute()
    pump(1.0)  # the panels refresh 0.15 s after the burst of changes
    STATUS["typed"] = {"typed": typed, "after_unrelated": box.value(),
                       "document": int(analysis.Photons), "state": panel.state_label.text()}
    # The panel did refresh on the move (its state line says the results are stale).
    expect("out of date" in panel.state_label.text(),
           f"the panel did not refresh on the move: {panel.state_label.text()}")
    expect(typed == 123456 and box.value() == 123456,
           f"the typed photons did not survive an unrelated change: {STATUS['typed']}")
    analysis.Photons = 50000  # what Undo of "Lighting settings" does to the document
    doc.recompute()
    ok = wait_until(lambda: box.value() == 50000, 2.0)
    STATUS["typed"]["after_document_change"] = box.value()
    expect(ok, f"the field did not follow the document's Photons: {box.value()}")
    box.clearFocus()
    panel.form.setFocus(QtCore.Qt.OtherFocusReason)


def body() -> None:
    import FreeCADGui

    import lighting
    import office_model
    from lighting.taskpanels import analysis_panel

    doc = office_model.build_office(photons=100000, seed=1)
    office_model.show_in_gui(doc)
    pump(0.5)
    workplane = [o for o in doc.Objects if o.Label == "Workplane"][0]
    workplane.Activity = OFFICE
    analysis = doc.getObject(office_model.OBJECTS["analysis"])
    eye = lighting.make_observer(doc, (2.5, 1.5, 1.2), analysis=analysis)
    doc.recompute()
    expect(float(eye.UgrMax) == 19.0, f"observer limit {eye.UgrMax}")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(analysis)
    FreeCADGui.runCommand("Lighting_Run")
    ok = wait_until(lambda: analysis_panel.last_run() is not None
                    and analysis_panel.last_run().finished, 180.0)
    expect(ok, "the run did not finish")
    pump(0.5)
    panel = analysis_panel.last_panel()
    check_observer_row(panel, eye)
    check_names(panel, "default width")
    check_all_columns(panel, eye)
    check_names(panel, "all columns")  # the panel's scroll bar narrows the table
    expect_no_sideways_scrolling(panel, "all columns")
    log(f"fit {STATUS.get('fit')}")
    panel.scroll.ensureWidgetVisible(panel.results_view.details)
    panel.scroll.ensureWidgetVisible(panel.table)
    pump(0.3)
    grab_window("panel_all_columns", docs_name="panel-all-columns.png")
    check_typed_value_kept(panel, doc, analysis)
    check_long_name(panel, doc)
    check_decide_off(panel, doc)


scenario(body)
