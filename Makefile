# Two-command quick start: `make run` (paper figures on built-in defaults), `make test`.
PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin

.PHONY: run test test-portable lint bench docs figures clean

$(BIN)/.installed: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[dev]'
	touch $@

run: $(BIN)/.installed
	$(BIN)/mcsim paper --overwrite

# -n 3: the tests spread over three worker processes (pytest-xdist), one more than CI's 2
# cores: many tests wait on a subprocess's start, a Dask cluster or a signal, and with two
# workers the cores idled a fifth of the time (measured on 2 cores, 2026-11-29: -n 2 729 s
# wall for 1160 s of CPU, -n 3 585 s, the cores 99 % busy). --dist worksteal lets an idle
# worker take tests queued on another, and tests/conftest.py starts the slow ones first, so
# the runs of the README's and the guide's pages overlap the rest of the suite
# (--durations: the 25 slowest tests, where to look when the suite grows)
test: $(BIN)/.installed
	$(BIN)/python -m pytest -q -n 3 --dist worksteal --durations=25
	$(MAKE) --no-print-directory test-portable

# NumPy's SIMD targets dispatched at run time on this CPU (numpy 2.4 on an AVX2 machine:
# X86_V3, i.e. AVX2 + FMA3; on an AVX-512 one also X86_V4, AVX512_ICL...): all of them
# disabled leaves NumPy's baseline build (X86_V2). Baseline features cannot be disabled.
NPY_FOUND = import numpy; print(*numpy.show_config("dicts")["SIMD Extensions"]["found"])

# The golden, run-file and example-file tests once more on another code path of this machine: numba
# compiling for a generic x86-64 (no AVX, no FMA) into a fresh cache (never the native
# kernels), NumPy's dispatch narrowed to its baseline (an ImportWarning, i.e. a value
# NumPy refuses, is an error). The numbers then differ from the native ones by rounding,
# within the tolerance table of tests/tolerances.py.
test-portable: $(BIN)/.installed
	cache=$$(mktemp -d) && trap 'rm -rf "$$cache"' EXIT && \
	NUMBA_CPU_NAME=generic NUMBA_CACHE_DIR="$$cache" MCSIM_CACHE_DIR="$$cache" \
	NPY_DISABLE_CPU_FEATURES="$$($(BIN)/python -c '$(NPY_FOUND)')" \
	$(BIN)/python -W error::ImportWarning -m pytest -q tests/program/test_seed_golden.py tests/store/test_runfile.py \
		tests/program/test_examples.py

# The benchmarks (validation/README.md: what each measures and its targets), about 10 minutes
# on 2 cores; each writes its table to validation/out/ and exits 1 if a target is missed.
# Every benchmark runs even when one misses its target (timings move with the machine's load).
bench: $(BIN)/.installed
	status=0; for script in benchmark sweep_benchmark scaling memory; do \
		$(BIN)/python validation/$$script.py || status=1; done; exit $$status

# The documentation site (Sphinx, MyST; the tutorials executed): docs/_build/html/index.html.
# Warnings are errors, as in tests/program/test_docs_site.py.
docs: $(BIN)/.installed
	$(BIN)/python -m sphinx -W --keep-going -b html docs docs/_build/html

# Every figure in docs/ and docs/figures.json, the digest of each figure's inputs that
# tests/program/test_docs_figures.py checks (a few minutes on 2 cores)
figures: $(BIN)/.installed
	$(BIN)/python docs/make_figures.py

lint: $(BIN)/.installed
	$(BIN)/ruff check . && $(BIN)/ruff format --check .
	$(BIN)/lint-imports

clean:
	rm -rf $(VENV) *.egg-info .pytest_cache
