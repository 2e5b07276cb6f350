# SPDX-License-Identifier: LGPL-2.1-or-later
"""``python3 -m lightsolver_report SCENE.json [--results R.json] [--annual annual.json]
--out report.pdf|.html``
(also run by ``lightsolver report``). Exit status 0, or 1 with a message on stderr."""
from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path
from typing import List, Optional

from lightsolver_report import ReportError, guard, render, reports_here, trace


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="lightsolver report",
        description="Write a lighting calculation report (HTML or PDF) of a scene and its "
                    "results; traces the scene first when no results are given.")
    p.add_argument("scene", help="scene file (lightsolver.scene/1 JSON)")
    p.add_argument("--results", help="results file of the scene (lightsolver run --out); "
                                     "without it the scene is traced with its settings")
    p.add_argument("--out", required=True, help="report file: .html or .pdf")
    p.add_argument("--annual", metavar="DIR/annual.json",
                   help="annual results of the scene (lightsolver annual --out-dir DIR): the "
                        "report gets a section on its year of daylight")
    p.add_argument("--date", help="date printed on the report, YYYY-MM-DD (default: "
                                  "SOURCE_DATE_EPOCH, else today), for reproducible output")
    p.add_argument("--title", help="title (default: the scene's metadata, else its file name)")
    p.add_argument("--photons", type=int, help="photons when tracing (default: the scene's)")
    p.add_argument("--seed", type=int, help="seed when tracing (default: the scene's)")
    p.add_argument("--backend", default="auto", help="backend when tracing (default: auto)")
    p.add_argument("--save-results", metavar="R.json",
                   help="when tracing, also write the results here")
    p.add_argument("--allow-partial", action="store_true",
                   help="report the results of a cancelled run (refused otherwise); every "
                        "page then says they are partial")
    p.add_argument("--allow-unverified", action="store_true",
                   help="accept results that do not say which scene they were traced from "
                        "(written before the solver recorded it); results shown to be of "
                        "another scene are refused anyway")
    signed = p.add_argument_group("sign-off block")
    signed.add_argument("--project", help="project name")
    signed.add_argument("--author", help="who made the calculation")
    signed.add_argument("--checked-by", help="who checked it")
    signed.add_argument("--project-number", help="the project's number (printed when given)")
    signed.add_argument("--client", help="the client (printed when given)")
    return p


def main(argv: Optional[List[str]] = None) -> int:
    args = parser().parse_args(argv)
    signoff = {"project": args.project, "author": args.author, "checked_by": args.checked_by,
               "project_number": args.project_number, "client": args.client}
    try:
        guard.output_path(args.out)  # before tracing: an hour's run must not end in a typo
        guard.annual_document(args.annual)
        if args.save_results and not os.path.isdir(os.path.dirname(
                os.path.abspath(args.save_results))):
            raise ReportError(f"{args.save_results}: its folder does not exist")
        results = args.results
        if results is None:
            results = trace(args.scene, photons=args.photons, seed=args.seed,
                            backend=args.backend)
            if not reports_here():
                return 0  # an MPI rank other than 0: it traced its share; rank 0 writes
            if args.save_results:
                text = json.dumps(results, indent=1) + "\n"
                guard.write_atomically(Path(args.save_results),
                                       lambda temporary: temporary.write_text(text, "utf-8"))
        out = render(args.scene, results, args.out, date=args.date, title=args.title,
                     allow_partial=args.allow_partial, signoff=signoff,
                     allow_unverified=args.allow_unverified, annual=args.annual)
    except ReportError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    except OSError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    print(f"report written to {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
