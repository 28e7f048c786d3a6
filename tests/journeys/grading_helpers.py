"""Helpers of the grading journeys (test_grading.py, test_gradescope.py): a class made of real notebooks.

A submission is the student edition of a chapter with the starters filled in (by the book's
reference answers unless a test says otherwise). :data:`HUNT` is a submission's code that looks
for everything it should not find; the tests put it where the sandbox runs it.
"""

import csv
import os
import re
import sys

import nbformat
import pytest
from journey_helpers import ROOT, run

from instructor import edition

CHAPTER = "03_winding_number"


def needs_root():
    if not sys.platform.startswith("linux") or os.geteuid() != 0:
        pytest.skip("the grading sandbox needs Linux and root (unshare, mount, chroot)")


def references(chapter=CHAPTER):
    nb = nbformat.read(ROOT / "book" / f"{chapter}.ipynb", as_version=4)
    return {re.search(r"def (\w+)", c.source).group(1): c.source for c in nb.cells
            if "solution" in c.metadata.get("tags", [])}


def submission(path, answers=None, first_cells=(), chapter=CHAPTER, drop=()):
    """Write a completed notebook of ``chapter`` to ``path``: the reference answers unless ``answers``
    says otherwise, ``first_cells`` inserted after the set-up cell, the starters named in ``drop``
    left out (a notebook from before those exercises were added)."""
    nb = edition.student_notebook(nbformat.read(ROOT / "book" / f"{chapter}.ipynb", as_version=4))
    reference, kept = references(chapter), []
    for cell in nb.cells:
        if "starter" in cell.metadata.get("tags", []):
            name = re.search(r"def (\w+)", cell.source).group(1)
            if name in drop:
                continue
            cell.source = (answers or {}).get(name, reference[name])
        kept.append(cell)
    nb.cells = kept
    nb.cells[1:1] = [nbformat.v4.new_code_cell(source) for source in first_cells]
    path.parent.mkdir(parents=True, exist_ok=True)
    nbformat.write(nb, path)
    return path


def in_root(root, command, env=(), binds=()):
    """Run ``command`` (a shell line) as root in ``root``, a new root made of this machine's system (read-only)
    and ``binds`` (``{inside: outside}``, read-only too), with new mount and PID namespaces: the way a container runs it."""
    import shlex
    import subprocess

    q = shlex.quote
    lines = ["set -e", "mount --make-rprivate /", f"R={q(str(root))}", 'mount --bind "$R" "$R"']  # / a mount point
    for path, source in [*((p, p) for p in ("/usr", "/bin", "/sbin", "/lib", "/lib64", "/etc")), *dict(binds).items()]:
        if os.path.islink(path) and path == source:
            lines.append(f'[ -e "$R{path}" ] || ln -s {q(os.readlink(path))} "$R{path}"')
        elif os.path.exists(source):
            lines += [f'mkdir -p "$R"{q(path)}', f'mount --bind {q(str(source))} "$R"{q(path)}',
                      f'mount -o remount,bind,ro "$R"{q(path)}']
    lines += ['mkdir -p "$R/proc" "$R/dev" "$R/tmp" "$R/root"', 'mount -t proc proc "$R/proc"',
              'mount --rbind /dev "$R/dev"', 'mount -t tmpfs tmp "$R/tmp"',
              f'exec chroot "$R" /usr/bin/env -i {" ".join(q(f"{k}={v}") for k, v in dict(env).items())} '
              f'/bin/bash -c {q(command)}']
    return subprocess.run(["unshare", "--mount", "--pid", "--fork", "--kill-child", "sh", "-c", "\n".join(lines)],
                          text=True, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=1200)


def grade(*arguments, check=True, timeout=900, env=None):
    """``python -m instructor.grade ARGUMENTS``, as an instructor runs it."""
    return run([sys.executable, "-m", "instructor.grade", *map(str, arguments)], timeout=timeout, check=check, env=env)


def rows(path):
    with open(path, newline="") as file:
        return list(csv.reader(file))


DIALECTS = {"comma": (",", "\n", ""), "excel-europe": (";", "\r\n", "\ufeff"), "crlf": (",", "\r\n", ""),
            "tab": ("\t", "\n", "\ufeff")}
"""How spreadsheets save CSV: delimiter, line end, byte order mark (Excel in much of Europe: the second)."""


def spreadsheet(table, dialect="excel-europe"):
    """The bytes of ``table`` (a list of rows) saved as CSV in ``dialect`` (a key of :data:`DIALECTS`)."""
    import io

    delimiter, end, bom = DIALECTS[dialect]
    buffer = io.StringIO()
    csv.writer(buffer, delimiter=delimiter, lineterminator=end).writerows(table)
    return (bom + buffer.getvalue()).encode("utf-8")


