"""Where a submission runs: a sandbox that holds nothing worth finding, or, where none can be made, a plain process.

:func:`run` runs ``instructor/harness.py`` on one job (the cells of one notebook and the input
specs of its exercises, never the secret they were drawn from) and returns what the harness
reported. Each grading thread keeps a *zygote*: a process that has imported what the chapters
import (numpy, matplotlib, IPython, ``ddg``) once, and forks a fresh process for each submission,
which reads nothing of it but the paths of its own job.

What bounds all of a submission's processes together, where the grader is root on Linux
(:func:`limits` says it in words, and :func:`run` with each result):

* a uid of its own, from :data:`FIRST_UID` on (a block per PID namespace: a container's graders keep to
  theirs), one for each sandbox running at once (never one that
  ``/etc/passwd``, ``/etc/group`` or a subordinate id range names), so that ``RLIMIT_NPROC``, which
  the kernel counts per uid, bounds how many processes it has, and whatever it leaves running is
  found and killed;
* a cgroup v1 (a memory and a pids cgroup) or v2 (one cgroup with both, see :func:`_v2_base`)
  below the grader's own, where the machine lets us make one, so that the kernel counts every page
  and process; ``DDG_SANDBOX_LIMITS=v1|v2|none`` chooses, unset means v2, else v1, else none;
* where no memory cgroup could be made, a watchdog that every 50 ms adds up the memory of the uid's
  processes (their share of it, ``Pss``) and kills the largest, the exercise's first, until the
  others fit in the limit: each counts as killed for memory;
* in any case, limits on each process: address space, file size, no core files.

On Linux, as root, with util-linux's ``unshare``, ``mount`` and ``chroot`` (:func:`available`), the
process also enters, before it reads its job,

* new mount, PID, network, IPC and UTS namespaces: no network but a loopback that is down, a
  ``/proc`` of its own that shows only its own processes, no way to signal others;
* a new root (``chroot``) assembled on a tmpfs from read-only bind mounts of ``/usr``, ``/bin``,
  ``/sbin``, ``/lib*``, ``/etc``, the Python installation, the virtual environment and the
  ``ddg`` package (each at its own absolute path), a ``/dev`` with ``null``, ``zero``, ``full``,
  ``random`` and ``urandom`` only, and tmpfs for ``/tmp`` and for ``/submission``, its working
  folder. The instructor's repository (``book/`` with the solutions, ``instructor/``), other
  submissions, the grader's files and home folders are not in it at all;
* its own uid, with every capability dropped and ``no_new_privs`` set, before the first line of
  the submission runs.

Between the zygote and the submission stays its *face* (:func:`_face`), as root, outside the
namespaces: the grader's time limit reaches the submission through it, it runs the watchdog, and
when the submission ends it kills whatever of its uid is left and reaps it.

Elsewhere (not Linux, not root, tools missing, or a container that forbids namespaces) the harness
runs in the same kind of process without the namespaces and the new root: as its own uid where the
grader is root on Linux, else as the grader's user; see INSTRUCTORS.md (Security) for what it can then see and do.
bubblewrap could make the namespaces and the new root, but only for a new program: a new Python that
imports what the zygote has takes about 0.6 s, a fork of the zygote, the sandbox made, under 0.1 s.
"""

import atexit
import contextlib
import ctypes
import errno
import fcntl
import functools
import grp
import itertools
import json
import os
import pathlib
import pwd
import re
import resource
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import traceback
import uuid

from . import harness

FIRST_UID = 200_000
"""The uid of the first sandbox; one more for each sandbox running at the same time."""

PIDS = 256
"""Processes (threads included) one submission may have at once."""

OWN_UID = sys.platform.startswith("linux") and os.geteuid() == 0
"""Whether each submission runs as a uid of its own (root on Linux), and so is bounded together."""

LOCKS = pathlib.Path("/run/ddg-sandbox")
"""Where each grader of this machine holds a lock on the uids its sandboxes use."""

SYSTEM = ("/usr", "/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32", "/etc")
DEVICES = ("null", "zero", "full", "random", "urandom")
TOOLS = ("unshare", "mount", "chroot")
NAMESPACES = 0x00020000 | 0x20000000 | 0x40000000 | 0x08000000 | 0x04000000  # mount, PID, network, IPC, UTS
HARNESS = pathlib.Path(harness.__file__)

