# Quick start: `make` runs every benchmark and writes the report (results/REPORT.md and
# results/report.html); `make test` runs the test suite. Both install missing dependencies
# first. Benchmarks run in parallel, one per core (JOBS=1 for one at a time).
.PHONY: run report table test convergence sweep bench deps clean workspace
# Debian's interpreter, where the deps script installs matplotlib (a pyenv shim may shadow it)
PYTHON := $(shell test -x /usr/bin/python3 && echo /usr/bin/python3 || echo python3)
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
NAMES = $(shell $(PYTHON) scripts/run_benchmarks.py --names)

run: deps
	@$(MAKE) --no-print-directory -j$(JOBS) report

report: $(addprefix benchmark-,$(NAMES)) convergence-quick
	@$(PYTHON) scripts/run_benchmarks.py --table
	@$(PYTHON) scripts/report.py

benchmark-%:
	@$(PYTHON) scripts/run_benchmarks.py --only $*

# Hertz refinement study for the report (h = a/10 .. a/80, about a minute)
convergence-quick:
	@$(PYTHON) scripts/hertz_convergence.py --levels 10,20,40,80 --cases plane,circle_vertical,circle_exact

test: deps
	$(PYTHON) tests/run_tests.py

# Hertz benchmarks refined from h = a/10 to a/160 (a few minutes): results/hertz_convergence.md
convergence: deps
	$(PYTHON) scripts/hertz_convergence.py --cases plane,circle_vertical,circle_linearized,circle_exact

# timings: Hertz from 10k to 1M DOFs, the cost of contact, IPOPT against Newton, 3D, the
# volumetric forms, two bodies: results/bench/BENCH.md
# PEERS=1: also DOLFINx's SNES-VI solve of the same Hertz meshes and FElupe on the O-ring
# (installs python3-dolfinx, and FElupe in a venv; 14 minutes in all on the 2-core machine)
bench: deps
	@if [ -n "$(PEERS)" ]; then bash scripts/install_deps.sh --peers; fi
	$(PYTHON) scripts/bench.py $(if $(PEERS),--peers)

# randomized parameter sets, checked for what must always hold (fixed seed; N=200 by default)
N ?= 200
sweep: deps
	$(PYTHON) scripts/sweep.py --n $(N)

# a folder of your own for your own problem: `make workspace DIR=~/my_contact` (docs/writing_your_own_problem.md)
workspace: deps
	@test -n "$(DIR)" || { echo "error: give the folder: make workspace DIR=<folder>"; exit 2; }
	@bash scripts/workspace.sh "$(DIR)"

# Debian's packages, then the suite's plugins: plugin/contact_runtime.cpp, which freefem++.pref loads,
# and the three that include/ loads where they are used
PLUGINS = plugin/contact_runtime.so plugin/schur_condensation.so plugin/fast_assembly.so plugin/msh_loader.so \
          plugin/vtu_writer.so
deps:
	@bash scripts/install_deps.sh
	@$(MAKE) -s --no-print-directory $(PLUGINS)

plugin/contact_runtime.so: plugin/contact_runtime.cpp
	@cd plugin && ff-c++ contact_runtime.cpp > build.log 2>&1 || { cat build.log; exit 1; }
	@rm -f plugin/contact_runtime.o

# the condensed solve's MUMPS Schur complement (include/solve/condensed_solve.idp)
plugin/schur_condensation.so: plugin/schur_condensation.cpp
	@cd plugin && ff-c++ schur_condensation.cpp -I/usr/include/mumps_seq -ldmumps_seq -lmetis > build_schur.log 2>&1 || { cat build_schur.log; exit 1; }
	@rm -f plugin/schur_condensation.o

# linear elasticity's stiffness on P1 tetrahedra (include/body/elastic_energy.idp) and the nodal
# penalty's coupling in plane strain (include/body/volumetric.idp)
plugin/fast_assembly.so: plugin/fast_assembly.cpp
	@cd plugin && ff-c++ fast_assembly.cpp > build_fast_assembly.log 2>&1 || { cat build_fast_assembly.log; exit 1; }
	@rm -f plugin/fast_assembly.o

# gmsh's msh 2.2 files read into a mesh3 with an odd number of vertices (include/mesh/gmsh_mesh.idp)
plugin/msh_loader.so: plugin/msh_loader.cpp
	@cd plugin && ff-c++ msh_loader.cpp > build_msh_loader.log 2>&1 || { cat build_msh_loader.log; exit 1; }
	@rm -f plugin/msh_loader.o

# the results' .vtu from the coefficient arrays (include/solver.idp)
plugin/vtu_writer.so: plugin/vtu_writer.cpp
	@cd plugin && ff-c++ vtu_writer.cpp > build_vtu_writer.log 2>&1 || { cat build_vtu_writer.log; exit 1; }
	@rm -f plugin/vtu_writer.o

clean:
	rm -rf results $(PLUGINS) plugin/build.log plugin/build_schur.log plugin/build_fast_assembly.log plugin/build_msh_loader.log plugin/build_vtu_writer.log
