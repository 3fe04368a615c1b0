# Quick start: `make` runs every benchmark and prints the results table;
# `make test` runs the test suite. Both install missing dependencies first.
.PHONY: run test convergence deps clean

run: deps
	python3 scripts/run_benchmarks.py

test: deps
	python3 tests/run_tests.py

# Hertz benchmarks refined from h = a/10 to a/160 (a few minutes): results/hertz_convergence.md
convergence: deps
	python3 scripts/hertz_convergence.py --cases plane,circle_vertical,circle_linearized,circle_exact

deps:
	@bash scripts/install_deps.sh

clean:
	rm -rf results
