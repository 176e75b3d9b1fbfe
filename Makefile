# Two commands on a fresh machine: `make demo` and `make test`.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: demo test lint bench clean

$(STAMP): pyproject.toml
	test -d $(VENV) || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/python examples/01_demo.py

lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks examples
	$(BIN)/ruff format --check src tests benchmarks examples
	$(BIN)/mypy
	$(BIN)/lint-imports

test: lint
	$(BIN)/pytest -n 2

bench: $(STAMP)
	@for peer in pin roboticstoolbox-python eaik; do \
	  $(BIN)/python -m pip install --quiet $$peer >/dev/null 2>&1 \
	    || echo "bench: $$peer not installable here; the benchmarks skip it"; \
	done
	$(BIN)/python benchmarks/fk.py
	@if [ -f benchmarks/ik.py ]; then $(BIN)/python benchmarks/ik.py; fi
	$(BIN)/python benchmarks/robot_files.py
	$(BIN)/python benchmarks/urdf.py
	$(BIN)/python benchmarks/motion.py
	$(BIN)/python benchmarks/viz.py
	$(BIN)/python benchmarks/design.py
	$(BIN)/python benchmarks/symbolic.py
	$(BIN)/python benchmarks/ik_small.py

clean:
	rm -rf $(VENV) build dist .pytest_cache .mypy_cache .ruff_cache
