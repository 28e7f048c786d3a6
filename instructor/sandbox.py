"""Where a submission runs: a sandbox that holds nothing worth finding, or, where none can be made, a plain process.

:func:`run` runs ``instructor/harness.py`` on one job (the cells of one notebook and the input
specs of its exercises, never the secret they were drawn from) and returns what the harness
reported. Each grading thread keeps a *zygote*: a process that has imported what the chapters
import (numpy, matplotlib, IPython, ``ddg``) once, and forks a fresh process for each submission,
which reads nothing of it but the paths of its own job. On Linux, as root, with util-linux's
``unshare``, ``mount`` and ``chroot`` (:func:`available`), that process, before it reads its job,
enters

* a memory and a pids cgroup of its own (cgroup v1, below the grader's own cgroup) where the
  machine has them, so the memory limit covers every process it starts; resource limits (address
  space, file size, core files) in any case;
* new mount, PID, network, IPC and UTS namespaces: no network but a loopback that is down, a
  ``/proc`` of its own that shows only its own processes, no way to signal others;
* a new root (``chroot``) assembled on a tmpfs from read-only bind mounts of ``/usr``, ``/bin``,
  ``/sbin``, ``/lib*``, ``/etc``, the Python installation, the virtual environment and the
  ``ddg`` package (each at its own absolute path), a ``/dev`` with ``null``, ``zero``, ``full``,
  ``random`` and ``urandom`` only, and tmpfs for ``/tmp`` and for ``/submission``, its working
  folder. The instructor's repository (``book/`` with the solutions, ``instructor/``), other
  submissions, the grader's files and home folders are not in it at all;
* user ``nobody``, with every capability dropped and ``no_new_privs`` set, before the first line
  of the submission runs.

Elsewhere (not Linux, not root, tools missing, or a container that forbids namespaces) the harness
runs in the same kind of process without the namespaces and the new root: as user ``nobody`` where
the grader is root, else as the grader's user; see the README for what it can then see and do.
"""

import atexit
import contextlib
import ctypes
import json
import os
import pathlib
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

NOBODY = 65534
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


def _script(root, tmpfs_mb):
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
             f'mount -t tmpfs -o mode=700,uid={NOBODY},gid={NOBODY},nosuid,nodev,size={tmpfs_mb}m work "$R/submission"',
             'mount -t tmpfs -o mode=755,nosuid,size=64k dev "$R/dev"',
             'mkdir "$R/dev/shm" && mount -t tmpfs -o mode=1777,nosuid,nodev,size=64m shm "$R/dev/shm"',
             'ln -s /proc/self/fd "$R/dev/fd"']
    lines += [f'touch "$R/dev/{name}" && mount --bind /dev/{name} "$R/dev/{name}"' for name in DEVICES]
    for path in [*SYSTEM, *map(str, binds)]:
        if os.path.islink(path):
            lines.append(f'ln -s {q(os.readlink(path))} "$R"{q(path)}')
        elif os.path.isdir(path):
            lines.append(f'mkdir -p "$R"{q(path)} && mount --bind -o ro,nosuid,nodev {q(path)} "$R"{q(path)}')
    lines.append('mount -t proc -o nosuid,nodev,noexec proc "$R/proc"')
    return "\n".join(lines)


class Cgroup:
    """A memory and a pids cgroup (v1) for one sandbox, below the grader's own; nothing where there are none."""

    def __init__(self, memory, pids=256):
        self.paths, name, own = {}, f"ddg-grade-{uuid.uuid4().hex[:12]}", {}
        with contextlib.suppress(OSError):
            for line in pathlib.Path("/proc/self/cgroup").read_text().splitlines():
                _, controllers, path = line.split(":", 2)
                own.update((controller, path) for controller in controllers.split(","))
        for controller, limits in (("memory", {"memory.limit_in_bytes": memory, "memory.memsw.limit_in_bytes": memory}),
                                   ("pids", {"pids.max": pids})):
            path = pathlib.Path("/sys/fs/cgroup", controller, own.get(controller, "/").lstrip("/"), name)
            try:
                path.mkdir()
            except OSError:
                continue
            self.paths[controller] = path
            for file, value in limits.items():
                with contextlib.suppress(OSError):
                    (path / file).write_text(str(value))

    def oom_kills(self):
        """How many processes the kernel killed for memory in this cgroup."""
        with contextlib.suppress(OSError, KeyError, ValueError):
            stats = dict(line.split() for line in (self.paths["memory"] / "memory.oom_control").read_text().splitlines())
            return int(stats.get("oom_kill", 0))
        return 0

    def remove(self):
        for path in self.paths.values():
            for _ in range(100):
                try:
                    path.rmdir()
                    break
                except FileNotFoundError:
                    break
                except OSError:
                    time.sleep(0.02)


# ------------------------------------------------------------------ the zygote and what it forks


