# SPDX-License-Identifier: LGPL-2.1-or-later
"""Messages of the Check/Prepare/Solve/Results stages and the errors the API raises."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Iterable, List, Optional

LEVELS = ("error", "warning", "info")


class LightingError(RuntimeError):
    """Any failure of the Lighting workbench with a message meant for the user."""


class CheckError(LightingError):
    """The model is not ready for an analysis (no luminaires, no targets, bad values...)."""

    def __init__(self, report: "Report") -> None:
        self.report = report
        super().__init__("Lighting check failed:\n" + report.format(levels=("error",)))


class ExportError(LightingError):
    """The scene could not be written."""


class SolverUnavailableError(LightingError):
    """The native module ``lightsolver`` cannot be imported."""


class SolverError(LightingError):
    """The solver rejected the scene or failed while tracing."""


class CancelledError(LightingError):
    """The run was cancelled before any result was available."""


@dataclass
class Message:
    """One finding: level "error" (blocks the run), "warning" or "info"."""

    level: str
    text: str
    object_name: Optional[str] = None

    def __str__(self) -> str:
        return f"{self.level}: {self.text}"


@dataclass
class Report:
    """Ordered list of messages with helpers to add, query and print them."""

    messages: List[Message] = field(default_factory=list)

    def add(self, level: str, text: str, object_name: Optional[str] = None) -> None:
        """Append a message; ``level`` is one of LEVELS."""
        if level not in LEVELS:
            raise ValueError(f"unknown message level {level!r}")
        self.messages.append(Message(level, text, object_name))

    @classmethod
    def one(cls, level: str, text: str) -> "Report":
        """A report holding a single message."""
        report = cls()
        report.add(level, text)
        return report

    def extend(self, problems: Iterable[tuple], object_name: Optional[str] = None) -> None:
        """Append (level, text) pairs, e.g. from an object's ``check()``."""
        for level, text in problems:
            self.add(level, text, object_name)

    def merge(self, other: "Report") -> None:
        """Append the messages of another report."""
        self.messages.extend(other.messages)

    @property
    def errors(self) -> List[Message]:
        """The messages that block a run."""
        return [m for m in self.messages if m.level == "error"]

    @property
    def warnings(self) -> List[Message]:
        """The warnings."""
        return [m for m in self.messages if m.level == "warning"]

    @property
    def ok(self) -> bool:
        """True when there is no error."""
        return not self.errors

    def format(self, levels: Iterable[str] = LEVELS) -> str:
        """The messages of the given levels, one per line as "- level: text"."""
        wanted = set(levels)
        return "\n".join(f"- {m.level}: {m.text}" for m in self.messages if m.level in wanted)

    def print_to_console(self, prefix: str = "Lighting") -> None:
        """Print every message to FreeCAD's report view with the matching colour."""
        import FreeCAD

        for m in self.messages:
            line = f"{prefix}: {m.text}\n"
            if m.level == "error":
                FreeCAD.Console.PrintError(line)
            elif m.level == "warning":
                FreeCAD.Console.PrintWarning(line)
            else:
                FreeCAD.Console.PrintMessage(line)
