# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Sky's panel: what it exports (sky, site, sun, each portal with its glazing, the glazing
defaults), from export/daylight.py ``summary_lines``; the values are edited in the property
editor, and the panel follows the document (taskpanels/sync.py)."""
from __future__ import annotations

from typing import Any

from PySide import QtGui

from lighting.taskpanels.modeless import ModelessPanel


class SkyPanel(ModelessPanel):
    """Read-only summary of a Sky; the model stays editable while it is open."""

    def __init__(self, sky: Any) -> None:
        self.sky = sky
        self.form = QtGui.QWidget()
        self.form.setWindowTitle(f"Sky: {sky.Label}")
        layout = QtGui.QVBoxLayout(self.form)
        self.text = QtGui.QLabel("")
        self.text.setWordWrap(True)
        layout.addWidget(self.text)
        hint = QtGui.QLabel("Edit the sky, the site, the sun and the glazing in the property "
                            "editor; the portals are the Arch windows hosted in walls.")
        hint.setWordWrap(True)
        layout.addWidget(hint)
        layout.addStretch(1)
        self.refresh()

    def refresh(self) -> None:
        """Show the Sky as the document holds it now."""
        from lighting.export import daylight
        from lighting.taskpanels import sync

        if not sync.object_alive(self.sky):
            self.close_dialog()
            return
        self.text.setText("\n\n".join(daylight.summary_lines(self.sky)))

    def getStandardButtons(self) -> int:  # noqa: N802 (FreeCAD API name)
        return int(QtGui.QDialogButtonBox.Close)

    def reject(self) -> bool:
        self.close_dialog()
        return True

    def accept(self) -> bool:
        return self.reject()
