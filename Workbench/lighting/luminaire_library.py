# SPDX-License-Identifier: LGPL-2.1-or-later
"""The luminaire library: the photometric files shipped with the workbench
(``Resources/luminaires``) and the user's own folder (the preference
``BaseApp/Preferences/Mod/Lighting/LuminaireFolder``), each with the facts the solver's
parser reads from it (:func:`lighting.photometry.summary`), and the assignment of a file to
luminaires. App code: no GUI imports, usable in scripts::

    from lighting import luminaire_library as library
    for entry in library.list_entries():
        print(entry.name, entry.lamp_lumens_lm, entry.error)
    library.assign(doc, [doc.Luminaire], entry.path)
"""
from __future__ import annotations

import hashlib
import os
import subprocess
import tempfile
from dataclasses import dataclass, field
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple

from lighting import photometry

PARAM_GROUP = "User parameter:BaseApp/Preferences/Mod/Lighting"
FOLDER_PARAM = "LuminaireFolder"
#: Environment override of the shipped folder (tests, unusual installs).
ENV_SHIPPED = "LIGHTING_LUMINAIRES"
SHIPPED, USER = "shipped", "user"
#: Keywords of the native summary text that name the maker and the product (IES keywords;
#: the EULUMDAT reader reports its header fields under the same kind of names).
MAKER_KEYS = ("MANUFAC", "COMPANY")
NAME_KEYS = ("LUMINAIRE",)
CATALOGUE_KEYS = ("LUMCAT",)
LAMP_KEYS = ("LAMP",)


@dataclass
class LibraryEntry:
    """One photometric file: its facts from the native parser, or why it cannot be read."""

    path: str
    source: str  # SHIPPED or USER
    summary: Optional[Dict[str, Any]] = None
    error: Optional[str] = None
    keywords: Dict[str, str] = field(default_factory=dict)

    @property
    def name(self) -> str:
        return os.path.basename(self.path)

    @property
    def ok(self) -> bool:
        """True when the parser read the file (only then can it be assigned)."""
        return self.summary is not None and self.error is None

    def fact(self, key: str) -> Any:
        return None if self.summary is None else self.summary.get(key)

    @property
    def lamp_lumens_lm(self) -> Optional[float]:
        """Rated lamp lumens; None for absolute photometry or an unreadable file."""
        value = self.fact("lamp_lumens_lm")
        return None if value is None else float(value)

    @property
    def maker(self) -> str:
        return _first(self.keywords, MAKER_KEYS)

    @property
    def luminaire_name(self) -> str:
        return _first(self.keywords, NAME_KEYS)

    @property
    def catalogue(self) -> str:
        return _first(self.keywords, CATALOGUE_KEYS)

    @property
    def lamp(self) -> str:
        return _first(self.keywords, LAMP_KEYS)

    @property
    def format_name(self) -> str:
        """E.g. 'IES LM-63-2002' or 'EULUMDAT' (from the parser's format and version)."""
        kind, version = self.fact("format"), str(self.fact("format_version") or "")
        if kind == "ies":
            return f"IES {version}".strip()
        return version or "EULUMDAT"

    @property
    def peak_cd_per_klm(self) -> Optional[float]:
        """Peak intensity per 1000 lamp lumens (the unit of DIALux's polar diagrams)."""
        lumens, peak = self.lamp_lumens_lm, self.fact("peak_cd")
        if not lumens or peak is None:
            return None
        return float(peak) * 1000.0 / lumens

    def facts(self) -> List[Tuple[str, str]]:
        """(label, value) rows of the summary as a designer reads it; one row with the error
        for a file the parser rejects."""
        if not self.ok:
            return [("Error", self.error or "not read")]
        rows = [("Luminaire", self.luminaire_name or self.name), ("Maker", self.maker or "-")]
        if self.catalogue:
            rows.append(("Catalogue no.", self.catalogue))
        if self.lamp:
            rows.append(("Lamp", self.lamp))
        lumens = self.lamp_lumens_lm
        count = int(self.fact("lamp_count") or 1)
        rows.append(("Lamp lumens", "absolute photometry" if lumens is None
                     else f"{lumens:.0f} lm" + (f" ({count} lamps)" if count > 1 else "")))
        peak = f"{float(self.fact('peak_cd')):.0f} cd"
        if self.peak_cd_per_klm is not None:
            peak += f" ({self.peak_cd_per_klm:.0f} cd/klm)"
        rows.append(("Peak", peak))
        rows.append(("Beam angle", _angles(self.fact("beam_angle_deg"))))
        rows.append(("Field angle", _angles(self.fact("field_angle_deg"))))
        rows.append(("Symmetry", str(self.fact("symmetry") or "-")))
        rows.append(("Format", f"{self.format_name}, type {self.fact('type')}"))
        for warning in self.fact("warnings") or []:
            rows.append(("Warning", str(warning)))
        return rows

    def describe(self) -> str:
        """The summary as plain text lines ("label: value")."""
        return "\n".join(f"{label}: {value}" for label, value in self.facts())


