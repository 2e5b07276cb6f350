# SPDX-License-Identifier: LGPL-2.1-or-later
"""What the report shows, gathered from the solver boundary only: the scene (docs/scene-format.md)
and the results (docs/schemas/results.schema.json, with the requirements, verdicts and
provenance when the solver wrote them). Plain data, no HTML: the templates lay it out.

The parts live in their own modules: calculation areas (``areas.py``), the luminaire schedule
(``schedule.py``), surfaces and materials (``surfaces.py``), power and LENI (``energy.py``),
light scenes (``scenes.py``), provenance and sign-off (``signoff.py``) and the client's wording
of the solver's remarks (``wording.py``)."""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

import lightsolver_results
from lightsolver_report import daylight, energy, scenes
from lightsolver_report.initial import InitialValues, initial_values
from lightsolver_report.areas import (QUANTITIES, Area, GridData, Requirement,  # noqa: F401
                                      Verdict, build_area)
from lightsolver_report.fmt import finite
from lightsolver_report.schedule import (LuminaireRow, PhotometricFiles, PhotometryFn,
                                         build_luminaires)
from lightsolver_report.signoff import Provenance, build_provenance, signoff_fields
from lightsolver_report.surfaces import MaterialRow, SurfaceRow, build_surfaces, unused
from lightsolver_report.wording import Namer, Note, client_notes

__all__ = ["Report", "Area", "GridData", "Verdict", "Requirement", "build_report", "QUANTITIES"]


@dataclass
class Report:
    """Everything the report prints. ``signoff`` and ``partial`` are set by the caller after
    :func:`build_report` (render's ``signoff`` and ``allow_partial``); ``plans`` and other
    pictures may be added as attributes."""

    title: str
    subtitle: str
    date: str
    solver_version: str
    scene_file: str
    document_file: str
    generator: str
    run: Dict[str, Any]
    verdict: Optional[str]
    luminaires: List[LuminaireRow]
    materials: List[MaterialRow]
    areas: List[Area]
    warnings: List[str]
    solver_total_flux_lm: Optional[float]
    #: The schedule's flux is the solver's record of what it traced (False: derived from the
    #: scene, for results written before the solver recorded it).
    traced_flux: bool = True
    surfaces: List[SurfaceRow] = field(default_factory=list)
    #: The run's remarks for the technical appendix, worded for a client.
    notes: List[Note] = field(default_factory=list)
    light_scenes: List[scenes.LightScene] = field(default_factory=list)
    #: What rescaled results show ("light scene Evening (...)"); None: as traced.
    shown_scene: Optional[str] = None
    leni: Optional[energy.Leni] = None
    #: Why there is no LENI although hours were given ("" otherwise).
    leni_missing: str = ""
    provenance: Optional[Provenance] = None
    metadata: Dict[str, Any] = field(default_factory=dict)
    #: Sign-off fields given by the caller ({project, author, checked_by}); None: the scene's
    #: ``metadata.report`` ones, else blank lines to sign on.
    signoff: Optional[Dict[str, Any]] = None
    #: Partial (cancelled) results let through on request: marked on every page.
    partial: bool = False
    #: The energy inputs (``metadata.report.energy``), None when not given.
    energy_inputs: Optional[energy.EnergyInputs] = None
    #: Initial (new-installation) values per area, or why there are none (initial.py).
    initial: InitialValues = field(default_factory=InitialValues)
    #: Daylight: the skies and suns (not luminaires), sunlight exposure (daylight.py).
    skies: List[daylight.SkyRow] = field(default_factory=list)
    suns: List[daylight.SunRow] = field(default_factory=list)
    sunlight: Optional[daylight.SunlightExposure] = None

    # --- what the page asks -------------------------------------------------------------

    @property
    def marked_partial(self) -> bool:
        """Every page carries the partial mark: the caller let partial results through, or
        the results say the run was cancelled."""
        return bool(self.partial or self.run.get("partial"))

    @property
    def signoff_rows(self) -> List[Tuple[str, str]]:
        return signoff_fields(self.signoff, self.metadata, self.title)

    @property
    def illuminance_areas(self) -> List[Area]:
        """Areas reported by their illuminance (daylight-factor grids have their own pages)."""
        return [a for a in self.areas if not a.is_glare and a.daylight is None]

    @property
    def daylight_areas(self) -> List[Area]:
        """Daylight-factor grids with the solver's daylight factor."""
        return [a for a in self.areas if a.daylight is not None]

    @property
    def has_daylight(self) -> bool:
        return bool(self.skies or self.suns or self.daylight_areas or self.sunlight)

    @property
    def glare_areas(self) -> List[Area]:
        return [a for a in self.areas if a.is_glare]

    @property
    def unused_materials(self) -> List[MaterialRow]:
        return unused(self.materials)

    @property
    def ugr_tables(self) -> List[LuminaireRow]:
        """The schedule's rows whose file has a UGR table, one per file (rows of the same file
        at other fluxes share the table: it is the file's, for the file's own flux)."""
        seen, out = set(), []
        for row in self.luminaires:
            key = tuple(sorted(row.files))
            if row.ugr_table is not None and key not in seen:
                seen.add(key)
                out.append(row)
        return out

    @property
    def total_count(self) -> int:
        return sum(r.count for r in self.luminaires)

    @property
    def total_flux_lm(self) -> float:
        return sum(r.total_flux_lm for r in self.luminaires)

    @property
    def installed_flux_lm(self) -> float:
        """The installation's flux at full output (TILT applied, no light scene's dimming):
        what the cover states whatever the results show."""
        return sum(r.rated_flux_lm * r.tilt_factor * r.count for r in self.luminaires)

    @property
    def tilted(self) -> bool:
        """Some luminaire's flux has a TILT table's factor other than 1 in it."""
        return any(r.tilt_factor != 1.0 for r in self.luminaires)

    @property
    def dimmed(self) -> bool:
        """Some luminaire is dimmed (rescaled results)."""
        return any(r.dimming != 1.0 for r in self.luminaires)

    @property
    def total_power_w(self) -> Optional[float]:
        """Installed power, only when every luminaire's power is known."""
        if not self.luminaires or any(r.power_w is None for r in self.luminaires):
            return None
        return sum(r.total_power_w for r in self.luminaires)

    @property
    def power_from_file(self) -> bool:
        """Some luminaire's power is its photometric file's input watts."""
        return any(r.power_from_file for r in self.luminaires)

    @property
    def common_mf(self) -> Optional[float]:
        """The maintenance factor of every luminaire that emits light, when they share one:
        then initial values are the maintained ones / MF (illuminance is linear in flux)."""
        return self.initial.common_mf

    @property
    def areas_with_requirements(self) -> List[Area]:
        return [a for a in self.areas if a.requirements or a.verdicts]

    @property
    def verdict_counts(self) -> Dict[str, int]:
        counts = {"pass": 0, "fail": 0, "undecided": 0}
        for area in self.areas:
            for v in area.verdicts:
                counts[v.verdict] = counts.get(v.verdict, 0) + 1
        return counts

    @property
    def energy_asked(self) -> bool:
        return bool(self.leni or self.leni_missing)


def _run_facts(scene: Dict[str, Any], results: Dict[str, Any]) -> Dict[str, Any]:
    settings = scene.get("settings") if isinstance(scene.get("settings"), dict) else {}
    keys = ("photons", "photons_requested", "seed", "confidence", "backend", "seconds",
            "stop_reason", "partial", "ray_segments", "decide", "target_accuracy",
            "accuracy_met", "max_seconds", "capped_paths", "cut_paths")
    run = {k: results.get(k) for k in keys}
    run["max_bounces"] = settings.get("max_bounces", 1000)
    return run


def _areas(read: lightsolver_results.Results, scene: Dict[str, Any],
           labels: Dict[str, str]) -> List[Area]:
    scene_targets = {str(t.get("name")): t for t in scene.get("targets", [])
                     if isinstance(t, dict)}
    return [build_area(t, scene_targets.get(t.name, {}), labels) for t in read.targets]


def _loads(report: Report, traced: Optional[Dict[str, Any]], scene: Dict[str, Any]) -> None:
    """W/m² for every upward-facing grid; W/m² per 100 lx from its Ēm with every group at
    100 % (the installation as installed: not a light scene's dimmed Ēm)."""
    power = report.total_power_w
    if power is None:
        return
    full: Dict[str, Optional[float]] = {}
    if traced is not None:
        for t in lightsolver_results.read(traced, scene, strict=False, check_schema=False).targets:
            full[t.name] = t.em.value
    for area in report.areas:
        if area.horizontal and area.area_m2 and area.daylight is None:
            area.power_density_w_m2, area.power_density_w_m2_100lx = energy.power_density(
                power, area.area_m2, full.get(area.name))


def _energy(report: Report, inputs: Optional[energy.EnergyInputs],
            floor_m2: Optional[float] = None) -> None:
    report.energy_inputs = inputs
    if inputs is None:
        return
    power = report.total_power_w
    grids = [(a.label, a.area_m2) for a in report.areas if a.horizontal and a.area_m2]
    where = energy.leni_area(inputs, grids, floor_m2)
    if power is None:
        report.leni_missing = "the power of every luminaire is needed"
    elif where is None:
        report.leni_missing = "the floor area is needed"
    else:
        report.leni = energy.leni(inputs, power, where[0], where[1])


def use_floor_area(report: Report, floor_m2: Optional[float]) -> None:
    """LENI again with the floor area the model's plan encloses (pictures.attach measures it
    after the plans are drawn); only where the designer stated none."""
    if report.energy_inputs is not None and report.energy_inputs.area_m2 is None:
        report.leni, report.leni_missing = None, ""
        _energy(report, report.energy_inputs, floor_m2)


