#!/usr/bin/env bash
# Installs the FreeCAD workbench "Lighting" (Workbench/) for the current user, so that
# `freecad` and `freecadcmd` find it, and makes the native module `lightsolver` importable.
#
#   scripts/install-workbench.sh                 symlink into every user Mod folder
#   scripts/install-workbench.sh --copy          copy instead of symlink
#   scripts/install-workbench.sh --mod-dir DIR   install into DIR only (DIR/Lighting)
#   scripts/install-workbench.sh --solver-path DIR   folder of lightsolver.cpython-*.so
#                                                (default: newest build*/NativeSolver/python)
#   scripts/install-workbench.sh --uninstall     remove what this script installed
#
# User Mod folders: ~/.FreeCAD/Mod (upstream 0.20), ~/.local/share/FreeCAD/Mod (Debian's 0.20,
# 0.21 and 1.0), plus the one FreeCAD reports (FREECAD_USER_HOME is honoured).
# The solver folder goes into a .pth file in /usr/bin/python3's user site-packages (FreeCAD
# embeds that interpreter, so plain python3 and FreeCAD both see it). A symlinked workbench
# also finds build folders of its own source tree without it.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
src="$repo/Workbench"
mode=link
uninstall=0
mod_dirs=()
solver_path=""

while [ $# -gt 0 ]; do
  case "$1" in
    --copy) mode=copy ;;
    --mod-dir) mod_dirs+=("$2"); shift ;;
    --solver-path) solver_path="$2"; shift ;;
    --uninstall) uninstall=1 ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    *) echo "install-workbench: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done

if [ ${#mod_dirs[@]} -eq 0 ]; then
  mod_dirs=("$HOME/.FreeCAD/Mod" "${XDG_DATA_HOME:-$HOME/.local/share}/FreeCAD/Mod")
  if command -v freecadcmd >/dev/null 2>&1; then
    reported="$(freecadcmd -c "import FreeCAD; print('USERDIR=' + FreeCAD.getUserAppDataDir())" 2>/dev/null \
                | sed -n 's/^USERDIR=//p' | tail -n 1 || true)"
    if [ -n "$reported" ]; then mod_dirs+=("${reported%/}/Mod"); fi
  fi
fi

site_dir="$(/usr/bin/python3 -m site --user-site)"
pth="$site_dir/lightsolver-build.pth"

if [ "$uninstall" -eq 1 ]; then
  for dir in "${mod_dirs[@]}"; do
    if [ -L "$dir/Lighting" ] || [ -f "$dir/Lighting/.installed-by-lighting" ]; then
      rm -rf "$dir/Lighting"
      echo "install-workbench: removed $dir/Lighting"
    fi
  done
  rm -f "$pth"
  exit 0
fi

declare -A done_dirs=()
for dir in "${mod_dirs[@]}"; do
  real="$(realpath -m "$dir")"
  [ -n "${done_dirs[$real]:-}" ] && continue
  done_dirs[$real]=1
  mkdir -p "$dir"
  target="$dir/Lighting"
  if [ -e "$target" ] && [ ! -L "$target" ] && [ ! -f "$target/.installed-by-lighting" ]; then
    echo "install-workbench: $target exists and was not installed by this script; skipped" >&2
    continue
  fi
  rm -rf "$target"
  if [ "$mode" = copy ]; then
    cp -r "$src" "$target"
    # The shipped data (photometric files, the EN 12464-1 table) lives beside Workbench/ in
    # the source tree; a copy takes it along (lighting/resources.py looks in both places).
    mkdir -p "$target/Resources"
    cp -r "$repo/Resources/luminaires" "$target/Resources/luminaires"
    cp -r "$repo/Resources/requirements" "$target/Resources/requirements"
    find "$target" -name __pycache__ -prune -exec rm -rf {} +
    touch "$target/.installed-by-lighting"
  else
    ln -s "$src" "$target"
  fi
  echo "install-workbench: $target -> $src ($mode)"
done

if [ -z "$solver_path" ]; then
  newest=""
  for so in "$repo"/build*/NativeSolver/python/lightsolver*.so; do
    [ -e "$so" ] || continue
    if [ -z "$newest" ] || [ "$so" -nt "$newest" ]; then newest="$so"; fi
  done
  [ -n "$newest" ] && solver_path="$(dirname "$newest")"
fi
if [ -n "$solver_path" ]; then
  mkdir -p "$site_dir"
  realpath "$solver_path" > "$pth"
  echo "install-workbench: lightsolver path $(cat "$pth") written to $pth"
else
  echo "install-workbench: lightsolver module not built yet (cmake --build build); the" \
       "workbench works without it except for solving, or set LIGHTSOLVER_PYTHONPATH" >&2
fi

# Smoke test: the module loads in freecadcmd.
if command -v freecadcmd >/dev/null 2>&1; then
  freecadcmd -c "import lighting, sys; ok, info = lighting.solver_available(); \
print('install-workbench: lighting', lighting.__version__, '| solver:', info if ok else 'not available')" \
    2>/dev/null | grep '^install-workbench' || echo "install-workbench: freecadcmd cannot import lighting" >&2
fi