def _first(keywords: Dict[str, str], keys: Sequence[str]) -> str:
    for key in keys:
        if keywords.get(key):
            return keywords[key]
    return ""


def _angles(pair: Any) -> str:
    """'C0-C180 54.0°, C90-C270 54.0°' from the parser's (C0, C90) tuple (None = undefined)."""
    if not pair:
        return "-"
    labels = ("C0-C180", "C90-C270")
    return ", ".join(f"{label} {'n/a' if value is None else f'{float(value):.1f}°'}"
                     for label, value in zip(labels, pair))


def keywords_of(text: str) -> Dict[str, str]:
    """``[KEY] value`` lines of the native summary text (first value of each key)."""
    found: Dict[str, str] = {}
    for line in text.splitlines():
        line = line.strip()
        if line.startswith("[") and "]" in line:
            key, value = line[1:].split("]", 1)
            found.setdefault(key.strip().upper(), value.strip())
    return found


# -- where the files are ---------------------------------------------------------------------
def _candidate_shipped_dirs() -> List[str]:
    """The workbench folder as FreeCAD sees it (``Mod/Lighting`` of a copied install) and the
    source tree it is a symlink of (``<repo>/Workbench``): the files live in
    ``<repo>/Resources/luminaires``, and scripts/install-workbench.sh --copy puts them into
    ``Mod/Lighting/Resources/luminaires``."""
    dirs = []
    env = os.environ.get(ENV_SHIPPED)
    if env:
        dirs.append(env)
    from lighting import resources

    dirs.extend(resources.candidates("luminaires"))
    return list(dict.fromkeys(dirs))


def shipped_folder() -> Optional[str]:
    """The folder of the shipped photometric files, or None when this install has none."""
    for folder in _candidate_shipped_dirs():
        if os.path.isdir(folder) and photometric_files(folder):
            return folder
    return None


def user_folder() -> str:
    """The user's luminaire folder (preference; '' when unset)."""
    try:
        import FreeCAD

        return FreeCAD.ParamGet(PARAM_GROUP).GetString(FOLDER_PARAM, "")
    except ImportError:  # plain Python without FreeCAD
        return ""


def set_user_folder(folder: str) -> None:
    """Store the user's luminaire folder in the preferences ('' clears it)."""
    import FreeCAD

    FreeCAD.ParamGet(PARAM_GROUP).SetString(FOLDER_PARAM, str(folder or ""))


def photometric_files(folder: str) -> List[str]:
    """The .ies and .ldt files of ``folder`` (any case), sorted by name."""
    try:
        names = sorted(os.listdir(folder), key=str.lower)
    except OSError:
        return []
    return [os.path.join(folder, n) for n in names
            if n.lower().endswith(photometry.EXTENSIONS)
            and os.path.isfile(os.path.join(folder, n))]


# -- reading ---------------------------------------------------------------------------------
def read_entry(path: str, source: str = USER) -> LibraryEntry:
    """The entry of one file; a file the parser rejects gets its message (file and line)."""
    entry = LibraryEntry(os.path.abspath(path), source)
    try:
        entry.summary = photometry.summary(entry.path)
    except (ValueError, OSError) as exc:
        entry.error = str(exc) or f"{entry.path}: cannot be read"
        return entry
    entry.keywords = keywords_of(str(entry.summary.get("text", "")))
    return entry


