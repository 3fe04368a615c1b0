# Quick start: `make` runs every benchmark and writes the report (results/REPORT.md and
# results/report.html); `make test` runs the test suite. Both install missing dependencies
# first. Benchmarks run in parallel, one per core (JOBS=1 for one at a time).
.PHONY: run report table test convergence sweep bench deps clean workspace check-driver reserved-names
# Debian's interpreter, where the deps script installs matplotlib (a pyenv shim may shadow it)
PYTHON := $(shell test -x /usr/bin/python3 && echo /usr/bin/python3 || echo python3)
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
N ?= 200
# The variables a user sets (make K=hertz, DIR=..., N=..., JOBS=..., PEERS=1) reach the recipes as
# environment variables, quoted by the shell ("$$K"), never as command text: make pastes $(K) into
# the line it hands the shell, where K='zz; touch M #' ran touch. (After the defaults: an export
# before them defined the names empty, and ?= then kept them so.)
export K DIR N JOBS PEERS F
NAMES = $(shell $(PYTHON) scripts/run_benchmarks.py --names)

run: deps
	@$(MAKE) --no-print-directory -j"$$JOBS" report

# the report first (a failing benchmark shows red in it), then the verdict table, whose exit code
# fails `make` when a verdict fails
report: $(addprefix benchmark-,$(NAMES)) convergence-quick
	@$(PYTHON) scripts/report.py
	@$(PYTHON) scripts/run_benchmarks.py --table

benchmark-%:
	@$(PYTHON) scripts/run_benchmarks.py --only $*

# Hertz refinement study for the report (h = a/10 .. a/80, about a minute)
convergence-quick:
	@$(PYTHON) scripts/hertz_convergence.py --levels 10,20,40,80 --cases plane,circle_vertical,circle_exact

# pytest over tests/test_*.py, one worker per core, the slowest tests listed; `make test K=hertz`
# runs the tests whose names contain hertz
test: deps
	$(PYTHON) -m pytest tests -n "$$JOBS" --durations=15 -p no:cacheprovider $${K:+"-k$$K"}

# Hertz benchmarks refined from h = a/10 to a/160 (a few minutes): results/hertz_convergence.md
convergence: deps
	$(PYTHON) scripts/hertz_convergence.py --cases plane,circle_vertical,circle_linearized,circle_exact

# timings: Hertz from 10k to 1M DOFs, the cost of contact, IPOPT against Newton, 3D, the
# volumetric forms, two bodies: results/performance/PERFORMANCE.md; then the 3D sphere (67k to 508k
# DOFs) and the 3D rubber indentation on 1 process, 2 MPI processes and 2 threads (about 30 minutes):
# results/performance/SCALING.md
# PEERS=1: also DOLFINx's SNES-VI solve of the same Hertz meshes and FElupe on the O-ring
# (installs python3-dolfinx, and FElupe in a venv; 14 minutes in all on the 2-core machine)
bench: deps
	@if [ -n "$$PEERS" ]; then bash scripts/install_deps.sh --peers; fi
	$(PYTHON) scripts/performance/studies.py $${PEERS:+--peers}
	$(PYTHON) scripts/performance/scaling.py

# randomized parameter sets, checked for what must always hold (fixed seed; N=200 by default)
sweep: deps
	$(PYTHON) scripts/sweep.py "--n=$$N"

# a folder of your own for your own problem: `make workspace DIR=~/my_contact` (docs/writing_your_own_problem.md)
workspace: deps
	@bash scripts/workspace.sh

# a driver's names that hide FreeFEM's or the suite's: `make check-driver F=my_problem.edp`
check-driver:
	@$(PYTHON) scripts/check_driver.py "$$F"

# docs/reserved_names.md from include/, after a new law, obstacle or file (make test checks it)
reserved-names:
	@$(PYTHON) scripts/reserved_names.py > docs/reserved_names.md.tmp && mv docs/reserved_names.md.tmp docs/reserved_names.md

# Debian's packages, then the suite's plugins (each plugin/<name>.cpp says what it is for):
# headless, which freefem++.pref loads; run_control (exit codes, wall clock), files (no shell),
# fold_search (the fold guard), schur_condensation (the condensed solve), fast_assembly (the
# energy's matrices and forces), dense_kkt (the contact sets' KKT systems),
# site_narrowing (friction's solve on its sites' dofs), msh_loader (gmsh files) and
# vtu_writer (the results' .vtu), which include/ loads where they are used
PLUGIN_NAMES = headless run_control files fold_search schur_condensation fast_assembly dense_kkt site_narrowing msh_loader vtu_writer
# and mpi_bridge, not a FreeFEM plugin: the MPI MUMPS and MPI calls that run_control and
# schur_condensation open in their own symbol scope under FreeFem++-mpi (plugin/mpi_bridge.cpp)
PLUGINS = $(PLUGIN_NAMES:%=plugin/%.so) plugin/mpi_bridge.so
deps:
	@bash scripts/install_deps.sh
	@$(MAKE) -s --no-print-directory $(PLUGINS)

# each with FreeFEM's ff-c++, its log in plugin/build_<name>.log. A plugin names the libraries it
# links as FreeFEM's own plugins do, on a line "//ff-c++-LIBRARY-dep: metis mumps_seq"; their flags
# come from FreeFEM's WHERE_LIBRARY-config (Debian's ff-c++ -auto cannot find that file itself);
# libraries that file does not know (MUMPS's single precision) on a line "//ff-c++-LIBRARY-extra:"
WHERE_LIBRARY = /usr/include/freefem++/WHERE_LIBRARY-config
library_flags = $(foreach d,$(shell sed -n 's|^//ff-c++-LIBRARY-dep:||p' $(1)),$(shell sed -n 's|^$(d) LD ||p' $(WHERE_LIBRARY))) \
                $(shell sed -n 's|^//ff-c++-LIBRARY-extra:||p' $(1))
plugin/%.so: plugin/%.cpp
	@cd plugin && ff-c++ $*.cpp $(call library_flags,$<) > build_$*.log 2>&1 || { cat build_$*.log; exit 1; }
	@rm -f plugin/$*.o
plugin/run_control.so plugin/schur_condensation.so: plugin/mpi_bridge.hpp
plugin/mpi_bridge.so: plugin/mpi_bridge.cpp
	@mpicxx -shared -fPIC -O2 -o $@ $< -ldmumps -lsmumps -lmumps_common > plugin/build_mpi_bridge.log 2>&1 || { cat plugin/build_mpi_bridge.log; exit 1; }

clean:
	rm -rf results plugin/*.so plugin/build_*.log
