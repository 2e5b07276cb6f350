# SPDX-License-Identifier: LGPL-2.1-or-later
"""GUI commands (toolbar and menu "Lighting"). Object creation goes through
``FreeCADGui.doCommand`` so the Python console shows the equivalent script, inside one
undo transaction per command."""
from __future__ import annotations

from typing import Any, Dict, List, Optional, Tuple

import FreeCAD
import FreeCADGui
from PySide import QtGui

from lighting import standards
from lighting.objects import analysis as analysis_mod
from lighting.objects import light_scene as light_scene_mod
from lighting.objects.base import proxy_type
from lighting.viewproviders.base import icon_path

COMMANDS: List[str] = []


def _doc() -> Optional[Any]:
    return FreeCAD.ActiveDocument


def active_analysis(create: bool = False) -> Optional[Any]:
    """The selected analysis, else the document's first one (created if asked)."""
    doc = _doc()
    if doc is None:
        return None
    for obj in FreeCADGui.Selection.getSelection():
        if proxy_type(obj) == analysis_mod.TYPE:
            return obj
        for parent in obj.InList:
            if proxy_type(parent) == analysis_mod.TYPE:
                return parent
    found = analysis_mod.find_analysis(doc)
    if found is None and create:
        FreeCADGui.doCommand("lighting.make_analysis(FreeCAD.ActiveDocument)")
        found = analysis_mod.find_analysis(doc)
    return found


def _analysis_arg() -> str:
    found = active_analysis()
    return f"FreeCAD.ActiveDocument.getObject('{found.Name}')" if found is not None else "None"


def _selected_faces() -> List[Tuple[Any, List[str]]]:
    faces = []
    for sel in FreeCADGui.Selection.getSelectionEx():
        names = [n for n in sel.SubElementNames if n.startswith("Face")]
        if names:
            faces.append((sel.Object, names))
    return faces


def _run_transaction(title: str, lines: List[str]) -> None:
    doc = _doc()
    doc.openTransaction(title)
    try:
        FreeCADGui.addModule("lighting")
        for line in lines:
            FreeCADGui.doCommand(line)
        FreeCADGui.doCommand("FreeCAD.ActiveDocument.recompute()")
    except Exception as exc:  # noqa: BLE001 - show and undo, never leave half an object
        doc.abortTransaction()
        FreeCAD.Console.PrintError(f"Lighting: {title} failed: {exc}\n")
        QtGui.QMessageBox.warning(FreeCADGui.getMainWindow(), "Lighting", f"{title} failed:\n{exc}")
        return
    doc.commitTransaction()


class BaseCommand:
    """Command resources from a table; active with an open document."""

    NAME = "Lighting_Base"
    MENU = ""
    TIP = ""
    ICON = "Lighting_Workbench"

    def GetResources(self) -> Dict[str, str]:  # noqa: N802 (FreeCAD API name)
        return {"Pixmap": icon_path(self.ICON), "MenuText": self.MENU, "ToolTip": self.TIP}

    def IsActive(self) -> bool:  # noqa: N802
        return _doc() is not None


class CommandAnalysis(BaseCommand):
    NAME, ICON = "Lighting_Analysis", "Lighting_Analysis"
    MENU = "Lighting analysis"
    TIP = "Create a lighting analysis: solver settings, scene export and results"

    def Activated(self) -> None:  # noqa: N802
        _run_transaction("Create lighting analysis",
                         ["lighting.make_analysis(FreeCAD.ActiveDocument)"])