_WORKS = {}


def available():
    """Whether :func:`run` can build the sandbox here: Linux, root, the util-linux tools, and namespaces
    that the machine lets us make (a container may not), tried once."""
    if "sandbox" not in _WORKS:
        works = (sys.platform.startswith("linux") and os.geteuid() == 0 and all(shutil.which(tool) for tool in TOOLS))
        if works:
            folder = tempfile.mkdtemp(prefix="ddg-probe-")
            probe = f'mount -t tmpfs probe {shlex.quote(folder)} && mkdir {shlex.quote(folder)}/proc && ' \
                    f'mount -t proc proc {shlex.quote(folder)}/proc'
            works = subprocess.run(["unshare", "--mount", "--pid", "--net", "--ipc", "--uts", "--fork", "--kill-child",
                                    "sh", "-c", probe], capture_output=True).returncode == 0
            os.rmdir(folder)
        _WORKS["sandbox"] = works
    return _WORKS["sandbox"]


def _ddg_home():
    import ddg

    return pathlib.Path(ddg.__file__).resolve().parent


def _script(root, tmpfs_mb, uid):
    """The shell script that assembles the new root at ``root`` (run inside the new namespaces)."""
    q = shlex.quote
    prefixes = {pathlib.Path(p) for p in (sys.prefix, sys.base_prefix, os.path.dirname(os.path.realpath(sys.executable)))}
    binds = sorted({*prefixes, _ddg_home()} - {pathlib.Path("/")}, key=lambda p: len(p.parts))
    binds = [p for p in binds if not any(p.is_relative_to(s) for s in SYSTEM) and p.exists()]
    binds = [p for i, p in enumerate(binds) if not any(p.is_relative_to(o) for o in binds[:i])]
    lines = ["set -e", "mount --make-rprivate /", f"R={q(str(root))}",  # nothing mounted here is seen outside
             'mount -t tmpfs -o mode=755,size=4m ddg-sandbox "$R"',
             'mkdir -p "$R/tmp" "$R/dev" "$R/proc" "$R/submission"',
             f'mount -t tmpfs -o mode=1777,nosuid,nodev,size={tmpfs_mb}m tmp "$R/tmp"',
             f'mount -t tmpfs -o mode=700,uid={uid},gid={uid},nosuid,nodev,size={tmpfs_mb}m work "$R/submission"',
             'mount -t tmpfs -o mode=755,nosuid,size=64k dev "$R/dev"',
             'mkdir "$R/dev/shm" && mount -t tmpfs -o mode=1777,nosuid,nodev,size=64m shm "$R/dev/shm"',
             'ln -s /proc/self/fd "$R/dev/fd"']
    lines += [f'touch "$R/dev/{name}" && mount --bind /dev/{name} "$R/dev/{name}"' for name in DEVICES]
    for path in [*SYSTEM, *map(str, binds)]:
        if os.path.islink(path):
            lines.append(f'ln -s {q(os.readlink(path))} "$R"{q(path)}')
        elif os.path.isdir(path):
            lines.append(f'mkdir -p "$R"{q(path)} && mount --bind -o ro,nosuid,nodev {q(path)} "$R"{q(path)}')
    # ddg's source is hidden, every copy of it (the zygote has loaded every module of it): no copy of
    # DiscreteCurve can be made by running ddg/curve.py again, with the quantity an exercise asks for left on
    places = [*binds, pathlib.Path("/usr"), pathlib.Path("/usr/local")]
    copies = {_ddg_home(), *(d for place in places for d in place.glob("lib/python3*/*-packages/ddg"))}
    lines += [f'mount -t tmpfs -o ro,mode=755,size=4k hidden "$R"{q(str(d))}' for d in sorted(copies) if d.is_dir()]
    lines.append('mount -t proc -o nosuid,nodev,noexec proc "$R/proc"')
    return "\n".join(lines)


# ------------------------------------------------------------------ what bounds a submission's processes together


def _read(path):
    try:
        return pathlib.Path(path).read_text()
    except OSError:
        return ""


