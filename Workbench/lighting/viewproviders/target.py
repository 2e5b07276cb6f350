# SPDX-License-Identifier: LGPL-2.1-or-later
"""View provider of targets: plain when not computed, false colours with results, and the
iso-lux lines of grids (Coin line sets over the cells, labelled with their level)."""
from __future__ import annotations

from typing import Any, List, Sequence, Tuple

from lighting.viewproviders.base import ViewProviderBase, set_if_exists

#: App properties whose change repaints the target (its colours come from its analysis'
#: results object, whose view provider repaints when they change).
REPAINT_ON = ("Shape",)
#: View properties of the iso-lux lines: (type, name, tool tip, default).
VIEW_PROPERTIES = (
    ("App::PropertyBool", "ShowIsolux", "Grids: draw iso-lux lines at the legend's levels", True),
    ("App::PropertyBool", "IsoluxLabels", "Grids: label the iso-lux lines with their lux", True),
)
#: Name of the iso-lux switch node (GUI tests find the lines by it).
ISOLUX_NODE = "LightingIsolux"

Polyline = Tuple[float, Sequence[Tuple[float, float, float]]]


def _coin() -> Any:
    from pivy import coin

    return coin


class ViewProviderTarget(ViewProviderBase):
    """Grid cells or target faces, coloured by illuminance; iso-lux lines on grids."""

    ICON = "Lighting_Target"

    def __init__(self, vobj: Any) -> None:
        super().__init__(vobj)
        set_if_exists(vobj, "LineColor", (0.2, 0.2, 0.2))
        set_if_exists(vobj, "LineWidth", 1.0)
        set_if_exists(vobj, "Lighting", "Two side")
        self._add_view_properties(vobj)

    @staticmethod
    def _add_view_properties(vobj: Any) -> None:
        """The iso-lux view properties (also on view providers restored from older files)."""
        for kind, name, tip, default in VIEW_PROPERTIES:
            if name not in vobj.PropertiesList:
                vobj.addProperty(kind, name, "Lighting", tip)
                setattr(vobj, name, default)

    def attach(self, vobj: Any) -> None:
        super().attach(vobj)
        self._add_view_properties(vobj)
        if getattr(self, "light_model", None) is None:
            coin = _coin()
            # False colours are shown unshaded (BASE_COLOR) so they match the legend exactly.
            self.light_model = coin.SoLightModel()
            self.light_model.model = coin.SoLightModel.PHONG
            vobj.RootNode.insertChild(self.light_model, 0)
        if getattr(self, "isolux_switch", None) is None:
            # Beside the display-mode switch, so hiding the object must hide it too (onChanged).
            coin = _coin()
            self.isolux_switch = coin.SoSwitch()
            self.isolux_switch.setName(ISOLUX_NODE)
            self.isolux_root = coin.SoSeparator()
            self.isolux_switch.addChild(self.isolux_root)
            vobj.RootNode.addChild(self.isolux_switch)
            self._lines: List[Polyline] = []
            self._update_switch(vobj)

    def set_unlit(self, unlit: bool) -> None:
        """Unshaded colours (results) or normal shading (no results)."""
        model = getattr(self, "light_model", None)
        if model is not None:
            coin = _coin()
            model.model = coin.SoLightModel.BASE_COLOR if unlit else coin.SoLightModel.PHONG

    # -- iso-lux lines ---------------------------------------------------------------------
    def set_isolux(self, lines: List[Polyline],
                   label_lift: Tuple[float, float, float] = (0.0, 0.0, 0.0)) -> None:
        """Show these iso-lux polylines: (level in lx, points in mm), their labels moved by
        ``label_lift`` (mm); [] removes them."""
        self._lines = list(lines)
        self.label_lift = label_lift
        self._rebuild_isolux()

    def isolux_lines(self) -> List[Polyline]:
        """The polylines shown (for scripts and tests)."""
        return list(getattr(self, "_lines", []))

    def _rebuild_isolux(self) -> None:
        root = getattr(self, "isolux_root", None)
        if root is None:
            return
        root.removeAllChildren()
        if not getattr(self, "_lines", None):
            return
        coin = _coin()
        for node in self._line_style(coin):
            root.addChild(node)
        points, counts = [], []
        for _, polyline in self._lines:
            points.extend(polyline)
            counts.append(len(polyline))
        coords = coin.SoCoordinate3()
        coords.point.setValues(0, len(points), points)
        root.addChild(coords)
        line_set = coin.SoLineSet()
        line_set.numVertices.setValues(0, len(counts), counts)
        root.addChild(line_set)
        vobj = getattr(self, "ViewObject", None)
        if vobj is None or getattr(vobj, "IsoluxLabels", True):
            root.addChild(self._labels(coin))

    @staticmethod
    def _line_style(coin: Any) -> List[Any]:
        pick = coin.SoPickStyle()
        pick.style = coin.SoPickStyle.UNPICKABLE
        light = coin.SoLightModel()
        light.model = coin.SoLightModel.BASE_COLOR
        colour = coin.SoBaseColor()
        colour.rgb = (0.05, 0.05, 0.05)
        style = coin.SoDrawStyle()
        style.lineWidth = 2.0
        return [pick, light, colour, style]

    def _labels(self, coin: Any) -> Any:
        """One label per line at its middle point (short stubs stay unlabelled), lifted
        further than the line: a bitmap text is depth-tested at its anchor, so a label close
        to a grid seen at a grazing angle would be cut by the grid's nearer part."""
        labels = coin.SoSeparator()
        lift = coin.SoTranslation()
        lift.translation = tuple(getattr(self, "label_lift", (0.0, 0.0, 0.0)))
        labels.addChild(lift)
        font = coin.SoFont()
        font.size = 12
        labels.addChild(font)
        for level, polyline in self._lines:
            if len(polyline) < 3:
                continue
            label = coin.SoSeparator()
            move = coin.SoTranslation()
            move.translation = polyline[len(polyline) // 2]
            label.addChild(move)
            text = coin.SoText2()
            text.string = f"{level:g}"
            label.addChild(text)
            labels.addChild(label)
        return labels

    def _update_switch(self, vobj: Any) -> None:
        switch = getattr(self, "isolux_switch", None)
        if switch is None:
            return
        shown = bool(vobj.Visibility) and bool(getattr(vobj, "ShowIsolux", True))
        switch.whichChild = 0 if shown else -1

    def onChanged(self, vobj: Any, prop: str) -> None:  # noqa: N802 (FreeCAD API name)
        if prop in ("Visibility", "ShowIsolux"):
            self._update_switch(vobj)
        elif prop == "IsoluxLabels" and getattr(self, "isolux_root", None) is not None:
            self._rebuild_isolux()

    def getIcon(self) -> str:  # noqa: N802 (FreeCAD API name)
        from lighting.viewproviders.base import icon_path

        grid = getattr(getattr(self, "Object", None), "TargetType", "") == "Grid"
        return icon_path("Lighting_Grid" if grid else "Lighting_Target")

    def updateData(self, obj: Any, prop: str) -> None:  # noqa: N802
        if prop in REPAINT_ON:
            from lighting.viewproviders import coloring

            coloring.refresh_later(obj)

