# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel "Choose luminaire data": the luminaire library (the shipped photometric files
and the user's folder, lighting/luminaire_library.py), the chosen file's summary and polar
diagram, then Assign: the selected Lighting luminaires become photometric with that file in
one undo step (a selected layout, or any of its luminaires clicked in the 3D view: its
template, so every member), or a new luminaire is made with it when none is selected.

The panel fits the default combo view (about 264 px): one column, word-wrapped texts, a
diagram that scales with the width, and the Assign / Close buttons in the task dialog's
button box, which FreeCAD keeps visible above the scrolled form."""
from __future__ import annotations

import os
from typing import Any, List, Optional, Tuple

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

from lighting import luminaire_library as library
from lighting.objects import analysis as analysis_mod
from lighting.objects.base import proxy_type
from lighting.objects.luminaire import TYPE as LUMINAIRE_TYPE
from lighting.objects.luminaire_layout import TYPE as LAYOUT_TYPE
from lighting.viewproviders.base import icon_path
from lighting.taskpanels.modeless import ModelessPanel
from lighting.taskpanels.ugr_table_dialog import UgrTableDialog

GROUP_TITLES = {library.SHIPPED: "Shipped samples", library.USER: "User folder"}
ERROR_COLOUR = QtGui.QColor(190, 30, 30)

_last_panel: Optional["LuminaireChooserPanel"] = None


def last_panel() -> Optional["LuminaireChooserPanel"]:
    """The most recently opened chooser (for scripts and the GUI scenarios)."""
    return _last_panel


class PolarView(QtGui.QWidget):
    """The native polar diagram (a square PNG) scaled to the panel's width."""

    def __init__(self, parent: Optional[QtGui.QWidget] = None) -> None:
        super().__init__(parent)
        self.image: Optional[QtGui.QImage] = None
        self.message = ""
        policy = QtGui.QSizePolicy(QtGui.QSizePolicy.Preferred, QtGui.QSizePolicy.Preferred)
        policy.setHeightForWidth(True)
        self.setSizePolicy(policy)
        self.setMinimumSize(120, 120)

    def hasHeightForWidth(self) -> bool:  # noqa: N802 (Qt API name)
        return True

    def heightForWidth(self, width: int) -> int:  # noqa: N802
        return width

    def sizeHint(self) -> QtCore.QSize:  # noqa: N802
        return QtCore.QSize(230, 230)

    def show_png(self, path: Optional[str], message: str = "") -> None:
        self.image = QtGui.QImage(path) if path else None
        if self.image is not None and self.image.isNull():
            self.image, message = None, f"cannot read {path}"
        self.message = message
        self.update()

    def paintEvent(self, event: Any) -> None:  # noqa: N802 (Qt API name)
        painter = QtGui.QPainter(self)
        side = min(self.width(), self.height())
        if self.image is not None:
            painter.setRenderHint(QtGui.QPainter.SmoothPixmapTransform, True)
            target = QtCore.QRect((self.width() - side) // 2, 0, side, side)
            painter.drawImage(target, self.image)
        else:
            painter.setPen(ERROR_COLOUR if self.message else self.palette().mid().color())
            painter.drawText(self.rect(), QtCore.Qt.AlignCenter | QtCore.Qt.TextWordWrap,
                             self.message or "no diagram")
        painter.end()


class _SelectionObserver:
    """Tells the panel when the selection changes (FreeCAD's selection observer protocol)."""

    def __init__(self, callback: Any) -> None:
        self.callback = callback

    def _changed(self) -> None:
        try:
            self.callback()
        except RuntimeError:  # the panel's widgets are gone (closed by another command)
            QtCore.QTimer.singleShot(0, lambda: FreeCADGui.Selection.removeObserver(self))

    def addSelection(self, *args: Any) -> None:  # noqa: N802 (FreeCAD API names)
        self._changed()

    def removeSelection(self, *args: Any) -> None:  # noqa: N802
        self._changed()

    def setSelection(self, *args: Any) -> None:  # noqa: N802
        self._changed()

    def clearSelection(self, *args: Any) -> None:  # noqa: N802
        self._changed()


def selected_luminaires() -> List[Any]:
    """The Lighting luminaires and luminaire layouts among the selected objects (a layout is
    selected by clicking any of its luminaires in the 3D view; Assign gives the file to its
    template, so every member changes)."""
    return [o for o in FreeCADGui.Selection.getSelection()
            if proxy_type(o) in (LUMINAIRE_TYPE, LAYOUT_TYPE)]


def _target_text(obj: Any) -> str:
    """How a target is named in the panel: a layout with its member count."""
    if proxy_type(obj) != LAYOUT_TYPE:
        return obj.Label
    return f"{obj.Label} (layout, all {obj.MemberCount} luminaires)"


def _selected_face() -> Optional[Tuple[Tuple[float, float, float], Tuple[float, float, float]]]:
    """(position_m, aim) 5 cm off the first selected face's centre, aimed along its normal
    (as the Luminaire command places one), or None."""
    for sel in FreeCADGui.Selection.getSelectionEx():
        for sub in sel.SubObjects:
            if getattr(sub, "ShapeType", "") == "Face":
                u0, u1, v0, v1 = sub.ParameterRange
                normal = sub.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1))
                point = sub.CenterOfMass + normal * 50.0
                return (point.x / 1000, point.y / 1000, point.z / 1000), (normal.x, normal.y,
                                                                          normal.z)
    return None


