"""The sandbox bounds all of a submission's processes together, in number and in memory, whatever the
machine has: cgroup v1, cgroup v2, or neither (then the submission's own uid, with RLIMIT_NPROC and
the grader's memory watchdog).

A fork attack and a memory attack run through ``sandbox.run``, each in the one cell of a real harness
job, under every mechanism this machine has (``DDG_SANDBOX_LIMITS``; one it lacks is skipped, and says
why). The setting up of a cgroup v2 is checked apart, on a tree of files made here that behaves as
the kernel's does where it matters, so that it is checked on a machine without cgroup v2 too.
"""

import contextlib
import errno
import json
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import uuid

import pytest

from instructor import sandbox

NAME = """import ctypes, json, os, signal, time


def named():  # so that the test finds what is left of the attack, whatever its uid
    ctypes.CDLL(None).prctl(15, b"{mark}", 0, 0, 0)  # PR_SET_NAME


"""

FORK = NAME + """children = []
for _ in range(300):
    try:
        pid = os.fork()
    except OSError:
        break
    if pid == 0:
        named()
        os.setsid()  # out of the harness's reach
        time.sleep(600)
        os._exit(0)
    children.append(pid)
for pid in children[5:]:  # five stay, for the sandbox to end
    os.kill(pid, signal.SIGKILL)
    os.waitpid(pid, 0)
print("FORKED", len(children))
attack = len
"""

MEMORY = NAME + """children = []
for _ in range(4):
    pid = os.fork()
    if pid == 0:
        named()
        try:
            block = bytearray(400 << 20)
            block[::4096] = b"x" * len(block[::4096])  # every page touched
        except MemoryError:
            os._exit(3)
        time.sleep(1)
        os._exit(0)
    children.append(pid)
print("ENDED", json.dumps([os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1]) for pid in children]))
attack = len
"""


def attack(cell, sandboxed, mark):
    """Run ``cell`` as the one cell of a job in the sandbox, with 1024 MB; what it printed, and the facts."""
    job = {"cells": [cell.replace("{mark}", mark)], "cell_timeout": 20, "answer_timeout": 5, "specs_fd": 3,
           "exercises": [{"label": "attack", "name": "turning_angles", "answer": "attack", "specs": [], "specs_at": []}]}
    reports, facts = sandbox.run(job, 60, 1024 << 20, sandboxed)
    assert reports and reports[-1] == {"done": True}, facts["log"]  # the harness lived to report
    return reports[0]["cells"]["0"]["stdout"], facts


def named(mark):
    """The processes called ``mark``, zombies included (a zombie still counts against RLIMIT_NPROC)."""
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        with contextlib.suppress(OSError):
            if pathlib.Path(f"/proc/{pid}/comm").read_text().strip() == mark:
                found.append(int(pid))
    return found


@pytest.fixture
def mark():
    """A name for an attack's processes; afterwards, whatever has it is killed, even when the test failed."""
    mark = f"ddg-{uuid.uuid4().hex[:8]}"
    yield mark
    for pid in named(mark):
        with contextlib.suppress(OSError):
            os.kill(pid, signal.SIGKILL)


@pytest.fixture(params=["v1", "v2", "none"])
def mechanism(request, monkeypatch):
    """DDG_SANDBOX_LIMITS set to each mechanism (one that this machine does not have is skipped)."""
    if not sandbox.OWN_UID:
        pytest.skip("a submission is bounded as a whole only where the grader is root on Linux")
    monkeypatch.setenv("DDG_SANDBOX_LIMITS", request.param)
    if request.param != "none" and not sandbox.limits().startswith(f"cgroup {request.param} "):
        pytest.skip(f"not on this machine: {sandbox.limits()}")
    return request.param


@pytest.fixture(params=[True, False], ids=["sandboxed", "plain"])
def sandboxed(request):
    """With the namespaces and the new root, and without (a container that forbids namespaces)."""
    if request.param and not sandbox.available():
        pytest.skip("no namespaces here (they need unshare, mount and chroot, and a machine that allows them)")
    if not request.param and not others_can_run_python():
        pytest.skip(f"another user cannot run {sys.executable} here (it is in root's home folder?)")
    return request.param


def others_can_run_python():
    try:
        return subprocess.run([sys.executable, "-c", "import bdb"], user=65534, group=65534, extra_groups=[],
                              capture_output=True).returncode == 0
    except OSError:
        return False


def test_a_fork_attack_gets_at_most_the_process_limit_and_leaves_nothing(mechanism, sandboxed, mark):
    out, facts = attack(FORK, sandboxed, mark)
    forked = int(out.split("FORKED ")[1])
    assert 200 < forked <= sandbox.PIDS, out  # the harness and the cell's own process count too
    assert named(mark) == []
    assert facts["limits"].startswith({"v1": "cgroup v1 (memory, pids) + own uid", "v2": "cgroup v2 (memory, pids) + "
                                       "own uid", "none": "own uid: RLIMIT_NPROC and a memory watchdog"}[mechanism])


