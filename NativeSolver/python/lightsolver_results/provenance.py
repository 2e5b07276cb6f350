# SPDX-License-Identifier: LGPL-2.1-or-later
"""The results' ``provenance`` (docs/scene-format.md, "Provenance") as a typed view: where the
results come from. ``lightsolver.verify_results`` compares it with a scene file."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional


@dataclass
class SourceFile:
    """A file the traced scene read (a mesh, a photometric file, the requirements table)."""

    path: str  # as the scene writes it; the requirements table: its file name
    kind: str  # mesh, photometric, requirements table, file
    sha256: str


@dataclass
class Provenance:
    """Where the results come from: the scene's content hash (None: a scene built in memory)
    and files, the solver, build, machine, options and time of the run."""

    scene_sha256: Optional[str]
    files: List[SourceFile]
    solver_version: str
    source_commit: str
    build_type: str
    backend: str
    device: str
    mpi_ranks: int
    threads: int
    options: Dict[str, Any]
    started_utc: str
    finished_utc: str
    host: str
    command: str
    #: An optimizer's output only (docs/optimization.md, "Provenance and configurations"): the
    #: SHA-256 of the optimization block searched, and the domain (each variable's ``name``,
    #: ``cells`` and ``min``/``max``/``periodic`` or ``levels``): how a member's cells give its
    #: values. None and empty in results.
    optimization_sha256: Optional[str] = None
    domain: List[Dict[str, Any]] = field(default_factory=list)


def read_provenance(doc: Dict[str, Any]) -> Optional[Provenance]:
    """The document's provenance (results, or an optimizer's output); None for one written
    before the solver recorded it."""
    p = doc.get("provenance")
    if not isinstance(p, dict):
        return None

    def text(key: str) -> str:
        return str(p.get(key, ""))

    return Provenance(
        scene_sha256=str(p["scene_sha256"]) if p.get("scene_sha256") else None,
        files=[SourceFile(str(f.get("path", "")), str(f.get("kind", "")), str(f.get("sha256", "")))
               for f in p.get("files") or [] if isinstance(f, dict)],
        solver_version=text("solver_version"), source_commit=text("source_commit"),
        build_type=text("build_type"), backend=text("backend"), device=text("device"),
        mpi_ranks=int(p.get("mpi_ranks") or 1), threads=int(p.get("threads") or 0),
        options=dict(p.get("options") or {}), started_utc=text("started_utc"),
        finished_utc=text("finished_utc"), host=text("host"), command=text("command"),
        optimization_sha256=str(p["optimization_sha256"]) if p.get("optimization_sha256")
        else None,
        domain=[dict(d) for d in p.get("domain") or [] if isinstance(d, dict)])


#: Provenance fields that say when, where and how a run was started, not what it computed:
#: two runs of the same scene and options differ only in these (and in the tracing time).
RUN_FACT_FIELDS = ("started_utc", "finished_utc", "host", "command", "threads")


def without_run_facts(doc: Dict[str, Any], top_level: tuple = ("seconds",),
                      fields: tuple = RUN_FACT_FIELDS) -> Dict[str, Any]:
    """The results without what differs between two runs of the same scene and options: the
    top-level ``top_level`` keys and the provenance's ``fields`` (:data:`RUN_FACT_FIELDS`)."""
    out = {k: v for k, v in doc.items() if k not in top_level}
    if isinstance(out.get("provenance"), dict):
        out["provenance"] = {k: v for k, v in out["provenance"].items() if k not in fields}
    return out
