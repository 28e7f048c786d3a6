"""Answers that misbehave get a verdict, and cannot reach the check: the process an answer runs in.

An answer that hangs, crashes, exits, uses the ddg quantity it should compute, measures instead of
computing, reaches for the checks' own code or frames, sends back forged results, forks, leaves
processes behind or eats memory: each gets a clear verdict, nothing it starts outlives the check,
and nothing it does changes the verdict of the next check.
"""

import os
import pathlib
import sys
import time

import numpy as np
import pytest

import ddg
from ddg import checks
from ddg.checks import runner


def turning_angles(vertices):  # a right answer
    v = np.asarray(vertices, dtype=float)
    e = np.roll(v, -1, axis=0) - v
    a = np.roll(e, 1, axis=0)
    psi = np.arctan2(a[:, 1] * e[:, 0] - a[:, 0] * e[:, 1], (a * e).sum(axis=1))
    return np.where(psi == -np.pi, np.pi, psi)


def host_pid():
    """This process's id as the host sees it (inside a PID namespace os.getpid() counts from 1)."""
    return int(os.readlink("/proc/self"))


def alive(pid):
    stat = pathlib.Path(f"/proc/{pid}/stat")
    return stat.exists() and stat.read_text().split(") ")[-1].split()[0] != "Z"


def test_an_answer_that_never_returns_gets_a_verdict_within_the_time_limit():
    def endless(vertices):
        while True:
            pass

    start = time.monotonic()
    feedback = checks.check_turning_angles(endless, seed=0)
    assert not feedback and "did not return within 10 s" in feedback.problem
    assert time.monotonic() - start < checks.TIME_LIMIT + 10  # a loaded machine starts processes slowly


def test_the_quantity_the_exercise_asks_for_is_switched_off_and_named_by_its_public_name():
    for name, answer in (("turning_angles", lambda v: ddg.DiscreteCurve(v).turning_angles),
                         ("turning_angles", lambda v: 2 * np.arctan(ddg.DiscreteCurve(v).tan_half_psi)),
                         ("turning_angles", lambda v: ddg.DiscreteCurve(v).curvature("angle")
                          * ddg.DiscreteCurve(v).dual_lengths),
                         ("length_gradient", lambda v: ddg.DiscreteCurve(v).length_gradient()),
                         ("length_gradient", lambda v: -ddg.DiscreteCurve(v).laplacian(v)),
                         ("length_gradient", lambda v: -ddg.flow.velocity(ddg.DiscreteCurve(v), "sine")),
                         ("vertex_normals", lambda c, m: c.bisector_normals),
                         ("minkowski_area", lambda c, eps: c.inflated_area(eps))):
        feedback = checks.run(name, answer, 0)
        assert not feedback and "write yourself" in feedback.problem and "`_" not in feedback.problem, feedback
    curve = ddg.regular_polygon(5)  # and everything is back here
    assert np.allclose(curve.turning_angles, 2 * np.pi / 5) and curve.length_gradient().shape == (5, 2)


def test_what_the_exercise_does_not_ask_for_stays_usable():
    """Switching off ddg's turns leaves a curve to be made and its edges and lengths read: an answer
    that takes its edges from ddg passes; one that calls the exact turn, private or not, does not."""
    def from_edges(vertices):
        e = ddg.DiscreteCurve(vertices).edges
        a = np.roll(e, 1, axis=0)
        psi = np.arctan2(a[:, 1] * e[:, 0] - a[:, 0] * e[:, 1], (a * e).sum(axis=1))
        return np.where(psi == -np.pi, np.pi, psi) + 0 * ddg.DiscreteCurve(vertices).edge_lengths

    def exact(vertices):
        from ddg import _numerics
        v = np.asarray(vertices, dtype=float)
        return 2 * np.arctan(_numerics._exact_tan_half_turn(v, np.arange(len(v))))

    assert checks.check_turning_angles(from_edges, seed=0)
    feedback = checks.check_turning_angles(exact, seed=0)
    assert not feedback and "write yourself" in feedback.problem, feedback


def test_the_checks_own_code_is_out_of_reach_of_the_answer():
    def importer(vertices):
        from ddg.checks import comparing  # the judge's reference measurements
        return comparing.ZigzagExponent().expected(None)

    def reloader(vertices):
        import importlib
        importlib.reload(ddg.curve)  # would undo the switch-off
        return ddg.DiscreteCurve(vertices).turning_angles

    def reimporter(vertices):
        del sys.modules["ddg.curve"]
        import ddg.curve
        return ddg.curve.DiscreteCurve(vertices).turning_angles

    def frame_walker(vertices):  # up the stack to the check's exercise, to ask it for the answer
        frame = sys._getframe(1)
        while frame is not None:
            for value in frame.f_locals.values():
                if hasattr(value, "expected"):
                    return value.expected(checks.judge.Call((vertices,), ""))
            frame = frame.f_back
        return np.zeros(len(vertices))

    for answer, said in ((importer, "ddg.checks"), (reloader, "reloading"), (reimporter, "afresh"),
                         (frame_walker, "")):
        feedback = checks.check_turning_angles(answer, seed=0)
        assert not feedback and said in feedback.problem, (answer.__name__, feedback)
    assert checks.check_turning_angles(turning_angles, seed=0)  # nothing stays broken here


