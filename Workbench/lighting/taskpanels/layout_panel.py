# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel "Luminaire layout": rows x columns, spacing, margins, mounting offset, rotation
and the luminaire type of a layout, edited live in the 3D view.

The panel works on a layout object inside one open transaction: every field change is
written to the object (and its template) at once, so the markers move while the user types;
OK commits the transaction (one undo step), Cancel aborts it (a new layout disappears, an
edited one gets its old values back). Fields are stacked (label above field), so the panel
fits FreeCAD's default combo view (about 264 px wide)."""
from __future__ import annotations

from typing import Any, Callable, Optional

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

from lighting.objects.luminaire import LUMINAIRE_TYPES
from lighting.viewproviders.base import icon_path

_last_panel: Optional["LayoutTaskPanel"] = None


def last_panel() -> Optional["LayoutTaskPanel"]:
    """The most recently opened panel (for scripts and the GUI scenarios)."""
    return _last_panel


def _metres(value: float, maximum: float = 100.0, step: float = 0.1) -> QtGui.QDoubleSpinBox:
    box = QtGui.QDoubleSpinBox()
    box.setDecimals(3)
    box.setRange(0.0, maximum)
    box.setSingleStep(step)
    box.setSuffix(" m")
    box.setValue(value)
    return box


class LayoutTaskPanel:
    """FreeCAD task dialog (``form`` + accept/reject) editing one luminaire layout."""

    def __init__(self, layout: Any, title: str = "Edit luminaire layout",
                 transaction_open: bool = False) -> None:
        global _last_panel
        _last_panel = self
        self.layout = layout
        self.doc = layout.Document
        if not transaction_open:
            self.doc.openTransaction(title)
        self.form = QtGui.QWidget()
        # A short title: the task box header is as wide as its title.
        self.form.setWindowTitle("Luminaire layout")
        self.form.setWindowIcon(QtGui.QIcon(icon_path("Lighting_LuminaireLayout")))
        self._loading = True
        self._build()
        self._loading = False
        self._update_summary()

    # -- widgets ---------------------------------------------------------------------------
    def _build(self) -> None:
        obj = self.layout
        template = obj.Template
        outer = QtGui.QVBoxLayout(self.form)
        self.field_label = QtGui.QLabel(self._field_text())
        self.field_label.setWordWrap(True)
        outer.addWidget(self.field_label)

        grid = QtGui.QGroupBox("Arrangement")
        form = self._form(grid)
        self.columns = QtGui.QSpinBox()
        self.columns.setRange(1, 100)
        self.columns.setValue(int(obj.Columns))
        self.rows = QtGui.QSpinBox()
        self.rows.setRange(1, 100)
        self.rows.setValue(int(obj.Rows))
        self.spacing_x = _metres(float(obj.SpacingX) / 1000.0)
        self.spacing_y = _metres(float(obj.SpacingY) / 1000.0)
        self.margin_x = _metres(float(obj.MarginX) / 1000.0)
        self.margin_y = _metres(float(obj.MarginY) / 1000.0)
        self.offset = _metres(float(obj.MountingOffset) / 1000.0, 50.0, 0.05)
        self.rotation = QtGui.QDoubleSpinBox()
        self.rotation.setRange(-360.0, 360.0)
        self.rotation.setSuffix(" °")
        self.rotation.setValue(float(obj.LuminaireRotation))
        for text, widget, tip in (
                ("Columns (x)", self.columns, "Luminaires along the field's x axis"),
                ("Rows (y)", self.rows, "Luminaires along the field's y axis"),
                ("Spacing x (0 = fill)", self.spacing_x, obj.getDocumentationOfProperty("SpacingX")),
                ("Spacing y (0 = fill)", self.spacing_y, obj.getDocumentationOfProperty("SpacingY")),
                ("Margin x to walls (0 = even)", self.margin_x,
                 obj.getDocumentationOfProperty("MarginX")),
                ("Margin y to walls (0 = even)", self.margin_y,
                 obj.getDocumentationOfProperty("MarginY")),
                (self._offset_text(), self.offset,
                 obj.getDocumentationOfProperty("MountingOffset")),
                ("Rotation of each", self.rotation,
                 obj.getDocumentationOfProperty("LuminaireRotation"))):
            widget.setToolTip(tip)
            form.addRow(text, widget)
        outer.addWidget(grid)

        kind = QtGui.QGroupBox("Luminaire type (all)")
        form = self._form(kind)
        self.kind = QtGui.QComboBox()
        self.kind.addItems(list(LUMINAIRE_TYPES))
        self.kind.setCurrentIndex(LUMINAIRE_TYPES.index(template.LuminaireType))
        self.flux = QtGui.QDoubleSpinBox()
        self.flux.setRange(0.0, 1.0e6)
        self.flux.setDecimals(0)
        self.flux.setSingleStep(100.0)
        self.flux.setSuffix(" lm")
        self.flux.setValue(float(template.FluxLumen))
        self.mf = QtGui.QDoubleSpinBox()
        self.mf.setRange(0.01, 1.0)
        self.mf.setSingleStep(0.05)
        self.mf.setValue(float(template.MaintenanceFactor))
        self.width = _metres(float(template.Width) / 1000.0, 10.0, 0.05)
        self.length = _metres(float(template.Length) / 1000.0, 10.0, 0.05)
        self.file = QtGui.QLineEdit(str(template.PhotometricFile))
        self.file.setPlaceholderText("IES / LDT file (Photometric)")
        for text, widget in (("Type", self.kind), ("Flux per luminaire", self.flux),
                             ("Maintenance factor", self.mf), ("Width (Area)", self.width),
                             ("Length (Area)", self.length), ("Photometric file", self.file)):
            form.addRow(text, widget)
        outer.addWidget(kind)

        self.summary = QtGui.QLabel()
        self.summary.setWordWrap(True)
        outer.addWidget(self.summary)
        outer.addStretch(1)
        self._connect()

    @staticmethod
    def _form(parent: QtGui.QWidget) -> QtGui.QFormLayout:
        form = QtGui.QFormLayout(parent)
        # Label above field: the panel stays narrow enough for the default combo view.
        form.setRowWrapPolicy(QtGui.QFormLayout.WrapAllRows)
        form.setFieldGrowthPolicy(QtGui.QFormLayout.AllNonFixedFieldsGrow)
        return form

    def _connect(self) -> None:
        layout_fields: list = [
            (self.columns, "Columns", 1.0), (self.rows, "Rows", 1.0),
            (self.spacing_x, "SpacingX", 1000.0), (self.spacing_y, "SpacingY", 1000.0),
            (self.margin_x, "MarginX", 1000.0), (self.margin_y, "MarginY", 1000.0),
            (self.offset, "MountingOffset", 1000.0), (self.rotation, "LuminaireRotation", 1.0)]
        for widget, prop, scale in layout_fields:
            widget.valueChanged.connect(self._setter(lambda: self.layout, prop, scale, widget))
        for widget, prop, scale in ((self.flux, "FluxLumen", 1.0),
                                    (self.mf, "MaintenanceFactor", 1.0),
                                    (self.width, "Width", 1000.0), (self.length, "Length", 1000.0)):
            widget.valueChanged.connect(self._setter(lambda: self.layout.Template, prop, scale,
                                                     widget))
        self.kind.currentIndexChanged.connect(lambda _i: self._set(
            self.layout.Template, "LuminaireType", self.kind.currentText()))
        self.file.editingFinished.connect(lambda: self._set(
            self.layout.Template, "PhotometricFile", self.file.text()))

    def _setter(self, target: Callable[[], Any], prop: str, scale: float,
                widget: Any) -> Callable[..., None]:
        def apply(*_args: Any) -> None:
            value = widget.value() * scale
            self._set(target(), prop, int(value) if isinstance(widget, QtGui.QSpinBox) else value)
        return apply

    def _set(self, obj: Any, prop: str, value: Any) -> None:
        """Write a field to the object and redraw the markers (live preview)."""
        if self._loading or obj is None:
            return
        try:
            setattr(obj, prop, value)
            self.layout.touch()
            self.doc.recompute()
        except Exception as exc:  # noqa: BLE001 - show it, keep the panel usable
            FreeCAD.Console.PrintError(f"Lighting: {obj.Label}.{prop}: {exc}\n")
        self._update_summary()

    # -- texts -----------------------------------------------------------------------------
    def _field_text(self) -> str:
        obj = self.layout
        link = obj.Base
        try:
            from lighting.objects.luminaire_layout import field_frame

            frame, _ = field_frame(obj)
            size = f"{(frame.u1 - frame.u0) / 1000.0:.2f} × {(frame.v1 - frame.v0) / 1000.0:.2f} m"
        except ValueError as exc:
            return f"Field: {exc}"
        if link and link[0] is not None:
            subs = ", ".join(link[1] or [])
            return f"Field: {link[0].Label} {subs} (room {size})"
        return f"Field: rectangle {size} at the layout's placement"

    def _offset_text(self) -> str:
        """What MountingOffset means for this field: below a ceiling, above a floor."""
        from lighting.objects.luminaire_layout import field_frame

        try:
            frame, face = field_frame(self.layout)
        except ValueError:
            return "Distance from the face"
        return "Height above floor" if face is not None and frame.normal.z > 0.5 \
            else "Distance from ceiling"

    def _update_summary(self) -> None:
        from lighting.objects.luminaire_layout import check

        obj = self.layout
        template = obj.Template
        count = int(obj.MemberCount)
        flux = float(template.FluxLumen) if template is not None else 0.0
        lines = [f"{count} luminaires, {count * flux:,.0f} lm installed"]
        lines += [text for _, text in check(obj)]
        self.summary.setText("\n".join(lines))

    # -- task dialog -----------------------------------------------------------------------
    def getStandardButtons(self) -> int:  # noqa: N802 (FreeCAD API name)
        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def accept(self) -> bool:
        """Keep the changes: one undo step."""
        self.file.editingFinished.emit()
        self.doc.commitTransaction()
        FreeCAD.Console.PrintMessage(f"Lighting: luminaire layout '{self.layout.Label}': "
                                     f"{self.summary.text().splitlines()[0]}\n")
        self._close()
        return True

    def reject(self) -> bool:
        """Undo everything the panel did (a new layout is removed)."""
        self.doc.abortTransaction()
        self.doc.recompute()
        self._close()
        return True

    def _close(self) -> None:
        FreeCADGui.Control.closeDialog()
        gui_doc = FreeCADGui.getDocument(self.doc.Name)
        if gui_doc is not None and gui_doc.getInEdit() is not None:
            QtCore.QTimer.singleShot(0, gui_doc.resetEdit)
