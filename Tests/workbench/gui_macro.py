"""FreeCAD GUI macro of the GUI test (run by run_gui_test.py under Xvfb; do not run alone).

Opens the example office with the Lighting workbench, runs the analysis through the
Lighting_Run command while a heartbeat timer measures how long the event loop stalls, saves
screenshots of the 3D view before, after and after save + reopen, measures their colours,
checks that colours follow display and results changes made outside the task panel, and
writes everything to status.json. Always ends the process with os._exit."""
import json
import os
import threading
import time
import traceback

OUT = os.environ["LIGHTING_GUI_OUT"]
STATUS = {"errors": [], "log": []}
SIZE = (1200, 900)


def log(text):
    STATUS["log"].append(text)


def finish(code=0):
    with open(os.path.join(OUT, "status.json"), "w", encoding="utf-8") as stream:
        json.dump(STATUS, stream, indent=1)
    os._exit(code)


threading.Timer(float(os.environ.get("LIGHTING_GUI_TIMEOUT", "200")),
                lambda: (STATUS["errors"].append("watchdog: GUI test timed out"), finish(3))).start()


def pump(seconds=0.3):
    from PySide import QtGui

    end = time.monotonic() + seconds
    while time.monotonic() < end:
        QtGui.QApplication.processEvents()
        time.sleep(0.01)


