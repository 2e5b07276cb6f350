#!/usr/bin/env bash
# scripts/install-workbench.sh into a throw-away HOME, both ways (symlink and copy): freecadcmd
# must then import the workbench from the user Mod folder and load documents that use it.
set -euo pipefail
command -v freecadcmd >/dev/null || { echo "freecadcmd not found: skipped"; exit 77; }
repo="$(cd "$(dirname "$0")/../.." && pwd)"
for mode in link copy; do
  home="$(mktemp -d)"
  trap 'rm -rf "$home"' EXIT
  args=()
  [ "$mode" = copy ] && args+=(--copy)
  HOME="$home" XDG_DATA_HOME= "$repo/scripts/install-workbench.sh" "${args[@]}"
  out="$(cd "$home" && HOME="$home" freecadcmd -c "
import sys, FreeCAD, lighting
where = lighting.__file__
print('LIGHTING_AT', where)
assert where.startswith(FreeCAD.getUserAppDataDir()), where
doc = FreeCAD.newDocument('T')
lighting.make_luminaire(doc)
doc.saveAs('$home/t.FCStd')
FreeCAD.closeDocument('T')
doc = FreeCAD.openDocument('$home/t.FCStd')
proxy = doc.getObject('Luminaire').Proxy
print('PROXY', type(proxy).__module__)
from lighting import luminaire_library
shipped = luminaire_library.shipped_folder()
count = len(luminaire_library.photometric_files(shipped)) if shipped else 0
print('LUMINAIRES', count, shipped)
sys.exit(0 if type(proxy).__module__ == 'lighting.objects.luminaire' and count == 8 else 3)
" 2>&1)" || { echo "$out"; echo "test_install: $mode install: freecadcmd failed"; exit 1; }
  echo "$out" | grep -E "LIGHTING_AT|PROXY|LUMINAIRES"
  for dir in "$home/.FreeCAD/Mod/Lighting" "$home/.local/share/FreeCAD/Mod/Lighting"; do
    [ -e "$dir/InitGui.py" ] || { echo "test_install: $dir missing"; exit 1; }
  done
  HOME="$home" XDG_DATA_HOME= "$repo/scripts/install-workbench.sh" --uninstall
  [ ! -e "$home/.local/share/FreeCAD/Mod/Lighting" ] || { echo "uninstall left files"; exit 1; }
  rm -rf "$home"
  trap - EXIT
  echo "test_install: $mode install OK"
done
