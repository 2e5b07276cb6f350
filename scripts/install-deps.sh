#!/usr/bin/env bash
# Installs every Debian 12 package the project needs (build, tests, FreeCAD workbench, Vulkan).
# Idempotent; run as root or with sudo available. Pass --minimal to skip the FreeCAD GUI extras.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
PKGS=(
  build-essential cmake ninja-build pkg-config git ccache
  libembree-dev libtbb-dev libglm-dev nlohmann-json3-dev libcli11-dev libassimp-dev librandom123-dev
  libboost-math-dev libssl-dev libnova-dev libeigen3-dev zlib1g-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  pybind11-dev python3-pybind11 python3-dev python3-numpy python3-pytest python3-jsonschema
  libvulkan-dev mesa-vulkan-drivers glslc glslang-tools spirv-tools vulkan-tools
  vulkan-validationlayers
  freecad xvfb xauth python3-matplotlib
  python3-jinja2 weasyprint poppler-utils fonts-dejavu-core
  libstb-dev
  openmpi-bin libopenmpi-dev python3-mpi4py
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PKGS[@]} packages already installed"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
