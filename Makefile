# Quick start: `make` runs every benchmark and prints the results table;
# `make test` runs the test suite. Both install missing dependencies first.
.PHONY: run test deps clean

run: deps
	python3 scripts/run_benchmarks.py

test: deps
	python3 tests/run_tests.py

deps:
	@bash scripts/install_deps.sh

clean:
	rm -rf results
