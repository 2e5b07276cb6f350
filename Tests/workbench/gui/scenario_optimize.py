"""GUI scenario: a designer optimizes the office's luminaire layout. From the Start page: the
Lighting workbench, a new document with the office example (four hand-placed ceiling panels,
a workplane that requires Em 500 lx and U0 0.6, a ceiling placement domain), Optimize
placement with small budgets. The panel must propose "meet Em and U0 with the least flux",
show progress with an estimated time left within seconds, ask before replacing the hand-placed
panels, list the optima, and Apply must leave exactly the chosen layout's luminaires - none
coincident - in one undo step. The panel's Decide then traces the applied layout with Decide on:
its verdicts are shown, decided or with what deciding needs and why the run stopped; after
Undo, Decide says the document no longer holds the layout instead of tracing."""
import os
import sys
import time

from guilib import (OUT, STATUS, expect, grab_window, log, main_window, pump, scenario,
                    toolbar_enabled, visible_in_window, wait_until)

REPO = os.environ.get("LIGHTING_SOURCE_DIR", "")


def build_office():
    """The office example in a new document, shown fitted (a user's first steps)."""
    import FreeCAD
    import FreeCADGui

    FreeCADGui.activateWorkbench("LightingWorkbench")
    doc = FreeCAD.newDocument("Office")
    pump(0.5)
    sys.path.insert(0, os.path.join(REPO, "Examples"))
    import office_model

    office_model.build_office(doc, photons=20000)
    FreeCADGui.SendMsgToActiveView("ViewFit")
    FreeCADGui.ActiveDocument.ActiveView.viewIsometric()
    pump(0.5)
    return doc, office_model.OBJECTS


def answer_replace_question(answer: str = "yes"):
    """Click the panel's question about the hand-placed luminaires when it appears (a modal
    dialog: only a timer gets to run while it is up)."""
    from PySide import QtCore, QtGui

    timer = QtCore.QTimer()
    timer.setInterval(100)

    def look() -> None:
        box = QtGui.QApplication.activeModalWidget()
        if box is not None and box.objectName() == "LightingOptimizeReplaceOthers":
            STATUS["question"] = box.text()
            path = os.path.join(OUT, "optimize_question.png")
            box.grab().save(path)
            STATUS["images"]["optimize_question"] = path
            button = QtGui.QMessageBox.Yes if answer == "yes" else QtGui.QMessageBox.No
            box.button(button).click()
            timer.stop()

    timer.timeout.connect(look)
    timer.start()
    return timer


def luminaire_layout(analysis):
    from lighting.objects import analysis as analysis_mod

    return {o.Label: o.getGlobalPlacement().Base for o in analysis_mod.luminaires(analysis)}