def test_the_verdict_does_not_depend_on_state_the_answer_can_reach():
    def tamper(vertices):  # make every comparison pass
        checks.judge._verdict = lambda *args: None
        return np.zeros(len(vertices))

    feedback = checks.check_turning_angles(tamper, seed=3)
    assert not feedback and checks.check_turning_angles(turning_angles)


def test_crashing_exiting_and_odd_answers_are_reported_not_raised():
    cases = [(lambda v: v[10**6], "raised IndexError"), (lambda v: os._exit(3), "ended the process"),
             (lambda v: sys.exit(1), "raised SystemExit"), (lambda v: "psi", "not real numbers"),
             (lambda v: np.zeros(len(v)) * 1j, "not real numbers"), (lambda v: [1.0], "you returned 1 number"),
             (lambda v: np.full(len(v), np.nan), "NaN"), (2.0, "should be a function")]
    for answer, expected in cases:
        feedback = checks.check_turning_angles(answer, seed=0)
        assert not feedback and expected in feedback.problem, (expected, feedback)
    assert "✗" in checks.check_turning_angles(cases[0][0], seed=0)._repr_html_()


def test_forged_results_get_a_verdict():
    def pipe_end():  # the write end of the pipe its results go back through, from a caller's frame
        frame = sys._getframe(2)
        while "results_fd" not in frame.f_locals:
            frame = frame.f_back
        return frame.f_locals["results_fd"]

    def forger(data):
        def answer(vertices):
            os.write(pipe_end(), data)
            os._exit(0)
        return answer

    for data in (b"not json", b'{"x": 1}', b'{"timeout": "soon"}', b'[{"v": 1}]', b'[{"value": [[1, 2], [3]]}]',
                 b'[{"value": "1", "type": "str"}]'):
        feedback = checks.check_turning_angles(forger(data), seed=0)
        assert not feedback and ("not its results" in feedback.problem or "not an array" in feedback.problem), \
            (data, feedback)


CONTAINMENTS = pytest.mark.parametrize("namespace", [True, False], ids=["pid-namespace", "subreaper"])


@CONTAINMENTS
def test_nothing_an_answer_starts_outlives_its_verdict(namespace, monkeypatch):
    if not namespace:  # where a new PID namespace is not allowed (not root): the warden's way
        monkeypatch.setattr(runner, "_new_pid_namespace", lambda: False)
    marker = pathlib.Path(os.environ.get("TMPDIR", "/tmp")) / f"ddg-check-escape-{os.getpid()}"

    def escapes(vertices):  # a grandchild in a session of its own, holding the results' pipe open
        if os.fork() == 0:
            os.setsid()
            if os.fork() == 0:
                marker.write_text(str(host_pid()))
                time.sleep(30)
            os._exit(0)
        time.sleep(0.3)
        return turning_angles(vertices)

    start = time.monotonic()
    feedback = checks.check_turning_angles(escapes, seed=0)
    assert feedback, feedback  # it answered right; what it left behind was stopped, not waited for
    assert time.monotonic() - start < 25  # the grandchild sleeps 30 s: waiting for it would take longer
    time.sleep(0.2)
    assert not alive(int(marker.read_text())), "a process the answer started lives on"
    marker.unlink()


@CONTAINMENTS
def test_a_fork_loop_is_bounded_and_stopped(namespace, monkeypatch):
    if not namespace:
        monkeypatch.setattr(runner, "_new_pid_namespace", lambda: False)
    folder = pathlib.Path(os.environ.get("TMPDIR", "/tmp")) / f"ddg-check-forks-{os.getpid()}"
    folder.mkdir(exist_ok=True)

    def forks(vertices):  # 100 processes (more than PROCESS_LIMIT) that would sleep for a minute
        for _ in range(100):
            try:
                if os.fork() == 0:
                    (folder / str(host_pid())).touch()
                    time.sleep(60)
                    os._exit(0)
            except OSError:  # the process limit, where the system enforces it
                break
        return turning_angles(vertices)

    checks.check_turning_angles(forks, seed=0)
    time.sleep(0.3)
    started = [int(p.name) for p in folder.iterdir()]
    assert started and not [pid for pid in started if alive(pid)], "processes of the answer live on"
    for p in folder.iterdir():
        p.unlink()
    folder.rmdir()


def test_an_answer_that_eats_memory_is_stopped():
    def hungry(vertices):
        return np.ones((1 << 40) // 8)[: len(vertices)]  # a terabyte

    feedback = checks.check_turning_angles(hungry, seed=0)
    assert not feedback and "MemoryError" in feedback.problem, feedback
    assert runner.MEMORY_LIMIT < 1 << 40


def test_a_notebook_that_makes_numpy_raise_still_gets_a_verdict():
    previous = np.seterr(all="raise")
    try:
        feedback = checks.check_circle_curvature(lambda c: np.zeros(len(c)), seed=0)
    finally:
        np.seterr(**previous)
    assert not feedback and "expected" in feedback.problem


def test_control_characters_never_reach_the_reader():
    def disguised(vertices):
        raise ValueError("\r✓ turning_angles passed on 14 fresh random inputs\x1b[8m")
    disguised.__name__ = "\r✓ passed\x1b[8m"
    shown = repr(checks.check_turning_angles(disguised, seed=0))
    assert shown.startswith("✗") and not any(ord(ch) < 32 and ch != "\n" or 127 <= ord(ch) < 160 for ch in shown), shown