def by_student(path):
    with open(path, newline="") as file:
        return {row["student_id"]: row for row in csv.DictReader(file)}


HUNT = r'''
import gc, json, os, pathlib, socket, sys

MARKERS = ("-" "-seed", "seed" "-file", "{solution" "-start}", "VICTIM" "-7f3a")  # not in this source as they are


def hunt(write=True):
    """Everything a submission could try to find the secret, the solutions or other submissions
    (and, with ``write``, to change what is not its own)."""
    tried, found = {}, []

    def look(where, text):
        for marker in MARKERS:
            at = text.find(marker)
            if at >= 0 and len(found) < 2000:
                found.append(f"{where}: {text[max(0, at - 30):at + 60]!r}")

    pids = [p for p in os.listdir("/proc") if p.isdigit()]
    tried["processes"] = len(pids)
    for pid in pids:  # every process's command line and environment, the grader's among them if visible
        for name in ("cmdline", "environ"):
            try:
                with open(f"/proc/{pid}/{name}", "rb") as file:
                    look(f"/proc/{pid}/{name}", file.read().replace(b"\0", b" ").decode(errors="replace"))
            except OSError:
                pass
    look("os.environ", json.dumps(dict(os.environ)))
    tried["environment"] = len(os.environ)
    import ddg
    here = pathlib.Path(ddg.__file__).resolve().parent
    starts = ["/", os.getcwd(), str(here.parent), str(here.parent.parent), os.path.expanduser("~"), "/tmp", "/work"]
    seen, notebooks = set(), 0
    for start in starts:  # the file system, three levels down from each start: the book would be there
        for folder, folders, files in os.walk(start):
            depth = len(pathlib.Path(folder).relative_to(start).parts)
            folders[:] = [] if depth >= 3 else [f for f in folders if f not in ("proc", "sys", "dev", "usr")]
            for name in files:
                path = os.path.join(folder, name)
                if path in seen:
                    continue
                seen.add(path)
                if name.endswith(".ipynb") or "seed" in name or "secret" in name or name == "autograder.json":
                    notebooks += 1
                    found.append(f"a file: {path}")
                    try:
                        with open(path, "rb") as file:
                            look(path, file.read(1 << 20).decode(errors="replace"))
                    except OSError:
                        pass
    tried["files"] = len(seen)
    for fd in os.listdir("/proc/self/fd"):  # what this process holds open
        try:
            target = os.readlink(f"/proc/self/fd/{fd}")
            look(f"fd {fd} -> {target}", target)
            if target.startswith("/") and os.path.isfile(target):
                with open(target, "rb") as file:
                    look(f"fd {fd}", file.read(1 << 20).decode(errors="replace"))
        except OSError:
            pass
    tried["descriptors"] = len(os.listdir("/proc/self/fd"))
    objects = gc.get_objects()  # the memory it shares with whatever started it: dicts, lists, frames
    tried["objects"] = len(objects)
    for thing in objects:
        if isinstance(thing, dict):
            look("a dict in memory", " ".join(v for v in list(thing.values()) if isinstance(v, str)))
        elif isinstance(thing, list):
            look("a list in memory", " ".join(v for v in thing[:1000] if isinstance(v, str)))
    frames = 0
    for frame in sys._current_frames().values():
        while frame is not None:
            frames += 1
            look(f"frame {frame.f_code.co_name}", " ".join(v for v in frame.f_locals.values() if isinstance(v, str)))
            frame = frame.f_back
    tried["frames"] = frames
    for address in (("1.1.1.1", 53), ("127.0.0.1", 22)):  # the network
        try:
            socket.create_connection(address, timeout=2).close()
            found.append(f"connected to {address}")
        except OSError as error:
            tried[f"connect {address[0]}"] = f"refused ({type(error).__name__})"
    for target in (str(here / "evil.py"), "/etc/evil", "/autograder/results/results.json") if write else ():
        try:
            open(target, "w").write("x")
            found.append(f"wrote {target}")
        except OSError as error:
            tried[f"write {target}"] = f"refused ({type(error).__name__})"
    return tried, found


print("HUNT " + json.dumps(hunt()))


def turning_angles(vertices):
    tried, found = hunt()
    raise RuntimeError(("FOUND " + " | ".join(found)) if found else "found nothing")
'''
"""A submission's answer cell that hunts (top-level, when the cell runs, and in the answer's own process)."""