class CommandLuminaire(BaseCommand):
    NAME, ICON = "Lighting_Luminaire", "Lighting_Luminaire"
    MENU = "Luminaire"
    TIP = ("Add a luminaire. With a face selected it goes to the centre of the face's room "
           "(walls cut out), 5 cm off it, aimed into the room (a floor face: under the ceiling "
           "above, aimed down); with a vertex selected, at the vertex aimed down; with nothing "
           "selected, under the ceiling at the centre of the model's room")

    def Activated(self) -> None:  # noqa: N802
        position, aim, where = _luminaire_spot()
        to_m = tuple(round(c / 1000.0, 6) for c in (position.x, position.y, position.z))
        aim_t = tuple(round(c, 12) + 0.0 for c in (aim.x, aim.y, aim.z))
        _run_transaction("Create luminaire", [
            f"lighting.make_luminaire(FreeCAD.ActiveDocument, position_m={to_m!r}, "
            f"aim={aim_t!r}, analysis={_analysis_arg()})"])
        FreeCAD.Console.PrintMessage(f"Lighting: luminaire placed at ({to_m[0]:.3f}, "
                                     f"{to_m[1]:.3f}, {to_m[2]:.3f}) m, {where}\n")


def _luminaire_spot() -> Tuple[Any, Any, str]:
    """(position mm, aim, description) for a new luminaire from the selection (a face, a
    vertex) or, with nothing usable selected, the room under the model's ceiling."""
    from lighting import placement

    doc = _doc()
    for sel in FreeCADGui.Selection.getSelectionEx():
        for name, sub in zip(sel.SubElementNames, sel.SubObjects):
            if sub.ShapeType == "Face":
                solids = placement.model_solids(doc, (sel.Object.Name,))
                position, aim = placement.spot_on_face(sub, solids)
                return position, aim, f"on {sel.Object.Label} {name} (centre of its room)"
            if sub.ShapeType == "Vertex":
                return (FreeCAD.Vector(sub.Point), FreeCAD.Vector(0, 0, -1),
                        f"at {sel.Object.Label} {name}")
    return placement.default_spot(doc)


class CommandTarget(BaseCommand):
    NAME, ICON = "Lighting_Target", "Lighting_Target"
    MENU = "Face target"
    TIP = "Report illuminance on the selected faces (front = outward face normal)"

    def IsActive(self) -> bool:  # noqa: N802
        return _doc() is not None and bool(_selected_faces())

    def Activated(self) -> None:  # noqa: N802
        faces = ", ".join(f"(FreeCAD.ActiveDocument.getObject('{o.Name}'), {names!r})"
                          for o, names in _selected_faces())
        _run_transaction("Create face target", [
            f"lighting.make_face_target(FreeCAD.ActiveDocument, [{faces}], "
            f"analysis={_analysis_arg()})"])


class CommandGrid(BaseCommand):
    NAME, ICON = "Lighting_Grid", "Lighting_Grid"
    MENU = "Calculation grid"
    TIP = ("Calculation grid. Floor, slab, Arch space or floor face: the work plane (0.80 m, "
           "0.5 m wall band, EN 12464-1 spacing). A wall's inner face or a ceiling's underside "
           "(any planar face): a wall or ceiling grid on it, facing the room, with the "
           "EN 12464-1 wall/ceiling requirement")
    #: Object name and Activity preset of a new grid by its Surface kind.
    KINDS = {"Work plane": ("Workplane", None), "Wall": ("WallGrid", standards.GENERAL),
             "Ceiling": ("CeilingGrid", standards.GENERAL), "Floor": ("FloorGrid", None)}

    def IsActive(self) -> bool:  # noqa: N802
        return _doc() is not None and bool(FreeCADGui.Selection.getSelection())

    @staticmethod
    def surface_of(obj: Any, face: Optional[str]) -> str:
        """The grid kind for a selection: from the selected face's room-side normal (faces
        looking up carry a work plane), the work plane when no face is selected."""
        from lighting import standards
        from lighting.geometry import face_index, global_shape, is_planar
        from lighting.objects.target import room_side_normal

        index = face_index(face) if face else None
        if index is None:
            return "Work plane"
        shape_face = global_shape(obj).Faces[index]
        if not is_planar(shape_face):
            return "Work plane"  # a curved face: the grid's Check explains what to select
        return standards.surface_kind(room_side_normal(obj, shape_face).z)

    def Activated(self) -> None:  # noqa: N802
        sel = FreeCADGui.Selection.getSelectionEx()[0]
        faces = [n for n in sel.SubElementNames if n.startswith("Face")]
        surface = self.surface_of(sel.Object, faces[0] if faces else None)
        name, activity = self.KINDS[surface]
        extra = "" if surface == "Work plane" else (f", surface={surface!r}, name={name!r}"
                                                    f", activity={activity!r}")
        face = repr(faces[0]) if faces else "None"
        title = "calculation" if surface == "Work plane" else surface.lower()
        _run_transaction(f"Create {title} grid", [
            f"lighting.make_grid_target(FreeCAD.ActiveDocument, "
            f"FreeCAD.ActiveDocument.getObject('{sel.Object.Name}'), face={face}{extra}, "
            f"analysis={_analysis_arg()})"])


class CommandPlacementDomain(BaseCommand):
    NAME, ICON = "Lighting_PlacementDomain", "Lighting_PlacementDomain"
    MENU = "Placement domain"
    TIP = "Face (e.g. the ceiling) where the optimizer may place luminaires"

    def IsActive(self) -> bool:  # noqa: N802
        return _doc() is not None and bool(_selected_faces())

    def Activated(self) -> None:  # noqa: N802
        obj, names = _selected_faces()[0]
        _run_transaction("Create placement domain", [
            f"lighting.make_placement_domain(FreeCAD.ActiveDocument, "
            f"FreeCAD.ActiveDocument.getObject('{obj.Name}'), {names[0]!r}, "
            f"analysis={_analysis_arg()})"])


def _open_analysis_panel() -> Optional[Any]:
    """The analysis panel shown in the task view now, else None (also when another Lighting
    panel, e.g. Optimize, replaced it: FreeCAD then deleted its widgets and set its ``form``
    to None)."""
    from lighting.taskpanels import analysis_panel, sync

    panel = analysis_panel.last_panel()
    return panel if sync.is_shown(panel) else None


def _show_panel(make_panel: Any, analysis: Any, **options: Any) -> Optional[Any]:
    """Closes the open task dialog and opens ``make_panel(analysis, **options)``; returns it.
    A Lighting panel that is still solving or searching is kept (None returned, the user told
    why): closing it would cancel the work the user is waiting for."""
    from lighting.taskpanels import sync

    if not sync.close_current():
        return None
    return sync.show(make_panel(analysis, **options))


def _show_analysis_panel(analysis: Any, **options: Any) -> Optional[Any]:
    """The analysis panel (Check, Export, Run, Results): the open one when it shows
    ``analysis`` (Run starts there unless it is already solving), else a new one."""
    from lighting.taskpanels.analysis_panel import AnalysisTaskPanel

    current = _open_analysis_panel()
    if current is not None and current.analysis == analysis:
        FreeCADGui.Control.showTaskView()  # the user may be in the Model tab
        if options.get("autostart"):
            current.run()  # returns at once while a run is in progress
        return current
    return _show_panel(AnalysisTaskPanel, analysis, **options)


class CommandCheck(BaseCommand):
    NAME, ICON = "Lighting_Check", "Lighting_Check"
    MENU = "Check"
    TIP = "Check the analysis: luminaires, targets, leaky geometry, absurd values"

    def Activated(self) -> None:  # noqa: N802
        """Opens the analysis panel and checks there (report view + the panel's log)."""
        panel = _show_analysis_panel(active_analysis(create=True))
        if panel is not None and not panel.is_busy():  # not while its run is solving
            panel.check()


class CommandExport(BaseCommand):
    NAME, ICON = "Lighting_Export", "Lighting_Export"
    MENU = "Export scene"
    TIP = "Write the analysis' scene file (scene.json) for the lightsolver CLI"

    def Activated(self) -> None:  # noqa: N802
        panel = _show_analysis_panel(active_analysis(create=True))
        if panel is not None and not panel.is_busy():  # not while its run is solving
            panel.export()


class CommandRun(BaseCommand):
    NAME, ICON = "Lighting_Run", "Lighting_Run"
    MENU = "Run analysis"
    TIP = "Check, export and solve the analysis (the solver runs in the background)"

    def Activated(self) -> None:  # noqa: N802
        _show_analysis_panel(active_analysis(create=True), autostart=True)


