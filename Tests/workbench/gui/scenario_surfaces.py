"""GUI scenario: results on walls and ceilings. From the Start page the user builds the
example office, selects the north wall's inner face and the ceiling's underside and makes a
calculation grid on each with the grid command, runs the analysis with few photons, and
sees every grid coloured cell by cell with iso-lux lines, then the plan view of the wall grid
in the analysis panel."""
import os
import sys

from guilib import (STATUS, expect, grab_window, log, main_window, pump, scenario,
                    wait_until)

PHOTONS = 100000


def build_office():
    """A new document with the example office (Examples/office_model.py)."""
    import FreeCAD
    import FreeCADGui

    sys.path.insert(0, os.path.join(os.environ["LIGHTING_SOURCE_DIR"], "Examples"))
    import office_model

    FreeCADGui.activateWorkbench("LightingWorkbench")
    doc = FreeCAD.newDocument("Office")
    pump(0.5)  # the 3D view Arch's recomputes ask for
    office_model.build_office(doc, photons=PHOTONS)
    FreeCADGui.SendMsgToActiveView("ViewFit")
    pump(0.3)
    return doc, office_model


def grid_on_selected_face(doc, obj, face):
    """Select one face as a user clicks it, then Lighting > Calculation grid; the new grid."""
    import FreeCADGui

    before = {o.Name for o in doc.Objects}
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(doc.Name, obj.Name, face)
    pump(0.1)
    FreeCADGui.runCommand("Lighting_Grid")
    pump(0.3)
    made = [o for o in doc.Objects if o.Name not in before]
    expect(len(made) == 1, f"the grid command on {obj.Label}.{face} made {made}")
    return made[0] if made else None


def run_analysis(doc):
    """Lighting_Run with few photons; waits for the run to end."""
    import FreeCADGui

    from lighting.taskpanels import analysis_panel

    analysis = doc.getObject("LightingAnalysis")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(analysis)
    FreeCADGui.runCommand("Lighting_Run")
    done = wait_until(lambda: analysis_panel.last_run() is not None
                      and analysis_panel.last_run().stage in ("done", "failed", "cancelled")
                      and not analysis_panel.last_panel().timer.isActive(), 120.0)
    job = analysis_panel.last_run()
    STATUS["run"] = {"stage": job.stage if job else None, "status": analysis.Status}
    expect(done and job is not None and job.stage == "done", f"run did not finish: {STATUS['run']}")
    pump(0.5)  # repaint (coloring.refresh_later)
    return analysis_panel.last_panel()


def grab_with_view(name, docs_name=None):
    """grab_window, with the 3D view painted in: under Xvfb a main-window grab (and the GL
    widget's own frame buffer) leaves the 3D view empty, so the view is rendered off screen
    at its size (View3DInventor.saveImage, which the old GUI test uses) and drawn over its
    place."""
    import FreeCADGui
    from PySide import QtCore, QtGui

    path = grab_window(name, docs_name)
    window = main_window()
    picture = QtGui.QImage(path)
    painter = QtGui.QPainter(picture)
    for widget in window.findChildren(QtGui.QOpenGLWidget):
        if widget.isVisible() and widget.width() > 50:
            rendered = path[:-4] + "_view.png"
            FreeCADGui.ActiveDocument.ActiveView.saveImage(rendered, widget.width(),
                                                           widget.height(), "Current")
            origin = widget.mapTo(window, QtCore.QPoint(0, 0))
            painter.drawImage(QtCore.QRect(origin, widget.size()), QtGui.QImage(rendered))
            break
    painter.end()
    picture.save(path)
    return path


def distinct_colours(vobj):
    return len({tuple(round(c, 3) for c in colour[:3]) for colour in vobj.DiffuseColor})


def isolux_segments(vobj):
    """Line sets under the iso-lux switch: (shown, number of polylines, number of points)."""
    from pivy import coin

    from lighting.viewproviders.target import ISOLUX_NODE

    search = coin.SoSearchAction()
    search.setName(ISOLUX_NODE)
    search.setInterest(coin.SoSearchAction.FIRST)
    search.apply(vobj.RootNode)
    path = search.getPath()
    if path is None:
        return False, 0, 0
    switch = path.getTail()
    lines = coin.SoSearchAction()
    lines.setType(coin.SoLineSet.getClassTypeId())
    lines.setInterest(coin.SoSearchAction.ALL)
    lines.apply(switch)
    polylines = points = 0
    for i in range(lines.getPaths().getLength()):
        node = lines.getPaths()[i].getTail()
        counts = list(node.numVertices.getValues())
        polylines += len(counts)
        points += sum(counts)
    return switch.whichChild.getValue() == 0, polylines, points


def inside_view(doc):
    """A perspective camera inside the room, looking at the north wall and the ceiling; the
    work-plane grid hidden so that the wall shows whole (its iso-lux lines hide with it)."""
    import FreeCADGui
    from pivy import coin

    workplane = doc.getObject("Workplane").ViewObject
    workplane.Visibility = False
    pump(0.1)
    expect(not isolux_segments(workplane)[0], "a hidden grid still shows its iso-lux lines")
    view = FreeCADGui.ActiveDocument.ActiveView
    view.setCameraType("Perspective")
    camera = view.getCameraNode()
    camera.position.setValue(coin.SbVec3f(2500, 250, 1300))
    camera.pointAt(coin.SbVec3f(2500, 4000, 2000), coin.SbVec3f(0, 0, 1))
    camera.heightAngle.setValue(1.2)
    pump(0.5)