def list_entries(folder: Optional[str] = None, shipped: bool = True) -> List[LibraryEntry]:
    """The shipped files (when ``shipped``) then the user folder's (``folder``; default: the
    preference), sorted by name within each; unreadable files are listed with their error."""
    entries: List[LibraryEntry] = []
    base = shipped_folder() if shipped else None
    if base:
        entries.extend(read_entry(p, SHIPPED) for p in photometric_files(base))
    user = user_folder() if folder is None else folder
    if user and os.path.isdir(user):
        seen = {os.path.realpath(e.path) for e in entries}
        entries.extend(read_entry(p, USER) for p in photometric_files(user)
                       if os.path.realpath(p) not in seen)
    return entries


# -- polar diagram -----------------------------------------------------------------------------
def polar_diagram_png(path: str, out_dir: Optional[str] = None) -> str:
    """A PNG of the file's polar diagram (C0-C180 red, C90-C270 blue), drawn by the native
    solver's own plotter: the module's ``write_polar_plot``, or where only the program is
    found, ``lightsolver photometry FILE --plot PNG``. Cached by path and modification time.
    Raises ValueError when neither is found or the file is rejected."""
    from lighting.solver import run

    stat = os.stat(path)
    key = hashlib.sha1(f"{os.path.abspath(path)}|{stat.st_mtime_ns}|{stat.st_size}"
                       .encode()).hexdigest()[:16]
    folder = out_dir or os.path.join(tempfile.gettempdir(), "lighting-polar")
    os.makedirs(folder, exist_ok=True)
    png = os.path.join(folder, f"{key}.png")
    if os.path.isfile(png):
        return png
    module = run.load_module() if run.solver_available()[0] else None
    if module is not None and hasattr(module, "write_polar_plot"):
        try:
            module.write_polar_plot(os.path.abspath(path), png)
        except ValueError as error:  # lightsolver.InputError names the file and line
            raise ValueError(str(error)) from error
        return png
    cli = run.cli_executable()
    if cli is None:
        raise ValueError(f"{path}: no polar diagram - neither the lightsolver module nor the "
                         f"program was found (build it, or set {run.ENV_CLI})")
    proc = subprocess.run([cli, "photometry", os.path.abspath(path), "--plot", png],
                          capture_output=True, text=True, timeout=60, check=False)
    if proc.returncode != 0 or not os.path.isfile(png):
        message = (proc.stderr or proc.stdout).strip().splitlines()
        raise ValueError(message[-1] if message else f"{path}: the polar diagram failed")
    return png


_ugr_cache: Dict[Tuple[str, int, int], Optional[Any]] = {}


def ugr_table(path: str) -> Optional[Any]:
    """The file's full UGR table (CIE 190 tabular method, as data sheets print it): the
    report's ``lightsolver_report.schedule.UgrTableView``, None when the solver is missing or
    cannot judge the file. Cached by path and modification time (a table takes ~1 s)."""
    import importlib

    from lighting.solver import run

    stat = os.stat(path)
    key = (os.path.abspath(path), stat.st_mtime_ns, stat.st_size)
    if key not in _ugr_cache:
        found = None
        if run.solver_available()[0]:
            from lighting.messages import LightingError
            from lighting.reporting import report_module

            try:
                report_module()
                schedule = importlib.import_module("lightsolver_report.schedule")
                found = schedule.ugr_table_view(os.path.abspath(path))
            except (LightingError, ImportError):
                found = None  # no report package beside the module: no table
        _ugr_cache[key] = found
    return _ugr_cache[key]


def headline_ugr(path: str) -> Optional[Tuple[float, float]]:
    """(crosswise, endwise) data-sheet UGR of the file (CIE 190 room 4H x 8H, reflectances
    0.7/0.5/0.2): the report's figure, from the same table as ``ugr_table``."""
    table = ugr_table(path)
    return table.headline() if table is not None else None


def ugr_table_note(table: Any) -> str:
    """What a UGR table (``ugr_table``) is and is not, as the report says it."""
    note = (f"CIE 190 tabular method for the file's own flux, {table.luminaire_flux_lm:.0f} lm "
            "(corrected values). Room X across and Y along the line of sight, in multiples of "
            "H, the luminaires' height above the eye; observer at the middle of the wall; "
            f"luminaire spacing S = {table.spacing_to_height:g} H. Corrections for other "
            "spacings are not given. Crosswise: line of sight in the file's C0-C180 plane. "
            "\u2013: no luminaire counts.")
    return " ".join([note] + [f"Warning: {w}." for w in table.warnings])