def _write(path, value):
    with open(path, "w") as file:
        file.write(str(value))


def _signal(pid, number=signal.SIGKILL):
    with contextlib.suppress(OSError):
        os.kill(pid, number)


def _own_cgroups():
    """The grader's cgroup in each v1 hierarchy, by controller, and in the v2 one (controller ``""``)."""
    own = {}
    for line in _read("/proc/self/cgroup").splitlines():
        _, controllers, path = line.split(":", 2)
        own.update((controller, path) for controller in controllers.split(","))
    return own


def _v1_bases():
    """``{controller: the grader's own cgroup}`` in the v1 memory and pids hierarchies there are."""
    own = _own_cgroups()
    bases = {c: pathlib.Path("/sys/fs/cgroup", c, own[c].lstrip("/")) for c in ("memory", "pids") if c in own}
    bases = {c: path for c, path in bases.items() if path.is_dir()}
    if not bases:
        raise OSError("no v1 memory or pids hierarchy in /sys/fs/cgroup")
    return bases


def _v2_where():
    """The grader's own cgroup in the cgroup2 file system."""
    own = pathlib.PurePosixPath(_own_cgroups().get("", "/"))
    for line in _read("/proc/self/mountinfo").splitlines():
        fields = line.split()
        if "-" in fields and fields[fields.index("-") + 1] == "cgroup2" and own.is_relative_to(fields[3]):
            return pathlib.Path(fields[4], own.relative_to(fields[3]))
    raise OSError("no cgroup2 file system is mounted")


def _v2_base(own):
    """The grader's own cgroup ``own``, with memory and pids on for its children, where each submission gets
    a cgroup. A cgroup with controllers on for its children may hold no process (but the root), so the
    processes in it, the grader's among them, move to a leaf ``ddg-grader`` first (a grader started from
    there uses the cgroup above it). Raises OSError saying why it cannot be had."""
    own = own.parent if own.name == "ddg-grader" else own
    offered = _read(own / "cgroup.controllers").split()
    if not {"memory", "pids"} <= set(offered):
        raise OSError(f"{own} offers {' '.join(offered) or 'no controller'}, not memory and pids")
    if {"memory", "pids"} <= set(_read(own / "cgroup.subtree_control").split()):
        return own
    try:
        _write(own / "cgroup.subtree_control", "+memory +pids")
    except OSError as error:
        if error.errno != errno.EBUSY:
            raise
        (own / "ddg-grader").mkdir(exist_ok=True)
        for pid in _read(own / "cgroup.procs").split():
            with contextlib.suppress(OSError):  # a process that ended meanwhile
                _write(own / "ddg-grader" / "cgroup.procs", pid)
        _write(own / "cgroup.subtree_control", "+memory +pids")
    return own


class Cgroup:
    """The cgroups of one sandbox, in ``base`` (see :func:`_choice`): for ``kind`` v1 a memory and a pids
    cgroup, for v2 one with both, for none nothing. ``dirs`` maps each controller to its cgroup."""

    SWAP = ("memory.memsw.limit_in_bytes", "memory.swap.max")  # missing where the kernel does not count swap

    def __init__(self, memory, kind, base):
        self.kind, self.dirs, self.error, name = kind, {}, "", f"ddg-grade-{uuid.uuid4().hex[:12]}"
        if kind == "v1":
            plan = [(base[c], (c,), files) for c, files in (
                ("memory", {"memory.limit_in_bytes": memory, "memory.memsw.limit_in_bytes": memory}),
                ("pids", {"pids.max": PIDS})) if c in base]
        elif kind == "v2":
            plan = [(base, ("memory", "pids"), {"memory.max": memory, "memory.swap.max": 0, "pids.max": PIDS})]
        else:
            plan = []
        for parent, controllers, files in plan:
            path = parent / name
            try:
                path.mkdir()
                for file, value in files.items():
                    try:
                        _write(path / file, value)
                    except OSError:
                        if file not in self.SWAP:
                            raise
            except OSError as error:
                self.error = str(error)
                _rmdir(path)
                continue
            self.dirs.update(dict.fromkeys(controllers, path))

    def procs(self):
        """The files a process writes its id to, to enter these cgroups."""
        return [str(path / "cgroup.procs") for path in dict.fromkeys(self.dirs.values())]

    def oom_kills(self):
        """How many processes the kernel killed for memory in this cgroup."""
        if "memory" not in self.dirs:
            return 0
        events = self.dirs["memory"] / ("memory.oom_control" if self.kind == "v1" else "memory.events")
        found = re.search(r"^oom_kill (\d+)$", _read(events), re.M)
        return int(found.group(1)) if found else 0

    def remove(self):
        for path in set(self.dirs.values()):
            _rmdir(path)


