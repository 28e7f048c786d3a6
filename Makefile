# Two commands do everything on a fresh machine (Python >= 3.11):
#   make book   build the course companion into _build/html
#   make test   run every test (unit tests, every notebook through nbval, the strict book build)
# and `make bench` prints the benchmark table, `make student` writes the student edition.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
JB     := $(BIN)/jupyter-book

.PHONY: book test bench student clean

# (Re)create the environment when it is missing or older than the pins.
$(STAMP): requirements.txt pyproject.toml
	@$(PYTHON) -c 'import sys; sys.exit(sys.version_info < (3, 11))' || \
		{ echo "error: $(PYTHON) is older than Python 3.11; run: make PYTHON=python3.11 ..." >&2; exit 1; }
	rm -rf $(VENV)
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --disable-pip-version-check -r requirements.txt
	$(BIN)/python -c "import matplotlib.pyplot"  # build matplotlib's font cache outside any notebook
	touch $@

# Front-end assets for a book that works offline, from two pinned npm packages (checked by hash):
# MathJax 3 (one component and its fonts) and the ipywidgets embedder (with its chunks and fonts).
# They are copied into _build/html/_static by the book build (html_static_path in _config.yml).
VENDOR := $(VENV)/vendor
MATHJAX := mathjax-3.2.2.tgz
MATHJAX_SHA256 := 1b9c0a1c44df864e915690558e72adb9cc5203360daefd385084ced3b6c64c09
WIDGETS := jupyter-widgets-html-manager-1.0.7.tgz
WIDGETS_SHA256 := b21e796f39be9e9a4c2f9843d362bba0b905bcaa62d4a1c12c52de0f67c244bf

$(VENDOR)/.installed: $(STAMP)
	@command -v npm >/dev/null || { echo "error: npm (Node.js) is needed to fetch MathJax and the widgets embedder" >&2; exit 1; }
	rm -rf $(VENDOR) && mkdir -p $(VENDOR)/tarballs $(VENDOR)/mathjax $(VENDOR)/widgets
	cd $(VENDOR)/tarballs && npm pack --silent mathjax@3.2.2 @jupyter-widgets/html-manager@1.0.7 >/dev/null
	cd $(VENDOR)/tarballs && printf '%s  %s\n' $(MATHJAX_SHA256) $(MATHJAX) $(WIDGETS_SHA256) $(WIDGETS) | sha256sum --quiet -c
	tar xzf $(VENDOR)/tarballs/$(MATHJAX) -C $(VENDOR)/mathjax --strip-components=2 \
		package/es5/tex-mml-chtml.js package/es5/output/chtml/fonts/woff-v2
	tar xzf $(VENDOR)/tarballs/$(WIDGETS) -C $(VENDOR)/widgets --strip-components=2 --wildcards \
		'package/dist/*embed.js' '*.woff2' '*.woff' --exclude='*amd*'  # browsers that run embed.js read woff2
	rm -rf $(VENDOR)/tarballs
	touch $@

# The notebook cache is keyed on code cells only: clear it whenever ddg/ changes.
_build/.ddg-stamp: $(wildcard ddg/*.py)
	rm -rf _build/.jupyter_cache
	mkdir -p _build && touch $@

book: $(STAMP) $(VENDOR)/.installed _build/.ddg-stamp
	$(JB) build . 
	@echo "The book is at $(CURDIR)/_build/html/index.html"

# Unit tests and every notebook (nbval runs each notebook's cells, asserts included, on one kernel
# per notebook), then the strict book build, which executes every notebook again, then the built
# site in a real browser (Debian's chromium: `.ci/run` installs it when it is missing).
test: $(STAMP) $(VENDOR)/.installed
	$(BIN)/python -m pytest -n 2 --dist loadscope --nbval-lax --nbval-current-env --ignore=tests/browser tests book
	rm -rf _build/.jupyter_cache  # the gating build re-executes every notebook
	$(JB) build . -W -n --keep-going
	mkdir -p _build && touch _build/.ddg-stamp
	$(BIN)/python -m pytest tests/browser

# The student edition: every solution removed, coding answers replaced by starter code (student/).
student: $(STAMP)
	$(BIN)/python -m ddg.edition --out student
	@echo "Build it with: $(JB) build student   (its notebooks are not executed: the starters raise)"

bench: $(STAMP)
	$(BIN)/python tests/benchmark.py

clean:
	rm -rf _build student
