# SPDX-License-Identifier: LGPL-2.1-or-later
"""The luminaire schedule of the report, from the scene, what the photometric files say of
themselves (``lightsolver.photometry_summary``) and the flux each luminaire emitted as the
solver traced it (the results' ``luminaires``, read by ``lightsolver_results``). Power is the
scene's ``power_w``, else the photometric file's input watts (said so on the page). The
materials table moved to ``surfaces.py`` (listed by surface)."""
from __future__ import annotations

import hashlib
import os
import re
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

from lightsolver_report.fmt import finite
from lightsolver_results import LuminaireFlux

#: IES keywords / EULUMDAT fields that name the maker, in order of preference.
MAKER_KEYS = ("MANUFAC", "COMPANY")

PhotometryFn = Callable[[str], Dict[str, Any]]


@dataclass
class LuminaireRow:
    """One line of the luminaire schedule: luminaires alike in type, file, flux and power."""

    kind: str
    file: Optional[str] = None
    file_format: Optional[str] = None
    maker: Optional[str] = None
    catalogue: Optional[str] = None
    product: Optional[str] = None
    lamp: Optional[str] = None
    file_lamp_lm: Optional[float] = None
    file_watts: Optional[float] = None
    names: List[str] = field(default_factory=list)
    files: List[str] = field(default_factory=list)  # identical files (copies) of the row
    #: The data-sheet UGR of the file (CIE 190 room 4H x 8H, reflectances 0.7/0.5/0.2):
    #: (crosswise, endwise), when the solver's tabular method can judge it.
    ugr_4h8h: Optional[Tuple[float, float]] = None
    #: The file's full UGR table (CIE 190), as data sheets print it; None where not judged.
    ugr_table: Optional["UgrTableView"] = None
    #: Emitted in the calculation, as traced (after TILT and a rescale's dimming; maintained,
    #: when a factor applied).
    flux_lm: float = 0.0
    #: Its flux before TILT and dimming (the scene's flux_lm, a file's own flux).
    rated_flux_lm: float = 0.0
    tilt_factor: float = 1.0  # a photometric TILT table's factor at the luminaire's tilt
    dimming: float = 1.0  # its group's factor in rescaled results
    maintenance_factor: Optional[float] = None
    power_w: Optional[float] = None
    #: The power is the photometric file's input watts (the scene gives no ``power_w``).
    power_from_file: bool = False
    #: The factor the file's input watts were scaled by: the luminaire's initial flux over the
    #: file's (another lumen package or a dimmed setting of the same luminaire; 1: as stated).
    power_scale: float = 1.0

    @property
    def title(self) -> str:
        """What the client reads as the luminaire: the file's product name, else its kind."""
        return self.product or self.kind

    @property
    def initial_flux_lm(self) -> Optional[float]:
        """The flux before the maintenance factor (the rated flux / MF)."""
        return self.rated_flux_lm / self.maintenance_factor if self.maintenance_factor else None

    @property
    def count(self) -> int:
        return len(self.names)

    @property
    def total_flux_lm(self) -> float:
        return self.flux_lm * self.count

    @property
    def total_power_w(self) -> Optional[float]:
        return None if self.power_w is None else self.power_w * self.count

    @property
    def efficacy_lm_w(self) -> Optional[float]:
        """Luminaire efficacy at full output: the initial flux (before maintenance, TILT and
        dimming) per watt."""
        flux = self.initial_flux_lm or self.rated_flux_lm
        return flux / self.power_w if self.power_w else None


def _keywords(summary: Dict[str, Any]) -> Dict[str, str]:
    """The file's own keywords: the summary's ``keywords`` pairs, else its text's ``[KEY]`` lines
    (modules built before ``keywords`` was added)."""
    pairs = summary.get("keywords")
    if pairs is None:
        pairs = re.findall(r"^\[(\w+)\] (.*)$", str(summary.get("text", "")), re.MULTILINE)
    found: Dict[str, str] = {}
    for key, value in pairs:
        key = str(key).upper()
        if key not in found and str(value).strip():
            found[key] = str(value).strip()
    return found


