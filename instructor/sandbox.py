"""Where a submission runs: a sandbox that holds nothing worth finding, or, where none can be made, a plain process.

:func:`run` starts ``instructor/harness.py`` on one job (the cells of one notebook and the input
specs of its exercises, never the secret they were drawn from) and returns what the harness
reported. On Linux, as root, with util-linux's ``unshare``, ``mount``, ``chroot`` and ``setpriv``
(:func:`available`), the harness runs in

* new mount, PID, network, IPC and UTS namespaces (``unshare``): no network but a loopback that
  is down, a ``/proc`` of its own that shows only its own processes, no way to signal others;
* a new root (``chroot``) assembled on a tmpfs from read-only bind mounts of ``/usr``, ``/bin``,
  ``/sbin``, ``/lib*``, ``/etc``, the Python installation, the virtual environment and the
  ``ddg`` package (each at its own absolute path), the harness at ``/grader/harness.py``, a
  ``/dev`` with ``null``, ``zero``, ``full``, ``random`` and ``urandom`` only, and tmpfs for
  ``/tmp`` and for ``/submission``, its working folder. The instructor's repository (``book/``
  with the solutions, ``instructor/``), other submissions, the grader's files and home folders
  are not in it at all;
* as user ``nobody``, every capability dropped and ``no_new_privs`` set (``setpriv``), before the
  first line of Python runs;
* a memory and a pids cgroup of its own (cgroup v1, below the grader's own cgroup) where the
  machine has them, so the memory limit covers every process it starts; resource limits (address
  space, file size, core files) in any case.

Elsewhere (not Linux, not root, tools missing) the harness runs as the grader's user, in an empty
temporary folder, with the resource limits only: see the README for what it can then see and do.
"""

import contextlib
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
import time
import uuid

HARNESS = pathlib.Path(__file__).with_name("harness.py")
NOBODY = 65534
SYSTEM = ("/usr", "/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32", "/etc")
DEVICES = ("null", "zero", "full", "random", "urandom")
TOOLS = ("unshare", "mount", "chroot", "setpriv")


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


def _font_cache():
    try:
        import matplotlib

        return pathlib.Path(matplotlib.get_cachedir())
    except ImportError:
        return None


def _environment(home, tmp, fonts):
    return {"PATH": "/usr/local/bin:/usr/bin:/bin:/usr/sbin:/sbin", "HOME": home, "TMPDIR": tmp, "LANG": "C.UTF-8",
            "MPLBACKEND": "Agg", "MPLCONFIGDIR": f"{tmp}/matplotlib", "IPYTHONDIR": f"{tmp}/ipython",
            "PYTHONPATH": str(_ddg_home().parent), "PYTHONDONTWRITEBYTECODE": "1", "PYTHONHASHSEED": "0",
            "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
            **({"DDG_FONT_CACHE": fonts} if fonts else {})}


def _script(root, memory_tmpfs):
    """The shell script that assembles the new root at ``root`` and starts the harness in it as nobody."""
    q = shlex.quote
    prefixes = {pathlib.Path(p) for p in (sys.prefix, sys.base_prefix, os.path.dirname(os.path.realpath(sys.executable)))}
    binds = sorted({*prefixes, _ddg_home()} - {pathlib.Path("/")}, key=lambda p: len(p.parts))
    binds = [p for p in binds if not any(p.is_relative_to(s) for s in SYSTEM) and p.exists()]
    binds = [p for i, p in enumerate(binds) if not any(p.is_relative_to(o) for o in binds[:i])]
    lines = ["set -e", "mount --make-rprivate /", f"R={q(str(root))}",
             'mount -t tmpfs -o mode=755,size=4m ddg-sandbox "$R"',
             'mkdir -p "$R/tmp" "$R/dev" "$R/proc" "$R/submission" "$R/grader"',
             f'mount -t tmpfs -o mode=1777,nosuid,nodev,size={memory_tmpfs}m tmp "$R/tmp"',
             f'mount -t tmpfs -o mode=700,uid={NOBODY},gid={NOBODY},nosuid,nodev,size={memory_tmpfs}m work "$R/submission"',
             'mount -t tmpfs -o mode=755,nosuid,size=64k dev "$R/dev"',
             'mkdir "$R/dev/shm" && mount -t tmpfs -o mode=1777,nosuid,nodev,size=64m shm "$R/dev/shm"',
             'ln -s /proc/self/fd "$R/dev/fd"']
    for name in DEVICES:
        lines.append(f'touch "$R/dev/{name}" && mount --bind /dev/{name} "$R/dev/{name}"')

    def bind(source, target):
        kind = "mkdir -p" if os.path.isdir(source) else "touch"
        lines.extend([f'mkdir -p "$(dirname "$R"{q(target)})" && {kind} "$R"{q(target)}',
                      f'mount --bind {q(source)} "$R"{q(target)}',
                      f'mount -o remount,bind,ro,nosuid,nodev "$R"{q(target)}'])

    for path in SYSTEM:
        if os.path.islink(path):
            lines.append(f'ln -s {q(os.readlink(path))} "$R"{q(path)}')
        elif os.path.isdir(path):
            bind(path, path)
    for path in binds:
        bind(str(path), str(path))
    bind(str(HARNESS), "/grader/harness.py")
    fonts = _font_cache()
    if fonts and fonts.is_dir():
        bind(str(fonts), "/grader/fonts")
    lines += ['mount -t proc -o nosuid,nodev,noexec proc "$R/proc"',
              f'exec chroot "$R" setpriv --reuid={NOBODY} --regid={NOBODY} --clear-groups --inh-caps=-all '
              f'--bounding-set=-all --no-new-privs -- "$@"']
    return "\n".join(lines)


class Cgroup:
    """A memory and a pids cgroup (v1) for one sandbox, below the grader's own; nothing where there are none."""

    def __init__(self, memory, pids=256):
        self.paths, name = {}, f"ddg-grade-{uuid.uuid4().hex[:12]}"
        own = {}
        with contextlib.suppress(OSError):
            for line in pathlib.Path("/proc/self/cgroup").read_text().splitlines():
                _, controllers, path = line.split(":", 2)
                for controller in controllers.split(","):
                    own[controller] = path
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

    def join(self):
        """Move the calling process into the cgroups (in the child, before ``exec``: async-signal-safe calls only)."""
        for path in self.paths.values():
            try:
                fd = os.open(str(path / "cgroup.procs"), os.O_WRONLY)
                os.write(fd, b"0")
                os.close(fd)
            except OSError:
                pass

    def oom_kills(self):
        """How many processes the kernel killed for memory in this cgroup."""
        with contextlib.suppress(OSError, KeyError):
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


def run(job, timeout, memory, sandboxed=None):
    """Run the harness on ``job``; returns ``(reports, facts)``.

    ``reports`` is the list of JSON objects the harness wrote (one per exercise, then
    ``{"done": true}``); ``facts`` says how it ended: ``timed_out``, ``oom_kills``, ``sandboxed``
    and ``log`` (the end of its standard output and error, for a harness that failed).
    """
    sandboxed = available() if sandboxed is None else sandboxed
    memory_mb = max(memory >> 20, 64)
    with tempfile.TemporaryDirectory(prefix="ddg-grade-") as folder, \
            tempfile.TemporaryFile() as results, tempfile.TemporaryFile() as stdin, \
            tempfile.TemporaryFile() as log:
        folder = pathlib.Path(folder)
        if sandboxed:
            root = folder / "root"
            root.mkdir()
            home, tmp, fonts = "/submission", "/tmp", "/grader/fonts"
            command = ["unshare", "--mount", "--pid", "--net", "--ipc", "--uts", "--fork", "--kill-child",
                       "sh", "-c", _script(root, min(memory_mb // 4, 1024)), "sandbox",
                       sys.executable, "/grader/harness.py"]
            cgroup = Cgroup(memory)
        else:  # the harness as a plain process; as user nobody where we are root (in a container, say)
            home, tmp = str(folder / "work"), str(folder / "tmp")
            os.mkdir(home)
            os.mkdir(tmp)
            shutil.copy(HARNESS, folder / "harness.py")  # readable wherever the grader's files are not
            fonts = str(_font_cache() or "")
            command, cgroup = [sys.executable, str(folder / "harness.py")], Cgroup.__new__(Cgroup)
            cgroup.paths = {}
            if os.geteuid() == 0 and shutil.which("setpriv"):
                os.chmod(folder, 0o755)
                for path in (home, tmp):
                    os.chown(path, NOBODY, NOBODY)
                command = ["setpriv", f"--reuid={NOBODY}", f"--regid={NOBODY}", "--clear-groups", "--no-new-privs",
                           "--", *command]
        stdin.write(json.dumps({**job, "results_fd": results.fileno()}).encode())
        stdin.seek(0)

        def limits():
            os.setsid()
            cgroup.join()
            # each process's address space: a request beyond it is a MemoryError in the cell that made it, at
            # once; the cgroup bounds what all of them use together (the kernel kills for it, after a while)
            for limit, value in ((resource.RLIMIT_AS, memory), (resource.RLIMIT_FSIZE, 64 << 20),
                                 (resource.RLIMIT_CORE, 0)):
                with contextlib.suppress(ValueError, OSError):
                    resource.setrlimit(limit, (value, value))

        start = time.monotonic()
        process = subprocess.Popen(command, cwd=home if not sandboxed else "/", env=_environment(home, tmp, fonts),
                                   stdin=stdin, stdout=log, stderr=subprocess.STDOUT, pass_fds=(results.fileno(),),
                                   preexec_fn=limits)
        try:
            process.wait(timeout=timeout)
            timed_out = False
        except subprocess.TimeoutExpired:
            timed_out = True
        finally:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(process.pid, signal.SIGKILL)
            process.wait()
        seconds = time.monotonic() - start
        oom = cgroup.oom_kills()
        cgroup.remove()
        reports = []
        results.seek(0)
        for line in results.read(64 << 20).decode(errors="replace").splitlines():
            with contextlib.suppress(ValueError):
                reports.append(json.loads(line))
        log.seek(max(0, log.seek(0, os.SEEK_END) - 4000))
        tail = log.read().decode(errors="replace")
    return reports, {"timed_out": timed_out, "oom_kills": oom, "sandboxed": sandboxed, "log": tail,
                     "seconds": round(seconds, 2)}
