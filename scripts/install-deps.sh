#!/usr/bin/env bash
# Installs every Debian 12 package forestwind needs to build, test and run. Run as root.
# This is the one list of dependencies; it is safe to run again (apt-get skips what is installed).
set -euo pipefail

if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps.sh: run as root (it calls apt-get)" >&2
  exit 1
fi

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config clang-format
  # OpenCL: headers, C++ bindings, ICD loader, PoCL (the CPU implementation CI runs on), clinfo
  opencl-headers opencl-clhpp-headers ocl-icd-opencl-dev pocl-opencl-icd clinfo
  # numerics
  libeigen3-dev libspectra-dev libglm-dev libmuparser-dev
  # output: VTK for ParaView, OpenVDB for Houdini/Blender (its CMake module needs boost-iostreams)
  libvtk9-dev libopenvdb-dev libboost-iostreams-dev
  # command line, config, logging, tests
  libcli11-dev libyaml-cpp-dev libfmt-dev libspdlog-dev catch2
)

export DEBIAN_FRONTEND=noninteractive
apt-get update
apt-get install -y --no-install-recommends "${packages[@]}"