class CommandOptimize(BaseCommand):
    NAME, ICON = "Lighting_Optimize", "Lighting_Optimize"
    MENU = "Optimize placement"
    TIP = ("Find where the placement domains' luminaires should go for a lighting intention "
           "(every statistically indistinguishable optimum, then Apply)")

    def Activated(self) -> None:  # noqa: N802
        from lighting.taskpanels.optimize_panel import OptimizeTaskPanel

        _show_panel(OptimizeTaskPanel, active_analysis(create=True))


class CommandResults(BaseCommand):
    NAME, ICON = "Lighting_Results", "Lighting_Results"
    MENU = "Results"
    TIP = "Show the results table and the colour scale of the analysis"

    def IsActive(self) -> bool:  # noqa: N802
        return _doc() is not None and active_analysis() is not None

    def Activated(self) -> None:  # noqa: N802
        _show_analysis_panel(active_analysis())


class CommandClearResults(BaseCommand):
    NAME, ICON = "Lighting_ClearResults", "Lighting_ClearResults"
    MENU = "Clear results"
    TIP = "Remove the stored results of the analysis (undoable)"

    def IsActive(self) -> bool:  # noqa: N802
        analysis = active_analysis() if _doc() is not None else None
        if analysis is None:
            return False
        from lighting.objects import results

        legacy = "ResultsJson" in analysis.PropertiesList  # not yet migrated (store.migrate)
        return results.of_analysis(analysis) is not None or legacy

    def Activated(self) -> None:  # noqa: N802
        from lighting.solver import store

        store.clear(active_analysis())


ALL = (CommandAnalysis, CommandLuminaire, CommandTarget, CommandGrid, CommandPlacementDomain,
       CommandCheck, CommandExport, CommandRun, CommandOptimize, CommandResults,
       CommandClearResults)
# Toolbar and menu order; the commands of their own modules (layout, chooser, observer,
# report, exclusion) are registered by register() below.
MODEL_COMMANDS = ["Lighting_Analysis", "Lighting_Luminaire", "Lighting_ChooseLuminaire",
                  "Lighting_LuminaireLayout", "Lighting_Target", "Lighting_Grid",
                  "Lighting_Observer", "Lighting_ObserverGrid", "Lighting_LightScene",
                  "Lighting_PlacementDomain", "Lighting_Sky", "Lighting_AnnualDaylight"]
RUN_COMMANDS = ["Lighting_Check", "Lighting_Export", "Lighting_Run", "Lighting_Live",
                "Lighting_Optimize",
                "Lighting_Results", "Lighting_Report", "Lighting_ClearResults"]
#: Toolbars, by role: the main commands first (Qt squeezes the last toolbars of a row behind
#: their overflow arrows first, and FreeCAD's own toolbars fill most of a 1280 px row), then
#: the model's objects, then the checks a user runs less often.
TOOLBARS = (("Lighting analysis", [c for c in RUN_COMMANDS
                                   if c not in ("Lighting_Check", "Lighting_Export")]),
            ("Lighting model", MODEL_COMMANDS),
            ("Lighting check", ["Lighting_Check", "Lighting_Export"]))


from lighting.commands import exclusion  # noqa: E402 - "Exclude from lighting" / "Include"

EXCLUSION_COMMANDS = exclusion.NAMES


def register() -> None:
    """Add every command to FreeCAD (once)."""
    from lighting.commands import annual, chooser, daylight, glare, light_scene, live, report
    from lighting.commands.layout import CommandLuminaireLayout

    more = (CommandLuminaireLayout, chooser.CommandChooseLuminaire, report.CommandReport,
            *glare.ALL, *light_scene.ALL, *live.ALL, *daylight.ALL, *annual.ALL)
    for cls in ALL + exclusion.ALL + more:
        if cls.NAME not in COMMANDS:
            FreeCADGui.addCommand(cls.NAME, cls())
            COMMANDS.append(cls.NAME)

