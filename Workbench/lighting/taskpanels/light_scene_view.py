# SPDX-License-Identifier: LGPL-2.1-or-later
"""The analysis panel's "Light scenes" section: which scene the results show and its level
per control group. A change rescales the stored run (objects/light_scene.py): the table,
colours, legend and verdicts follow at once, with no tracing. Each edit is one undo step."""
from __future__ import annotations

from typing import Any, Callable, List, Optional

from PySide import QtCore, QtGui

from lighting.objects import light_scene
from lighting.objects import results as results_obj

#: The combo's first entry: the results as traced.
AS_TRACED = "As traced (all 100 %)"


class LightSceneView(QtGui.QWidget):
    """Scene chooser, a level per group of the scene shown, and what is shown."""

    def __init__(self, analysis: Any, changed: Callable[[], None],
                 parent: Optional[QtGui.QWidget] = None) -> None:
        super().__init__(parent)
        self.analysis = analysis
        self.changed = changed  # the panel redraws its results table
        self._filling = False
        layout = QtGui.QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        row = QtGui.QHBoxLayout()
        self.combo = QtGui.QComboBox()
        self.combo.setSizeAdjustPolicy(QtGui.QComboBox.AdjustToMinimumContentsLengthWithIcon)
        self.combo.setMinimumContentsLength(8)
        self.combo.setToolTip("The light scene the results show: rescaled from the last run, "
                              "no tracing")
        self.combo.currentIndexChanged.connect(self._scene_chosen)
        self.new_button = QtGui.QPushButton("New")
        self.new_button.setToolTip("A new light scene with every control group at 100 %")
        self.new_button.clicked.connect(self._new_scene)
        row.addWidget(self.combo, 1)
        row.addWidget(self.new_button)
        layout.addLayout(row)
        self.table = QtGui.QTableWidget(0, 2)
        self.table.setHorizontalHeaderLabels(["Group", "Level %"])
        self.table.verticalHeader().setVisible(False)
        self.table.horizontalHeader().setStretchLastSection(False)
        self.table.horizontalHeader().setSectionResizeMode(0, QtGui.QHeaderView.Stretch)
        self.table.horizontalHeader().setSectionResizeMode(1, QtGui.QHeaderView.ResizeToContents)
        self.table.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarAlwaysOff)
        layout.addWidget(self.table)
        self.note = QtGui.QLabel("")
        self.note.setWordWrap(True)
        layout.addWidget(self.note)
        self.refresh()

    # -- showing -------------------------------------------------------------------------
    def refresh(self) -> None:
        """Fill the chooser and the table from the document."""
        self._filling = True
        try:
            scenes = light_scene.scenes(self.analysis)
            shown = light_scene.active(self.analysis)
            self.combo.clear()
            self.combo.addItem(AS_TRACED)
            for scene in scenes:
                self.combo.addItem(scene.Label, scene.Name)
            self.combo.setCurrentIndex(scenes.index(shown) + 1 if shown in scenes else 0)
            self._fill_table(shown)
        finally:
            self._filling = False
        found = results_obj.of_analysis(self.analysis)
        note = found.LightScene if found is not None and "LightScene" in found.PropertiesList \
            else ""
        if not scenes:
            note = ("No light scenes: New makes one (the next run then traces each control "
                    "group separately).")
        self.note.setText(note)

    def _fill_table(self, scene: Optional[Any]) -> None:
        self.table.setRowCount(0)
        self.table.setEnabled(scene is not None)
        if scene is None:
            return
        # Groups made after the scene (a luminaire added later) are listed too, at the 100 %
        # they get, and say so; setting their level adds them to the scene.
        from lighting.objects import analysis as analysis_mod

        self._missing = [g for g in analysis_mod.control_groups(self.analysis)
                         if g not in list(scene.Groups)]
        rows = list(zip(scene.Groups, scene.Levels)) + [(g, 1.0) for g in self._missing]
        for row, (group, level) in enumerate(rows):
            self.table.insertRow(row)
            new = row >= len(scene.Groups)
            item = QtGui.QTableWidgetItem(f"{group} (new: not in this scene)" if new else group)
            if new:
                item.setToolTip(f"Group '{group}' was made after this scene: it is at 100 % "
                                "until you set its level here")
            item.setFlags(item.flags() & ~QtCore.Qt.ItemIsEditable)
            self.table.setItem(row, 0, item)
            spin = QtGui.QDoubleSpinBox()
            spin.setRange(0.0, 1000.0)
            spin.setDecimals(0)
            spin.setSingleStep(10.0)
            spin.setValue(float(level) * 100.0)
            spin.setKeyboardTracking(False)  # one rescale per finished entry, not per digit
            spin.valueChanged.connect(lambda value, r=row: self._level_changed(r, value))
            self.table.setCellWidget(row, 1, spin)
        height = self.table.horizontalHeader().height() + 4
        height += sum(self.table.rowHeight(r) for r in range(self.table.rowCount()))
        self.table.setFixedHeight(min(height, 220))

    # -- editing -------------------------------------------------------------------------
    def _scene_chosen(self, index: int) -> None:
        if self._filling:
            return
        from lighting.solver.store import undo_step

        scenes = light_scene.scenes(self.analysis)
        chosen = scenes[index - 1] if 0 < index <= len(scenes) else None
        if light_scene.active(self.analysis) is not chosen:
            with undo_step(self.analysis.Document, "Show light scene"):
                self.analysis.ActiveLightScene = chosen
        self._done()

    def _level_changed(self, row: int, percent: float) -> None:
        from lighting.solver.store import undo_step

        scene = light_scene.active(self.analysis)
        if scene is None:
            return
        values: List[float] = list(scene.Levels)
        missing = getattr(self, "_missing", [])
        if row >= len(values):  # a group made after the scene: it joins the scene now
            extra = row - len(values)
            if extra >= len(missing):
                return
            with undo_step(self.analysis.Document, "Light scene level"):
                scene.Levels = values + [percent / 100.0]
                scene.Groups = list(scene.Groups) + [missing[extra]]
            self._done()
            return
        if abs(values[row] - percent / 100.0) < 1e-12:
            return
        values[row] = percent / 100.0
        with undo_step(self.analysis.Document, "Light scene level"):
            scene.Levels = values
        self._done()

    def _new_scene(self) -> None:
        from lighting.solver.store import undo_step

        count = len(light_scene.scenes(self.analysis)) + 1
        with undo_step(self.analysis.Document, "Create light scene"):
            light_scene.make(self.analysis, f"Light scene {count}")
        self._done()

    def _done(self) -> None:
        # Later: the table's spin boxes are rebuilt, and one of them may be sending now.
        QtCore.QTimer.singleShot(0, self._redraw)

    def _redraw(self) -> None:
        self.refresh()
        self.changed()
