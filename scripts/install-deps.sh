#!/usr/bin/env bash
# Installs every Debian 12 package forestwind needs to build, test and run. Run as root.
# This is the one list of dependencies; it is safe to run again (apt-get skips what is installed).
#
#   bash scripts/install-deps.sh               check for known conflicts, then apt-get update and install
#   bash scripts/install-deps.sh --check-only  only check for known conflicts (needs no root, changes nothing)
#
# Exit codes: 0 done (or no conflict found), 1 not root, 2 bad usage,
# 3 an installed package conflicts with the list below (nothing was installed or removed).
#
# For tests only: when FORESTWIND_DEPS_ASSUME_INSTALLED is set (even to ""), the conflict check treats
# exactly the space-separated package names in it as installed instead of asking dpkg.
set -euo pipefail

usage() {
  echo "usage: bash scripts/install-deps.sh [--check-only]"
}

check_only=0
if [ $# -gt 1 ]; then
  usage >&2
  exit 2
fi
case "${1-}" in
  "") ;;
  --check-only) check_only=1 ;;
  -h | --help)
    usage
    exit 0
    ;;
  *)
    echo "install-deps.sh: unknown argument '$1'" >&2
    usage >&2
    exit 2
    ;;
esac

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config clang-format
  # fuzzing and sanitizers (make fuzz, make sanitize): clang 14 and its runtimes (libFuzzer, ASan, UBSan),
  # which clang only recommends, so --no-install-recommends would leave them out
  clang libclang-rt-14-dev
  # OpenCL: headers, C++ bindings, ICD loader, PoCL (the CPU implementation CI runs on), clinfo
  opencl-headers opencl-clhpp-headers ocl-icd-opencl-dev pocl-opencl-icd clinfo
  # MPI: OpenMPI's library and its launcher (mpirun), one rank per device (docs/parallel.md)
  libopenmpi-dev openmpi-bin
  # numerics
  libeigen3-dev libspectra-dev libglm-dev libmuparser-dev libfftw3-dev
  # output: VTK for ParaView, OpenVDB for Houdini/Blender (its CMake module needs boost-iostreams)
  libvtk9-dev libopenvdb-dev libboost-iostreams-dev
  # GIS (io/gis): terrain from any raster GDAL reads (GeoTIFF, ESRI ASCII), with its CRS
  libgdal-dev
  # statistics (io/StatsNetcdf): stats.nc as NetCDF-4; ncdump to look into it, and xarray, what LES users
  # open it with (the tests open it so)
  libnetcdf-dev netcdf-bin python3-xarray python3-netcdf4
  # pictures (viz/): cairo draws without an X server or GL; DejaVu is the face of their text
  libcairo2-dev fonts-dejavu-core
  # render decodes a frame's cell offsets (LZ4 or zlib, as VTK stores them) before VTK reads the file
  liblz4-dev zlib1g-dev
  # command line, config, logging, tests
  libcli11-dev libyaml-cpp-dev libfmt-dev libspdlog-dev catch2
)

# is_present PACKAGE: true when dpkg has PACKAGE unpacked (installed or part way there), which is
# when apt honours its Conflicts. Removed-but-not-purged (config-files) packages do not count.
is_present() {
  if [ -n "${FORESTWIND_DEPS_ASSUME_INSTALLED+set}" ]; then
    [[ " ${FORESTWIND_DEPS_ASSUME_INSTALLED} " == *" $1 "* ]]
    return
  fi
  dpkg-query -W -f='${db:Status-Status}\n' "$1" 2>/dev/null | grep -qvxE '(not-installed|config-files)?'
}

# Debian 12 (apt-cache show): libvtk9-dev depends on python3-vtk9 (same version), and
# python3-paraview 5.11 declares "Conflicts: python3-vtk9" (both ship the Python modules vtk and
# vtkmodules). apt-get install would stop with an unresolvable conflict; say why and what to do first.
check_conflicts() {
  if is_present python3-paraview; then
    cat >&2 <<'MSG'
install-deps.sh: python3-paraview (ParaView's Python support) is installed, and Debian 12 cannot
install forestwind's dependencies next to it. Nothing has been installed or removed.

Why: forestwind builds against VTK 9 from the package libvtk9-dev, and libvtk9-dev depends on
python3-vtk9. python3-paraview declares "Conflicts: python3-vtk9" (both ship the Python modules
vtk and vtkmodules), so Debian 12 cannot have python3-paraview and python3-vtk9 installed together
and apt-get would refuse to install libvtk9-dev.

Choose one:
  (a) Remove ParaView's Python support on this machine, then run this script again:
        sudo apt-get remove python3-paraview
      What it costs: the ParaView application (package paraview) stays and still opens forestwind's
      output, but it loses everything that needs Python: the Python Shell, Python tracing and
      scripting, pvpython, `paraview --script`, and Python-based filters such as the Programmable
      Filter and Python Calculator. apt-get lists every package it would remove before it asks;
      packages that depend on python3-paraview (for example pan-tomography) go with it.
      To undo later: sudo apt-get install python3-paraview (apt then removes python3-vtk9 and
      libvtk9-dev, so forestwind can no longer be built here).
  (b) Keep ParaView's Python here and build forestwind elsewhere: in a Debian 12 container
      (for example `docker run -it -v "$PWD":/src debian:12`), a Debian 12 chroot (debootstrap
      bookworm), or another machine. Run this script there, and open the output files with ParaView
      here.
MSG
    return 1
  fi
  return 0
}

if ! check_conflicts; then
  exit 3
fi
if [ "$check_only" -eq 1 ]; then
  echo "install-deps.sh: no known conflict with the installed packages"
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps.sh: run as root (it calls apt-get)" >&2
  exit 1
fi

export DEBIAN_FRONTEND=noninteractive
apt-get update
apt-get install -y --no-install-recommends "${packages[@]}"