def _describe(lum: Dict[str, Any]) -> str:
    kind = lum.get("type", "")
    if kind == "point":
        return "Point source, isotropic"
    if kind == "spot":
        return (f"Spot, beam {lum.get('beam_angle_deg', 0):g}°, "
                f"field {lum.get('field_angle_deg', 0):g}°")
    if kind == "area":
        a = float(np.linalg.norm(lum.get("edge1", (0, 0, 0))))
        b = float(np.linalg.norm(lum.get("edge2", (0, 0, 0))))
        return f"Area source, Lambertian, {a:.2f} × {b:.2f} m"
    if kind == "directional":
        return f"Directional beam, {lum.get('illuminance_lx', 0):g} lx"
    if kind == "photometric":
        return "Photometric luminaire"
    return str(kind)


def scene_flux(lum: Dict[str, Any], summary: Optional[Dict[str, Any]]) -> float:
    """The luminaire's flux derived from its scene entry (docs/scene-format.md, Ranges), TILT
    not applied: only for results that do not record the traced flux (lightsolver_results'
    migration step calls it through :meth:`PhotometricFiles.scene_flux`)."""
    kind = lum.get("type")
    if kind == "directional":
        e1 = np.asarray(lum.get("edge1", (0, 0, 0)), dtype=float)
        e2 = np.asarray(lum.get("edge2", (0, 0, 0)), dtype=float)
        d = np.asarray(lum.get("direction", (0, 0, -1)), dtype=float)
        normal = np.cross(e1, e2)
        norm_d = float(np.linalg.norm(d))
        return float(lum.get("illuminance_lx", 0.0)) * (
            abs(float(normal @ d)) / norm_d if norm_d else 0.0)
    flux = finite(lum.get("flux_lm"))
    if kind == "photometric" and summary is not None:
        integrated = finite(summary.get("integrated_lumens_lm")) or 0.0
        lamp = finite(summary.get("lamp_lumens_lm"))
        if flux is None:
            return integrated
        if lamp and not summary.get("absolute_photometry"):
            return integrated * flux / lamp
    return flux or 0.0


def flux_ratio(lum: Dict[str, Any], summary: Dict[str, Any], mf: Optional[float]) -> float:
    """The luminaire's initial flux (the scene's ``flux_lm`` ÷ MF) over the flux its
    photometric file states (the lamp lumens the solver scales by; an absolute file's own
    flux): the factor by which its input watts are scaled when the scene asks for another
    flux. 1 where the scene keeps the file's flux or either flux is unknown."""
    flux = finite(lum.get("flux_lm"))
    if flux is None:
        return 1.0
    if summary.get("absolute_photometry"):
        stated = finite(summary.get("integrated_lumens_lm"))
    else:
        stated = finite(summary.get("lamp_lumens_lm"))
    if not stated or stated <= 0:
        return 1.0
    ratio = flux / (mf or 1.0) / stated
    return 1.0 if abs(ratio - 1.0) <= 1e-9 else ratio


def maintenance_factor(lum: Dict[str, Any], extra: Any) -> Optional[float]:
    """The luminaire's maintenance factor (its own key, else ``metadata.luminaires``'), None
    where none is given or it does not apply (a photometric file at its own absolute flux)."""
    extra = extra if isinstance(extra, dict) else {}
    mf = finite(lum.get("maintenance_factor", extra.get("maintenance_factor")))
    if lum.get("type") == "photometric" and lum.get("flux_lm") is None:
        return None  # the file's own absolute flux: no maintenance factor was applied
    return mf if mf else None


class PhotometricFiles:
    """The scene's photometric files: each summary read once, with the parser's warnings."""

    def __init__(self, base_dir: str, photometry: Optional[PhotometryFn]) -> None:
        self.base_dir, self.photometry = base_dir, photometry
        self.summaries: Dict[str, Optional[Dict[str, Any]]] = {}
        self.warnings: List[str] = []

    def summary(self, file: str) -> Optional[Dict[str, Any]]:
        if file not in self.summaries:
            self.summaries[file] = _summary(file, self.base_dir, self.photometry, self.warnings)
        return self.summaries[file]

    def scene_flux(self, lum: Dict[str, Any]) -> float:
        """The luminaire's flux from the scene (results without ``luminaires``)."""
        file = lum.get("file") if lum.get("type") == "photometric" else None
        return scene_flux(lum, self.summary(str(file)) if file is not None else None)