def _rmdir(path):
    for _ in range(100):  # a cgroup whose last processes are still ending is busy
        try:
            path.rmdir()
            return
        except FileNotFoundError:
            return
        except OSError:
            time.sleep(0.02)


def _choice():
    """``(kind, base, why)``: the cgroups that bound a submission here (``v1``, ``v2`` or ``none``), where
    they go, and why none could be had, as ``DDG_SANDBOX_LIMITS`` asks (unset: v2, else v1, else none)."""
    asked = os.environ.get("DDG_SANDBOX_LIMITS", "")
    if asked not in ("", "v1", "v2", "none"):
        raise ValueError(f"DDG_SANDBOX_LIMITS={asked}: give v1, v2 or none (or leave it unset: the best there is)")
    return _choose(asked)


@functools.cache
def _choose(asked):
    if not OWN_UID or asked == "none":
        return "none", None, ""
    reasons = []
    for kind in [asked] if asked else ["v2", "v1"]:
        try:
            base = _v2_base(_v2_where()) if kind == "v2" else _v1_bases()
            probe = Cgroup(1 << 30, kind, base)
            probe.remove()
            if probe.dirs:
                return kind, base, ""
            reasons.append(f"{kind}: {probe.error}")
        except OSError as error:
            reasons.append(f"{kind}: {error}")
    return "none", None, "no cgroup " + "; ".join(reasons)


def _words(kind, controllers, why):
    if not OWN_UID:
        return "none: limits on each process only (the grader is not root on Linux)"
    words = f"cgroup {kind} ({', '.join(sorted(controllers))}) + own uid" if controllers else "own uid: RLIMIT_NPROC"
    return words + ("" if "memory" in controllers else " and a memory watchdog") + (f" ({why})" if why else "")


def limits():
    """What bounds a submission's processes together here, in words, as :func:`run` reports it: "cgroup v1
    (memory, pids) + own uid", "cgroup v2 (memory, pids) + own uid", "own uid: RLIMIT_NPROC and a memory
    watchdog" (then why no cgroup, in brackets, where one was tried), or "none: limits on each process only
    (...)". ``DDG_SANDBOX_LIMITS`` chooses (v1, v2 or none); a choice that cannot be had falls back to none."""
    kind, base, why = _choice()
    return _words(kind, set(base) if kind == "v1" else {"memory", "pids"} if kind == "v2" else set(), why)


@functools.cache
def _reserved():
    """The ids this machine gives to someone: users, groups, and subordinate ranges (containers')."""
    ranges = [range(p.pw_uid, p.pw_uid + 1) for p in pwd.getpwall()]
    ranges += [range(g.gr_gid, g.gr_gid + 1) for g in grp.getgrall()]
    for line in (_read("/etc/subuid") + _read("/etc/subgid")).splitlines():
        with contextlib.suppress(ValueError):
            _, start, count = line.split(":")
            ranges.append(range(int(start), int(start) + int(count)))
    return ranges


def _first_uid():
    """Where this grader's uids start: :data:`FIRST_UID`, plus a block of 256 chosen by its PID namespace, so
    that graders in two containers of one machine (each with its own locks) do not share a uid."""
    try:
        block = os.stat("/proc/self/ns/pid").st_ino % 1024
    except OSError:
        block = 0
    return FIRST_UID + 256 * block


