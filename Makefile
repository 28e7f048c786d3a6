# Two commands do everything on a fresh machine (Python >= 3.11):
#   make book   build the course companion into _build/html
#   make test   run every test (unit tests, every notebook through nbval, the strict book build)
# and `make bench` prints the benchmark table.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
JB     := $(BIN)/jupyter-book

.PHONY: book test bench clean

# (Re)create the environment when it is missing or older than the pins.
$(STAMP): requirements.txt pyproject.toml
	@$(PYTHON) -c 'import sys; sys.exit(sys.version_info < (3, 11))' || \
		{ echo "error: $(PYTHON) is older than Python 3.11; run: make PYTHON=python3.11 ..." >&2; exit 1; }
	rm -rf $(VENV)
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --disable-pip-version-check -r requirements.txt
	$(BIN)/python -c "import matplotlib.pyplot"  # build matplotlib's font cache outside any notebook
	touch $@

# The notebook cache is keyed on code cells only: clear it whenever ddg/ changes.
_build/.ddg-stamp: $(wildcard ddg/*.py)
	rm -rf _build/.jupyter_cache
	mkdir -p _build && touch $@

book: $(STAMP) _build/.ddg-stamp
	$(JB) build . 
	@echo "The book is at $(CURDIR)/_build/html/index.html"

# Unit tests and every notebook (nbval runs each notebook's cells, asserts included, on one kernel
# per notebook), then the strict book build, which executes every notebook again.
test: $(STAMP)
	$(BIN)/python -m pytest -n 2 --dist loadscope --nbval-lax --nbval-current-env tests book
	rm -rf _build/.jupyter_cache  # the gating build re-executes every notebook
	$(JB) build . -W -n --keep-going
	mkdir -p _build && touch _build/.ddg-stamp

bench: $(STAMP)
	$(BIN)/python tests/benchmark.py

clean:
	rm -rf _build student