def build_luminaires(scene: Dict[str, Any], files: PhotometricFiles,
                     traced: Sequence[LuminaireFlux]) -> List[LuminaireRow]:
    """The schedule of electric light (alike luminaires on one row, in scene order; skies and
    suns are daylight, reported apart), each luminaire at the flux
    ``traced`` gives it (the results' ``luminaires``, migrated: derived from the scene for
    older results); 0 lm for a luminaire the results do not list."""
    meta = scene.get("metadata") if isinstance(scene.get("metadata"), dict) else {}
    labels = meta.get("labels") if isinstance(meta.get("labels"), dict) else {}
    per_lum = meta.get("luminaires") if isinstance(meta.get("luminaires"), dict) else {}
    by_name = {lum.name: lum for lum in traced}
    rows: Dict[Tuple[Any, ...], LuminaireRow] = {}
    # The UGR table of each file content, computed once (the workbench copies one file per
    # luminaire; the table takes seconds).
    tables: Dict[Optional[str], Optional[UgrTableView]] = {}
    for lum in scene.get("luminaires", []):
        if lum.get("type") in ("sky", "sun"):
            continue  # daylight: its own schedule (daylight.py), no lumens, watts or MF
        name = str(lum.get("name", ""))
        extra = per_lum.get(name) if isinstance(per_lum.get(name), dict) else {}
        file = lum.get("file") if lum.get("type") == "photometric" else None
        summary = files.summary(file) if file is not None else None
        mf = maintenance_factor(lum, extra)
        flux = by_name.get(name)
        row = LuminaireRow(kind=_describe(lum), file=file,
                           flux_lm=flux.emitted_flux_lm if flux else 0.0,
                           rated_flux_lm=flux.flux_lm if flux else 0.0,
                           tilt_factor=flux.tilt_factor if flux else 1.0,
                           dimming=flux.dimming if flux else 1.0,
                           maintenance_factor=mf if mf else None,
                           power_w=finite(lum.get("power_w")))
        if summary is not None:
            keys = _keywords(summary)
            row.maker = next((keys[k] for k in MAKER_KEYS if k in keys), None)
            row.catalogue, row.product = keys.get("LUMCAT"), keys.get("LUMINAIRE")
            row.lamp = keys.get("LAMP")
            row.file_format = f"{str(summary.get('format', '')).upper()} " \
                              f"{summary.get('format_version', '')}".strip()
            row.file_lamp_lm = finite(summary.get("rated_lumens_lm"))
            row.file_watts = finite(summary.get("input_watts")) or None
            if row.power_w is None and row.file_watts:
                row.power_scale = flux_ratio(lum, summary, mf)
                row.power_w, row.power_from_file = row.file_watts * row.power_scale, True
        same_file = _content_key(file, files.base_dir)
        if summary is not None:
            if same_file not in tables:
                tables[same_file] = ugr_table_view(file if os.path.isabs(file) else
                                                   os.path.join(files.base_dir, file))
            row.ugr_table = tables[same_file]
            row.ugr_4h8h = row.ugr_table.headline() if row.ugr_table else None
        key = (row.kind, same_file, row.flux_lm, row.rated_flux_lm, row.tilt_factor,
               row.dimming, row.maintenance_factor, row.power_w, row.power_from_file,
               row.power_scale)
        entry = rows.setdefault(key, row)
        entry.names.append(str(labels.get(name, name)))
        if file is not None and file not in entry.files:
            entry.files.append(file)
    return list(rows.values())


@dataclass
class UgrTableRowView:
    """One room of a UGR table: X (across the line of sight) and Y (along it) in multiples of
    H, and one UGR per reflectance combination, crosswise and endwise (None: no luminaire
    counts)."""

    x_h: float
    y_h: float
    crosswise: List[Optional[float]]
    endwise: List[Optional[float]]


@dataclass
class UgrTableView:
    """A photometric file's UGR table by CIE 190's tabular method (``lightsolver.ugr_table``,
    docs/glare.md), laid out as data sheets print it: 19 rooms from 2H x 2H to 12H x 8H, five
    (ceiling, walls, floor) reflectance combinations, crosswise and endwise."""

    spacing_to_height: float
    luminaire_flux_lm: float
    reflectances: List[Tuple[float, float, float]]
    rows: List[UgrTableRowView]
    warnings: List[str] = field(default_factory=list)

    def headline(self) -> Optional[Tuple[float, float]]:
        """(crosswise, endwise) in room 4H x 8H at 0.7/0.5/0.2, the figure data sheets quote."""
        try:
            column = [tuple(round(r, 2) for r in refl)
                      for refl in self.reflectances].index((0.7, 0.5, 0.2))
            row = next(r for r in self.rows if (r.x_h, r.y_h) == (4.0, 8.0))
        except (ValueError, StopIteration):
            return None
        cross, end = row.crosswise[column], row.endwise[column]
        return None if cross is None or end is None else (cross, end)

    def groups(self) -> List[List[UgrTableRowView]]:
        """The rooms grouped by X, as data sheets separate them."""
        out: List[List[UgrTableRowView]] = []
        for row in self.rows:
            if not out or out[-1][0].x_h != row.x_h:
                out.append([])
            out[-1].append(row)
        return out


def ugr_table_view(path: str) -> Optional[UgrTableView]:
    """The file's UGR table from ``lightsolver.ugr_table`` at the data-sheet spacing
    S = 0.25 H; None where it cannot be judged (no module, a point opening, a bad file)."""
    try:
        import lightsolver

        table = lightsolver.ugr_table(path)
        rows = [UgrTableRowView(float(r["x_h"]), float(r["y_h"]),
                                [finite(v) for v in r["crosswise"]],
                                [finite(v) for v in r["endwise"]]) for r in table["rows"]]
        return UgrTableView(spacing_to_height=float(table["spacing_to_height"]),
                            luminaire_flux_lm=float(table["luminaire_flux_lm"]),
                            reflectances=[tuple(float(x) for x in refl)
                                          for refl in table["reflectances"]],
                            rows=rows, warnings=[str(w) for w in table.get("warnings", [])])
    except Exception:  # noqa: BLE001 - no table is printed rather than a wrong one
        return None


def headline_ugr(path: str) -> Optional[Tuple[float, float]]:
    """(crosswise, endwise) UGR of the file in CIE 190's room 4H x 8H with reflectances
    0.7/0.5/0.2 (the figure data sheets quote), from ``lightsolver.ugr_table``
    (docs/glare.md); None where it cannot judge (no module, a point opening). The
    workbench's luminaire chooser shows the same figure through this function."""
    view = ugr_table_view(path)
    return view.headline() if view else None


def _content_key(file: Optional[str], base_dir: str) -> Optional[str]:
    """Identical photometric files are one type, whatever they are called (the workbench
    copies each luminaire's file next to the scene under the luminaire's name)."""
    if file is None:
        return None
    try:
        with open(file if os.path.isabs(file) else os.path.join(base_dir, file), "rb") as f:
            return hashlib.sha256(f.read()).hexdigest()
    except OSError:
        return file


def _summary(file: str, base_dir: str, photometry: Optional[PhotometryFn],
             warnings: List[str]) -> Optional[Dict[str, Any]]:
    if photometry is None:
        warnings.append(f"{file}: not read (the lightsolver module is not available)")
        return None
    path = file if os.path.isabs(file) else os.path.join(base_dir, file)
    try:
        summary = photometry(path)
    except Exception as exc:  # noqa: BLE001 - the parser's message, shown in the report
        warnings.append(str(exc).replace(path, file))
        return None
    warnings.extend(f"{file}: {str(w).replace(path, file)}" for w in summary.get("warnings", []))
    return summary