@contextlib.contextmanager
def _own_uid():
    """A uid for one submission (``None`` unless :data:`OWN_UID`), held until the block ends: the first from
    :data:`FIRST_UID` on that no other sandbox of this machine holds. What a grader that died left running as
    it is killed first."""
    if not OWN_UID:
        yield None
        return
    LOCKS.mkdir(mode=0o700, parents=True, exist_ok=True)
    for uid in itertools.count(_first_uid()):
        if any(uid in taken for taken in _reserved()):
            continue
        lock = os.open(LOCKS / str(uid), os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o600)
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
            break
        except BlockingIOError:
            os.close(lock)
    try:
        for pid in _processes(uid):
            _signal(pid)
        yield uid
    finally:
        os.close(lock)


def _processes(uid, memory=False):
    """The processes of ``uid`` that are alive (a zombie is not, unless other threads of it are); with
    ``memory``, as ``(oom_score_adj, bytes, pid)``, the bytes its share of memory (Pss; else resident)."""
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        status = _read(f"/proc/{pid}/status")
        if f"\nUid:\t{uid}\t" not in status or ("\nState:\tZ" in status and "\nThreads:\t1\n" in status):
            continue
        if not memory:
            found.append(int(pid))
            continue
        size = re.search(r"^(?:Pss|VmRSS):\s+(\d+)", _read(f"/proc/{pid}/smaps_rollup") or status, re.M)
        adjust = int(_read(f"/proc/{pid}/oom_score_adj") or 0)
        found.append((adjust, int(size.group(1)) << 10 if size else 0, int(pid)))
    return found


def _trim(uid, limit, killed):
    """One round of the memory watchdog: kill the largest processes of ``uid``, those of an exercise first
    (the harness gives them oom_score_adj 1000), until the others fit in ``limit`` bytes; add them to ``killed``."""
    processes = sorted((p for p in _processes(uid, memory=True) if p[2] not in killed), reverse=True)
    total = sum(size for _, size, _ in processes)
    for _, size, pid in processes:
        if total <= limit:
            break
        _signal(pid)
        killed.add(pid)
        total -= size


def _kill_all(uid):
    """Kill every process of ``uid``, and reap those that came to this process (their subreaper), until
    none is alive; 10 s at most (a process stuck in the kernel does not end at once)."""
    end = time.monotonic() + 10
    while True:
        alive = _processes(uid)
        for pid in alive:
            _signal(pid)
        with contextlib.suppress(ChildProcessError):
            while os.waitpid(-1, os.WNOHANG)[0]:
                pass
        if not alive or time.monotonic() > end:
            return
        time.sleep(0.005)


# ------------------------------------------------------------------ the zygote and what it forks


def _enter(request):
    """In a child of the zygote, as root: the cgroups, the limits, the namespaces; then, in a child (this
    process stays as its face: :func:`_face`), the new root and the submission's uid; then the harness,
    on the job named in ``request``. Never returns."""
    try:
        for path in request["cgroups"]:
            _write(path, 0)
        for fd, name, mode in ((0, "job", os.O_RDONLY), (1, "log", os.O_WRONLY), (3, "results", os.O_WRONLY),
                               (4, "specs", os.O_RDONLY)):
            opened = os.open(request[name], mode)
            if opened != fd:
                os.dup2(opened, fd)
                os.close(opened)
        os.dup2(1, 2)
        os.closerange(5, 1 << 16)  # the zygote's pipes to the grader among them
        os.setsid()
        uid = request["uid"]
        rlimits = [(resource.RLIMIT_AS, request["memory"]), (resource.RLIMIT_FSIZE, 64 << 20), (resource.RLIMIT_CORE, 0)]
        for limit, value in rlimits + ([(resource.RLIMIT_NPROC, PIDS)] if uid is not None else []):
            with contextlib.suppress(ValueError, OSError):
                resource.setrlimit(limit, (value, value))
        libc = ctypes.CDLL(None, use_errno=True)
        if request["script"] is not None and libc.unshare(NAMESPACES) != 0:
            raise OSError(ctypes.get_errno(), "unshare")
        if uid is not None:
            libc.prctl(36, 1, 0, 0, 0)  # PR_SET_CHILD_SUBREAPER: what the submission leaves behind comes to the face
        pid = os.fork()
        if pid:  # outside the new PID namespace
            os._exit(_face(pid, request))
        os.setpgid(0, 0)
        if request["script"] is not None:
            subprocess.run(["sh", "-c", request["script"]], check=True, stdout=2)
            os.chroot(request["root"])
            os.chdir("/")
            for capability in range(64):
                libc.prctl(24, capability, 0, 0, 0)  # PR_CAPBSET_DROP
        if uid is not None:
            os.setgroups([])
            os.setgid(uid)
            os.setuid(uid)  # the kernel clears every capability with it
        libc.prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG (setuid clears it): killing the face kills it
        libc.prctl(38, 1, 0, 0, 0)  # PR_SET_NO_NEW_PRIVS
        os.environ.clear()
        os.environ.update(request["env"])
        os.chdir(request["env"]["HOME"])
        harness.main()
    except BaseException:  # noqa: BLE001 - whatever happened is for the grader's log
        traceback.print_exc()
        os._exit(70)
    os._exit(0)


