# Two commands do everything on a fresh machine (Linux or macOS, Python >= 3.11):
#   make book   build the course companion into _build/html
#   make test   run every test (unit tests, notebooks, the strict build, browser, user journeys)
# and: make lab (JupyterLab on book/), make bench, make student, make dist, make repo URL=...,
# make screenshots, make clean. Each creates .venv from the exact pins in requirements.txt when
# it is missing or the pins changed. Needs GNU make 3.81 or newer (Linux; the make of macOS) and a POSIX sh.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
PY     := $(BIN)/python
JB     := $(BIN)/jupyter-book
ENV    := $(VENV)/.installed
VENDOR := $(VENV)/vendor/.installed

# The notebooks import the ddg of this checkout, whatever the environment holds.
export PYTHONPATH := $(CURDIR)
# What the pages are computed from (Python, ddg/, the pins, the configuration): a change here means
# every notebook must run again.
INPUTS = $$({ $(PY) -VV; find ddg -name '*.py' | sort | xargs cat; cat requirements.txt pyproject.toml _config.yml; } | cksum)
# What every page carries but Sphinx does not watch: the book's stylesheet, scripts and extensions,
# and the pinned MathJax that typesets its formulas (tools/vendor.py).
ASSETS = $$(find book/_assets tools/sphinx_*.py tools/vendor.py -type f | sort | xargs cat | cksum)

.PHONY: book book-strict test lab bench student pdf dist repo screenshots clean

# The environment, rebuilt when requirements*.txt or pyproject.toml change (by content, so a fresh
# clone or a copy with the same pins keeps it). The pins are installed by uv (pinned below; about
# 15 s here against 95 s with pip), or by pip where uv cannot reach the index (uv does not read
# pip's configuration). uv compiles the bytecode as pip does (it would not by default): where
# PYTHONDONTWRITEBYTECODE is set, every Python process, each notebook's kernel among them, would
# otherwise compile matplotlib & co. again (imports 2.4 s instead of 0.9 s here). Also a
# wheelhouse, downloaded meanwhile: the pinned wheels a notebook needs, so the journey tests can
# install into fresh environments without the network.
UV := uv==0.13.9
WHEELS := numpy matplotlib ipywidgets shapely pillow tqdm ipython ipykernel nbclient setuptools wheel
$(ENV): requirements.txt requirements-build.txt pyproject.toml
	@$(PYTHON) -c 'import sys; sys.exit(sys.version_info < (3, 11))' || \
		{ echo "error: $(PYTHON) is older than Python 3.11; run: make PYTHON=python3.11 ..." >&2; exit 1; }
	@sum="$$(cat requirements.txt requirements-build.txt pyproject.toml | cksum)"; \
	if [ -f $@ ] && [ "$$(cat $@)" = "$$sum" ]; then touch $@; exit 0; fi; \
	echo "setting up $(VENV) from requirements.txt ..."; \
	rm -rf $(VENV) && $(PYTHON) -m venv $(VENV) && \
	grep -v '^-e' requirements.txt > $(VENV)/constraints.txt && \
	{ $(BIN)/pip download --quiet --disable-pip-version-check -d $(VENV)/wheelhouse \
		-c $(VENV)/constraints.txt $(WHEELS) > $(VENV)/wheelhouse.log 2>&1 & } && download=$$! && \
	{ { $(BIN)/pip install --quiet --disable-pip-version-check "$(UV)" && \
	    $(BIN)/uv pip install --quiet --compile-bytecode --python $(PY) -r requirements.txt -r requirements-build.txt; } || \
	  { echo "uv could not install the pins; installing them with pip ..."; \
	    $(BIN)/pip install --quiet --disable-pip-version-check -r requirements.txt -r requirements-build.txt; }; } && \
	{ wait $$download || { cat $(VENV)/wheelhouse.log >&2; exit 1; }; } && \
	$(PY) -c "import matplotlib.pyplot" && \
	echo "$$sum" > $@

