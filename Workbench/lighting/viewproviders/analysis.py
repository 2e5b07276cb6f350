# SPDX-License-Identifier: LGPL-2.1-or-later
"""View provider of the analysis: the group in the tree, its task panel, the colour legend.

The legend is drawn by Coin in the 3D view (so ``saveImage`` screenshots contain it): an
annotation with its own orthographic camera, inside a group that the view's bounding box
ignores (FreeCAD's SoSkipBoundingGroup) so that "fit all" is unaffected."""
from __future__ import annotations

from typing import Any, List, Optional, Sequence, Tuple

import FreeCAD

from lighting.colormap import Scale
from lighting.viewproviders.base import ViewProviderBase

#: App properties of the analysis whose change repaints its targets and legend: the display
#: settings and the group (a results object added or removed; the results object's own view
#: provider repaints when its results change).
REPAINT_ON = ("ColorMap", "ScaleMode", "ScaleMinLux", "ScaleMaxLux", "ShowLegend", "Group")
LEGEND_STEPS = 32
LEGEND_TICKS = 6
# Legend rectangle in the legend camera's coordinates (x, y in -1..1 over the viewport).
# The bar ends at 0.65 so that up to four title lines fit above it; the title goes one short
# line per part (title_lines) so that it stays at the left, clear of the navigation cube in
# the top-right corner.
X0, X1, Y0, Y1 = -0.97, -0.92, -0.75, 0.65
TITLE_STEP = 0.05


def _coin() -> Any:
    from pivy import coin

    return coin


def _skip_bounding_group() -> Any:
    """A group that the bounding-box action skips, or a plain separator if unavailable."""
    coin = _coin()
    try:
        node_type = coin.SoType.fromName("SoSkipBoundingGroup")
        if not node_type.isBad():
            node = node_type.createInstance()
            if hasattr(node, "addChild"):
                return node
    except Exception:  # noqa: BLE001 - fall back below
        pass
    return coin.SoSeparator()


#: Legend of stale results: colours washed towards this grey, and this title.
STALE_GREY = (0.72, 0.72, 0.72)
STALE_WASH = 0.7
STALE_TITLE = "Illuminance [lx] - OUT OF DATE: the model changed - press Run"


def title_lines(title: str) -> List[str]:
    """The legend title as drawn: one line per " - " part, top first (a long single line
    ran under the navigation cube)."""
    return [part.strip() for part in title.split(" - ") if part.strip()]


def _washed(rgb: Tuple[float, float, float]) -> Tuple[float, float, float]:
    return tuple(STALE_WASH * g + (1.0 - STALE_WASH) * c for c, g in zip(rgb, STALE_GREY))


#: Colours of the verdict markers under the legend: pass green, FAIL red, undecided amber.
VERDICT_RGB = {"pass": (0.0, 0.55, 0.0), "FAIL": (0.85, 0.0, 0.0), "undecided": (0.85, 0.5, 0.0)}