def _face(pid, request):
    """The submission's parent, as root: on SIGTERM (the grader's time limit) it kills the submission; while
    the submission runs, the memory watchdog runs here where asked (``watch``: the limit); when it ends, every
    process of its uid is killed and reaped. Returns the exit status to report (128 + signal if killed)."""
    signal.signal(signal.SIGTERM, lambda *_: (_signal(pid), _signal(-pid)))
    uid, killed = request["uid"], set()
    status = None
    while request["watch"] and status is None:  # every 50 ms until the submission ends (waitpid: any kernel)
        done, status = os.waitpid(pid, os.WNOHANG)
        status = status if done else None
        if status is None:
            _trim(uid, request["watch"], killed)
            time.sleep(0.05)
    status = os.waitpid(pid, 0)[1] if status is None else status
    _signal(-pid)
    if uid is not None:
        _kill_all(uid)
    _write(request["facts"], json.dumps({"oom_kills": len(killed)}))
    code = os.waitstatus_to_exitcode(status)
    return code if code >= 0 else 128 - code


def zygote():
    """The fork server: import once, then for each request on standard input fork :func:`_enter`, report
    ``{"pid"}`` and then ``{"status"}`` on standard output. It reads the paths of a job, never a job."""
    harness.preload()
    for line in sys.stdin:
        request = json.loads(line)
        pid = os.fork()
        if pid == 0:
            _enter(request)
        print(json.dumps({"pid": pid}), flush=True)
        print(json.dumps({"status": os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1])}), flush=True)


_LOCAL, _ZYGOTES = threading.local(), []


@atexit.register
def close():
    """End every zygote (each ends when its standard input does), and wait for it."""
    while _ZYGOTES:
        process = _ZYGOTES.pop()
        with contextlib.suppress(OSError):
            process.stdin.close()
        process.wait()


def _zygote():
    """This thread's zygote (started the first time), with an environment of its own."""
    process = getattr(_LOCAL, "zygote", None)
    if process is None or process.poll() is not None:
        paths = [str(_ddg_home().parent), str(pathlib.Path(__file__).resolve().parents[1])]
        code = f"import sys; sys.path[:0] = {paths!r}; from instructor import sandbox; sandbox.zygote()"
        try:
            import matplotlib

            fonts = {"MPLCONFIGDIR": matplotlib.get_cachedir()}  # its font list: read once, by the zygote
        except ImportError:
            fonts = {}
        env = {"PATH": os.environ.get("PATH", "/usr/bin:/bin"), "MPLBACKEND": "Agg", "OPENBLAS_NUM_THREADS": "1",
               "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1", "PYTHONDONTWRITEBYTECODE": "1", **fonts}
        process = subprocess.Popen([sys.executable, "-c", code], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                   env=env, cwd="/", text=True)
        _LOCAL.zygote = process
        _ZYGOTES.append(process)
    return process


def _specs_apart(job, path):
    """The job as the harness reads it: each exercise's input specs moved to the file ``path`` (one JSON
    line per input, readable by root only), which the harness holds as descriptor 4 and never reads
    itself: it hands each input to the one process that answers it (``harness._serve``)."""
    exercises, lines, offset = [], [], 0
    for exercise in job["exercises"]:
        at = []
        for specs in exercise["specs"]:
            line = (json.dumps(specs) + "\n").encode()
            at.append([offset, len(line)])
            lines.append(line)
            offset += len(line)
        exercises.append({**{k: v for k, v in exercise.items() if k != "specs"}, "specs_at": at})
    descriptor = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    with os.fdopen(descriptor, "wb") as file:
        file.write(b"".join(lines))
    return {**job, "exercises": exercises, "results_fd": 3, "specs_fd": 4}