class LuminaireChooserPanel(ModelessPanel):
    """FreeCAD task dialog: library list, summary, polar diagram, Assign."""

    def __init__(self, luminaire: Any = None) -> None:
        global _last_panel
        _last_panel = self
        self.entries: List[library.LibraryEntry] = []
        self.button_box: Optional[QtGui.QDialogButtonBox] = None
        self.form = QtGui.QWidget()
        self.form.setWindowTitle("Choose luminaire data")
        self.form.setWindowIcon(QtGui.QIcon(icon_path("Lighting_Luminaire")))
        self._build()
        if luminaire is not None:
            FreeCADGui.Selection.clearSelection()
            FreeCADGui.Selection.addSelection(luminaire)
        self.observer = _SelectionObserver(self._update_targets)
        FreeCADGui.Selection.addObserver(self.observer)
        self.reload()

    # -- layout --------------------------------------------------------------------------
    def _build(self) -> None:
        layout = QtGui.QVBoxLayout(self.form)
        # What Assign will do comes first, right under the Assign button.
        self.targets = QtGui.QLabel()
        self.targets.setWordWrap(True)
        layout.addWidget(self.targets)
        self.keep_flux = QtGui.QCheckBox("Keep each luminaire's own flux")
        self.keep_flux.setToolTip("Unticked: FluxLumen becomes the file's lamp lumens")
        layout.addWidget(self.keep_flux)
        self.status = QtGui.QLabel()
        self.status.setWordWrap(True)
        self.status.hide()
        layout.addWidget(self.status)
        self.tree = QtGui.QTreeWidget()
        self.tree.setColumnCount(2)
        self.tree.setHeaderLabels(["File", "Lumens"])
        self.tree.setRootIsDecorated(False)
        self.tree.setMinimumHeight(110)
        self.tree.setMaximumHeight(170)
        self.tree.header().setStretchLastSection(False)
        self.tree.header().setSectionResizeMode(0, QtGui.QHeaderView.Stretch)
        self.tree.header().setSectionResizeMode(1, QtGui.QHeaderView.ResizeToContents)
        self.tree.currentItemChanged.connect(lambda *_: self._show_current())
        layout.addWidget(self.tree)
        # The full UGR table needs twelve columns: its own window, not the narrow panel;
        # the button sits under the list, where it is seen without scrolling.
        self.ugr_button = QtGui.QPushButton("UGR table...")
        self.ugr_button.setToolTip("The file's UGR table (CIE 190) as data sheets print it")
        self.ugr_button.clicked.connect(self.show_ugr_table)
        layout.addWidget(self.ugr_button)
        self.ugr_dialog: Optional[UgrTableDialog] = None

        folder_row = QtGui.QHBoxLayout()
        self.folder = QtGui.QLineEdit()
        self.folder.setReadOnly(True)
        self.folder.setPlaceholderText("no user folder")
        self.folder.setToolTip("Your own IES/LDT files (preference Mod/Lighting/LuminaireFolder)")
        self.folder_button = QtGui.QToolButton()
        self.folder_button.setText("Folder...")
        self.folder_button.setToolTip("Choose the folder of your own photometric files")
        self.folder_button.clicked.connect(self.choose_folder)
        folder_row.addWidget(QtGui.QLabel("User"))
        folder_row.addWidget(self.folder, 1)
        folder_row.addWidget(self.folder_button)
        layout.addLayout(folder_row)

        self.polar = PolarView()
        layout.addWidget(self.polar)
        self.caption = QtGui.QLabel()
        self.caption.setWordWrap(True)
        layout.addWidget(self.caption)
        self.summary = QtGui.QLabel()
        self.summary.setWordWrap(True)
        self.summary.setTextInteractionFlags(QtCore.Qt.TextSelectableByMouse)
        self.summary.setAlignment(QtCore.Qt.AlignTop | QtCore.Qt.AlignLeft)
        layout.addWidget(self.summary)

        layout.addStretch(1)

    # -- the library ----------------------------------------------------------------------
    def reload(self) -> None:
        """Read the library again (after the user folder changed)."""
        self.folder.setText(library.user_folder())
        self.entries = library.list_entries()
        self.tree.clear()
        groups = {}
        for entry in self.entries:
            if entry.source not in groups:
                group = QtGui.QTreeWidgetItem([GROUP_TITLES[entry.source], ""])
                group.setFlags(QtCore.Qt.ItemIsEnabled)
                font = group.font(0)
                font.setBold(True)
                group.setFont(0, font)
                self.tree.addTopLevelItem(group)
                group.setFirstColumnSpanned(True)
                groups[entry.source] = group
            lumens = entry.lamp_lumens_lm
            item = QtGui.QTreeWidgetItem([entry.name, "error" if not entry.ok else
                                          "abs." if lumens is None else f"{lumens:.0f} lm"])
            item.setData(0, QtCore.Qt.UserRole, self.entries.index(entry))
            item.setToolTip(0, entry.describe())
            if not entry.ok:
                for column in (0, 1):
                    item.setForeground(column, QtGui.QBrush(ERROR_COLOUR))
            self.tree.addTopLevelItem(item)
        if not self.entries:
            self.summary.setText("No photometric files found: the shipped folder is missing "
                                 "and no user folder is set.")
        self.tree.resizeColumnToContents(1)
        self._select_initial()
        self._update_targets()

    def _items(self) -> List[QtGui.QTreeWidgetItem]:
        items = [self.tree.topLevelItem(i) for i in range(self.tree.topLevelItemCount())]
        return [i for i in items if i.data(0, QtCore.Qt.UserRole) is not None]

    def _select_initial(self) -> None:
        """The selected luminaire's own file when the library has it, else the first file."""
        current = {os.path.realpath(str(o.PhotometricFile)) for o in selected_luminaires()
                   if str(o.PhotometricFile)}
        items = self._items()
        for item in items:
            if os.path.realpath(self.entry_of(item).path) in current:
                self.tree.setCurrentItem(item)
                return
        if items:
            self.tree.setCurrentItem(items[0])

    def entry_of(self, item: Optional[QtGui.QTreeWidgetItem]) -> Optional[library.LibraryEntry]:
        index = None if item is None else item.data(0, QtCore.Qt.UserRole)
        return None if index is None else self.entries[int(index)]

    def current_entry(self) -> Optional[library.LibraryEntry]:
        return self.entry_of(self.tree.currentItem())

    def select(self, name: str) -> library.LibraryEntry:
        """Make the file called ``name`` the current entry (scripts and tests)."""
        for item in self._items():
            if self.entry_of(item).name == name:
                self.tree.setCurrentItem(item)
                return self.entry_of(item)
        raise KeyError(f"no library entry {name!r}")

    def choose_folder(self) -> None:
        folder = QtGui.QFileDialog.getExistingDirectory(
            self.form, "Folder of your photometric files", library.user_folder() or
            os.path.expanduser("~"))
        if folder:
            self.set_folder(folder)

    def set_folder(self, folder: str) -> None:
        """Store the user folder (preference) and list its files."""
        library.set_user_folder(folder)
        self.reload()

    # -- showing an entry -----------------------------------------------------------------
    def _show_current(self) -> None:
        entry = self.current_entry()
        self._set_status("")
        if entry is None:
            self.summary.setText("")
            self.polar.show_png(None)
            self.caption.setText("")
        else:
            self.summary.setText(_summary_html(entry) + _ugr_html(entry))
            self._show_polar(entry)
        self.ugr_button.setEnabled(entry is not None and entry.ok
                                   and library.ugr_table(entry.path) is not None)
        self._update_buttons()

    def show_ugr_table(self) -> Optional[UgrTableDialog]:
        """Open the current file's UGR table in its own window (replacing one already open)."""
        entry = self.current_entry()
        table = library.ugr_table(entry.path) if entry is not None and entry.ok else None
        if table is None:
            return None
        if self.ugr_dialog is not None:
            self.ugr_dialog.close()
        self.ugr_dialog = UgrTableDialog(entry.name, table, self.form)
        self.ugr_dialog.show()
        return self.ugr_dialog

    def _show_polar(self, entry: library.LibraryEntry) -> None:
        if not entry.ok:
            self.polar.show_png(None, "no diagram: the file cannot be read")
            self.caption.setText("")
            return
        try:
            self.polar.show_png(library.polar_diagram_png(entry.path))
        except (ValueError, OSError) as exc:
            self.polar.show_png(None, str(exc))
        # The native diagram is scaled to its own maximum (printed in it, in cd; rings at
        # 25 % steps); the peak per 1000 lm is the figure to compare files by.
        per_klm = entry.peak_cd_per_klm
        scale = f"; peak {per_klm:.0f} cd/klm" if per_klm is not None else ""
        self.caption.setText("<span style='color:#c81e1e'>C0-C180</span>, "
                             f"<span style='color:#1e46c8'>C90-C270</span>{scale}; "
                             "rings: 25 % steps of the maximum")

    def _update_targets(self) -> None:
        lums = selected_luminaires()
        if lums:
            names = ", ".join(_target_text(o) for o in lums)
            self.targets.setText(f"Assign to: {names}")
        elif FreeCAD.ActiveDocument is None:
            self.targets.setText("Open a document to assign luminaire data.")
        else:
            where = "at the selected face" if _selected_face() else "at the default position"
            self.targets.setText(f"No luminaire selected: Assign creates a new one {where}.")
        self._update_buttons()

    def _update_buttons(self) -> None:
        if self.button_box is None:
            return
        entry = self.current_entry()
        ok = entry is not None and entry.ok and FreeCAD.ActiveDocument is not None
        self.button_box.button(QtGui.QDialogButtonBox.Apply).setEnabled(ok)

    # -- assigning ------------------------------------------------------------------------
    def assign(self) -> List[Any]:
        """Assign the current file to the selected luminaires (or create one): one undo
        step, echoed in the Python console. Returns the luminaires changed or made."""
        entry, doc = self.current_entry(), FreeCAD.ActiveDocument
        if entry is None or doc is None:
            return []
        if not entry.ok:
            self._set_status(f"Cannot assign: {entry.error}")
            return []
        lums = selected_luminaires()
        FreeCADGui.addModule("lighting")
        try:
            if lums:
                names = ", ".join(f"FreeCAD.ActiveDocument.getObject({o.Name!r})" for o in lums)
                FreeCADGui.doCommand(
                    f"lighting.assign_photometry(FreeCAD.ActiveDocument, [{names}], "
                    f"{entry.path!r}, keep_flux={self.keep_flux.isChecked()})")
                done = lums
            else:
                done = [self._create(doc, entry)]
        except Exception as exc:  # noqa: BLE001 - shown in the panel, nothing half-done
            self._set_status(f"Assign failed: {exc}")
            FreeCAD.Console.PrintError(f"Lighting: assigning {entry.name} failed: {exc}\n")
            return []
        self._set_status(f"Assigned {entry.name} to {', '.join(_target_text(o) for o in done)}.")
        return done

    def _set_status(self, text: str) -> None:
        self.status.setText(text)
        self.status.setVisible(bool(text))

    def _create(self, doc: Any, entry: library.LibraryEntry) -> Any:
        placed = _selected_face()
        where = "" if placed is None else f", position_m={placed[0]!r}, aim={placed[1]!r}"
        analysis = analysis_mod.find_analysis(doc)
        arg = "None" if analysis is None else f"FreeCAD.ActiveDocument.getObject({analysis.Name!r})"
        before = {o.Name for o in doc.Objects}
        FreeCADGui.addModule("lighting.luminaire_library")
        FreeCADGui.doCommand(
            f"lighting.luminaire_library.create(FreeCAD.ActiveDocument, {entry.path!r}"
            f"{where}, analysis={arg})")
        made = [o for o in doc.Objects
                if o.Name not in before and proxy_type(o) == LUMINAIRE_TYPE][0]
        # Selected, so the next Assign changes it instead of making another one.
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(made)
        return made

    # -- task dialog protocol -------------------------------------------------------------
    def getStandardButtons(self) -> int:  # noqa: N802 (FreeCAD API name)
        return int(QtGui.QDialogButtonBox.Apply | QtGui.QDialogButtonBox.Close)

    def modifyStandardButtons(self, box: QtGui.QDialogButtonBox) -> None:  # noqa: N802
        self.button_box = box
        apply = box.button(QtGui.QDialogButtonBox.Apply)
        apply.setText("Assign")
        apply.setToolTip("Give the selected luminaires this file (or create a luminaire)")
        self._update_buttons()

    def clicked(self, button: int) -> None:
        if button == int(QtGui.QDialogButtonBox.Apply):
            self.assign()

    def reject(self) -> bool:
        """Close (nothing to undo: every Assign was its own undo step)."""
        FreeCADGui.Selection.removeObserver(self.observer)
        if self.ugr_dialog is not None:
            self.ugr_dialog.close()
        self.close_dialog()
        return True

    def accept(self) -> bool:
        return self.reject()