def image_metrics(path):
    """Colourful pixels (saturation > 0.6, value > 0.35) outside the legend strip and the
    hue bins (30 deg) holding at least 0.2 % of the measured pixels."""
    from PySide import QtGui

    image = QtGui.QImage(path)
    width, height = image.width(), image.height()
    x0 = int(width * 0.2)  # the legend sits at the left
    total = colourful = 0
    bins = [0] * 12
    for y in range(0, height, 2):
        for x in range(x0, width, 2):
            colour = QtGui.QColor(image.pixel(x, y))
            total += 1
            if colour.saturationF() > 0.6 and colour.valueF() > 0.35:
                colourful += 1
                bins[int(max(colour.hueF(), 0.0) * 12) % 12] += 1
    distinct = sum(1 for b in bins if b > 0.002 * total)
    legend = legend_total = 0
    for y in range(0, height, 2):
        for x in range(0, x0, 2):
            colour = QtGui.QColor(image.pixel(x, y))
            legend_total += 1
            legend += colour.saturationF() > 0.6 and colour.valueF() > 0.35
    non_white = 0
    for y in range(0, height, 8):
        for x in range(0, width, 8):
            if QtGui.QColor(image.pixel(x, y)).valueF() < 0.95:
                non_white += 1
    return {"path": path, "colourful_fraction": colourful / max(total, 1),
            "legend_fraction": legend / max(legend_total, 1),
            "hue_bins": distinct, "bins": bins, "non_white_fraction":
            non_white / max(((width + 7) // 8) * ((height + 7) // 8), 1)}


def screenshot(doc, name):
    import FreeCADGui

    view = FreeCADGui.getDocument(doc.Name).ActiveView
    view.viewIsometric()
    view.fitAll()
    pump(0.5)
    path = os.path.join(OUT, f"{name}.png")
    view.saveImage(path, SIZE[0], SIZE[1], "White")
    STATUS.setdefault("images", {})[name] = image_metrics(path)
    log(f"screenshot {path}")
    return path


def hide_for_view(doc, hide=True):
    """Look into the room from above: hide the ceiling and the placement domain's points.
    Hidden objects stay in the analysis (only LightingExclude leaves them out), so the
    numbers do not depend on it."""
    for label in ("Ceiling", "CeilingDomain"):
        for obj in doc.getObjectsByLabel(label):
            obj.ViewObject.Visibility = not hide


def stored(doc):
    """The results object of the document's analysis (None without results)."""
    from lighting.objects import results as results_obj

    return results_obj.of_analysis(doc.getObject("LightingAnalysis"))


def stored_mean_lux(doc, name="Workplane"):
    from lighting.objects import results as results_obj

    found = stored(doc)
    return results_obj.mean_lux(found, name) if found is not None else None


def lighting_view_providers(doc):
    """Object name -> class name of the view provider, for the Lighting objects."""
    return {o.Name: type(o.ViewObject.Proxy).__name__ for o in doc.Objects
            if getattr(o, "Proxy", None) is not None
            and type(o.Proxy).__module__.startswith("lighting")}


def distinct_colours(obj):
    return len({tuple(round(c, 3) for c in col[:3]) for col in obj.ViewObject.DiffuseColor})


def cancel_run(doc):
    """Lighting_Run with far too many photons, then the panel's Cancel button: the run must
    stop soon with partial results, the GUI alive."""
    import FreeCADGui
    from PySide import QtCore

    from lighting.taskpanels import analysis_panel

    analysis = doc.getObject("LightingAnalysis")
    analysis.Photons = 500000000
    analysis.Decide = False  # a run that only Cancel ends
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(analysis)
    loop = QtCore.QEventLoop()
    state = {"clicked": None}
    # The run before this one: until the new run is registered, last_run() is still that
    # finished job, and taking it for the new one quit the loop at once (seen on a loaded
    # machine, where the new run registers later than the first poll).
    before = analysis_panel.last_run()

    def poll():
        job = analysis_panel.last_run()
        if job is None or job is before:
            return
        if state["clicked"] is None and job.stage == "solve" and job.done > 0:
            analysis_panel.last_panel().buttons["cancel"].click()
            state["clicked"] = time.monotonic()
        if job.stage in ("done", "failed", "cancelled"):
            loop.quit()
    timer = QtCore.QTimer()
    timer.setInterval(20)
    timer.timeout.connect(poll)
    timer.start()
    FreeCADGui.runCommand("Lighting_Run")
    QtCore.QTimer.singleShot(120000, loop.quit)
    loop.exec_()
    timer.stop()
    job = analysis_panel.last_run()
    STATUS["cancel"] = {"stage": job.stage if job else None,
                        "stop_seconds": (time.monotonic() - state["clicked"])
                        if state["clicked"] else None,
                        "partial": bool(stored(doc) and stored(doc).Partial),
                        "photons": stored(doc).Photons if stored(doc) else 0.0,
                        "status": analysis.Status}
    pump(0.3)
    FreeCADGui.Control.closeDialog()


def run_analysis(doc):
    """Lighting_Run on the analysis; waits in a real event loop with a heartbeat."""
    import FreeCADGui
    from PySide import QtCore

    from lighting.taskpanels import analysis_panel

    analysis = doc.getObject("LightingAnalysis")
    analysis.Photons = int(os.environ.get("LIGHTING_GUI_PHOTONS", "1500000"))
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(analysis)
    beats = []
    loop = QtCore.QEventLoop()
    heartbeat = QtCore.QTimer()
    heartbeat.setInterval(20)

    def beat():
        job = analysis_panel.last_run()
        beats.append((time.monotonic(), job.stage if job is not None else "none"))
        if job is not None and job.stage in ("done", "failed", "cancelled"):
            loop.quit()
    heartbeat.timeout.connect(beat)
    heartbeat.start()
    started = time.monotonic()
    FreeCADGui.runCommand("Lighting_Run")
    QtCore.QTimer.singleShot(120000, loop.quit)
    loop.exec_()
    heartbeat.stop()
    job = analysis_panel.last_run()
    gaps = [b[0] - a[0] for a, b in zip(beats, beats[1:]) if a[1] == "solve" and b[1] == "solve"]
    solve_times = [b[0] for b in beats if b[1] == "solve"]
    STATUS["run"] = {"stage": job.stage if job else None, "seconds": time.monotonic() - started,
                     "solve_beats": len(gaps) + 1 if gaps else 0,
                     "solve_seconds": (solve_times[-1] - solve_times[0]) if solve_times else 0.0,
                     "max_gap_solve_s": max(gaps) if gaps else None,
                     "max_gap_all_s": max((b[0] - a[0] for a, b in zip(beats, beats[1:])),
                                          default=None),
                     "error": str(job.error) if job and job.error else None,
                     "status": analysis.Status}
    pump(0.5)
    FreeCADGui.Control.closeDialog()


def display_updates(doc):
    """With no task panel open, colours follow the document through the view providers'
    updateData (App code never paints): a script changing the colour map, Clear results,
    Undo of the clear."""
    import FreeCADGui

    analysis = doc.getObject("LightingAnalysis")
    workplane = doc.getObject("Workplane")

    def state():
        diffuse = workplane.ViewObject.DiffuseColor
        colours = {tuple(round(c, 3) for c in col[:3]) for col in diffuse}
        holder = getattr(analysis.ViewObject.Proxy, "legend_holder", None)
        return {"distinct": len(colours), "has_results": stored_mean_lux(doc) is not None,
                "grey": all(max(c) - min(c) < 0.01 for c in colours),
                "legend_nodes": holder.getNumChildren() if holder is not None else None}
    info = {"start": state()}
    analysis.ColorMap = "Grey"
    pump(0.3)
    info["grey_map"] = state()
    analysis.ColorMap = "Rainbow"
    pump(0.3)
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(analysis)
    FreeCADGui.runCommand("Lighting_ClearResults")
    pump(0.3)
    info["cleared"] = state()
    doc.undo()
    pump(0.3)
    info["undone"] = state()
    STATUS["display"] = info


def legacy_document(doc):
    """A file as older versions wrote it (results JSON on the analysis, numbers on the
    targets) opened in the GUI: the observer moves the JSON into a results object, which gets
    its view provider and paints the grid."""
    import FreeCAD

    analysis, found = doc.getObject("LightingAnalysis"), stored(doc)
    text = found.ResultsJson
    analysis.removeObject(found)
    doc.removeObject(found.Name)
    analysis.addProperty("App::PropertyString", "ResultsJson", "Results")
    analysis.ResultsJson = text
    workplane = doc.getObject("Workplane")
    workplane.addProperty("App::PropertyBool", "HasResults", "Results")
    workplane.HasResults = True
    path = os.path.join(OUT, "legacy.FCStd")
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    pump(0.3)
    doc = FreeCAD.openDocument(path)
    pump(1.0)
    STATUS["legacy"] = {
        "view_providers": lighting_view_providers(doc), "mean_lux": stored_mean_lux(doc),
        "colours": distinct_colours(doc.getObject("Workplane")),
        "legacy_props": sorted(f"{o.Name}.{p}" for o in doc.Objects for p in o.PropertiesList
                               if p in ("ResultsJson", "HasResults")
                               and o.Name in ("LightingAnalysis", "Workplane"))}
    # Deleting the analysis (what Std_Delete does, without its confirmation dialog) takes its
    # results object along and keeps its members.
    analysis = doc.getObject("LightingAnalysis")
    doc.openTransaction("Delete")
    if analysis.ViewObject.Proxy.onDelete(analysis.ViewObject, []):
        doc.removeObject(analysis.Name)
    doc.commitTransaction()
    pump(0.3)
    STATUS["legacy"]["after_delete"] = sorted(lighting_view_providers(doc).values())


def commands_smoke():
    """The toolbar commands on a plain slab: create every object from a selection, undo,
    Check and Export through their commands."""
    import FreeCAD
    import FreeCADGui

    from lighting.objects.base import proxy_type

    doc = FreeCAD.newDocument("Commands")
    slab = doc.addObject("Part::Box", "Slab")
    slab.Length, slab.Width, slab.Height = 4000, 3000, 200
    doc.recompute()
    sel = FreeCADGui.Selection

    def run(command, sub=None):
        sel.clearSelection()
        if sub is not None:
            sel.addSelection(doc.Name, slab.Name, sub) if sub else sel.addSelection(doc.Name, slab.Name)
        FreeCADGui.runCommand(command)
        pump(0.2)
    run("Lighting_Analysis")
    run("Lighting_Luminaire", "Face5")  # the slab's underside: 5 cm below it, aimed down
    run("Lighting_Target", "Face6")
    run("Lighting_Grid", "")
    run("Lighting_PlacementDomain", "Face5")
    kinds = sorted(proxy_type(o) for o in doc.Objects if proxy_type(o))
    lum = [o for o in doc.Objects if proxy_type(o) == "Lighting::Luminaire"]
    info = {"created": kinds,
            "luminaire_z": lum[0].Placement.Base.z if lum else None,
            "luminaire_aim_z": lum[0].AimDirection.z if lum else None,
            "icons": {o.Name: bool(o.ViewObject.Proxy.getIcon()) for o in doc.Objects
                      if proxy_type(o)}}
    doc.undo()
    info["after_undo"] = sorted(proxy_type(o) for o in doc.Objects if proxy_type(o))
    run("Lighting_Check")
    FreeCADGui.Control.closeDialog()
    run("Lighting_Export")
    FreeCADGui.Control.closeDialog()
    analysis = [o for o in doc.Objects if proxy_type(o) == "Lighting::Analysis"][0]
    run("Lighting_Results")
    info["results_panel"] = bool(FreeCADGui.Control.activeDialog())
    FreeCADGui.Control.closeDialog()
    FreeCADGui.getDocument(doc.Name).setEdit(analysis.Name)  # what a double click does
    pump(0.2)
    info["edit_panel"] = bool(FreeCADGui.Control.activeDialog())
    FreeCADGui.Control.closeDialog()
    FreeCADGui.getDocument(doc.Name).resetEdit()
    info["scene_file"] = analysis.SceneFile
    info["scene_exists"] = bool(analysis.SceneFile) and os.path.exists(analysis.SceneFile)
    STATUS["commands"] = info
    FreeCAD.closeDocument(doc.Name)
    pump(0.2)


def optimize_in_gui(doc):
    """Lighting_Optimize on the office: one luminaire on the ceiling domain, maximise the
    workplane's mean, Run on the worker thread, Apply the best, Undo (one step)."""
    import FreeCADGui

    from lighting.taskpanels import optimize_panel

    domain = doc.getObject("CeilingDomain")
    domain.MaxLuminaires, domain.MinLuminaires = 1, 1
    doc.recompute()
    template = domain.Template
    before = [template.Placement.Base.x, template.Placement.Base.y, template.Placement.Base.z]
    FreeCADGui.runCommand("Lighting_Optimize")
    pump(0.3)
    panel = optimize_panel.last_panel()
    panel.target.setCurrentText(doc.getObject("Workplane").Label)
    panel.goal.setCurrentIndex(panel.goal.findData("maximize_mean_illuminance"))
    panel.iterations.setValue(8)
    panel.screening.setValue(20000)
    panel.confirmation.setValue(100000)
    panel.ask_replace_others = lambda others: False  # keep the other panels (no dialog here)
    panel.buttons["run"].click()
    start = time.monotonic()
    while panel.job is not None and not (panel.job.finished and not panel.timer.isActive()):
        pump(0.1)
        if time.monotonic() - start > 120:
            break
    info = {"seconds": time.monotonic() - start, "status": panel.status.text(),
            "rows": panel.table.rowCount(), "before_mm": before}
    if panel.result is not None and panel.result.members:
        best = panel.result.members[0]["positions_m"][template.Name]
        info["best_mm"] = [1000.0 * x for x in best]
        panel.buttons["apply"].click()
        pump(0.2)
        b = template.Placement.Base
        info["applied_mm"] = [b.x, b.y, b.z]
        doc.undo()
        b = template.Placement.Base
        info["after_undo_mm"] = [b.x, b.y, b.z]
    STATUS["optimize"] = info
    FreeCADGui.Control.closeDialog()


def main():
    import FreeCAD
    import FreeCADGui

    FreeCADGui.getMainWindow().resize(1280, 1000)
    FreeCADGui.activateWorkbench("LightingWorkbench")
    import lighting

    STATUS["workbench"] = FreeCADGui.activeWorkbench().name()
    ok, info = lighting.solver_available()
    STATUS["solver"], STATUS["solver_info"] = ok, info
    commands_smoke()
    doc = FreeCAD.openDocument(os.environ["LIGHTING_GUI_FILE"])
    pump(0.5)
    STATUS["view_providers"] = {
        o.Name: type(o.ViewObject.Proxy).__name__ for o in doc.Objects
        if getattr(o, "Proxy", None) is not None and type(o.Proxy).__module__.startswith("lighting")}
    hide_for_view(doc)
    STATUS["visible_opened"] = sorted(o.Name for o in doc.Objects
                                      if getattr(o, "ViewObject", None) is not None
                                      and o.ViewObject.Visibility)
    screenshot(doc, "before")
    hide_for_view(doc, False)
    if not ok:
        log("solver not available: stopping after the first screenshot")
        return
    run_analysis(doc)
    STATUS["workplane_colours_after"] = distinct_colours(doc.getObject("Workplane"))
    STATUS["mean_lux_gui"] = stored_mean_lux(doc)
    STATUS["photons_gui"] = stored(doc).Photons if stored(doc) else 0.0
    hide_for_view(doc)
    screenshot(doc, "after")
    path = os.path.join(OUT, "solved.FCStd")
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    pump(0.3)
    doc = FreeCAD.openDocument(path)
    pump(1.0)
    hide_for_view(doc)
    STATUS["visible_reopened"] = sorted(o.Name for o in doc.Objects
                                        if getattr(o, "ViewObject", None) is not None
                                        and o.ViewObject.Visibility)
    STATUS["workplane_colours_reopened"] = distinct_colours(doc.getObject("Workplane"))
    STATUS["mean_lux_reopened"] = stored_mean_lux(doc)
    STATUS["view_providers_reopened"] = lighting_view_providers(doc)
    from lighting.objects.base import proxy_type

    STATUS["result_props_on_inputs"] = sorted(
        f"{o.Name}.{p}" for o in doc.Objects for p in o.PropertiesList
        if p in ("MeanLux", "CellsLux", "HasResults", "ResultsJson")
        and proxy_type(o) != "Lighting::Results")
    screenshot(doc, "reopened")
    hide_for_view(doc, False)
    display_updates(doc)
    cancel_run(doc)
    optimize_in_gui(doc)
    legacy_document(doc)


try:
    main()
    finish(0)
except Exception:  # noqa: BLE001 - reported through status.json
    STATUS["errors"].append(traceback.format_exc())
    finish(1)
