#!/usr/bin/env bash
# Installs the Debian 12 packages Rumble needs, only those missing (idempotent; sudo if not root).
set -euo pipefail
PKGS=(cmake ninja-build g++ pkg-config clang-format
      libeigen3-dev libsuitesparse-dev libboost-dev nlohmann-json3-dev libspdlog-dev
      libgmsh-dev libfftw3-dev libssl-dev libgtest-dev libgmock-dev libbenchmark-dev libvalijson-dev
      liblapacke-dev  # the track's band Cholesky; bench/numerics compares our solvers with LAPACK's
      libopenblas0-pthread python3-matplotlib python3-numpy
      clang-14 libclang-rt-14-dev llvm-14  # the asan preset and the fuzz targets: libFuzzer, llvm-symbolizer
      lld  # the dev and asan presets link with it (cmake/RumbleLinker.cmake)
      chromium-headless-shell  # the study report's test renders it in a headless browser
      graphviz  # dot: tools/architecture_graph.sh draws docs/architecture.svg
      universal-ctags  # tools/check_function_length.py finds the functions
      libpetsc-real-dev libopenmpi-dev openmpi-bin  # the FEM soil's distributed back end (docs/toolchain.md section 9)
      python3-vtk9)  # tests/mpi/pvtu_agrees.py opens the ranks' .pvtu snapshots with VTK's reader
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null | grep -qx installed || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get -o DPkg::Lock::Timeout=600 update -qq
  $SUDO apt-get -o DPkg::Lock::Timeout=600 install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "all ${#PKGS[@]} packages already installed"
fi
