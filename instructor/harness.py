"""What runs inside the grading sandbox: one submission's answers, on input the grader sends.

The grader (``instructor/sandbox.py``) runs :func:`main` with a job on standard input::

    {"cells": [source of each cell, or null for a markdown cell], "cell_timeout": s, "answer_timeout": s,
     "results_fd": n, "specs_fd": n,
     "exercises": [{"label", "name" (the exercise in ddg.checks), "answer" (the function),
                    "specs_at": [[offset, length] of each input's specs, a JSON line in specs_fd]]}]}

and reads what it finds, one JSON line per exercise, from the file descriptor ``results_fd``, which
only this process holds. The input specs drawn by the grader (never the secret they were drawn
from, never what a right answer returns) are in the file ``specs_fd``, which only this process
holds and never reads into its own memory: each input goes from there straight (``os.sendfile``)
to the one process that answers it, when that process asks, once. So no process that runs the
submission's code ever holds another input than its own; nothing here judges: the grader does.

For each exercise, in a child process of its own:

1. the ``ddg`` quantity the exercise asks for is switched off *before* any cell of the submission
   runs (``ddg.checks.seal.switch_off``), so no cell can keep a copy of it for later;
2. only the cells the answer needs run (:func:`plan`: the last cell that defines the answer, then,
   recursively, for each name a chosen cell uses, the cell that defines it), one by one, in
   IPython (magics work), each with a time limit: a loop elsewhere in the notebook costs nothing;
3. the answer runs on the input in ``ddg.checks.answer_results``: each input in a process of its
   own, which asks this process for it (:func:`_serve`), with the checks' code gone, under a time
   limit; the raw results go back to the grader. Nothing of the grader (``instructor``) can be
   imported by the submission.

A cell that must be killed (it ignored its time limit, ended the process, or was killed for
memory) is skipped, and the exercise runs again without it. The cells' outputs go back too: the
grader writes them into the executed notebook it keeps for the instructor.
"""

import ast
import builtins
import io
import json
import os
import re
import select
import signal
import sys
import time

GRACE = 2.0
"""Seconds a cell gets beyond its limit to stop by itself before it is killed."""

OUTPUT_LIMIT = 20_000
"""Characters of output kept per cell."""

MESSAGE_LIMIT = 4 << 20
"""Bytes the parent reads from one exercise's child: a flood is cut off there."""

SHELL_NAMES = {"get_ipython", "display", "In", "Out", "exit", "quit", "_", "__", "___"}


class CellTimeout(KeyboardInterrupt):
    """Raised in a cell that reached its time limit (a KeyboardInterrupt: ``except Exception`` does not catch it)."""


# ------------------------------------------------------------------ which cells an answer needs


SCOPES = (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef,
          ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp)


