# voroforge developer tasks. `make run` and `make test` work on a fresh machine with Python >= 3.11.
PY ?= python3
VENV ?= .venv
BIN := $(VENV)/bin
PIP := $(BIN)/python -m pip install -q
LINT_PATHS := $(wildcard src tests benchmarks)

.PHONY: help run demo test lint format bench clean

help:
	@echo "make run    - install into $(VENV) and write the demo to out/"
	@echo "make test   - run the test suite"
	@echo "make lint   - ruff check and format check"
	@echo "make bench  - run benchmarks/bench_2d.py"
	@echo "make clean  - remove out/ and caches, numba's included (keeps $(VENV))"

# The virtual environment, created once.
$(BIN)/python:
	@$(PY) -c 'import sys; sys.exit(sys.version_info < (3, 11))' || \
		{ echo "voroforge needs Python >= 3.11; try: make PY=python3.12 ..." >&2; exit 1; }
	$(PY) -m venv $(VENV)

# Installs are redone only when pyproject.toml changes (the package itself is editable).
$(VENV)/.installed-run: pyproject.toml | $(BIN)/python
	$(PIP) -e .
	@touch $@

$(VENV)/.installed-test: pyproject.toml | $(BIN)/python
	$(PIP) -e '.[test]'
	@touch $@

$(VENV)/.installed-bench: pyproject.toml | $(BIN)/python
	$(PIP) -e '.[bench]'
	@touch $@

run: $(VENV)/.installed-run
	$(BIN)/voroforge demo -o out

demo: run

test: $(VENV)/.installed-test
	$(BIN)/python -m pytest

lint: $(VENV)/.installed-test
	$(BIN)/ruff check $(LINT_PATHS)
	$(BIN)/ruff format --check $(LINT_PATHS)

format: $(VENV)/.installed-test
	$(BIN)/ruff format $(LINT_PATHS)

bench: $(VENV)/.installed-bench
	$(BIN)/python benchmarks/bench_2d.py

# numba's cache checks only the file of the function it caches: after editing a kernel that
# others call (predicates.py, say), clear it or the callers keep the old code.
clean:
	rm -rf out .pytest_cache .ruff_cache .hypothesis
	find src -name '*.nbi' -delete -o -name '*.nbc' -delete
