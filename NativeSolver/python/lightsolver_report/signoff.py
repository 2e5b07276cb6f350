# SPDX-License-Identifier: LGPL-2.1-or-later
"""The provenance and sign-off block: who signs (project, prepared by, checked by), what was
calculated (the results' fingerprint, the scene's and every input file's, from the results'
``provenance`` object, docs/schemas/results.schema.json) and how (solver version, backend and
device, threads and MPI ranks, start and end time). Results written before provenance existed
have none: the block then says so and shows what the results themselves record."""
from __future__ import annotations

import hashlib
import json
import os
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

#: The sign-off fields a report prints, with their captions.
SIGNOFF_FIELDS: Tuple[Tuple[str, str], ...] = (
    ("project", "Project"), ("author", "Prepared by"), ("checked_by", "Checked by"))
#: Printed after those, and only when given (no line to write on: the client's name and the
#: project number are known when the report is made, or not wanted).
OPTIONAL_SIGNOFF_FIELDS: Tuple[Tuple[str, str], ...] = (
    ("project_number", "Project no."), ("client", "Client"))


@dataclass
class InputFile:
    """An input file the results were traced from, with what it is for the reader and its
    SHA-256 (as the results record it)."""

    role: str
    sha256: str
    copies: int = 1  # files with the same content and role (six luminaires, one IES file)


@dataclass
class Provenance:
    """Where the results came from (None fields: not recorded)."""

    results_sha256: str
    results_hash_of: str  # what the fingerprint is of: "file" or "content"
    scene_sha256: Optional[str] = None
    files: List[InputFile] = field(default_factory=list)
    solver_version: Optional[str] = None
    source_commit: Optional[str] = None
    build_type: Optional[str] = None
    backend: Optional[str] = None
    device: Optional[str] = None
    threads: Optional[int] = None
    mpi_ranks: Optional[int] = None
    started_utc: Optional[str] = None
    finished_utc: Optional[str] = None
    recorded: bool = False  # the results carry a provenance object

    @property
    def solver(self) -> Optional[str]:
        """"0.1.0 (commit 379eac7, Release)" or None."""
        if not self.solver_version:
            return None
        extra = [f"commit {self.source_commit[:12]}" if self.source_commit else "",
                 self.build_type or ""]
        extra = [e for e in extra if e]
        return self.solver_version + (f" ({', '.join(extra)})" if extra else "")


def content_sha256(results: Dict[str, Any]) -> str:
    """SHA-256 of the results' content as canonical JSON (keys sorted, no spaces, UTF-8):
    the same for the same results whatever their file's layout."""
    import lightsolver_results

    # solve()'s and rescale()'s dicts carry numpy cell arrays beside the layout: the file's
    # content is the layout alone.
    text = json.dumps(lightsolver_results.plain(results), sort_keys=True, separators=(",", ":"),
                      ensure_ascii=False, default=_listed)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _listed(value: Any) -> Any:
    """A numpy array (or scalar) left inside the results, as JSON would hold it."""
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"not JSON data: {type(value).__name__}")


def _text(value: Any) -> Optional[str]:
    return str(value) if isinstance(value, (str, int, float)) and str(value) else None


def _count(value: Any) -> Optional[int]:
    return int(value) if isinstance(value, int) and not isinstance(value, bool) else None


def build_provenance(results: Dict[str, Any], roles: Dict[str, str],
                     results_sha256: Optional[str] = None) -> Provenance:
    """The block's data from the results (``provenance`` when recorded, else the run fields
    the results have). ``roles`` names an input file for the reader by its path ("photometric
    data: <product>"); ``results_sha256``: the results file's own hash when the caller read a
    file, else the canonical content's is computed."""
    raw = results.get("provenance") if isinstance(results.get("provenance"), dict) else None
    found = raw or {}
    prov = Provenance(results_sha256=results_sha256 or content_sha256(results),
                      results_hash_of="file" if results_sha256 else "content",
                      recorded=raw is not None)
    prov.scene_sha256 = _text(found.get("scene_sha256"))
    prov.solver_version = _text(found.get("solver_version"))
    prov.source_commit = _text(found.get("source_commit"))
    prov.build_type = _text(found.get("build_type"))
    prov.backend = _text(found.get("backend")) or _text(results.get("backend"))
    prov.device = _text(found.get("device"))
    prov.threads, prov.mpi_ranks = _count(found.get("threads")), _count(found.get("mpi_ranks"))
    prov.started_utc, prov.finished_utc = (_text(found.get("started_utc")),
                                           _text(found.get("finished_utc")))
    # The results may name a file as the scene does or by another path (absolute): its base
    # name finds it too.
    by_name = {os.path.basename(path): role for path, role in roles.items()}
    for entry in found.get("files") or []:
        if isinstance(entry, dict) and _text(entry.get("sha256")):
            path = str(entry.get("path", ""))
            role = roles.get(path) or by_name.get(os.path.basename(path)) or _role(path)
            same = next((f for f in prov.files
                         if (f.role, f.sha256) == (role, str(entry["sha256"]))), None)
            if same:  # the client sees no file names: one line per content
                same.copies += 1
            else:
                prov.files.append(InputFile(role, str(entry["sha256"])))
    return prov


def _role(path: str) -> str:
    """What an input file is, for a file the report has no name for (by its kind)."""
    ext = os.path.splitext(path)[1].lower()
    if ext in (".ies", ".ldt"):
        return "photometric data"
    if ext in (".ply", ".obj"):
        return "geometry"
    return "input file"


def signoff_fields(given: Optional[Dict[str, Any]], metadata: Dict[str, Any],
                   title: str) -> List[Tuple[str, str]]:
    """(caption, value) of each sign-off field: ``given`` (render's ``signoff``) over the
    scene's ``metadata.report`` over the title (the project); "" where nobody is named (a line
    to write on); the project number and client only where given."""
    report_meta = metadata.get("report") if isinstance(metadata.get("report"), dict) else {}
    out = []
    for key, caption in SIGNOFF_FIELDS:
        value = (given or {}).get(key) or report_meta.get(key) or (
            title if key == "project" else "")
        out.append((caption, str(value)))
    for key, caption in OPTIONAL_SIGNOFF_FIELDS:
        value = (given or {}).get(key) or report_meta.get(key)
        if value:
            out.append((caption, str(value)))
    return out