# The kernels that run the notebooks, without ipykernel 7's notice about unencrypted loopback TCP
# at every start (tools/ipython_kernel_config.py; IPython reads it from .venv/etc/ipython).
KERNEL := $(VENV)/etc/ipython/ipython_kernel_config.py
$(KERNEL): tools/ipython_kernel_config.py $(ENV)
	@mkdir -p $(@D) && cp tools/ipython_kernel_config.py $@

# MathJax, pinned: for Node, which typesets the formulas when the book is built, and its fonts,
# which the book serves itself (offline): tools/vendor.py.
$(VENDOR): $(ENV) tools/vendor.py
	$(PY) tools/vendor.py $(VENV)/vendor $(VENV)/node_modules

# The book. Sphinx re-reads only pages whose source changed and the notebook cache knows only
# code cells, so when ddg/, the pins or the configuration changed since the last build, the
# cache and Sphinx's state are dropped: every notebook runs again and every page is rebuilt.
# When only the book's assets changed, every page is written again from the cached outputs.
book: $(ENV) $(VENDOR) $(KERNEL)
	@$(PY) tools/repo.py --from-git
	@inputs="$(INPUTS)"; assets="$(ASSETS)"; \
	if [ "$$(cat _build/.inputs 2>/dev/null)" != "$$inputs" ]; then \
		[ -d _build/.doctrees ] && echo "ddg/, the pins or _config.yml changed: every notebook runs again"; \
		rm -rf _build/.jupyter_cache _build/.doctrees _build/html; \
	elif [ "$$(cat _build/.assets 2>/dev/null)" != "$$assets" ]; then \
		[ -d _build/.doctrees ] && echo "book/_assets or tools/sphinx_*.py changed: every page is written again"; \
		rm -rf _build/.doctrees _build/html; fi; \
	$(JB) build . && mkdir -p _build && echo "$$inputs" > _build/.inputs && echo "$$assets" > _build/.assets
	@echo "The book is at $(CURDIR)/_build/html/index.html"

# The build `make test` gates on: re-reads every page and re-executes every notebook, whatever was
# built before; any warning, stray stderr or failing cell fails it.
book-strict: $(ENV) $(VENDOR) $(KERNEL)
	@inputs="$(INPUTS)"; assets="$(ASSETS)"; rm -rf _build/.jupyter_cache && \
	$(JB) build . --all -W -n --keep-going && echo "$$inputs" > _build/.inputs && echo "$$assets" > _build/.assets

# First a browser (found or installed, or one line saying what to install), then the unit tests
# and every notebook (nbval), the strict build and the student edition (side by side: each runs
# its notebooks one at a time), the PDFs, and what runs on the built
# sites and on the repository as a user would: tests/browser (Chromium, network cut) and
# tests/journeys.
test: $(ENV) $(VENDOR) $(KERNEL)
	@$(PY) tools/browser.py >/dev/null
	$(PY) -m pytest -n 2 --dist loadscope --nbval-lax --nbval-current-env tests book \
		--ignore=tests/browser --ignore=tests/journeys
	$(MAKE) -j2 book-strict student FRESH=1 STUDENT_REPO=
	$(MAKE) pdf
	$(PY) -m pytest -n 2 --dist worksteal --durations=12 tests/journeys tests/browser

# JupyterLab on the chapter notebooks; it prints the URL to open (with its token).
lab: $(ENV) $(KERNEL)
	@echo "Starting JupyterLab on book/ (Ctrl-C stops it); open the URL printed below."
	$(BIN)/jupyter lab --notebook-dir=book --ip=127.0.0.1 $$([ "$$(id -u)" = 0 ] && echo --allow-root)

