# Two commands on a fresh machine: `make demo` and `make test`.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
# The compiled core: its sources, and the stamp of the build installed from them.
CORE_SOURCES := CMakeLists.txt $(shell find cpp -name '*.hpp' -o -name '*.cpp' 2>/dev/null)
CORE_STAMP   := $(VENV)/.core-built
# The development build turns compiler warnings into errors (-Wall -Wextra, clean).
CORE_FLAGS   := --config-settings=cmake.define.KM_WERROR=ON

.PHONY: demo test suite lint docs notebook bench sanitize clean ctest

# --no-compile: pip would byte-compile every module of every dependency (about 9,000
# files, 20-30 s of one core), most of which nothing here imports; the suite reads
# its bytecode from .venv/pycache anyway (below), and any other process compiles a module
# the first time it imports it.
#
# After `make demo` (kinematica installed and its core built from these very sources and
# pyproject.toml), the test tools alone are added: installing the package again would
# compile the whole core a second time (pip builds it in a new, isolated environment).
TEST_EXTRA := import subprocess, sys, tomllib; \
  extra = tomllib.load(open("pyproject.toml", "rb"))["project"]["optional-dependencies"]["test"]; \
  subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", "--no-compile", *extra])
$(STAMP): pyproject.toml
	test -d $(VENV) || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --no-compile --upgrade pip
	if [ -f $(DEMO_STAMP) ] && [ -z "$$(find pyproject.toml $(CORE_SOURCES) -newer $(DEMO_STAMP))" ]; \
	then $(BIN)/python -c '$(TEST_EXTRA)'; \
	else $(BIN)/python -m pip install --quiet --no-compile $(CORE_FLAGS) -e '.[test]'; fi
	touch $(STAMP)

# An edit of the core rebuilds it (incrementally, in build/) and reinstalls it; right
# after an install of the whole package (above), which built it, there is nothing to rebuild.
$(CORE_STAMP): $(STAMP) $(CORE_SOURCES)
	if [ -z "$$(find $(CORE_SOURCES) -newer $(STAMP))" ]; then :; \
	else $(BIN)/python -m pip install --quiet --no-deps $(CORE_FLAGS) -e .; fi
	touch $(CORE_STAMP)

# The demo needs numpy and the compiled core, nothing more: on a fresh clone it installs
# kinematica alone (no extra), in the same venv that `make test` later completes with the
# test tools. A venv the tests have set up is used as it is.
DEMO_STAMP := $(VENV)/.installed-core
$(DEMO_STAMP): pyproject.toml $(CORE_SOURCES)
	test -d $(VENV) || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --no-compile $(CORE_FLAGS) -e .
	touch $(DEMO_STAMP)

demo:
	@if [ -f $(STAMP) ]; then $(MAKE) --no-print-directory $(CORE_STAMP); \
	else $(MAKE) --no-print-directory $(DEMO_STAMP); fi
	$(BIN)/python examples/01_demo.py

lint: $(CORE_STAMP)
	$(BIN)/ruff check src tests benchmarks examples
	$(BIN)/ruff format --check src tests benchmarks examples
	$(BIN)/mypy
	$(BIN)/lint-imports

# The C++ tests, the checks (lint) and the test suite run side by side: the C++ build
# keeps one core busy for a minute with its general 6R and mypy for about 20 s, which the
# suite's two workers would otherwise wait for. Any failing fails `make test`.
test: $(CORE_STAMP)
	$(MAKE) --no-print-directory -j3 ctest lint suite

# The core's headers tested from C++ alone (tests/cpp: FK against a hand-worked 2R, one
# closed form per family built in C++, the general 6R on a CRX-like arm), by ctest; Eigen
# from the venv's cmeel-eigen (found as the core's build finds it).
CPP_TESTS  := build/cpp-tests
CMEEL_PATH := import pathlib, sys; \
  print(";".join(str(p) for p in (pathlib.Path(e) / "cmeel.prefix" for e in sys.path if e) if p.is_dir()))
ctest: $(STAMP)
	cmake -S tests/cpp -B $(CPP_TESTS) -G Ninja -DCMAKE_BUILD_TYPE=Release \
	  -DCMAKE_PREFIX_PATH="$$($(BIN)/python -c '$(CMEEL_PATH)')" > /dev/null
	cmake --build $(CPP_TESTS)
	ctest --test-dir $(CPP_TESTS) --output-on-failure

