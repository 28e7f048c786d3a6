"""Running an answer apart from the check: a child process, a time limit, and what crosses back.

:func:`evaluate` calls ``answer(*args)`` for every argument tuple, each in a process of its own (a
copy of the caller's, made with ``fork``), and returns what came back as plain data: the values as
nested lists of numbers, or what went wrong. Each input's process receives its own input and no
other (the grader serves them one at a time, :class:`Feed`), builds it, and only then loses the
checks' code and calls the answer. Inside it:

* the ``ddg`` quantities the exercise asks for are switched off (they raise ``WriteItYourself``),
  as is anything the check uses to measure (``measures``: shapely's ``buffer``, say), both where
  they are implemented (every reference to the original is replaced, so ``gc`` finds none);
* the check's own code is gone: the modules that draw input, hold the public results or judge are
  emptied and cannot be imported or reloaded again, and ``importlib.reload`` refuses;
* the answer has at most :data:`MEMORY_LIMIT` bytes more than the caller, at most
  :data:`PROCESS_LIMIT` processes (where the operating system enforces it for the user), and
  everything it starts is stopped: on Linux as root the inputs' processes run below process 1 of a
  new PID namespace, which stops what each input's process left before the next one starts, and
  the kernel ends the namespace as a whole; elsewhere a warden process, made the subreaper of
  everything the answer starts (even after ``setsid``), stops them all at the end.

Where ``fork`` is missing (Windows) the answer runs in a thread of this process: the time limit
still gives a verdict, but nothing above is in place. None of this stops an answer that copies
``ddg``'s public source, which is always at hand.
"""

import contextlib
import ctypes
import io
import json
import os
import resource
import select
import signal
import sys
import threading
import time

import numpy as np

from .seal import WriteItYourself, drop_checks, switch_off  # noqa: F401 (WriteItYourself: part of the runner's API)

TIME_LIMIT = 10.0
"""Seconds an answer may run, for all the input of one check together."""

MEMORY_LIMIT = 2 << 30
"""Bytes of address space an answer may use beyond what its process starts with."""

PROCESS_LIMIT = 64
"""Processes an answer may start (counted, as the operating system does, per user)."""

class Feed:
    """Input served one at a time: ``count`` inputs, ``fetch(i)`` the argument specs of the ``i``-th, called
    in the process that answers it (the grader's harness serves each from outside, once)."""

    def __init__(self, count, fetch):
        self.count, self.fetch = count, fetch

    def __len__(self):
        return self.count


def evaluate(answer, calls, forbidden=(), measures=(), limit=TIME_LIMIT, build=lambda spec: spec):
    """``answer(*build(args))`` for each ``args`` in ``calls`` (a list, or a :class:`Feed`), apart from the caller.

    Returns a list with one entry per call (``{"value": ..., "type": ..., "mutated": bool}``,
    ``{"error": ..., "kind": ...}`` or ``{"missing": True}``), or a dict if the whole run failed
    (``{"timeout": limit}``, ``{"exited": True}`` or ``{"error": ...}``). ``forbidden`` names
    ``DiscreteCurve`` attributes to switch off, ``measures`` the ``"module.attribute"`` callables.
    """
    if not callable(answer):
        return {"error": f"the answer should be a function, got {type(answer).__name__} {answer!r:.40}"}
    if hasattr(os, "fork") and sys.platform.startswith(("linux", "darwin")):
        return _in_child(answer, calls, forbidden, measures, limit, build)
    box, specs = {}, calls if isinstance(calls, list) else [calls.fetch(i) for i in range(len(calls))]
    thread = threading.Thread(target=lambda: box.update(results=answers(answer, specs, build)), daemon=True)
    thread.start()
    thread.join(limit)
    return box.get("results", {"timeout": limit})


def answers(answer, calls, build):
    """Call the answer on every input; each result or failure as plain data."""
    return answer_all(answer, [[build(a) for a in spec] for spec in calls])


def answer_all(answer, inputs):
    """Call the answer on every list of arguments in ``inputs``; each result or failure as plain data."""
    results = []
    for args in inputs:
        results.append(answer_one(answer, args))
        if "missing" in results[-1]:
            break
    return results


def answer_one(answer, args):
    """Call the answer on one list of arguments: its result or failure as plain data."""
    before = [np.array(a) if isinstance(a, np.ndarray) else None for a in args]
    try:
        value = answer(*args)
    except NotImplementedError:
        return {"missing": True}
    except BaseException as error:  # noqa: BLE001 - an answer may raise anything, SystemExit too
        try:
            return {"error": str(error)[:300], "kind": type(error).__name__}
        except BaseException:  # noqa: BLE001 - its __str__ too
            return {"error": "(an error that cannot be shown)", "kind": type(error).__name__}
    mutated = any(b is not None and (b.shape != a.shape or not np.array_equal(a, b, equal_nan=True))
                  for a, b in zip(args, before, strict=True))
    return {**plain(value), "mutated": mutated}


RESULT_LIMIT = 1_000_000
"""Numbers an answer's result may hold: far more than any exercise asks for."""


