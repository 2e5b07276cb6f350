# SPDX-License-Identifier: LGPL-2.1-or-later
"""What the report refuses, and how it writes (docs/report.md, "What the report refuses").

A report is a document an engineer signs, so :func:`lightsolver_report.render` checks before it
writes anything: the output's place (an existing folder, ``.html`` or ``.pdf``), the results
(readable, of the results schema, with targets, not cancelled unless asked for), that they
belong to the scene (``lightsolver_report.provenance`` where present), and the sign-off fields.
Each refusal is a :class:`ReportError` that names the file or field; none leaves a file or a
folder behind. :func:`write_atomically` writes the page whole or not at all: a temporary file in
the output's own folder, renamed over the old report only once it is complete."""
from __future__ import annotations

import importlib
import importlib.util
import os
import secrets
from pathlib import Path
from typing import Any, Callable, Dict, Mapping, Optional, Union

import lightsolver_results

__all__ = ["ReportError", "SUFFIXES", "SIGNOFF_KEYS", "output_path", "results_document",
           "describe", "annual_document", "is_partial", "refuse_partial", "check_provenance",
           "signoff", "view_png", "write_atomically"]

PathLike = Union[str, "os.PathLike[str]"]
#: The report's file types by suffix.
SUFFIXES = {".html": "html", ".htm": "html", ".pdf": "pdf"}
#: The sign-off block's fields (COMMON interface: project, author, checked by).
SIGNOFF_KEYS = ("project", "author", "checked_by")
#: Sign-off keys printed only when given (signoff.OPTIONAL_SIGNOFF_FIELDS).
OPTIONAL_SIGNOFF_KEYS = ("project_number", "client")
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


class ReportError(Exception):
    """The report cannot be made (bad input, a missing library); the message says why."""


# --- where it goes -----------------------------------------------------------------------------

def output_path(out_path: PathLike) -> Path:
    """``out_path`` checked before anything is computed or written: a ``.html``/``.htm`` or
    ``.pdf`` name in a folder that exists (never created here: a mistyped folder is an error,
    not a new directory), and not itself a folder."""
    out = Path(out_path)
    suffix = out.suffix.lower()
    if suffix not in SUFFIXES:
        raise ReportError(f"{out}: the report is written as .html or .pdf (got '{suffix}')")
    folder = out.parent
    if not folder.is_dir():
        what = "is not a folder" if folder.exists() else "does not exist"
        raise ReportError(f"{out}: the folder {folder} {what}; create it first or choose "
                          "another place for the report")
    if out.is_dir():
        raise ReportError(f"{out}: is a folder, not a report file")
    return out


# --- the results -------------------------------------------------------------------------------

def describe(source: Any) -> str:
    """How messages name the results: their file, else 'the results'."""
    return str(source) if isinstance(source, (str, os.PathLike)) else "the results"


def results_document(source: Union[PathLike, Dict[str, Any]],
                     where: Optional[str] = None) -> Dict[str, Any]:
    """The results of ``source`` (a dict or a file) as plain data, refused unless they are a
    whole results document: readable JSON (a truncated or garbled file is refused), the results
    format, at least one target, and the results schema after the reader's migration of older
    layouts (``lightsolver_results.read``, strict). Older results that the reader migrates
    stay accepted; what the migration needed is said among the report's warnings. ``where``
    names the results in messages (default: their file, else "the results")."""
    where = where or describe(source)
    try:
        doc = source if isinstance(source, dict) else lightsolver_results.load(source)
    except lightsolver_results.ResultsError as exc:
        raise ReportError(str(exc)) from exc
    if doc.get("format") != lightsolver_results.FORMAT:
        raise ReportError(f"{where}: not a results file of this solver (format: "
                          f"{doc.get('format')!r}, expected {lightsolver_results.FORMAT!r})")
    targets = doc.get("targets")
    if not isinstance(targets, list) or not targets:
        found = "an empty targets list" if isinstance(targets, list) else (
            "no 'targets'" if targets is None else f"'targets' of type {type(targets).__name__}")
        raise ReportError(f"{where}: the results hold no targets ({found}): there is nothing "
                          "to report; give the results file the solver wrote for this scene")
    odd = [str(i) for i, t in enumerate(targets) if not isinstance(t, dict)]
    if odd:  # the reader's migration reads each target as an object
        raise ReportError(f"{where}: targets {', '.join(odd)}: not an object; the results are "
                          "malformed")
    try:
        lightsolver_results.read(doc, strict=True)
    except lightsolver_results.ResultsError as exc:
        raise ReportError(f"{where}: {exc}") from exc
    except (AttributeError, TypeError, ValueError, KeyError) as exc:  # a field's wrong shape
        raise ReportError(f"{where}: the results are malformed: {exc!r}") from exc
    return lightsolver_results.plain(doc)


def annual_document(source: Union[None, PathLike, Dict[str, Any]]
                    ) -> Union[None, PathLike, Dict[str, Any]]:
    """``source`` (an annual.json of ``lightsolver annual``, or its dict) once the results
    reader accepts it (``lightsolver_results.read_annual``: readable JSON of the annual format
    that keeps docs/schemas/annual.schema.json, where jsonschema is installed) and it holds a
    grid; None stays None. Whether its grids are the scene's is checked when the section is
    built (lightsolver_report.annual.read_section)."""
    if source is None:
        return None
    try:
        view = lightsolver_results.read_annual(source)
    except lightsolver_results.ResultsError as exc:
        raise ReportError(str(exc)) from exc
    if not view.grids:
        raise ReportError(f"{describe(source)}: the annual results hold no grid: there is "
                          "nothing to report")
    return source


