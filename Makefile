# Two commands on a fresh machine: `make run` and `make test`.
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
# Keep BLAS single-threaded: tasks are parallelised by the sweep executor, not by BLAS.
export OMP_NUM_THREADS ?= 1
export OPENBLAS_NUM_THREADS ?= 1
export MKL_NUM_THREADS ?= 1
export MPLBACKEND ?= Agg

.PHONY: run test validate bench lint docs clean

$(BIN)/activate:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

# The docs extra is part of the test install: tests/test_docs_build.py builds the docs.
$(VENV)/.installed: $(BIN)/activate pyproject.toml
	$(BIN)/python -m pip install --quiet -e ".[test,topography,docs]"
	touch $@

$(VENV)/.installed-bench: $(VENV)/.installed
	$(BIN)/python -m pip install --quiet -e ".[test,bench,topography]"
	touch $@

# A second `make run` replaces the results of the first (its solves come from the cache).
run: $(VENV)/.installed
	$(BIN)/rubbercontact run --output results --overwrite

test: $(VENV)/.installed
	$(BIN)/python -m pytest -q -m "not slow"

validate: $(VENV)/.installed
	$(BIN)/python -m pytest -q -m slow
	$(BIN)/python -m studies validate

bench: $(VENV)/.installed-bench
	$(BIN)/python benchmarks/run_all.py
	$(BIN)/python benchmarks/collect.py

# The documentation site (Sphinx; examples/plot_*.py run on their reduced settings for the
# gallery) with warnings as errors -> docs/_build/html.
docs: $(VENV)/.installed
	$(BIN)/python -m pip install --quiet -e ".[docs]"
	$(BIN)/sphinx-build -W --keep-going -b html docs docs/_build/html

lint: $(VENV)/.installed
	$(BIN)/ruff check src tests benchmarks studies

clean:
	rm -rf $(VENV) results docs/_build docs/api/generated docs/auto_examples