# The tests build the docs site too (tests/test_docs.py), with --strict. The Python
# processes they start (the console script, the examples, Dask's workers) read bytecode
# compiled once, kept in the venv, even where PYTHONDONTWRITEBYTECODE is set (each would
# otherwise compile the whole package again: about 0.2 s of CPU a start). worksteal: an
# idle worker takes tests queued for the other, so neither waits for the other's tail.
# One BLAS thread a worker: two workers already fill the two cores, and OpenBLAS's own
# threads fighting them made a 0.2 s least-squares fit take 5-14 s of wall time.
suite: $(CORE_STAMP)
	env -u PYTHONDONTWRITEBYTECODE PYTHONPYCACHEPREFIX="$(CURDIR)/$(VENV)/pycache" \
	  OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 MKL_NUM_THREADS=1 \
	  $(BIN)/pytest -n 2 --dist worksteal

# The documentation site, into site/ (open site/index.html); --strict: a broken link or
# a missing reference entry fails the build.
docs: $(CORE_STAMP)
	$(BIN)/mkdocs build --strict

# Run the lecture-notes notebook and store its outputs (the docs site shows them).
notebook: $(CORE_STAMP)
	$(BIN)/python -c "import nbformat, nbclient; p = 'examples/lecture_notes.ipynb'; \
	nb = nbformat.read(p, as_version=4); nbclient.NotebookClient(nb, timeout=120, record_timing=False).execute(); \
	nbformat.write(nb, p)"

# The core built with AddressSanitizer and UndefinedBehaviorSanitizer (in its own venv
# and build folder), running the FK, IK and numeric tests: any invalid memory access or
# undefined behaviour aborts the run. Not part of `make test` (it takes minutes more).
SAN_VENV := .venv-sanitize
SAN_ENV  := ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 \
            UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
            LD_PRELOAD="$$(gcc -print-file-name=libasan.so) $$(gcc -print-file-name=libubsan.so)"
SAN_TESTS := tests/robot/test_robot.py tests/robot/test_robot_jacobian.py tests/dh/test_link.py tests/dh/test_lines.py \
             tests/robot/test_makers_ik.py tests/motion/test_optimal.py tests/motion/test_scurve.py tests/motion/test_scurve_via.py tests/motion/test_scurve_via_core.py \
             tests/robot/test_urdf_exact.py tests/robot/test_self_motion.py \
             $(wildcard tests/core/test_*.py tests/ik/test_*.py tests/ik/analytic/test_*.py)

sanitize:
	test -d $(SAN_VENV) || $(PYTHON) -m venv $(SAN_VENV)
	$(SAN_VENV)/bin/python -m pip install --quiet --upgrade pip
	$(SAN_VENV)/bin/python -m pip install --quiet -e '.[test]' \
	  --config-settings=cmake.define.KM_SANITIZE=ON --config-settings=build-dir=build/sanitize
	$(SAN_ENV) $(SAN_VENV)/bin/pytest -q -p no:cacheprovider -p no:warnings $(sort $(SAN_TESTS))

bench: $(CORE_STAMP)
	@for peer in pin roboticstoolbox-python eaik ssik; do \
	  $(BIN)/python -m pip install --quiet $$peer >/dev/null 2>&1 \
	    || echo "bench: $$peer not installable here; the benchmarks skip it"; \
	done
	$(BIN)/python benchmarks/fk.py
	@if [ -f benchmarks/ik.py ]; then $(BIN)/python benchmarks/ik.py; fi
	$(BIN)/python benchmarks/ik_makers.py
	$(BIN)/python benchmarks/robot_files.py
	$(BIN)/python benchmarks/urdf.py
	$(BIN)/python benchmarks/xacro_expansion.py
	$(BIN)/python benchmarks/motion.py
	$(BIN)/python benchmarks/scurve.py
	$(BIN)/python benchmarks/optimal.py
	$(BIN)/python benchmarks/viz.py
	$(BIN)/python benchmarks/design.py
	$(BIN)/python benchmarks/calibration.py  # pybotics, its peer, pins numpy<2: by hand, --no-deps
	$(BIN)/python benchmarks/reach.py
	$(BIN)/python benchmarks/ik_parallel_near.py --timing-only
	$(BIN)/python benchmarks/symbolic.py
	$(BIN)/python benchmarks/ik_small.py
	$(BIN)/python benchmarks/ik_redundant.py
	$(BIN)/python benchmarks/ik_held.py
	$(BIN)/python benchmarks/ik_srs.py
	$(BIN)/python benchmarks/robustness.py
	$(BIN)/python benchmarks/audit_ik.py --poses 300  # the full audit (10,000 a class) by hand
	$(BIN)/python benchmarks/audit_unreachable.py --arms 30 --edges 10

clean:
	rm -rf $(VENV) $(SAN_VENV) build dist site .pytest_cache .mypy_cache .ruff_cache