def run(job, timeout, memory, sandboxed=None):
    """Run the harness on ``job``; returns ``(reports, facts)``.

    ``reports`` is the list of JSON objects the harness wrote (one per exercise, then
    ``{"done": true}``); ``facts`` says how it ended: ``timed_out``, ``oom_kills`` (processes killed for
    memory, by the kernel or the watchdog), ``sandboxed``, ``limits`` (what bounded its processes
    together, in words: :func:`limits`), ``uid``, ``status``, ``seconds`` and ``log`` (the end of its
    output, for a harness that failed).
    """
    sandboxed = available() if sandboxed is None else sandboxed
    kind, base, why = _choice()
    with tempfile.TemporaryDirectory(prefix="ddg-grade-") as folder, _own_uid() as uid:
        folder = pathlib.Path(folder)
        paths = {name: folder / name for name in ("job", "log", "results", "facts", "specs")}
        paths["job"].write_text(json.dumps(_specs_apart(job, paths["specs"])))
        for name in ("job", "log", "results"):  # opened by root for the harness: no one else reads them
            paths[name].touch()
            paths[name].chmod(0o600)
        cgroup = Cgroup(memory, kind, base)
        try:
            request = {**{name: str(path) for name, path in paths.items()}, "memory": memory, "script": None,
                       "root": None, "cgroups": cgroup.procs(), "uid": uid,
                       "watch": memory if uid is not None and "memory" not in cgroup.dirs else None}
            if sandboxed:
                root = folder / "root"
                root.mkdir()
                home, tmp = "/submission", "/tmp"
                request.update(script=_script(root, min(max(memory >> 22, 16), 1024), uid), root=str(root))
            else:
                home, tmp = str(folder / "work"), str(folder / "tmp")
                for path in (home, tmp):
                    os.mkdir(path)
                    if uid is not None:
                        os.chown(path, uid, uid)
                os.chmod(folder, 0o711)  # its own folders are reached, not listed
            request["env"] = {"PATH": "/usr/local/bin:/usr/bin:/bin", "HOME": home, "TMPDIR": tmp, "LANG": "C.UTF-8",
                              "MPLBACKEND": "Agg", "MPLCONFIGDIR": f"{tmp}/matplotlib", "IPYTHONDIR": f"{tmp}/ipython",
                              "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
            zygote, start = _zygote(), time.monotonic()
            zygote.stdin.write(json.dumps(request) + "\n")
            zygote.stdin.flush()
            pid = json.loads(zygote.stdout.readline())["pid"]
            ended = threading.Event()
            watchdog = threading.Timer(timeout, lambda: ended.is_set() or _signal(pid, signal.SIGTERM))
            watchdog.start()
            status = json.loads(zygote.stdout.readline())["status"]
            ended.set()
            watchdog.cancel()
            seconds = time.monotonic() - start
            try:  # written by the face, as root (a submission run without root could write it too)
                counted = json.loads(_read(paths["facts"]) or "{}").get("oom_kills", 0)
            except (ValueError, AttributeError):
                counted = 0
            oom = cgroup.oom_kills() + (counted if isinstance(counted, int) else 0)
        finally:
            cgroup.remove()
        reports = []
        with open(paths["results"], "rb") as file:
            for line in file.read(64 << 20).decode(errors="replace").splitlines():
                with contextlib.suppress(ValueError):
                    reports.append(json.loads(line))
        log = paths["log"].read_bytes()[-4000:].decode(errors="replace")
    why = why or (f"no cgroup this time: {cgroup.error}" if kind != "none" and cgroup.error else "")
    return reports, {"timed_out": seconds >= timeout, "oom_kills": oom, "sandboxed": sandboxed, "log": log,
                     "limits": _words(kind, set(cgroup.dirs), why), "uid": uid, "status": status,
                     "seconds": round(seconds, 2)}
