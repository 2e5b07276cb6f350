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
# The same office turned 30° off the model's axes (plan and picture follow the room): its
# results are the office's own (the same room, turned), without their provenance since the
# turned scene is another file.
/usr/bin/python3 - "$F" "$tmp" <<'PY'
import json, math, os, sys
src, out = sys.argv[1], sys.argv[2]
c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
turn = lambda p: [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]]
scene = json.load(open(os.path.join(src, "workbench.scene.json")))
for m in scene["meshes"]:
    m["vertices"] = [turn(v) for v in m["vertices"]]
for lum in scene["luminaires"]:
    lum["position"], lum["aim"] = turn(lum["position"]), turn(lum["aim"])
    lum["rotation_deg"] = lum.get("rotation_deg", 0.0) + 30.0
    lum["file"] = os.path.abspath(os.path.join(src, lum["file"]))
for t in scene["targets"]:
    for key in ("corner", "edge1", "edge2", "position", "view_direction"):
        if key in t:
            t[key] = turn(t[key])
json.dump(scene, open(os.path.join(out, "turned.scene.json"), "w"))
results = json.load(open(os.path.join(src, "workbench.results.json")))
results.pop("provenance")
json.dump(results, open(os.path.join(out, "turned.results.json"), "w"))
PY
"$cli" report "$tmp/turned.scene.json" --results "$tmp/turned.results.json" --allow-unverified \
  --date 2026-01-01 --out "$tmp/turned.pdf" > /dev/null
shot "$tmp/turned.pdf" "Floor plan" report-turned-plan -W 827 -H 820
shot "$tmp/turned.pdf" "Axonometric view" report-turned-model -W 827 -H 660