def _light_scenes(report: Report, doc: Dict[str, Any], scene: Dict[str, Any],
                  given: Any, labels: Dict[str, str]) -> Optional[Dict[str, Any]]:
    """Each light scene's areas; returns the results with every group at 100 %."""
    rescale = scenes.solver_rescale()
    report.light_scenes = scenes.read_light_scenes(given, report.metadata, labels)
    scenes.fill(report.light_scenes, doc, rescale)
    for light in report.light_scenes:
        if light.results is not None:
            read = lightsolver_results.read(light.results, scene, strict=False,
                                            check_schema=False)
            light.areas = _areas(read, scene, labels)
            verdict = light.results.get("verdict")
            light.verdict = verdict if isinstance(verdict, str) else None
    report.shown_scene = scenes.shown_scene(doc, report.light_scenes, labels)
    return scenes.as_traced(doc, rescale)


def _file_names(luminaires: List[LuminaireRow]) -> Dict[str, str]:
    """Each photometric file as the client reads it: "the photometric data of <product>"."""
    names = {}
    for row in luminaires:
        for file in row.files:
            names[file] = f"the photometric data of {row.title}"
    return names


def build_report(scene: Dict[str, Any], results: Dict[str, Any], *, scene_name: str,
                 base_dir: str, date: str, solver_version: str, title: Optional[str] = None,
                 photometry: Optional[PhotometryFn] = None,
                 material_defaults: Optional[Dict[str, Dict[str, Any]]] = None,
                 light_scenes: Any = None, results_sha256: Optional[str] = None,
                 sun_position: Optional[daylight.SunFn] = None) -> Report:
    """The report's content. ``scene_name`` is printed as the scene file (give a base name so
    that the output does not depend on where the files lie). ``light_scenes`` ({name: {group:
    level}}) overrides the scene's ``metadata.light_scenes``; ``results_sha256`` is the results
    file's hash when the caller read one (else the content's canonical hash is printed).
    ``sun_position`` (``lightsolver.sun_position``) places a sun given by site and time.
    Raises ReportError naming the field for unusable ``metadata.report.energy`` inputs."""
    meta = scene.get("metadata") if isinstance(scene.get("metadata"), dict) else {}
    labels = meta.get("labels") if isinstance(meta.get("labels"), dict) else {}
    report_meta = meta.get("report") if isinstance(meta.get("report"), dict) else {}
    try:
        inputs = energy.read_inputs(report_meta.get("energy"),
                                    f"{scene_name or 'scene'}: metadata.report.energy")
    except energy.EnergyInputError as exc:
        from lightsolver_report import ReportError  # the package's error (no import cycle)

        raise ReportError(str(exc)) from exc
    files = PhotometricFiles(base_dir, photometry)
    # Read once: schema-checked, older layouts migrated (the luminaires' flux then derived
    # from the scene), problems and migrations said among the warnings.
    read = lightsolver_results.read(results, scene, files.scene_flux, strict=False)
    doc = read.doc
    luminaires = build_luminaires(scene, files, read.luminaires)
    surfaces, materials = build_surfaces(scene, material_defaults)
    warnings = [str(w) for w in doc.get("warnings", [])] + files.warnings + read.notes
    report = Report(
        title=title or str(report_meta.get("project") or meta.get("project")
                           or meta.get("title") or meta.get("document")
                           or os.path.splitext(scene_name)[0]),
        subtitle=str(meta.get("description") or ""),
        date=date, solver_version=solver_version, scene_file=scene_name,
        document_file=os.path.basename(str(meta.get("document_file") or "")),
        generator=str(meta.get("generator") or ""),
        run=_run_facts(scene, doc),
        verdict=doc.get("verdict") if isinstance(doc.get("verdict"), str) else None,
        luminaires=luminaires, materials=materials, surfaces=surfaces,
        areas=_areas(read, scene, labels), warnings=warnings,
        notes=client_notes(warnings, Namer(labels, _file_names(luminaires))),
        solver_total_flux_lm=finite(doc.get("total_flux_lm")), traced_flux=read.traced_flux,
        metadata=meta)
    traced = _light_scenes(report, doc, scene, light_scenes, labels)
    report.initial = initial_values(scene, doc, read.targets, read.luminaires,
                                    scenes.solver_rescale(), labels)
    _loads(report, traced, scene)
    _energy(report, inputs)
    roles = {f: f"photometric data: {r.title}" for r in luminaires for f in r.files}
    for mesh in scene.get("meshes", []):
        if isinstance(mesh, dict) and mesh.get("file"):
            name = str(mesh.get("name"))
            roles[str(mesh["file"])] = f"geometry: {labels.get(name, name)}"
    report.provenance = build_provenance(results, roles, results_sha256)
    flux = {lum.name: lum.emitted_flux_lm for lum in read.luminaires}
    report.skies, report.suns = daylight.build_schedule(scene, flux, labels, sun_position)
    report.sunlight = daylight.read_exposure(doc, scene, labels)
    for area in report.daylight_areas:
        sky = next((s for s in report.skies if s.label == area.daylight.sky_label), None)
        area.daylight.sky = sky
    return report