def _bound_in(scope):
    """The names a function, lambda, class or comprehension binds for itself (its local names)."""
    names, declared = set(), set()
    if isinstance(scope, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
        a = scope.args
        names |= {x.arg for x in [*a.posonlyargs, *a.args, *a.kwonlyargs, a.vararg, a.kwarg] if x}
        stack = list(scope.body) if isinstance(scope.body, list) else [scope.body]
    else:
        stack = list(scope.body if isinstance(scope, ast.ClassDef) else scope.generators)
    while stack:
        node = stack.pop()
        if isinstance(node, ast.Name) and not isinstance(node.ctx, ast.Load):
            names.add(node.id)
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            names |= {(a.asname or a.name).split(".")[0] for a in node.names}
        elif isinstance(node, ast.ExceptHandler) and node.name:
            names.add(node.name)
        elif isinstance(node, (ast.Global, ast.Nonlocal)):
            declared |= set(node.names)
        if isinstance(node, SCOPES):
            names |= {node.name} if hasattr(node, "name") else set()
            continue
        stack.extend(ast.iter_child_nodes(node))
    return names - declared


class Names(ast.NodeVisitor):
    """The names a cell defines at its top level, the global names it uses anywhere, and star imports."""

    def __init__(self):
        self.defined, self.used, self.star, self.scopes = set(), set(), False, []

    def generic_visit(self, node):
        if not isinstance(node, SCOPES):
            return super().generic_visit(node)
        if getattr(node, "name", None) and not self.scopes:
            self.defined.add(node.name)
        self.scopes.append(_bound_in(node))
        super().generic_visit(node)
        self.scopes.pop()

    def visit_Name(self, node):
        if isinstance(node.ctx, ast.Load):
            if not any(node.id in scope for scope in self.scopes):
                self.used.add(node.id)
        elif not self.scopes:
            self.defined.add(node.id)

    def visit_Import(self, node):
        if not self.scopes:
            self.defined.update((a.asname or a.name).split(".")[0] for a in node.names)

    def visit_ImportFrom(self, node):
        if not self.scopes:
            self.star |= any(a.name == "*" for a in node.names)
            self.defined.update(a.asname or a.name for a in node.names if a.name != "*")


def analyse(cells, transform=lambda source: source):
    """For each code cell: ``{"defined", "used", "star"}``, or ``{"syntax": (line, message)}``."""
    info = {}
    for i, source in enumerate(cells):
        if source is None:
            continue
        try:
            tree = ast.parse(transform(source))
        except SyntaxError as error:
            info[i] = {"syntax": (error.lineno, error.msg)}
            continue
        except (ValueError, RecursionError, MemoryError) as error:
            info[i] = {"syntax": (None, str(error) or type(error).__name__)}
            continue
        names = Names()
        names.visit(tree)
        info[i] = {"defined": names.defined, "used": names.used, "star": names.star}
    return info


def plan(info, answer):
    """The cells to run for ``answer``, in notebook order; or why there are none (a dict)."""
    def definers(name, before=None):
        found = [i for i, c in info.items() if name in c.get("defined", ())]
        earlier = [i for i in found if before is None or i < before]
        return earlier[-1] if earlier else (found[-1] if found else None)

    first = definers(answer)
    if first is None:
        broken = sorted(i for i, c in info.items() if "syntax" in c)
        return {"missing": answer, "syntax": {i: info[i]["syntax"] for i in broken}}
    chosen, queue = {first}, [first]
    while queue:
        cell = queue.pop()
        for name in sorted(info[cell]["used"] - info[cell]["defined"]):
            where = definers(name, before=cell)
            if where is None and not hasattr(builtins, name) and name not in SHELL_NAMES:
                stars = [i for i, c in info.items() if c.get("star") and i < cell]
                new = [i for i in stars if i not in chosen]
            else:
                new = [where] if where is not None and where not in chosen else []
            chosen.update(new)
            queue += new
    return sorted(chosen)


# ------------------------------------------------------------------ the child: cells, then the answer


def _shell():
    from IPython.core.interactiveshell import InteractiveShell
    from traitlets.config import Config

    config = Config()
    config.HistoryManager.enabled = False
    config.InteractiveShell.colors = "nocolor"
    shell = InteractiveShell.instance(config=config)
    shell.enable_gui = lambda gui=None: None  # %matplotlib inline and friends: nothing to start here
    return shell


class _Capture(io.TextIOBase):
    """A cell's standard output or error, kept up to :data:`OUTPUT_LIMIT` characters."""

    def __init__(self):
        self.parts, self.size = [], 0

    def writable(self):
        return True

    def write(self, text):
        text = str(text)
        if self.size < OUTPUT_LIMIT:
            self.parts.append(text[:OUTPUT_LIMIT - self.size])
        self.size += len(text)
        return len(text)

    def value(self):
        cut = f"\n[{self.size - OUTPUT_LIMIT} more characters not kept]\n" if self.size > OUTPUT_LIMIT else ""
        return "".join(self.parts) + cut


class _NoGrader:
    """An import hook that refuses the grader's own modules (its answer key among them)."""

    def find_spec(self, name, path=None, target=None):
        if name == "instructor" or name.startswith("instructor."):
            raise ImportError(f"{name} is the grader's, not for a submission")
        return None


def _child(shell, cells, order, exercise, limits, channel, feed):
    """In the exercise's process: switch off, run the cells, run the answer; report on ``channel``; each
    input arrives on ``feed``, asked for by the process that answers it."""
    from ddg.checks import answer_results, runner, seal
    from ddg.checks import EXERCISES

    def send(message):
        data = (json.dumps(message) + "\n").encode()
        view = memoryview(data)
        while view:
            view = view[os.write(channel, view):]

    def fetch(i):  # in the process that answers input i
        send({"input": i})
        data = b""
        while not data.endswith(b"\n"):
            chunk = os.read(feed, 1 << 16)
            if not chunk:
                raise EOFError("the grader sent no input")
            data += chunk
        return json.loads(data)

    null = os.open(os.devnull, os.O_RDWR)
    for fd in (0, 1, 2):  # C-level output of the submission goes nowhere, and it reads nothing
        os.dup2(null, fd)
    try:
        with open("/proc/self/oom_score_adj", "w") as file:  # under memory pressure: this process, not the harness
            file.write("1000")
    except OSError:
        pass
    checked = EXERCISES[exercise["name"]]
    seal.switch_off(checked.forbidden, checked.measures)
    for name in [m for m in sys.modules if m == "instructor" or m.startswith("instructor.")]:
        sys.modules[name] = None
    sys.meta_path.insert(0, _NoGrader())
    errors = []
    shell._showtraceback = lambda etype, value, stb: errors.append(
        {"ename": etype.__name__, "evalue": str(value)[:500], "traceback": [str(s)[:4000] for s in stb][-6:]})

    def stop(*_):
        raise CellTimeout(f"the cell was stopped after {limits['cell']:g} s")

    for i in order:
        send({"start": i})
        out, err = _Capture(), _Capture()
        errors.clear()
        sys.stdout, sys.stderr = out, err
        signal.signal(signal.SIGALRM, stop)
        signal.setitimer(signal.ITIMER_REAL, limits["cell"])
        start = time.monotonic()
        try:
            shell.run_cell(cells[i], store_history=True)
        except BaseException as error:  # noqa: BLE001 - whatever escapes IPython is this cell's error
            errors.append({"ename": type(error).__name__, "evalue": str(error)[:500], "traceback": []})
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
            sys.stdout, sys.stderr = sys.__stdout__, sys.__stderr__
        error = errors[-1] if errors else None
        send({"end": i, "seconds": round(time.monotonic() - start, 3), "stdout": out.value(), "stderr": err.value(),
              "error": error, "timeout": bool(error and error["ename"] == "CellTimeout")})
    answer = shell.user_ns.get(exercise["answer"], _child)
    send({"answer": None if answer is _child else type(answer).__name__})
    if answer is not _child:
        send({"raw": answer_results(exercise["name"], answer, runner.Feed(len(exercise["specs_at"]), fetch),
                                    limits["answer"])})


# ------------------------------------------------------------------ the parent: deadlines and reports


def _stop_child(pid):
    """Kill ``pid`` and everything it started (in the sandbox: every process but this one)."""
    if os.getpid() == 1:
        for entry in os.listdir("/proc"):
            if entry.isdigit() and int(entry) != 1:
                try:
                    os.kill(int(entry), signal.SIGKILL)
                except OSError:
                    pass
    for target in (-pid, pid):
        try:
            os.kill(target, signal.SIGKILL)
        except OSError:
            pass


def _reap():
    try:
        while os.waitpid(-1, os.WNOHANG)[0] > 0:
            pass
    except ChildProcessError:
        pass


def _checked(message, order):
    """A message from the child as the parent may use it, or ``None``: the submission's code runs in the
    child, and can write to the channel too (what it can claim there is no more than its answer can)."""
    if not isinstance(message, dict):
        return None
    if "start" in message:
        return {"start": message["start"]} if type(message["start"]) is int and message["start"] in order else None
    if "end" in message:
        error = message.get("error")
        if type(message["end"]) is not int or message["end"] not in order or not isinstance(error, (dict, type(None))):
            return None
        if error is not None:
            trace = error.get("traceback")
            error = {"ename": str(error.get("ename"))[:100], "evalue": str(error.get("evalue"))[:500],
                     "traceback": [str(t)[:4000] for t in trace[-6:]] if isinstance(trace, list) else []}
        seconds = message.get("seconds")
        return {"end": message["end"], "seconds": seconds if isinstance(seconds, (int, float)) else None,
                "stdout": str(message.get("stdout", ""))[:2 * OUTPUT_LIMIT],
                "stderr": str(message.get("stderr", ""))[:2 * OUTPUT_LIMIT], "error": error,
                "timeout": message.get("timeout") is True}
    if "answer" in message:
        return {"answer": message["answer"] if isinstance(message["answer"], str) else None}
    if "input" in message:
        return {"input": message["input"]} if type(message["input"]) is int else None
    return {"raw": message["raw"]} if "raw" in message else None


def _serve(out, specs, at, deadline):
    """Send one input's specs (``at``: offset and length in the file ``specs``) to ``out``, kernel to kernel."""
    offset, length = at
    while length > 0 and time.monotonic() < deadline:
        if not select.select([], [out], [], max(0.0, deadline - time.monotonic()))[1]:
            return
        try:
            sent = os.sendfile(out, specs, offset, length)
        except BlockingIOError:
            continue
        except OSError:  # the submission closed its end of the pipe: it gets nothing
            return
        if not sent:
            return
        offset, length = offset + sent, length - sent


def run_once(shell, cells, order, exercise, limits, specs):
    """Run one child for ``exercise`` over the cells ``order``; what it reported, and where it was stopped."""
    read, write = os.pipe()
    feed, serve = os.pipe()
    pid = os.fork()
    if pid == 0:
        try:
            os.close(read)
            os.close(serve)
            keep = sorted((write, feed))
            os.closerange(3, keep[0])  # the grader's results and specs files among them: only the harness has those
            os.closerange(keep[0] + 1, keep[1])
            os.closerange(keep[1] + 1, 1 << 16)
            os.setpgid(0, 0)
            try:  # it ends with the harness, sandbox or not
                import ctypes

                ctypes.CDLL(None).prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG
            except (OSError, AttributeError):
                pass
            _child(shell, cells, order, exercise, limits, write, feed)
        finally:
            os._exit(0)
    os.close(write)
    os.close(feed)
    os.set_blocking(serve, False)
    served = 0  # each input once, in order
    reports, buffer, received, current = [], b"", 0, None
    deadline, stopped = time.monotonic() + 30, None
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            stopped = {"cell": current, "why": "time"} if current is not None else {"cell": None, "why": "answer-time"}
            break
        if not select.select([read], [], [], min(left, 1.0))[0]:
            _reap()
            continue
        chunk = os.read(read, 1 << 16)
        received += len(chunk)
        if not chunk or received > MESSAGE_LIMIT:
            if received > MESSAGE_LIMIT:
                stopped = {"cell": current, "why": "flood"}
            break
        buffer += chunk
        *lines, buffer = buffer.split(b"\n")
        for line in lines:
            try:
                message = _checked(json.loads(line), order)
            except ValueError:
                continue
            if message is None:
                continue
            if "input" in message:
                if message["input"] == served < len(exercise["specs_at"]):
                    _serve(serve, specs, exercise["specs_at"][served], deadline)
                    served += 1
                continue
            reports.append(message)
            if "start" in message:
                current, deadline = message["start"], time.monotonic() + limits["cell"] + GRACE
            elif "end" in message:
                current, deadline = None, time.monotonic() + 30
            elif "answer" in message:
                deadline = time.monotonic() + limits["answer"] + 15
        if reports and "raw" in reports[-1]:  # the last word: nothing the child sends after it counts
            break
    os.close(read)
    os.close(serve)
    _stop_child(pid)
    status = None
    try:
        status = os.waitpid(pid, 0)[1]
    except ChildProcessError:
        pass
    _reap()
    if stopped is None and current is not None:  # the process ended inside a cell
        how = (f"signal {os.WTERMSIG(status)}" if status is not None and os.WIFSIGNALED(status)
               else f"exit status {os.WEXITSTATUS(status)}" if status is not None else "ended")
        stopped = {"cell": current, "why": "died", "how": how}
    return reports, stopped


def run_exercise(shell, cells, info, exercise, limits, specs):
    """Everything the grader needs to know about one exercise (see the module's docstring)."""
    order = plan(info, exercise["answer"])
    result = {"label": exercise["label"], "plan": order if isinstance(order, list) else [], "ran": [],
              "cells": {}, "stopped": [], "answer": None, "raw": None}
    if isinstance(order, dict):
        defines = re.compile(rf"^\s*(async\s+def|def|class)\s+{re.escape(exercise['answer'])}\b|"
                             rf"^\s*{re.escape(exercise['answer'])}\s*=", re.MULTILINE)
        result["missing"] = {"syntax": {str(i): [*v, bool(defines.search(cells[i]))]
                                        for i, v in order["syntax"].items()}}
        return result
    skipped = set()
    for _ in range(3):
        reports, stopped = run_once(shell, cells, [i for i in order if i not in skipped], exercise, limits, specs)
        for report in reports:
            if "end" in report and str(report["end"]) not in result["cells"]:
                i = report["end"]
                result["ran"].append(i)
                result["cells"][str(i)] = {k: report.get(k) for k in ("seconds", "stdout", "stderr", "error", "timeout")}
            elif "answer" in report:
                result["answer"] = report["answer"]
            elif "raw" in report:
                result["raw"] = report["raw"]
        if stopped is None or stopped["cell"] is None:
            if stopped is not None:
                result["stopped"].append(stopped)
            break
        result["stopped"].append(stopped)
        skipped.add(stopped["cell"])
        result["answer"] = result["raw"] = None
    return result


def preload():
    """What the chapters import, loaded once before any submission: each process forked for one starts with it
    (the sandbox's zygote calls this; so does :func:`main`, where it then costs nothing). Every module of
    ``ddg`` among them: the sandbox hides ddg's source files."""
    os.environ.setdefault("MPLBACKEND", "Agg")
    for name in ("numpy", "shapely", "matplotlib.pyplot", "ddg", "ddg.checks", "ddg.plot", "ddg.explore", "ddg.scene",
                 "IPython.core.interactiveshell", "IPython.core.completer", "traitlets.config"):
        try:
            __import__(name)
        except Exception:  # noqa: BLE001 - a chapter that needs it will say so in its own cell
            pass


def main():
    """Run the job on standard input; write each exercise's result to the descriptor the job names."""
    for number in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGUSR1, signal.SIGUSR2, signal.SIGQUIT):
        signal.signal(number, signal.SIG_IGN)  # a cell's os.kill(1, ...) or os.kill(os.getppid(), ...) does not end us
    with open(0, "rb", closefd=False) as source:
        job = json.load(source)
    results = os.fdopen(job["results_fd"], "w", buffering=1)
    os.set_inheritable(job["results_fd"], False)
    os.set_inheritable(job["specs_fd"], False)
    try:  # no process of the same user may read this one's memory or descriptors
        import ctypes

        ctypes.CDLL(None).prctl(4, 0, 0, 0, 0)  # PR_SET_DUMPABLE 0
    except (OSError, AttributeError):
        pass
    preload()
    shell = _shell()
    cells = job["cells"]
    info = analyse(cells, shell.transform_cell)
    limits = {"cell": float(job["cell_timeout"]), "answer": float(job["answer_timeout"])}
    for exercise in job["exercises"]:
        result = run_exercise(shell, cells, info, exercise, limits, job["specs_fd"])
        results.write(json.dumps(result) + "\n")
    results.write(json.dumps({"done": True}) + "\n")