def _enter(request):
    """In a child of the zygote, as root: the cgroups, the limits, the namespaces and the new root, nobody;
    then the harness, on the job named in ``request``. Never returns."""
    try:
        for path in request["cgroups"]:
            with open(path, "w") as file:
                file.write("0")
        for fd, name, mode in ((0, "job", os.O_RDONLY), (1, "log", os.O_WRONLY), (3, "results", os.O_WRONLY)):
            opened = os.open(request[name], mode)
            if opened != fd:
                os.dup2(opened, fd)
                os.close(opened)
        os.dup2(1, 2)
        os.closerange(4, 1 << 16)  # the zygote's pipes to the grader among them
        os.setsid()
        for limit, value in ((resource.RLIMIT_AS, request["memory"]), (resource.RLIMIT_FSIZE, 64 << 20),
                             (resource.RLIMIT_CORE, 0)):
            with contextlib.suppress(ValueError, OSError):
                resource.setrlimit(limit, (value, value))
        libc = ctypes.CDLL(None, use_errno=True)
        if request["script"] is not None:
            if libc.unshare(NAMESPACES) != 0:
                raise OSError(ctypes.get_errno(), "unshare")
            pid = os.fork()
            if pid:  # outside the new PID namespace, the sandbox's face to the zygote: it ends when that ends
                os._exit(os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1]) & 0x7F)
            libc.prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG: killing the face kills the whole sandbox
            subprocess.run(["sh", "-c", request["script"]], check=True, stdout=2)
            os.chroot(request["root"])
            os.chdir("/")
            for capability in range(64):
                libc.prctl(24, capability, 0, 0, 0)  # PR_CAPBSET_DROP
        if os.geteuid() == 0:
            os.setgroups([])
            os.setgid(NOBODY)
            os.setuid(NOBODY)  # the kernel clears every capability with it
        libc.prctl(38, 1, 0, 0, 0)  # PR_SET_NO_NEW_PRIVS
        os.environ.clear()
        os.environ.update(request["env"])
        os.chdir(request["env"]["HOME"])
        harness.main()
    except BaseException:  # noqa: BLE001 - whatever happened is for the grader's log
        traceback.print_exc()
        os._exit(70)
    os._exit(0)


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


def run(job, timeout, memory, sandboxed=None):
    """Run the harness on ``job``; returns ``(reports, facts)``.

    ``reports`` is the list of JSON objects the harness wrote (one per exercise, then
    ``{"done": true}``); ``facts`` says how it ended: ``timed_out``, ``oom_kills``, ``sandboxed``,
    ``seconds`` and ``log`` (the end of its output, for a harness that failed).
    """
    sandboxed = available() if sandboxed is None else sandboxed
    with tempfile.TemporaryDirectory(prefix="ddg-grade-") as folder:
        folder = pathlib.Path(folder)
        paths = {name: folder / name for name in ("job", "log", "results")}
        paths["job"].write_text(json.dumps({**job, "results_fd": 3}))
        paths["log"].touch()
        paths["results"].touch()
        request = {**{name: str(path) for name, path in paths.items()}, "memory": memory, "script": None,
                   "root": None, "cgroups": []}
        cgroup = Cgroup(memory) if sandboxed else None
        if sandboxed:
            root = folder / "root"
            root.mkdir()
            home, tmp = "/submission", "/tmp"
            request.update(script=_script(root, min(max(memory >> 22, 16), 1024)), root=str(root),
                           cgroups=[str(p / "cgroup.procs") for p in cgroup.paths.values()])
        else:
            home, tmp = str(folder / "work"), str(folder / "tmp")
            for path in (home, tmp):
                os.mkdir(path)
                if os.geteuid() == 0:  # where the harness runs as nobody
                    os.chown(path, NOBODY, NOBODY)
            os.chmod(folder, 0o755)
        request["env"] = {"PATH": "/usr/local/bin:/usr/bin:/bin", "HOME": home, "TMPDIR": tmp, "LANG": "C.UTF-8",
                          "MPLBACKEND": "Agg", "MPLCONFIGDIR": f"{tmp}/matplotlib", "IPYTHONDIR": f"{tmp}/ipython",
                          "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
        zygote, start = _zygote(), time.monotonic()
        zygote.stdin.write(json.dumps(request) + "\n")
        zygote.stdin.flush()
        pid = json.loads(zygote.stdout.readline())["pid"]
        ended = threading.Event()
        watchdog = threading.Timer(timeout, lambda: ended.is_set() or _kill(pid))
        watchdog.start()
        status = json.loads(zygote.stdout.readline())["status"]
        ended.set()
        watchdog.cancel()
        seconds = time.monotonic() - start
        oom = cgroup.oom_kills() if cgroup else 0
        if cgroup:
            cgroup.remove()
        reports = []
        with open(paths["results"], "rb") as file:
            for line in file.read(64 << 20).decode(errors="replace").splitlines():
                with contextlib.suppress(ValueError):
                    reports.append(json.loads(line))
        log = paths["log"].read_bytes()[-4000:].decode(errors="replace")
    return reports, {"timed_out": seconds >= timeout, "oom_kills": oom, "sandboxed": sandboxed, "log": log,
                     "status": status, "seconds": round(seconds, 2)}


def _kill(pid):
    """Stop a submission: its process group, and (in the sandbox) with its face everything inside."""
    for target in (-pid, pid):
        with contextlib.suppress(OSError):
            os.kill(target, signal.SIGKILL)