def plain(value):
    """What an answer returned, as JSON-ready numbers and its type (or a description of what it was).

    Real numbers only: text that looks like a number, complex numbers, ``None`` and other objects
    inside a list are described, never converted.
    """
    if value is None:
        return {"error": "it returned None, not real numbers (a missing `return`?)", "kind": "type"}
    kind = type(value).__name__
    try:
        array = None if isinstance(value, (str, bytes)) else np.asarray(value)
        if array is not None and array.size > RESULT_LIMIT:
            return {"error": f"it returned {array.size} numbers, far more than any exercise asks for", "kind": "type"}
        if array is not None and array.dtype.kind == "O" and all(
                isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, bool) for x in array.flat):
            array = array.astype(float)
        if array is not None and array.dtype.kind in "biuf":
            return {"value": array.astype(float).tolist(), "type": kind}
    except BaseException:  # noqa: BLE001 - an object's own __array__ or __float__ may raise anything
        pass
    try:
        shown = f" {str(value)[:40]!r}"
    except BaseException:  # noqa: BLE001 - its __str__ too
        shown = ""
    return {"error": f"it returned {kind}{shown}, not real numbers", "kind": "type"}


def well_formed(results):
    """Whether ``results`` is a list of results as :func:`answers` makes them."""
    def entry(r):
        return isinstance(r, dict) and (
            (isinstance(r.get("value"), (int, float, list)) and isinstance(r.get("type"), str))
            or (isinstance(r.get("error"), str) and isinstance(r.get("kind"), str))
            or r == {"missing": True})
    return isinstance(results, list) and all(entry(r) for r in results)


# ------------------------------------------------------------------ the answer's process


def _limits():
    """Limits on the answer's memory, processes and core files."""
    with contextlib.suppress(OSError, ValueError):
        pages = int(open("/proc/self/statm").read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
        resource.setrlimit(resource.RLIMIT_AS, (pages + MEMORY_LIMIT, pages + MEMORY_LIMIT))
    with contextlib.suppress(OSError, ValueError, AttributeError):
        running = len([p for p in os.listdir("/proc") if p.isdigit()]) if os.path.isdir("/proc") else 0
        resource.setrlimit(resource.RLIMIT_NPROC, (running + PROCESS_LIMIT, running + PROCESS_LIMIT))
    with contextlib.suppress(OSError, ValueError):
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


def _libc():
    try:
        return ctypes.CDLL(None, use_errno=True)
    except OSError:
        return None


def _new_pid_namespace():
    """Whether this process's next child will be process 1 of a new PID namespace (Linux, as root)."""
    libc = _libc()
    return bool(sys.platform.startswith("linux") and libc is not None and libc.unshare(0x20000000) == 0)


def _reap(pid):
    with contextlib.suppress(ChildProcessError):
        os.waitpid(pid, 0)


def _descendants(pid):
    """Every process below ``pid``, from ``/proc`` (Linux)."""
    found, frontier = [], [pid]
    while frontier:
        parent = frontier.pop()
        with contextlib.suppress(OSError):
            for task in os.listdir(f"/proc/{parent}/task"):
                with open(f"/proc/{parent}/task/{task}/children") as file:
                    children = [int(c) for c in file.read().split()]
                found += children
                frontier += children
    return found


def _stop_all_below(pid):
    """Kill every descendant of ``pid`` until none is left (they may be forking meanwhile)."""
    for _ in range(200):
        below = _descendants(pid)
        if not below:
            return
        for child in below:
            with contextlib.suppress(OSError):
                os.kill(child, signal.SIGKILL)
        with contextlib.suppress(ChildProcessError):
            while os.waitpid(-1, os.WNOHANG)[0]:
                pass
        time.sleep(0.001)


def _warden(answer, calls, forbidden, measures, build, results_fd, control_fd):
    """The child: start the answer's process, hand its pid to the caller, and stop all it leaves."""
    contained = _new_pid_namespace()
    if not contained:
        _libc() and _libc().prctl(36, 1, 0, 0, 0)  # PR_SET_CHILD_SUBREAPER: orphans come to us
    pid = os.fork()
    if pid == 0:  # the answer's process: one process per input below it
        try:
            os.close(control_fd)
            sys.stdout = sys.stderr = io.StringIO()  # the kernel's streams belong to the caller
            _limits()
            switch_off(forbidden, measures)  # once, for every input's process below
            _write_all(results_fd, json.dumps(_each_apart(answer, calls, build)).encode())
        finally:
            os._exit(0)
    os.close(results_fd)
    os.write(control_fd, f"{pid} {int(contained)}\n".encode())
    os.close(control_fd)

    def stop(*_):
        with contextlib.suppress(OSError):
            os.kill(pid, signal.SIGKILL)
        _stop_all_below(os.getpid())
        os._exit(0)

    signal.signal(signal.SIGTERM, stop)
    with contextlib.suppress(ChildProcessError):
        os.waitpid(pid, 0)
    stop()


def _each_apart(answer, calls, build):
    """Each input in a process of its own, which fetches that input (and no other), builds it, drops
    the checks and calls the answer; its result comes back through a pipe. (What the exercise asks
    for is already switched off, in the process that forks them.)"""
    results = []
    for i in range(len(calls)):
        read, write = os.pipe()
        pid = os.fork()
        if pid == 0:
            try:
                os.close(read)
                spec = calls[i] if isinstance(calls, list) else calls.fetch(i)
                args = [build(a) for a in spec]  # before the builders are sealed away
                del calls, spec
                drop_checks()
                _write_all(write, json.dumps(answer_one(answer, args)).encode())
            finally:
                os._exit(0)
        os.close(write)
        chunks = _read_until_ended(read, pid)
        if os.getpid() == 1:  # process 1 of a PID namespace of its own: what that input's process left behind
            with contextlib.suppress(OSError):
                os.kill(-1, signal.SIGKILL)
            with contextlib.suppress(ChildProcessError):
                while os.waitpid(-1, 0):
                    pass
        try:
            result = json.loads(b"".join(chunks))
        except ValueError:
            result = {"error": "it ended the process it ran in (os._exit, or a crash)", "kind": "exited"}
        results.append(result)
        if "missing" in result:
            break
    return results


def _write_all(fd, data):
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]