def body() -> None:
    import FreeCADGui

    from lighting.taskpanels import optimize_panel

    doc, names = build_office()
    analysis = doc.getObject(names["analysis"])
    before = luminaire_layout(analysis)
    log(f"luminaires before: {sorted(before)}")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(analysis)
    FreeCADGui.runCommand("Lighting_Optimize")
    pump(0.5)
    panel = optimize_panel.last_panel()
    expect(panel is not None, "Lighting_Optimize opened no panel")
    # Modeless: the model toolbar stays usable while the optimizer panel is open.
    STATUS["luminaire_enabled_with_panel"] = toolbar_enabled("Lighting_Luminaire")
    expect(STATUS["luminaire_enabled_with_panel"],
           "Lighting_Luminaire is disabled while the optimizer panel is open")
    panel.target.setCurrentText(doc.getObject(names["workplane"]).Label)
    pump(0.2)
    goal = panel.goal.currentData()
    STATUS["default_goal"] = goal
    expect(goal == "minimize_installed_flux",
           f"the default intention for a target with requirements is {goal}")
    expect(abs(panel.min_lux.value() - 500.0) < 1e-9 and abs(panel.min_u0.value() - 0.6) < 1e-9,
           f"required levels not taken from the target: {panel.min_lux.value()}, "
           f"{panel.min_u0.value()}")
    # Small budgets, set in the panel's fields as a user would.
    panel.evaluations.setValue(300)
    panel.screening.setValue(20000)
    panel.confirmation.setValue(200000)
    for name, button in panel.buttons.items():
        expect(visible_in_window(button), f"the {name} button is not fully visible")
    STATUS["panel_width"] = panel.form.width()
    watcher = answer_replace_question("yes")
    start = time.monotonic()
    panel.buttons["run"].click()
    watcher.stop()
    expect("question" in STATUS, "no question before replacing the hand-placed luminaires")
    got_eta = wait_until(lambda: " left" in panel.status.text(), 10.0)
    STATUS["first_progress_s"] = round(time.monotonic() - start, 2)
    STATUS["progress_line"] = panel.status.text()
    log(f"progress after {STATUS['first_progress_s']} s: {panel.status.text()}")
    expect(got_eta, f"no progress line with a time estimate within 10 s: {panel.status.text()!r}")
    expect(visible_in_window(panel.buttons["cancel"]) and panel.buttons["cancel"].isEnabled(),
           "Cancel is not visible and enabled while searching")
    grab_window("optimize_running")
    finished = wait_until(lambda: panel.job is not None and panel.job.finished
                          and not panel.timer.isActive(), 400.0, 0.1)
    expect(finished, "the search did not finish")
    rows = panel.table.rowCount()
    STATUS["rows"] = rows
    STATUS["status"] = panel.status.text()
    log(f"{rows} optima: {panel.status.text()}")
    expect(rows > 0, f"no optimum listed: {panel.status.text()}")
    if not rows:
        return
    best = panel.result.members[0]
    STATUS["best"] = {"count": best["count"], "flux_lm": best["mean"],
                      "em_u0": best["constraints"]}
    undo_before = doc.UndoCount
    panel.buttons["apply"].click()
    pump(0.5)
    after = luminaire_layout(analysis)
    STATUS["luminaires_after"] = sorted(after)
    expect(doc.UndoCount == undo_before + 1, "Apply is not one undo step")
    expect(len(after) == best["count"],
           f"{len(after)} luminaires after Apply, the optimum has {best['count']}")
    template = doc.getObject("CeilingDomain").Template
    own = [label for label in after if label == template.Label
           or label.startswith(f"{template.Label}_copy")]
    expect(len(own) == len(after), f"luminaires not of the domain left: {sorted(after)}")
    points = list(after.values())
    gaps = [(a - b).Length for i, a in enumerate(points) for b in points[i + 1:]]
    STATUS["smallest_gap_mm"] = round(min(gaps), 1) if gaps else None
    expect(not gaps or min(gaps) >= 599.0, f"coincident or overlapping luminaires: {min(gaps)}")
    FreeCADGui.Selection.clearSelection()
    panel.table.selectRow(0)
    # For the picture only (the search is over): look down through the ceiling at the layout.
    doc.getObject(names["ceiling"]).ViewObject.Visibility = False
    FreeCADGui.ActiveDocument.ActiveView.viewTop()
    FreeCADGui.SendMsgToActiveView("ViewFit")
    grab_window("optimize", docs_name="optimize.png")
    check_decide(panel, doc)
    while doc.UndoCount > undo_before:  # Decide's results and settings, then the Apply
        doc.undo()
    pump(0.3)
    restored = luminaire_layout(analysis)
    expect(sorted(restored) == sorted(before)
           and all((restored[k] - before[k]).Length < 1e-6 for k in before),
           f"undo did not restore the hand-placed layout: {sorted(restored)}")
    # The document no longer holds the applied layout: Decide says so instead of tracing.
    runs = panel.decider.job
    panel.buttons["decide"].click()
    pump(0.3)
    STATUS["decide_after_undo"] = panel.decider.label.text()
    expect(panel.decider.job is runs and "no longer holds layout 1" in
           panel.decider.label.text(), f"Decide after Undo: {panel.decider.label.text()}")
    FreeCADGui.Control.closeDialog()


def check_decide(panel, doc) -> None:
    """The panel's own Decide for the applied layout: one click runs the analysis with Decide
    on; its verdicts follow, each pass or FAIL, or what deciding needs and why the run stopped
    (with the next click's budget on the button)."""
    from lighting.solver import store

    expect(panel.buttons["decide"].isEnabled() and visible_in_window(panel.buttons["decide"]),
           "Decide is not enabled and visible after the search")
    results_before = doc.UndoCount
    panel.buttons["decide"].click()
    # Seen busy, or already done: a fast machine traces this layout in 0.3 s.
    seen: dict = {}

    def started() -> bool:
        if panel.is_busy():
            seen["run_enabled"] = panel.buttons["run"].isEnabled()
            return True
        return doc.UndoCount > results_before
    expect(wait_until(started, 5.0, 0.01), "the Decide run did not start")
    expect(not seen.get("run_enabled", False), "Run stays enabled while Decide runs")
    done = wait_until(lambda: not panel.is_busy() and not panel.decider.timer.isActive(),
                      300.0, 0.1)
    expect(done, "the Decide run did not finish")
    text = panel.decider.label.text()
    STATUS["decide"] = text
    STATUS["decide_button"] = panel.buttons["decide"].toolTip()
    log(f"Decide: {text} | button {panel.buttons['decide'].toolTip()}")
    expect(visible_in_window(panel.decider.label), "the Decide outcome is not in view")
    expect(doc.UndoCount > results_before, "the Decide run stored no results")
    expect(text.startswith("Layout 1 traced:") and "Workplane: Em" in text and "U0" in text,
           f"the Decide run's verdicts are not shown: {text}")
    result = store.load_from_document(panel.analysis)  # what the document holds now
    decided = "Every requirement decided." in text
    why = "Undecided:" in text and "press Decide" in text and "photons" in text
    expect(decided != why, f"neither decided nor said why not: {text}")
    if why:
        tip = panel.buttons["decide"].toolTip()
        expect("at most" in tip and "photons" in tip,
               f"the button does not give the next budget: {tip}")
    if result is not None:
        workplane = [t for t in result.targets if t.label == "Workplane"]
        expect(bool(workplane) and ((not workplane[0].undecided) == decided),
               f"the panel's words disagree with the stored results: {text}")
    grab_window("optimize_decide", docs_name="optimize-decide.png")


scenario(body)
