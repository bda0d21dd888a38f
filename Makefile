# betvdesign: two commands do all set-up (see README).
#   make demo  -> .venv, install (with the layout and explore extras), byte-compiled modules (.pyc), compiled solver kernels (cached), design reports (HTML + PDF) of shin2004 and push_demo, and shin2004's mask layout (GDS + SVG) under reports/; then `betv explore devices/push_demo.yaml`
#   make test  -> .venv with test extras, system packages (when root), whole suite on every core (pytest-xdist; each test file on one worker)
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin

.PHONY: demo test lint sysdeps sysdeps-runtime clean

$(VENV)/.stamp-run: pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q -e '.[layout,explore]'
	touch $@

$(VENV)/.stamp-test: pyproject.toml $(VENV)/.stamp-run
	$(BIN)/python -m pip install -q -e '.[test]'
	touch $@

sysdeps-runtime:
	@bash scripts/sysdeps.sh runtime

sysdeps:
	@bash scripts/sysdeps.sh test

# The byte-compile and the layout (no solver kernels) run beside the kernels' compile.
demo: sysdeps-runtime $(VENV)/.stamp-run
	mkdir -p reports
	$(BIN)/python -m compileall -q betvdesign & c=$$!; \
	$(BIN)/betv layout devices/shin2004.yaml -o reports/shin2004.gds --svg reports/shin2004.svg & l=$$!; \
	$(BIN)/python -m betvdesign.dynamics.warm; w=$$?; \
	wait $$c && wait $$l && test $$w -eq 0
	$(BIN)/betv report devices/shin2004.yaml devices/push_demo.yaml -o reports/

test: sysdeps $(VENV)/.stamp-test
	$(BIN)/ruff check betvdesign tests benchmarks
	$(BIN)/python -m pytest -n auto --dist loadfile

lint: $(VENV)/.stamp-test
	$(BIN)/ruff check betvdesign tests benchmarks
	$(BIN)/ruff format --check betvdesign tests benchmarks

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache
