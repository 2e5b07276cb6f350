"""GUI scenario: live results while designing (issue 16).

From the Start page the user opens the example office (built by Examples/office.py without
solving), picks the Lighting workbench and turns Live on from the toolbar. Numbers appear and
refine by themselves while the GUI stays responsive (the timer keeps ticking); the legend shows
photons and the worst cell's +-%. The user moves a luminaire (through the API, one undo step):
the cell under its new position brightens, the one it left darkens, within a bounded number of
frames; every frame shown carries the model revision it was traced for. Undo restores the first
numbers; no live frame adds an undo step. Live off stops the session."""
import math
import time

from guilib import (build_example_file, STATUS, expect, grab_window, log, pump, scenario,
                    wait_until)

PHOTONS = 1 << 24  # seconds of refining (about 6e6 photons/s here): the heartbeat sees it all


def grid_cells(doc):
    from lighting.objects import results as results_obj

    found = results_obj.of_analysis(doc.getObject("LightingAnalysis"))
    data = results_obj.data(found) if found is not None else None
    if not data:
        return None
    tgt = next(t for t in data["targets"] if t["name"] == "Workplane")
    return [(c["lux"], c["ci_low_lux"], c["ci_high_lux"]) for c in tgt["cells"]]


def cell_under(grid, x_mm, y_mm):
    iu = int((x_mm - grid.corner.x) / grid.edge1.x * grid.nu)
    iv = int((y_mm - grid.corner.y) / grid.edge2.y * grid.nv)
    return iv * grid.nu + iu


def body() -> None:
    import FreeCAD
    import FreeCADGui

    from lighting.commands import live as live_cmd
    from lighting.objects import target as target_mod

    path = build_example_file(PHOTONS)
    FreeCADGui.activateWorkbench("LightingWorkbench")
    doc = FreeCAD.openDocument(path)
    pump(1.0)
    # The user looks into the room through the ceiling (made transparent, as the example does).
    doc.getObjectsByLabel("Ceiling")[0].ViewObject.Transparency = 80
    FreeCADGui.ActiveDocument.ActiveView.viewIsometric()
    FreeCADGui.SendMsgToActiveView("ViewFit")
    analysis = doc.getObject("LightingAnalysis")
    analysis.Decide = False  # refine to Photons: a fixed number of frames
    grid = target_mod.grid_rectangle(doc.getObject("Workplane"))
    undo_start = doc.UndoCount

    # 1. Live on: the first numbers come quickly, then refine to the goal; a heartbeat timer
    # measures how long the event loop ever waits meanwhile (the GUI thread only paints).
    from PySide import QtCore

    beats = []
    heartbeat = QtCore.QTimer()
    heartbeat.setInterval(20)
    heartbeat.timeout.connect(lambda: beats.append(time.monotonic()))
    heartbeat.start()
    started = time.monotonic()
    FreeCADGui.runCommand("Lighting_Live")
    expect(analysis.Live, "the Live command did not turn Live on")
    ctrl = live_cmd.controller(analysis)
    if not expect(ctrl is not None, "no live session started"):
        return
    ok = wait_until(lambda: grid_cells(doc) is not None, 60, 0.02)
    STATUS["first_numbers_s"] = round(time.monotonic() - started, 2)
    expect(ok, "no live numbers within 60 s")
    ok = wait_until(lambda: analysis.Status.endswith("(done)"), 120)
    STATUS["status_done"] = analysis.Status
    heartbeat.stop()
    expect(ok and f"{PHOTONS:,}".replace(",", " ") in analysis.Status,
           f"live did not refine to its goal: {analysis.Status!r}")
    gaps = [b - a for a, b in zip(beats, beats[1:])]
    STATUS["heartbeats"] = len(beats)
    STATUS["max_gap_s"] = round(max(gaps), 3) if gaps else None
    expect(len(beats) > 20 and max(gaps) < 1.0,
           f"the event loop stalled while live: {STATUS['max_gap_s']} s")
    legend = analysis.ViewObject.Proxy.legend_title()
    STATUS["legend_title"] = legend
    expect("worst cell +-" in legend and "photons" in legend,
           f"the legend does not show the live state: {legend!r}")
    before = grid_cells(doc)
    # The results panel follows the live frames.
    from lighting.taskpanels import analysis_panel

    FreeCADGui.runCommand("Lighting_Results")
    pump(0.5)
    panel = analysis_panel.last_panel()
    expect(panel is not None and "live:" in panel.status.text(),
           f"the panel does not show the live state: {panel.status.text() if panel else None}")
    grab_window("live_first")

    # 2. Move a luminaire: the cells follow within a bounded number of frames.
    lum = doc.getObject("Luminaire01")
    old_xy, new_xy = (1250.0, 1000.0), (2500.0, 2000.0)
    left, under = cell_under(grid, *old_xy), cell_under(grid, *new_xy)
    shown_before = ctrl.frames_shown
    doc.openTransaction("Move luminaire")
    lum.Placement.Base = FreeCAD.Vector(new_xy[0], new_xy[1], lum.Placement.Base.z)
    doc.commitTransaction()
    moved_at = time.monotonic()

    def moved():
        now = grid_cells(doc)
        return (now is not None and now[under][1] > before[under][2]
                and now[left][2] < before[left][1])
    ok = wait_until(moved, 60, 0.02)
    STATUS["move_shown_s"] = round(time.monotonic() - moved_at, 2)
    STATUS["move_frames"] = ctrl.frames_shown - shown_before
    expect(ok and ctrl.frames_shown - shown_before <= 6,
           f"the move did not show within 6 frames: {STATUS['move_frames']}")
    expect(ctrl.session.latest.revision == ctrl.session.revision == 1 and
           ctrl.session.latest.path == "luminaires",
           f"frame revision/path after the move: {ctrl.session.latest}")
    wait_until(lambda: analysis.Status.endswith("(done)"), 120)
    pump(0.3)
    expect(panel.status.text() == f"Status: {analysis.Status}",
           f"the panel lags the live frames: {panel.status.text()!r} vs {analysis.Status!r}")
    grab_window("live_moved", docs_name="live-moved.png")
    expect(doc.UndoCount == undo_start + 1,
           f"live frames added undo steps: {doc.UndoNames[:4]}")

    # 3. Undo: back to the first numbers (same scene, seed, photons: bit for bit).
    FreeCADGui.runCommand("Std_Undo")
    expect(lum.Placement.Base.x == old_xy[0], "Undo did not move the luminaire back")
    ok = wait_until(lambda: ctrl.session.revision == 2 and analysis.Status.endswith("(done)")
                    and grid_cells(doc) == before, 120)
    expect(ok, "after Undo the live numbers are not the first ones again")
    worst = ctrl.session.latest.worst_cell_relative
    expect(math.isfinite(worst) and worst > 0, f"worst cell +-: {worst}")

    stale = [pair for pair in ctrl.shown_revisions if pair[0] != pair[1]]
    STATUS["frames_shown"] = len(ctrl.shown_revisions)
    expect(not stale, f"frames of an older model revision were shown: {stale}")

    # 4. Live off: the session ends, the status settles.
    FreeCADGui.runCommand("Lighting_Live")
    pump(0.5)
    expect(not analysis.Live and live_cmd.controller(analysis) is None,
           "Live off did not stop the session")
    expect(not analysis.Status.startswith("live"), f"Status after Live off: {analysis.Status}")
    log(f"live scenario: {STATUS.get('first_numbers_s')} s to first numbers, move shown after "
        f"{STATUS.get('move_frames')} frame(s)")


scenario(body)