def ugr_table_texts(table: Any) -> List[List[str]]:
    """A UGR table's printed rows: X (on the first row of its group only), Y, then the ten
    UGR values to one decimal (crosswise, endwise; \u2013 where no luminaire counts)."""
    rows: List[List[str]] = []
    for group in table.groups():
        for i, row in enumerate(group):
            values = [("\u2013" if v is None else f"{v:.1f}") for v in row.crosswise + row.endwise]
            rows.append([f"{row.x_h:g}H" if i == 0 else "", f"{row.y_h:g}H"] + values)
    return rows


# -- assignment ------------------------------------------------------------------------------
def _readable(path: str) -> LibraryEntry:
    entry = read_entry(path)
    if not entry.ok:
        raise ValueError(f"Cannot assign '{os.path.basename(path)}': {entry.error}")
    return entry


def _apply(obj: Any, entry: LibraryEntry, keep_flux: bool) -> None:
    obj.LuminaireType = "Photometric"
    obj.PhotometricFile = entry.path
    if not keep_flux:
        # 0 lm means "the file's own flux" (absolute photometry has no lamp lumens).
        obj.FluxLumen = entry.lamp_lumens_lm or 0.0


def _in_transaction(doc: Any, title: str, work: Any) -> Any:
    """``work()`` inside one undo step (or inside the caller's, when one is open)."""
    import FreeCAD

    own = FreeCAD.getActiveTransaction() is None
    if own:
        doc.openTransaction(title)
    try:
        result = work()
        doc.recompute()
    except Exception:
        if own:
            doc.abortTransaction()
        raise
    if own:
        doc.commitTransaction()
    return result


def layout_templates(objects: Iterable[Any]) -> List[Any]:
    """``objects`` with each luminaire layout replaced by its template luminaire (the type
    every member shares), without duplicates, in order."""
    from lighting.objects.base import proxy_type
    from lighting.objects.luminaire_layout import TYPE as LAYOUT

    out: List[Any] = []
    for obj in objects:
        if proxy_type(obj) == LAYOUT:
            if obj.Template is None:
                raise ValueError(f"Luminaire layout '{obj.Label}' has no template luminaire")
            obj = obj.Template
        if all(obj is not o for o in out):
            out.append(obj)
    return out


def assign(doc: Any, luminaires: Iterable[Any], path: str, keep_flux: bool = False) -> List[Any]:
    """Make ``luminaires`` photometric with ``path`` in one undo step (a luminaire layout
    stands for its template: all its members change). Their FluxLumen becomes
    the file's lamp lumens (0 = the file's own flux for absolute photometry) unless
    ``keep_flux``. A file the parser rejects raises ValueError (file and line) and changes
    nothing."""
    from lighting.objects.base import proxy_type
    from lighting.objects.luminaire import TYPE

    targets = layout_templates(luminaires)
    for obj in targets:
        if proxy_type(obj) != TYPE:
            raise ValueError(f"'{obj.Label}' is not a Lighting luminaire")
    if not targets:
        raise ValueError("no luminaire to assign the file to")
    entry = _readable(path)

    def work() -> List[Any]:
        for obj in targets:
            _apply(obj, entry, keep_flux)
        return targets

    return _in_transaction(doc, "Assign luminaire data", work)


def create(doc: Any, path: str, position_m: Tuple[float, float, float] = (0.0, 0.0, 2.5),
           aim: Tuple[float, float, float] = (0.0, 0.0, -1.0),
           analysis: Optional[Any] = None) -> Any:
    """A new photometric luminaire with ``path`` (flux: the file's lamp lumens), one undo
    step; raises ValueError for a file the parser rejects."""
    from lighting.objects.factory import make_luminaire

    entry = _readable(path)
    name = os.path.splitext(entry.name)[0]

    def work() -> Any:
        obj = make_luminaire(doc, position_m=position_m, kind="Photometric", aim=aim,
                             name="Luminaire", analysis=analysis)
        obj.Label = f"Luminaire {name}"
        _apply(obj, entry, keep_flux=False)
        return obj

    return _in_transaction(doc, "Create luminaire", work)
