# SPDX-License-Identifier: LGPL-2.1-or-later
"""Client wording: what the solver says for its users (mesh names, file names, internal keys)
turned into what a client reads: the names the designer gave (labels), grouped where one
remark repeats, the rest kept for the report's technical appendix.

Nothing here changes a number; it only decides how a remark is worded and where it goes."""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Dict, Iterable, List, Optional

#: The solver's coincident-surface remark (prepare: docs/scene-format.md, meshes).
_OVERLAP = re.compile(r'meshes "(?P<a>[^"]+)" \(material "(?P<ma>[^"]*)"\) and "(?P<b>[^"]+)" '
                      r'\(material "(?P<mb>[^"]*)"\) overlap in one plane over '
                      r'(?P<area>[0-9.eE+-]+) m²')
_QUOTED = re.compile(r'"([^"]+)"')

#: The solver's other run remarks (run_results.cpp's add_warnings), in a client's words.
_REWORDED = (
    (re.compile(r"^(?P<n>\d+) photon path\(s\) were still alive at max_bounces = (?P<b>\d+)"),
     lambda m: (f"{int(m.group('n')):,}".replace(",", "\u202f") + " light path(s) were still "
                f"bouncing after {m.group('b')} reflections and were ended there; the little "
                "light they still carried is missing from the results (they are very slightly "
                "low).")),
    (re.compile(r"^(?P<n>\d+) photon path\(s\) on the (?P<b>\S+) backend were longer"),
     lambda m: (f"{m.group('n')} light path(s) were too long for the {m.group('b')} "
                "calculation engine and were dropped; the results are slightly low (the embree "
                "engine has no such limit).")),
    (re.compile(r"^run stopped early: results are from the photons traced"),
     lambda m: "The calculation was stopped early: the results are those of the light paths "
               "traced until then."),
    (re.compile(r"^the run ended before every verdict was decided"),
     lambda m: "The calculation ended before every requirement was decided: each undecided "
               "one says how long a calculation would decide it."),
    (re.compile(r"^the photon budget ran out before every (?P<what>\w+) reached"),
     lambda m: f"The planned light paths ran out before every {m.group('what')} reached the "
               "requested accuracy."),
    (re.compile(r"^all luminaires have zero flux"),
     lambda m: "Every luminaire is switched off (0 lm): every result is 0 lx."),
    (re.compile(r"^(?P<p>[\d.e+-]+ %) of the daylight photons entering through portals"),
     lambda m: (f"{m.group('p')} of the daylight entering through the window openings was "
                "blocked by surfaces outside them (overhangs, neighbouring buildings): their "
                "shadows are included, the daylight they reflect into the room is not.")),
    (re.compile(r"^(?P<p>[\d.e+-]+ %) of the daylight photons through openings met a modelled"),
     lambda m: (f"{m.group('p')} of the daylight met modelled glass outside a window opening "
                "and was not counted: the opening's glazing already stands for the glass.")),
)


@dataclass
class Note:
    """A remark of the calculation for the technical appendix: a client sentence, and the
    details it stands for (shown small under it)."""

    text: str
    details: List[str] = field(default_factory=list)


class Namer:
    """Names for the client: a mesh, target or luminaire by its label (a mesh part
    ``Object.part`` by its object's label), a photometric file by what it describes."""

    def __init__(self, labels: Dict[str, str], files: Optional[Dict[str, str]] = None) -> None:
        self.labels = {str(k): str(v) for k, v in labels.items()}
        self.files = dict(files or {})

    def name(self, internal: str) -> str:
        if internal in self.labels:
            return self.labels[internal]
        obj = internal.split(".", 1)[0]
        return self.labels.get(obj, internal)

    def text(self, message: str) -> str:
        """A message with quoted names and file names replaced by the client's names."""
        for path, described in sorted(self.files.items(), key=lambda kv: -len(kv[0])):
            message = message.replace(path, described)
        return _QUOTED.sub(lambda m: f"“{self.name(m.group(1))}”", message)


def _overlap_note(found: List[re.Match], namer: Namer) -> Note:
    pairs, seen = [], set()
    for m in found:
        a, b = namer.name(m.group("a")), namer.name(m.group("b"))
        what = f"{a} and {b}" if a != b else f"two parts of {a}"
        pairs.append(f"{what}: {float(m.group('area')):.2f} m²")
        seen.add((m.group("ma"), m.group("mb")))
    places = "one place" if len(found) == 1 else f"{len(found)} places"
    return Note(f"In {places} two surfaces of the model lie in the same plane (where an object "
                "stands on or touches another). There the light meets either surface's "
                "material at random; this matters only where their reflectances differ "
                "noticeably.", pairs)


def client_notes(warnings: Iterable[str], namer: Namer) -> List[Note]:
    """The run's warnings for the technical appendix: the coincident-surface remarks as one
    note (each place a detail), every other remark with the client's names, in order and each
    once."""
    notes: List[Note] = []
    overlaps: List[re.Match] = []
    seen = set()
    for warning in warnings:
        text = str(warning)
        match = _OVERLAP.search(text)
        if match:
            if (match.group("a"), match.group("b")) not in seen:
                seen.add((match.group("a"), match.group("b")))
                overlaps.append(match)
            continue
        worded = namer.text(_reword(text))
        worded = worded[:1].upper() + worded[1:]
        if worded not in seen:
            seen.add(worded)
            notes.append(Note(worded))
    if overlaps:
        notes.insert(0, _overlap_note(overlaps, namer))
    return notes


def _reword(text: str) -> str:
    """A known solver remark in a client's words; the results reader's schema notes said
    without the schema's path; anything else as it is."""
    for pattern, worded in _REWORDED:
        match = pattern.match(text)
        if match:
            return worded(match)
    if text.startswith("schema: "):
        return ("The results file does not follow the expected layout in one place; the "
                f"report shows what it could read ({text[len('schema: '):]}).")
    return text


#: How a run ended, in the client's words (results' ``stop_reason``).
STOPPED = {"photons": "after the planned number of light paths",
           "accuracy": "when the accuracy goal was met",
           "decided": "as soon as every requirement was decided",
           "time": "at its time limit",
           "cancelled": "early: it was stopped by hand (partial results)"}


def stopped(reason: Optional[str]) -> str:
    """How the calculation ended (the solver's stop reason for a client)."""
    return STOPPED.get(str(reason), "–") if reason else "–"


def group_levels(levels: Dict[str, float]) -> str:
    """"Window row 50 %, Back row off" (groups at 100 % not named; none: "all at 100 %")."""
    parts = [f"{group} {'off' if level == 0 else f'{100 * level:.4g} %'}"
             for group, level in levels.items() if level != 1]
    return ", ".join(parts) if parts else "all at 100 %"
