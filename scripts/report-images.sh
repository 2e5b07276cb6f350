#!/usr/bin/env bash
# The report pictures of docs/report.md (docs/images/report-*.png), each the page of a report
# that holds a given heading, found with pdftotext (page numbers move as the report grows).
# Run from the repository root after building; needs poppler-utils.
set -euo pipefail
cli=${LIGHTSOLVER_CLI:-build/NativeSolver/cli/lightsolver}
F=Tests/python/fixtures/report
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# page PDF TEXT: the first page of PDF whose text holds TEXT.
page() {
  local pages n
  pages=$(pdfinfo "$1" | sed -n 's/^Pages: *//p')
  for ((n = 1; n <= pages; n++)); do
    if pdftotext -f "$n" -l "$n" -layout "$1" - | grep -qE -- "$2"; then echo "$n"; return; fi
  done
  echo "no page of $1 holds '$2'" >&2
  return 1
}
# shot PDF TEXT NAME [pdftoppm options]: that page as docs/images/NAME.png.
shot() {
  local n
  n=$(page "$1" "$2")
  pdftoppm -r 100 -png -f "$n" -l "$n" -singlefile "${@:4}" "$1" "docs/images/$3"
  echo "docs/images/$3.png: page $n of $(basename "$1") ('$2')"
}

# The room and office fixtures are results no solver wrote: unverified (make_fixtures.py).
"$cli" report $F/room.scene.json --results $F/room.results.json --allow-unverified \
  --date 2026-01-01 --out "$tmp/room.pdf" > /dev/null
shot "$tmp/room.pdf" "Overall verdict" report-page1
shot "$tmp/room.pdf" "[0-9] Calculation areas" report-page3
"$cli" report Tests/golden/scenes/lamps.json --results Tests/golden/lamps.embree.results.json \
  --date 2026-01-01 --out "$tmp/lamps.pdf" > /dev/null
shot "$tmp/lamps.pdf" "Floor plan" report-plan
"$cli" report $F/office.scene.json --results $F/office.results.json --allow-unverified \
  --date 2026-01-01 --out "$tmp/office.pdf" > /dev/null
shot "$tmp/office.pdf" "Axonometric view" report-model -W 827 -H 600
# The office as the workbench exports it, with the solver's own results and provenance.
"$cli" report $F/workbench.scene.json --results $F/workbench.results.json \
  --date 2026-01-01 --out "$tmp/workbench.pdf" > /dev/null
shot "$tmp/workbench.pdf" "[0-9] Luminaires" report-office-schedule
shot "$tmp/workbench.pdf" "[0-9] Calculation areas" report-office-workplane
shot "$tmp/workbench.pdf" "[0-9] Provenance and sign-off" report-office-signoff