def _ugr_html(entry: library.LibraryEntry) -> str:
    """The data-sheet UGR line (CIE 190 room 4H x 8H, 0.70/0.50/0.20), when it can be judged."""
    if not entry.ok:
        return ""
    ugr = library.headline_ugr(entry.path)
    if ugr is None:
        return ""
    return (f"<br>UGR (4H\u00d78H, 0.7/0.5/0.2, CIE 190): {ugr[0]:.1f} crosswise, "
            f"{ugr[1]:.1f} endwise")


def _summary_html(entry: library.LibraryEntry) -> str:
    """The entry's facts in a few wrapped lines (the panel is narrow): name and maker, lumens
    and format, peak, beam and field angles (C0-C180 / C90-C270), symmetry, warnings."""
    from html import escape

    where = GROUP_TITLES.get(entry.source, entry.source)
    head = f"<b>{escape(entry.name)}</b> <i>({escape(where.lower())})</i>"
    if not entry.ok:
        return f"{head}<br><span style='color:#be1e1e'>{escape(entry.error or '')}</span>"
    rows = dict(entry.facts())
    lines = [head, f"<b>{escape(rows['Luminaire'])}</b>"
             + (f" ({escape(entry.catalogue)})" if entry.catalogue and
                entry.catalogue not in rows["Luminaire"] else ""),
             f"Maker: {escape(rows['Maker'])}"]
    if entry.lamp:
        lines.append(f"Lamp: {escape(entry.lamp)}")
    lines += [f"Lamp lumens: <b>{escape(rows['Lamp lumens'])}</b>",
              f"Peak: {escape(rows['Peak'])}",
              f"Beam angle: {escape(rows['Beam angle'])}",
              f"Field angle: {escape(rows['Field angle'])}",
              f"Symmetry: {escape(rows['Symmetry'])}",
              f"Format: {escape(rows['Format'])}"]
    lines += [f"<span style='color:#be1e1e'>Warning: {escape(str(w))}</span>"
              for w in entry.fact("warnings") or []]
    return "<br>".join(lines)


def show(luminaire: Any = None) -> LuminaireChooserPanel:
    """Open the chooser in the task view (closing any other task dialog)."""
    from lighting.taskpanels import sync

    FreeCADGui.Control.closeDialog()
    return sync.show(LuminaireChooserPanel(luminaire))