def is_partial(results: Mapping[str, Any]) -> bool:
    """The results of a cancelled run (``partial``, or ``stop_reason`` "cancelled"): the
    photons traced until the cancel, not the run that was asked for."""
    return results.get("partial") is True or results.get("stop_reason") == "cancelled"


def refuse_partial(results: Mapping[str, Any], where: str = "the results") -> None:
    """ReportError for partial results: they are reported only when asked for explicitly
    (``allow_partial``/``--allow-partial``), and then marked on every page."""
    if not is_partial(results):
        return
    photons, requested = results.get("photons"), results.get("photons_requested")
    traced = (f" after {photons:,} of {requested:,} photons"
              if isinstance(photons, int) and isinstance(requested, int) else "")
    raise ReportError(f"{where}: partial results: the run was cancelled{traced}. Run it to "
                      "the end, or ask for a report marked partial on every page "
                      "(allow_partial=True, lightsolver report --allow-partial)")


# --- do they belong to the scene ---------------------------------------------------------------

def _provenance_check() -> Optional[Callable[..., None]]:
    """``lightsolver_report.provenance.check`` where that module exists (issue 24's provenance
    part); None where it does not. An error *inside* the module is not hidden."""
    if importlib.util.find_spec("lightsolver_report.provenance") is None:
        return None
    return importlib.import_module("lightsolver_report.provenance").check


def check_provenance(scene_path: Optional[PathLike], results: Dict[str, Any],
                     allow_unverified: bool = False, allow_stale: bool = False) -> Optional[str]:
    """Refuse results that do not belong to the scene file (another scene, changed input
    files): ``provenance.check`` raises ReportError naming what differs. Without a scene file
    (a scene given as a dict only) there is nothing to compare with. ``allow_stale``: the
    caller knows the results describe an earlier state of the model (the workbench's stale
    results, written anyway at the user's request): what differs is returned, for the page,
    instead of raised."""
    check = _provenance_check()
    if check is None or scene_path is None:
        return None
    try:
        check(scene_path, results, allow_unverified=allow_unverified)
    except ReportError as exc:
        if not allow_stale:
            raise
        return f"These results describe an earlier state of the model: {exc}"
    return None


# --- what the caller adds ----------------------------------------------------------------------

def signoff(fields: Optional[Mapping[str, Any]]) -> Dict[str, str]:
    """The sign-off block's fields, every key present ("" where not given); an unknown key is
    an error (a misspelt ``checked_by`` must not vanish from a signed page)."""
    fields = dict(fields or {})
    unknown = sorted(set(fields) - set(SIGNOFF_KEYS) - set(OPTIONAL_SIGNOFF_KEYS))
    if unknown:
        raise ReportError(f"signoff: unknown field(s) {', '.join(map(repr, unknown))}; "
                          f"expected {', '.join(SIGNOFF_KEYS + OPTIONAL_SIGNOFF_KEYS)}")
    out = {key: str(fields.get(key) or "").strip() for key in SIGNOFF_KEYS}
    out.update({key: str(fields[key]).strip() for key in OPTIONAL_SIGNOFF_KEYS
                if str(fields.get(key) or "").strip()})
    return out


def view_png(path: Optional[PathLike]) -> Optional[str]:
    """The false-colour picture of the model (absolute path) checked to be a PNG file, or
    None when none is given."""
    if path is None:
        return None
    try:
        with open(path, "rb") as stream:
            head = stream.read(len(PNG_MAGIC))
    except OSError as exc:
        raise ReportError(f"view_png: cannot read the picture of the model: {exc}") from exc
    if head != PNG_MAGIC:
        raise ReportError(f"view_png: {path} is not a PNG picture")
    return os.path.abspath(path)


# --- writing -----------------------------------------------------------------------------------

def _create_beside(out: Path) -> Path:
    """A new empty file beside ``out`` with a random name, created with the permissions a plain
    ``open`` gives (the umask applies; not mkstemp's 0600, and no process-wide umask change,
    which a GUI thread could see)."""
    for _ in range(100):
        temporary = out.with_name(f".{out.name}.{secrets.token_hex(6)}.tmp")
        try:
            os.close(os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
        except FileExistsError:
            continue
        return temporary
    raise FileExistsError(f"{out.parent}: no free temporary name for the report")


def write_atomically(out: Path, write: Callable[[Path], None]) -> Path:
    """Call ``write(temporary)`` for a fresh temporary file beside ``out``, then rename it over
    ``out`` (os.replace: atomic within a folder). Whatever ``write`` raises (WeasyPrint, a full
    disk, an interrupt), the temporary file is removed and an old report at ``out`` is left as
    it was."""
    temporary = _create_beside(out)
    try:
        write(temporary)
        os.replace(temporary, out)
    finally:
        if temporary.exists():
            temporary.unlink()
    return out