def test_a_memory_attack_of_four_children_is_cut_down_and_reported(mechanism, sandboxed, mark):
    out, facts = attack(MEMORY, sandboxed, mark)
    ended = json.loads(out.split("ENDED ")[1])
    assert 3 not in ended, out  # each child got its 400 MB: what stopped them is the limit on them all
    assert ended.count(-signal.SIGKILL) >= 1 and ended.count(0) < 4, out
    assert facts["oom_kills"] >= 1, facts
    assert named(mark) == []


# ------------------------------------------------------------------ cgroup v2, on a tree of files


@pytest.fixture
def tree(tmp_path, monkeypatch):
    """A cgroup2 file system (``mount``) where the grader's cgroup is ``mount/grader`` and offers memory and
    pids; ``_write`` refuses, as the kernel does, controllers for the children of a cgroup that holds
    processes, and moves a process whose id is written to a cgroup.procs there."""
    mount = tmp_path / "cgroup"
    own = mount / "grader"
    own.mkdir(parents=True)
    (mount / "cgroup.controllers").write_text("cpu memory pids hugetlb\n")
    (mount / "cgroup.subtree_control").write_text("memory pids\n")
    (own / "cgroup.controllers").write_text("memory pids\n")
    (own / "cgroup.subtree_control").write_text("\n")
    (own / "cgroup.procs").write_text("")

    def write(path, value):
        path = pathlib.Path(path)
        if path.name == "cgroup.subtree_control" and (path.parent / "cgroup.procs").read_text().split():
            raise OSError(errno.EBUSY, "Device or resource busy")
        if path.name == "cgroup.procs":
            for procs in mount.rglob("cgroup.procs"):
                procs.write_text("".join(f"{p}\n" for p in procs.read_text().split() if p != str(value)))
            value = (path.read_text() if path.exists() else "") + f"{value}\n"
        path.write_text(str(value))

    monkeypatch.setattr(sandbox, "_write", write)
    monkeypatch.setattr(sandbox, "_rmdir", shutil.rmtree)  # a directory of files, not a cgroup
    sandbox._choose.cache_clear()
    yield mount, own
    sandbox._choose.cache_clear()


def test_v2_a_submission_gets_its_cgroup_with_its_limits_below_the_graders(tree):
    mount, own = tree
    base = sandbox._v2_base(own)
    assert base == own and (own / "cgroup.subtree_control").read_text() == "+memory +pids"
    cgroup = sandbox.Cgroup(1 << 30, "v2", base)
    path = cgroup.dirs["memory"]
    assert cgroup.dirs == {"memory": path, "pids": path} and path.parent == own
    assert {f: (path / f).read_text() for f in ("memory.max", "memory.swap.max", "pids.max")} == {
        "memory.max": str(1 << 30), "memory.swap.max": "0", "pids.max": str(sandbox.PIDS)}
    assert cgroup.procs() == [str(path / "cgroup.procs")]
    (path / "memory.events").write_text("low 0\nhigh 0\nmax 7\noom 3\noom_kill 2\noom_group_kill 0\n")
    assert cgroup.oom_kills() == 2
    cgroup.remove()
    assert not path.exists()


def test_v2_the_processes_of_the_graders_cgroup_move_to_a_leaf_first(tree):
    mount, own = tree
    (own / "cgroup.procs").write_text("41\n42\n")  # the grader and, say, the shell that started it
    assert sandbox._v2_base(own) == own
    assert (own / "ddg-grader" / "cgroup.procs").read_text().split() == ["41", "42"]
    assert (own / "cgroup.procs").read_text() == ""
    assert (own / "cgroup.subtree_control").read_text() == "+memory +pids"
    assert sandbox.Cgroup(1 << 30, "v2", own).dirs["pids"].parent == own
    assert sandbox._v2_base(own / "ddg-grader") == own  # the next grader, started from there: no leaf in a leaf
    assert not (own / "ddg-grader" / "ddg-grader").exists()


def test_v2_without_memory_and_pids_falls_back_and_says_why(tree, monkeypatch):
    mount, own = tree
    monkeypatch.setattr(sandbox, "_v2_where", lambda: own)
    monkeypatch.setattr(sandbox, "OWN_UID", True)
    monkeypatch.setenv("DDG_SANDBOX_LIMITS", "v2")
    assert sandbox.limits() == "cgroup v2 (memory, pids) + own uid"

    (own / "cgroup.controllers").write_text("hugetlb\n")
    sandbox._choose.cache_clear()
    assert sandbox.limits() == (f"own uid: RLIMIT_NPROC and a memory watchdog (no cgroup v2: {own} offers hugetlb, "
                                "not memory and pids)")
    monkeypatch.setenv("DDG_SANDBOX_LIMITS", "v3")
    with pytest.raises(ValueError, match="give v1, v2 or none"):
        sandbox.limits()
