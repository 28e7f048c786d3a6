# Two commands do everything on a fresh machine (Linux or macOS, Python >= 3.11):
#   make book   build the course companion into _build/html
#   make test   run every test (unit tests, notebooks, the strict build, browser, user journeys)
# and: make lab (JupyterLab on book/), make bench, make student, make pdf, make dist,
# make repo URL=..., make publish, make publish-student STUDENT_REPO=..., make screenshots,
# make clean. Each creates .venv from the exact pins when it is missing or the pins changed (tools/env.py). The recipes call small Python scripts in tools/,
# which say what they do; CONTRIBUTING.md says how the pieces fit.
PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
ENV    := $(VENV)/.installed
VENDOR := $(VENV)/vendor/.installed
KERNEL := $(VENV)/etc/ipython/ipython_kernel_config.py

# The notebooks import the ddg of this checkout, whatever the environment holds.
export PYTHONPATH := $(CURDIR)

.PHONY: book book-strict test pytest lab bench student pdf dist repo publish publish-student screenshots clean

# The environment from requirements.txt and requirements-build.txt (tools/env.py).
$(ENV): requirements.txt requirements-build.txt pyproject.toml tools/env.py
	@$(PYTHON) tools/env.py $(VENV)

# The kernels that run the notebooks, without ipykernel 7's notice about unencrypted loopback TCP.
$(KERNEL): tools/ipython_kernel_config.py $(ENV)
	@mkdir -p $(@D) && cp tools/ipython_kernel_config.py $@

# MathJax and polygon-clipping, pinned: Node typesets the formulas with MathJax, the book serves its
# fonts; the lab of chapter 10 unites polygons with polygon-clipping (tools/vendor.py).
$(VENDOR): $(ENV) tools/vendor.py
	$(PY) tools/vendor.py $(VENV)/vendor $(VENV)/node_modules

# The book; only what changed is built again (tools/build.py says what and why).
book: $(ENV) $(VENDOR) $(KERNEL)
	@$(PY) tools/repo.py --from-git
	@$(PY) tools/build.py book

# What `make test` gates on: every notebook executed, every page re-read, no warning.
book-strict: $(ENV) $(VENDOR) $(KERNEL)
	@$(PY) tools/build.py strict

# A browser first (found or installed, or one line saying what to install); the unit tests and
# every notebook (nbval); the strict build and the student edition side by side; the PDFs; then
# what runs on the built sites and the repository as a user would (tests/browser, tests/journeys).
test: $(ENV) $(VENDOR) $(KERNEL)
	@$(PY) tools/browser.py >/dev/null
	$(PY) -m pytest -n 2 --dist loadscope --nbval-lax --nbval-current-env tests book \
		--ignore=tests/browser --ignore=tests/journeys
	$(MAKE) -j2 book-strict student FRESH=1 STUDENT_REPO=
	$(MAKE) pdf
	$(PY) -m pytest -n 2 --dist worksteal --durations=12 tests/journeys tests/browser

# One test file, one test or one notebook, as `make test` runs them, for example
#   make pytest ARGS="tests/unit/test_curve.py -k area"    make pytest ARGS=book/02_discrete_curves.ipynb
pytest: $(ENV) $(VENDOR) $(KERNEL)
	$(PY) -m pytest --nbval-lax --nbval-current-env $(ARGS)

# JupyterLab on the chapter notebooks; it prints the URL to open (with its token).
lab: $(ENV) $(KERNEL)
	@echo "Starting JupyterLab on book/ (Ctrl-C stops it); open the URL printed below."
	$(VENV)/bin/jupyter lab --notebook-dir=book --ip=127.0.0.1 $$([ "$$(id -u)" = 0 ] && echo --allow-root)

# The student edition in _build/student (its site in _build/student/html). FRESH=1 runs every
# notebook again; STUDENT_REPO=https://github.com/owner/name gives its pages launch buttons.
student: $(ENV) $(VENDOR) $(KERNEL)
	@$(PY) tools/build.py student $(if $(FRESH),--fresh) $(if $(FORCE),--force) \
		$(if $(STUDENT_REPO),--student-repo $(STUDENT_REPO))

