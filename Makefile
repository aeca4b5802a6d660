# Two commands on a fresh machine: `make run` and `make test`.
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
# Keep BLAS single-threaded: tasks are parallelised by the sweep executor, not by BLAS.
export OMP_NUM_THREADS ?= 1
export OPENBLAS_NUM_THREADS ?= 1
export MKL_NUM_THREADS ?= 1
export MPLBACKEND ?= Agg

.PHONY: run test validate bench lint clean

$(BIN)/activate:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

$(VENV)/.installed: $(BIN)/activate pyproject.toml
	$(BIN)/python -m pip install --quiet -e ".[test,topography]"
	touch $@

$(VENV)/.installed-bench: $(VENV)/.installed
	$(BIN)/python -m pip install --quiet -e ".[test,bench,topography]"
	touch $@

run: $(VENV)/.installed
	$(BIN)/rubbercontact run --output results

test: $(VENV)/.installed
	$(BIN)/python -m pytest -q -m "not slow"

validate: $(VENV)/.installed
	$(BIN)/python -m pytest -q -m slow
	$(BIN)/python -m studies validate

bench: $(VENV)/.installed-bench
	$(BIN)/python benchmarks/run_all.py
	$(BIN)/python benchmarks/collect.py

lint: $(VENV)/.installed
	$(BIN)/ruff check src tests benchmarks studies

clean:
	rm -rf $(VENV) results