def build_legend(scale: Scale, title: str = "Illuminance [lx]", stale: bool = False,
                 verdicts: Sequence[Tuple[str, str]] = (), digits: int = 0) -> Any:
    """Coin nodes of a vertical colour bar with tick labels at the left of the view; greyed,
    with a title that says so, when the results are stale. ``verdicts``: (target label,
    verdict word) lines drawn under the bar in the verdict's colour."""
    coin = _coin()
    root = coin.SoAnnotation()
    camera = coin.SoOrthographicCamera()
    camera.viewportMapping = coin.SoCamera.LEAVE_ALONE
    camera.position = (0.0, 0.0, 5.0)
    camera.height = 2.0
    camera.nearDistance = 0.5
    camera.farDistance = 10.0
    root.addChild(camera)
    light_model = coin.SoLightModel()
    light_model.model = coin.SoLightModel.BASE_COLOR
    root.addChild(light_model)
    pick = coin.SoPickStyle()
    pick.style = coin.SoPickStyle.UNPICKABLE
    root.addChild(pick)
    # Colour bar: LEGEND_STEPS quads, bottom = min.
    points, colours = [], []
    dy = (Y1 - Y0) / LEGEND_STEPS
    for i in range(LEGEND_STEPS):
        y = Y0 + i * dy
        points += [(X0, y, 0.0), (X1, y, 0.0), (X1, y + dy, 0.0), (X0, y + dy, 0.0)]
        rgb = scale.colour(scale.min_lux + (i + 0.5) / LEGEND_STEPS *
                           (scale.max_lux - scale.min_lux))
        colours.append(_washed(rgb) if stale else rgb)
    material = coin.SoMaterial()
    material.diffuseColor.setValues(0, len(colours), colours)
    root.addChild(material)
    binding = coin.SoMaterialBinding()
    binding.value = coin.SoMaterialBinding.PER_FACE
    root.addChild(binding)
    coords = coin.SoCoordinate3()
    coords.point.setValues(0, len(points), points)
    root.addChild(coords)
    faces = coin.SoFaceSet()
    faces.numVertices.setValues(0, LEGEND_STEPS, [4] * LEGEND_STEPS)
    root.addChild(faces)
    # Labels.
    text_sep = coin.SoSeparator()
    text_colour = coin.SoBaseColor()
    text_colour.rgb = (0.0, 0.0, 0.0)
    text_sep.addChild(text_colour)
    font = coin.SoFont()
    font.size = 14
    text_sep.addChild(font)
    for value in scale.ticks(LEGEND_TICKS):
        y = Y0 + scale.position(value) * (Y1 - Y0)
        label = coin.SoSeparator()
        move = coin.SoTranslation()
        move.translation = (X1 + 0.01, y - 0.01, 0.0)
        label.addChild(move)
        text = coin.SoText2()
        text.string = f"{value:.{digits}f}"  # a daylight factor's 0.5 % steps: 1 digit
        label.addChild(text)
        text_sep.addChild(label)
    title_sep = coin.SoSeparator()
    if stale:  # bright: readable on FreeCAD's dark-blue to light background
        warn_colour = coin.SoBaseColor()
        warn_colour.rgb = (1.0, 0.45, 0.3)
        title_sep.addChild(warn_colour)
    lines = title_lines(STALE_TITLE if stale else title)
    for row, line_text in enumerate(lines):
        line = coin.SoSeparator()
        move = coin.SoTranslation()
        move.translation = (X0, Y1 + 0.05 + TITLE_STEP * (len(lines) - 1 - row), 0.0)
        line.addChild(move)
        text = coin.SoText2()
        text.string = line_text
        line.addChild(text)
        title_sep.addChild(line)
    text_sep.addChild(title_sep)
    for row, (label, word) in enumerate(verdicts):
        line = coin.SoSeparator()
        move = coin.SoTranslation()
        move.translation = (X0, Y0 - 0.07 - 0.05 * row, 0.0)
        line.addChild(move)
        colour = coin.SoBaseColor()
        colour.rgb = VERDICT_RGB.get(word, (0.0, 0.0, 0.0))
        line.addChild(colour)
        marker = coin.SoText2()
        marker.string = f"{label}: {word}"
        line.addChild(marker)
        text_sep.addChild(line)
    root.addChild(text_sep)
    return root