def _read_until_ended(fd, pid, limit=64 << 20):
    """What ``pid`` wrote to ``fd`` until it ended (a process it started may hold the pipe open longer), up
    to ``limit`` bytes (more is no result: the judge says so)."""
    chunks, ended, size = [], False, 0
    os.set_blocking(fd, False)
    while True:
        if select.select([fd], [], [], 0.02)[0]:
            with contextlib.suppress(BlockingIOError):
                chunk = os.read(fd, 1 << 16)
                size += len(chunk)
                if not chunk or size > limit:
                    break
                chunks.append(chunk)
                continue
        if ended:
            break
        try:
            ended = os.waitpid(pid, os.WNOHANG)[0] != 0
        except ChildProcessError:
            ended = True
    os.close(fd)
    with contextlib.suppress(ChildProcessError):
        os.waitpid(pid, 0)
    return chunks


def _in_child(answer, calls, forbidden, measures, limit, build):
    """Run the answer in a warden's child; read its results back through a pipe."""
    results_read, results_write = os.pipe()
    control_read, control_write = os.pipe()
    warden = os.fork()
    if warden == 0:
        try:
            os.close(results_read)
            os.close(control_read)
            os.setpgid(0, 0)
            _warden(answer, calls, forbidden, measures, build, results_write, control_write)
        finally:
            os._exit(0)
    os.close(results_write)
    os.close(control_write)
    with contextlib.suppress(OSError):
        os.setpgid(warden, warden)
    deadline = time.monotonic() + limit
    answering, contained = _read_pid(control_read, deadline)
    chunks = []
    try:
        while True:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([results_read], [], [], left)[0]:
                return {"timeout": limit}
            chunk = os.read(results_read, 1 << 16)
            if not chunk:
                break
            chunks.append(chunk)
    finally:
        os.close(results_read)
        _end(warden, answering, contained)
    if not chunks:
        return {"exited": True}
    try:
        results = json.loads(b"".join(chunks))
    except ValueError:
        results = None
    return results if well_formed(results) else {"error": "the process the answer ran in sent back something that "
                                                          "is not its results"}


def _read_pid(fd, deadline):
    """The answer's process id, as its warden reports it (``None`` if it does not), and whether it
    is process 1 of a PID namespace of its own."""
    data = b""
    while not data.endswith(b"\n") and time.monotonic() < deadline:
        if not select.select([fd], [], [], max(0.0, deadline - time.monotonic()))[0]:
            break
        chunk = os.read(fd, 64)
        if not chunk:
            break
        data += chunk
    os.close(fd)
    words = data.split()
    if len(words) != 2 or not all(w.isdigit() for w in words):
        return None, False
    return int(words[0]), words[1] == b"1"


def _end(warden, answering, contained=False):
    """Stop the warden (which stops everything below it) and, to be sure, the answer's process.

    When the answer is process 1 of its own PID namespace and started nothing that is still there,
    the namespace holds no one else: the reaping, which waits for the namespace to be torn down
    (milliseconds), is left to a thread, and the verdict need not wait for it."""
    if contained and answering and not _descendants(answering):
        for pid in (answering, warden):
            with contextlib.suppress(OSError):
                os.kill(pid, signal.SIGKILL)
        threading.Thread(target=_reap, args=(warden,), daemon=True).start()
        return
    with contextlib.suppress(OSError):
        os.kill(warden, signal.SIGTERM)
    for _ in range(2000):  # up to 1 s for the warden to clean up
        with contextlib.suppress(ChildProcessError):
            if os.waitpid(warden, os.WNOHANG)[0]:
                break
        time.sleep(0.0005)
    for pid in (answering, warden):
        if pid:
            with contextlib.suppress(OSError):
                os.kill(pid, signal.SIGKILL)
    with contextlib.suppress(OSError):
        os.killpg(warden, signal.SIGKILL)
    with contextlib.suppress(ChildProcessError):
        os.waitpid(warden, 0)
