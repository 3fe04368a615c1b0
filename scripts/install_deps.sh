#!/usr/bin/env bash
# Installs what the suite needs on Debian/Ubuntu, skipping what is already there:
# FreeFEM with its plugins (ff-Ipopt, iovtk, msh3, gsl) and its plugin compiler ff-c++ (with g++:
# the suite's own plugins, plugin/*.cpp), gmsh, python3 with matplotlib, pytest and pytest-xdist
# (the tests), GNU time
# (the bench's peak-memory measurement), Chromium (the report's test in a real browser), sequential MUMPS's and METIS's headers (the condensed solve's plugin),
# OpenMPI and the MPI MUMPS (runs on several processes),
# and OpenBLAS: Debian's
# MUMPS (IPOPT's linear solver) otherwise runs on the reference BLAS, and the factorisations
# that dominate every contact solve take 4x longer (3D Hertz, 23.6k dofs: 53 s -> 12 s).
# Called by every make target; uses sudo when not root.
set -euo pipefail

have_plugin() {
  for dir in /usr/lib/freefem++ /usr/local/lib/ff++/*/lib /usr/lib/ff++/*/lib; do
    [ -f "$dir/$1.so" ] && return 0
  done
  return 1
}

missing=()
# need COMMAND PACKAGE: every external command the Makefile, scripts, tests and drivers call
# (tests/check_commands.py holds this list against the code)
need() { command -v "$1" >/dev/null 2>&1 || missing+=("$2"); }
need FreeFem++ freefem++
have_plugin ff-Ipopt || missing+=(libfreefem++)
need ff-c++ libfreefem++-dev
need g++ g++
need gmsh gmsh
need python3 python3
need /usr/bin/python3 python3   # Debian's interpreter: matplotlib, DOLFINx (bench) and the peers' venv
need /usr/bin/time time
need awk mawk
dpkg -s libopenblas0-pthread >/dev/null 2>&1 || missing+=(libopenblas0-pthread)
# sequential MUMPS's headers and library, for the condensed solve's plugin (plugin/schur_condensation.cpp)
dpkg -s libmumps-seq-dev >/dev/null 2>&1 || missing+=(libmumps-seq-dev)
dpkg -s libmetis-dev >/dev/null 2>&1 || missing+=(libmetis-dev)
# LAPACK to link the friction polish's dense KKT solve (plugin/dense_kkt.cpp: -llapack -lblas),
# OpenBLAS's as at run time
dpkg -s libopenblas-pthread-dev >/dev/null 2>&1 || missing+=(libopenblas-pthread-dev)
# runs on several processes (docs/scaling.md): mpirun, mpicxx and the MPI MUMPS for plugin/mpi_bridge.cpp
need mpirun openmpi-bin
need mpicxx libopenmpi-dev
dpkg -s libmumps-dev >/dev/null 2>&1 || missing+=(libmumps-dev)
# the report's figures: matplotlib for Debian's python3 (the Makefile runs /usr/bin/python3)
dpkg -s python3-matplotlib >/dev/null 2>&1 || missing+=(python3-matplotlib)
# the tests: pytest, and pytest-xdist to run them on every core
dpkg -s python3-pytest >/dev/null 2>&1 || missing+=(python3-pytest)
dpkg -s python3-pytest-xdist >/dev/null 2>&1 || missing+=(python3-pytest-xdist)
# the report as a reader sees it: tests/test_report.py renders report.html in headless Chromium
need chromium chromium

# --peers (make bench PEERS=1): DOLFINx for scripts/peers/dolfinx_hertz.py, and python3-venv for the venv in
# which scripts/peers/felupe_oring.py installs FElupe with pip
if [ "${1:-}" = "--peers" ]; then
  dpkg -s python3-dolfinx >/dev/null 2>&1 || missing+=(python3-dolfinx)
  dpkg -s python3-venv >/dev/null 2>&1 || missing+=(python3-venv)
fi

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

# a package may be listed twice (two commands it provides)
mapfile -t missing < <(printf '%s\n' "${missing[@]}" | sort -u)
echo "installing: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null 2>&1 || { echo "error: need root or sudo to install ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "installed: ${missing[*]}"