class ViewProviderAnalysis(ViewProviderBase):
    """Analysis group: opens the run/results task panel; draws the legend."""

    ICON = "Lighting_Analysis"
    MODELESS = True

    def __init__(self, vobj: Any) -> None:
        super().__init__(vobj)

    def attach(self, vobj: Any) -> None:
        super().attach(vobj)
        if getattr(self, "legend_root", None) is not None:
            return
        # The legend hangs under the root node, beside the display-mode switch, so it works
        # however the view provider was attached (new, restored, or added to a file saved
        # headless); visibility follows ShowLegend and the analysis' own visibility.
        coin = _coin()
        self.legend_root = coin.SoSeparator()
        self.legend_holder = _skip_bounding_group()
        self.legend_root.addChild(self.legend_holder)
        vobj.RootNode.addChild(self.legend_root)
        from PySide import QtCore

        # Restored documents: paint once every object is there.
        QtCore.QTimer.singleShot(0, self._refresh_later)

    def _refresh_later(self) -> None:
        try:
            obj = self.Object
            obj.Name  # noqa: B018 - raises if the object was deleted
        except Exception:  # noqa: BLE001
            return
        from lighting.viewproviders import coloring

        coloring.refresh(obj)

    def onChanged(self, vobj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API name)
        if prop == "Visibility" and getattr(self, "legend_root", None) is not None:
            self._refresh_later()

    def updateData(self, obj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API name)
        """Results or display settings changed (by the task panel, a script, undo...)."""
        if prop == "Live" and not getattr(obj.Document, "Restoring", False):
            from lighting.commands import live

            live.sync(obj)  # start or stop the live session (commands/live.py)
        if prop in REPAINT_ON and getattr(self, "legend_root", None) is not None:
            from lighting.viewproviders import coloring

            coloring.refresh_later(obj)

    def update_legend(self, scale: Optional[Scale], title: Optional[str] = None,
                      digits: int = 0) -> None:
        """Show the legend of ``scale`` (None hides it); ``title``: another quantity's (a
        daylight factor's, viewproviders/daylight_coloring.py) instead of the lux one."""
        holder = getattr(self, "legend_holder", None)
        if holder is None:
            return
        holder.removeAllChildren()
        vobj = getattr(self, "ViewObject", None)
        if scale is not None and (vobj is None or vobj.Visibility):
            holder.addChild(build_legend(scale, title=title or self.legend_title(),
                                         stale=self.results_stale(),
                                         verdicts=self.verdict_lines(), digits=digits))

    def legend_title(self) -> str:
        """The legend's title, with the overall verdict on the requirements when the solver
        judged them (pass, FAIL or undecided: from the intervals, docs/statistics.md)."""
        try:
            from lighting.objects import results as results_obj

            found = results_obj.of_analysis(self.Object)
            typed = results_obj.read(results_obj.data(found))
            scene = str(getattr(found, "LightScene", "") or "") if found is not None else ""
        except Exception:  # noqa: BLE001 - never break the legend
            typed, scene = None, ""
        word = {"pass": "pass", "fail": "FAIL", "undecided": "undecided"}.get(
            typed.verdict if typed is not None else None)
        title = "Illuminance [lx]" + (f" - requirements: {word}" if word else "")
        # A scale that stays the same from run to run says so (plots.scale_note).
        try:
            from lighting import plots

            if plots.scale_note(self.Object)[0]:
                title = title.replace("[lx]", "[lx, locked scale]", 1)
        except Exception:  # noqa: BLE001 - never break the legend
            pass
        # The light scene shown (rescaled), so a screenshot says which one it is.
        if scene and "not shown" not in scene:
            title += f" - {scene.split(':')[0]}"
        status = str(getattr(self.Object, "Status", ""))
        return f"{title} - {status}" if status.startswith("live:") else title

    def verdict_lines(self) -> List[Tuple[str, str]]:
        """(label, pass/FAIL/undecided) of every target the solver judged, for the markers
        under the legend (results without the solver's verdicts show none)."""
        try:
            from lighting.objects import results as results_obj

            typed = results_obj.read(results_obj.data(results_obj.of_analysis(self.Object)))
            doc = self.Object.Document
        except Exception:  # noqa: BLE001 - never break the legend
            return []
        lines = []
        for target in typed.targets if typed is not None else []:
            word = {"pass": "pass", "fail": "FAIL", "undecided": "undecided"}.get(
                target.verdict or "")
            if word:
                obj = doc.getObject(target.name)
                lines.append((obj.Label if obj is not None else target.name, word))
        return lines

    def results_stale(self) -> bool:
        """True when the stored results no longer describe the model (or cannot tell)."""
        try:
            from lighting.viewproviders.results import current_state

            return current_state(self.Object).state in ("stale", "unknown")
        except Exception:  # noqa: BLE001 - never break the legend
            return False

    def task_panel(self, vobj: Any) -> Optional[Any]:
        from lighting.taskpanels.analysis_panel import AnalysisTaskPanel

        return AnalysisTaskPanel(vobj.Object)

    def claimChildren(self) -> list:  # noqa: N802
        return list(getattr(self.Object, "Group", []))

    def onDelete(self, vobj: Any, subelements: Any) -> bool:  # noqa: N802
        """Deleting the analysis keeps its members (they move to the document root), but not
        its results object: results without their analysis mean nothing (same undo step)."""
        from lighting.objects import results

        analysis = vobj.Object
        FreeCAD.Console.PrintLog(f"Lighting: deleting analysis {analysis.Name}\n")
        from lighting.taskpanels import analysis_panel

        panel = analysis_panel.panel_of(analysis)
        if panel is not None:  # its panel goes first (a run of it is cancelled)
            panel.reject()
        found = results.of_analysis(analysis)
        if found is not None:
            analysis.removeObject(found)
            analysis.Document.removeObject(found.Name)
        return True
