# study: every target sets up its own virtual environment in .venv on first use.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed-stamp
CONFIG ?= configs/default.toml
RUNS   ?= 10

.PHONY: help setup test test-generic sweep charts bench bench-compile bench-sweep-default bench-large validate coverage faults clean chromium

help:
	@echo "make setup     install into .venv and compile the solver kernels ahead (every target does it first)"
	@echo "make test      install (first time) and run the whole test suite"
	@echo "make test-generic  the precision-sensitive tests again, numba compiling for a generic x86-64 CPU (CI runs it)"
	@echo "make sweep     run the default study: $(CONFIG) -> outputs/<name>/"
	@echo "make charts    redraw the charts of the default study"
	@echo "make bench     benchmark the methods side by side, about 8 minutes on 2 quiet cores (docs/performance.md);"
	@echo "               one section alone: .venv/bin/study bench --section NAME (the names: study.bench.SECTIONS)"
	@echo "make bench-compile  the opt-in section: study compile into an empty cache, minutes (docs/performance_compile.md)"
	@echo "make bench-sweep-default  the opt-in section: the default study's sweep on about 100 points against workers,"
	@echo "               minutes (docs/performance_sweep-default.md)"
	@echo "make bench-large  the measured sweep of 10^5 points (docs/large_sweep.md: hours on 2 cores now, see its first note);"
	@echo "               POINTS=N: its grid thinned to N points, a smoke test of the command (outputs/large_sweep_N.md)"
	@echo "make validate  compare with the printed numbers (docs/validation.md)"
	@echo "make coverage  the stated errors against 4x-modes, 4x-window runs on 20 impacting points (docs/validation.md;"
	@echo "               hours at 256 modes; MODES=2 WINDOW=2 about 35 minutes on 2 cores; resumable)"
	@echo "make faults    kill sweeps and their workers at random moments RUNS=$(RUNS) times (docs/reliability.md)"
	@echo "make clean     remove outputs and the virtual environment"

setup: $(STAMP)

$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	@echo "installing study and its pinned dependencies into $(VENV) (quiet; about 2 minutes the first time)"
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -e '.[test]'
	$(BIN)/study compile
	touch $(STAMP)

# The whole suite in two pytest-xdist workers (the machine's two cores; the kernels are compiled ahead by setup),
# each test file on one worker, so that a module's fixtures (the validation record's, 2 minutes) are computed once.
test: $(STAMP) chromium
	$(BIN)/python -m pytest -q -n 2 --dist loadfile

# The precision-sensitive tests (marker `precision`, tests/conftest.py) again with numba compiling for a generic
# x86-64 CPU: figures held to their real accuracy, not to this machine's last bits. CI runs it after make test.
test-generic: $(STAMP)
	NUMBA_CPU_NAME=generic $(BIN)/python -m pytest -q -m precision -n 2 --dist loadfile -p no:cacheprovider

# The report test opens outputs in a headless browser: Debian's chromium, installed once if absent.
chromium:
	@test -x /usr/bin/chromium || { apt-get update -qq && apt-get install -y -qq chromium >/dev/null; }

sweep: $(STAMP)
	$(BIN)/study sweep $(CONFIG) --record docs/runs

charts: $(STAMP)
	$(BIN)/study charts outputs/$$($(BIN)/python -c "import study.config as c; print(c.load('$(CONFIG)').name)")/results.nc

bench: $(STAMP)
	$(BIN)/study bench --out docs/performance.md

bench-compile: $(STAMP)
	$(BIN)/study bench --section compile --out docs/performance_compile.md

bench-sweep-default: $(STAMP)
	$(BIN)/study bench --section sweep-default --out docs/performance_sweep-default.md

bench-large: $(STAMP)
ifdef POINTS
	mkdir -p outputs
	$(BIN)/study bench --large --points $(POINTS) --out outputs/large_sweep_$(POINTS).md
else
	$(BIN)/study bench --large --out docs/large_sweep.md
endif

validate: $(STAMP)
	$(BIN)/study validate --out docs/validation.md

# Resumable (finished runs kept in outputs/coverage/); SAMPLE, MODES and WINDOW make a smaller, labelled run.
SAMPLE ?= 20
MODES  ?= 4
WINDOW ?= 4
coverage: $(STAMP)
	$(BIN)/study coverage --sample $(SAMPLE) --modes-factor $(MODES) --window-factor $(WINDOW)

faults: $(STAMP)
	$(BIN)/python -m study.workflow.faults --runs $(RUNS)

clean:
	find outputs -mindepth 1 ! -name README.md -exec rm -rf {} +
	rm -rf $(VENV) .pytest_cache *.egg-info