# Both editions as PDF in _build/pdf (the book is built first where missing).
pdf: $(ENV) $(VENDOR) $(KERNEL)
	@$(PY) tools/browser.py >/dev/null
	@$(PY) tools/build.py pdf

# A screenshot of every page of both sites in each view the browser tests check, in
# _build/screenshots/<site>/<view>/ (both sites built first where missing).
screenshots: $(ENV) $(VENDOR) $(KERNEL)
	@[ -f _build/html/index.html ] || $(MAKE) book
	@[ -f _build/student/html/index.html ] || $(MAKE) student
	@$(PY) tools/browser.py >/dev/null
	rm -rf _build/screenshots
	DDG_SCREENSHOTS=1 $(PY) -m pytest -q -n 2 tests/browser/test_site.py -k every_view

# The speed of ddg and of grading, then what each page of both sites costs a phone on 3G.
bench: $(ENV) $(VENDOR) $(KERNEL)
	$(PY) tests/bench/bench_ddg.py
	$(PY) tests/bench/bench_grading.py
	@[ -f _build/html/index.html ] || $(MAKE) book
	@[ -f _build/student/html/index.html ] || $(MAKE) student
	@$(PY) tools/browser.py >/dev/null
	$(PY) tests/bench/bench_pages.py

# The wheel and the source distribution of ddg (the distribution ddg-plane-curves) in dist/.
dist: $(ENV)
	$(PY) -m build --no-isolation --outdir dist .

# Point the launch buttons, the repository button and every notebook's set-up cell at URL.
repo: $(ENV)
	@[ -n "$(URL)" ] || { echo "usage: make repo URL=https://github.com/owner/name" >&2; exit 1; }
	$(PY) tools/repo.py "$(URL)"

# The book online: built with its PDFs, then _build/html onto the gh-pages branch of REMOTE (default
# origin; a remote's name, a URL or a path), with .nojekyll (tools/publish.py, by ghp-import).
publish: $(ENV) $(VENDOR) $(KERNEL)
	@$(PY) tools/publish.py book --check $(if $(REMOTE),--remote $(REMOTE))
	@$(MAKE) --no-print-directory book
	@$(MAKE) --no-print-directory pdf
	@$(PY) tools/publish.py book $(if $(REMOTE),--remote $(REMOTE))

# The student edition online: built for STUDENT_REPO (its launch buttons and set-up cells lead
# there) and printed, its files pushed to that repository's main branch and its site (with its
# PDFs) to its gh-pages branch.
# STUDENT_REMOTE: where to push instead of STUDENT_REPO itself (an ssh URL, a path).
publish-student: $(ENV) $(VENDOR) $(KERNEL)
	@[ -n "$(STUDENT_REPO)" ] || { echo "usage: make publish-student STUDENT_REPO=https://github.com/owner/name [STUDENT_REMOTE=where to push]" >&2; exit 1; }
	@$(PY) tools/publish.py student --check --repo $(STUDENT_REPO) $(if $(STUDENT_REMOTE),--remote $(STUDENT_REMOTE))
	@$(MAKE) --no-print-directory student STUDENT_REPO=$(STUDENT_REPO)
	@$(PY) tools/browser.py >/dev/null
	@$(PY) tools/pdf.py _build/student/html _build/pdf/student
	@$(PY) tools/publish.py student --repo $(STUDENT_REPO) $(if $(STUDENT_REMOTE),--remote $(STUDENT_REMOTE))

# Everything built; the student edition too, unless a notebook there was changed since `make
# student` wrote it (a student's answers): then it refuses, unless FORCE=1.
clean:
	@if [ -x $(PY) ]; then $(PY) -m instructor.edition --check-unchanged _build/student/book $(if $(FORCE),--force); \
	elif [ -d _build/student/book ] && [ -z "$(FORCE)" ]; then \
		echo "error: cannot check _build/student/book for students' changes without $(VENV); use FORCE=1" >&2; exit 1; fi
	rm -rf _build dist