# The student edition: every solution removed, coding answers replaced by starter code, executed
# and built like the book. _build/student/ is what a repository of student notebooks holds (set
# STUDENT_REPO=https://github.com/owner/name for its launch buttons); _build/student/html the site.
# The outputs of the last edition's notebooks are kept while ddg/, the pins and _config.yml are
# unchanged since it was built, so only notebooks whose code changed run again; FRESH=1 (any
# value) runs them all (`make test` does).
student: $(ENV) $(VENDOR) $(KERNEL)
	@inputs="$(INPUTS)"; cache=_build/student/_build/.jupyter_cache; kept=_build/.student-cache; \
	rm -rf $$kept; \
	if [ -z "$(FRESH)" ] && [ -d $$cache ] && [ "$$(cat _build/student/_build/.inputs 2>/dev/null)" = "$$inputs" ]; then \
		mv $$cache $$kept; fi; \
	$(PY) -m instructor.edition --out _build/student --vendor $(VENV)/vendor $(if $(FORCE),--force) \
		$(if $(STUDENT_REPO),--student-repo $(STUDENT_REPO)) || \
		{ status=$$?; if [ -d $$kept ]; then mkdir -p _build/student/_build && mv $$kept $$cache; fi; exit $$status; }; \
	mkdir -p _build/student/_build && echo "$$inputs" > _build/student/_build/.inputs; \
	if [ -d $$kept ]; then mv $$kept $$cache; \
		echo "ddg/, the pins and _config.yml unchanged: only notebooks whose code changed run again"; \
	else echo "every notebook of the student edition runs"; fi
	$(JB) build _build/student -W -n --keep-going
	rm -rf _build/student/html && mv _build/student/_build/html _build/student/html
	@echo "The student site is at $(CURDIR)/_build/student/html/index.html"

# The book (and the student edition, when it is built) as PDF: _build/pdf/book.pdf, one PDF per
# chapter, and the same for students in _build/pdf/student/. Printed by Chromium (tools/pdf.py),
# both editions at once.
pdf: $(ENV)
	@[ -f _build/html/index.html ] || $(MAKE) book
	@$(PY) tools/browser.py >/dev/null
	@student=; if [ -f _build/student/html/index.html ]; then \
		$(PY) tools/pdf.py _build/student/html _build/pdf/student & student=$$!; fi; \
	$(PY) tools/pdf.py _build/html _build/pdf; book=$$?; \
	if [ -n "$$student" ]; then wait $$student || exit 1; fi; exit $$book

# A screenshot of every page of both sites in each view the browser tests check (desktop, phone,
# dark), in _build/screenshots/<site>/<view>/, from the sites as they are built (both are built
# first where missing). `make test` takes none: they assert nothing, and cost a quarter of the time.
screenshots: $(ENV) $(VENDOR) $(KERNEL)
	@[ -f _build/html/index.html ] || $(MAKE) book
	@[ -f _build/student/html/index.html ] || $(MAKE) student
	@$(PY) tools/browser.py >/dev/null
	rm -rf _build/screenshots
	DDG_SCREENSHOTS=1 $(PY) -m pytest -q -n 2 tests/browser/test_site.py -k every_view
	@echo "The screenshots are in $(CURDIR)/_build/screenshots/"

# The speed of ddg and of grading, then what each page of both sites costs a phone on a slow
# connection (tests/bench_pages.py; both sites are built first where missing).
bench: $(ENV)
	$(PY) tests/benchmark.py
	$(PY) tests/bench_grading.py
	@[ -f _build/html/index.html ] || $(MAKE) book
	@[ -f _build/student/html/index.html ] || $(MAKE) student
	@$(PY) tools/browser.py >/dev/null
	$(PY) tests/bench_pages.py

# The wheel and the source distribution of ddg (the distribution ddg-plane-curves) in dist/.
dist: $(ENV)
	$(PY) -m build --no-isolation --outdir dist .

# Point the launch buttons, the repository button and every notebook's set-up cell at URL.
repo: $(ENV)
	@[ -n "$(URL)" ] || { echo "usage: make repo URL=https://github.com/owner/name" >&2; exit 1; }
	$(PY) tools/repo.py "$(URL)"

# Everything built; the student edition too, unless a notebook there was changed since `make
# student` wrote it (a student's answers): then it refuses, unless FORCE=1.
clean:
	@if [ -x $(PY) ]; then $(PY) -m instructor.edition --check-unchanged _build/student/book $(if $(FORCE),--force); \
	elif [ -d _build/student/book ] && [ -z "$(FORCE)" ]; then \
		echo "error: cannot check _build/student/book for students' changes without $(VENV); use FORCE=1" >&2; exit 1; fi
	rm -rf _build dist