def check_grids(doc, grids):
    """Every grid coloured cell by cell with iso-lux lines; the switch follows ShowIsolux."""
    for grid in grids:
        vobj = grid.ViewObject
        colours = distinct_colours(vobj)
        shown, polylines, points = isolux_segments(vobj)
        STATUS.setdefault("grids", {})[grid.Name] = {
            "surface": grid.Surface, "cells": len(grid.Shape.Faces), "colours": colours,
            "isolux_shown": shown, "isolux_polylines": polylines, "isolux_points": points,
            "required": [grid.RequiredLux, grid.RequiredUniformity]}
        expect(colours >= 4, f"{grid.Label}: only {colours} distinct cell colours")
        expect(shown and polylines > 0 and points > polylines,
               f"{grid.Label}: no iso-lux lines drawn ({shown}, {polylines}, {points})")
    wall = grids[0].ViewObject
    wall.ShowIsolux = False
    pump(0.1)
    expect(not isolux_segments(wall)[0], "ShowIsolux = False left the iso-lux lines shown")
    wall.ShowIsolux = True
    pump(0.1)
    expect(isolux_segments(wall)[0], "ShowIsolux = True did not show the iso-lux lines again")


def check_plan_view(panel, wall):
    """The analysis panel's plan view shows the wall grid, painted."""
    from PySide import QtGui

    plan = panel.plan_view
    names = [plan.choice.itemData(i) for i in range(plan.choice.count())]
    expect(wall.Name in names, f"plan view does not offer {wall.Name}: {names}")
    plan.choice.setCurrentIndex(plan.choice.findData(wall.Name))
    pump(0.5)
    for scroll in plan.window().findChildren(QtGui.QScrollArea):
        if scroll.isAncestorOf(plan):
            scroll.ensureWidgetVisible(plan, 0, 0)
    pump(0.5)
    pixmap = plan.image.pixmap()
    image = plan.image.grab().toImage()
    colours = {image.pixel(x, y) for x in range(0, image.width(), 3)
               for y in range(0, image.height(), 3)}
    STATUS["plan_view"] = {"pixmap": [pixmap.width(), pixmap.height()] if pixmap else None,
                           "widget": [plan.image.width(), plan.image.height()],
                           "colours": len(colours), "png_bytes": len(plan.png),
                           "visible": plan.image.visibleRegion().boundingRect().height()}
    expect(pixmap is not None and not pixmap.isNull() and pixmap.width() >= 200,
           f"plan view not painted: {STATUS['plan_view']}")
    expect(len(colours) > 30, f"plan view looks blank: {STATUS['plan_view']}")


def body() -> None:
    import FreeCAD
    import FreeCADGui

    expect(STATUS["start_workbench"] == "StartWorkbench",
           f"FreeCAD did not start on the Start page: {STATUS['start_workbench']}")
    doc, office_model = build_office()
    walls = doc.getObject(office_model.OBJECTS["walls"])
    ceiling = doc.getObject(office_model.OBJECTS["ceiling"])
    ceiling_face = office_model.find_face(ceiling.Shape, FreeCAD.Vector(0, 0, -1),
                                          FreeCAD.Vector(0, 0, 3000))
    wall = grid_on_selected_face(doc, walls, office_model.OBJECTS["wall_face"])
    top = grid_on_selected_face(doc, ceiling, ceiling_face)
    if wall is None or top is None:
        return
    expect((wall.Surface, top.Surface) == ("Wall", "Ceiling"),
           f"grid kinds {wall.Surface}, {top.Surface}")
    # The slab's underside runs 0.2 m over the walls: the user sets the border band.
    doc.openTransaction("Border band")
    top.WallBand = 200.0
    doc.commitTransaction()
    doc.recompute()
    log(f"grids {wall.Name} {wall.CellsU}x{wall.CellsV}, {top.Name} {top.CellsU}x{top.CellsV}")
    panel = run_analysis(doc)
    check_grids(doc, [wall, top, doc.getObject("Workplane")])
    inside_view(doc)
    FreeCADGui.Selection.clearSelection()
    grab_with_view("surfaces_walls", docs_name="surfaces-walls.png")
    check_plan_view(panel, wall)
    grab_with_view("surfaces_plan", docs_name="surfaces-plan.png")
    export_plan(wall)


def export_plan(wall):
    """The wall grid's plan view as the report gets it (lighting.plots, no GUI involved)."""
    from lighting import plots
    from PySide import QtGui

    path = os.path.join(os.environ.get("LIGHTING_GUI_OUT", "."), "surfaces_plan_export.png")
    plots.save_grid_png(wall, path, width_px=900)
    image = QtGui.QImage(path)
    expect(image.width() == 900 and image.height() > 300,
           f"exported plan view {image.width()} x {image.height()}")
    STATUS["images"]["surfaces_plan_export"] = path
    STATUS["docs_images"]["surfaces_plan_export"] = "surfaces-plan-export.png"


scenario(body)
