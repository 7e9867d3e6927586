"""Wave tables: the same numbers whatever the number of BLAS threads of the job."""

from pathlib import Path

import numpy as np
from threadpoolctl import threadpool_limits

from stabflow.waves.synthesis import station_wave_table


def test_wave_table_independent_of_blas_threads():
    """A job given one thread and one given several (Snakemake exports the rule's threads to
    OPENBLAS_NUM_THREADS) write bit-identical wave tables: the product runs on one BLAS thread
    (with OpenBLAS threaded, a 120-component table over 3000 steps differed in the last bits)."""
    rng = np.random.default_rng(3)
    nc = 120
    amp, w, ph = rng.uniform(0.01, 0.2, nc), np.linspace(0.3, 2.0, nc), rng.uniform(-np.pi, np.pi, nc)
    xs = np.linspace(-50.0, 50.0, 21)
    t = np.arange(3000) * 0.1
    tabs = []
    for n in (1, 2, 4):
        with threadpool_limits(limits=n, user_api="blas"):
            tabs.append(station_wave_table(amp, w, ph, xs, 90.0, 0.0, t))
    assert all(np.array_equal(tabs[0], x) for x in tabs[1:])


def _two_threads_in_and_out():
    """Two Python threads (the split-time step runs records in a thread pool) enter the one-thread
    BLAS context, the first leaves while the second is inside: returns the BLAS libraries' thread
    counts before, inside the second after the first left, and after both left."""
    import threading

    from threadpoolctl import threadpool_info

    from stabflow.waves.synthesis import one_blas_thread

    def blas_threads():
        return {d["num_threads"] for d in threadpool_info() if d["user_api"] == "blas"}

    entered, a_left, b_in, seen = threading.Event(), threading.Event(), threading.Event(), []

    def a():
        with one_blas_thread():
            entered.set()
            b_in.wait()
        a_left.set()

    def b():
        entered.wait()
        with one_blas_thread():
            b_in.set()
            a_left.wait()
            seen.append(blas_threads())

    before = blas_threads()
    ta, tb = threading.Thread(target=a), threading.Thread(target=b)
    ta.start(), tb.start()
    # both must have left before the limit is read back (a 5-s join timed out on a loaded machine:
    # threadpool_info inside b took longer, and the check ran with b still inside)
    ta.join(120), tb.join(120)
    assert not ta.is_alive() and not tb.is_alive()
    return before, seen, blas_threads()


def _check_two_threads(before, seen, after):
    assert seen == [{1}] or not before  # no threaded BLAS loaded: nothing to see
    assert after == before  # restored when both left


def test_blas_limit_holds_while_any_thread_is_inside():
    """The one-thread BLAS limit holds until the last thread leaves (the first to leave must not
    lift it for the other), then the original count is back."""
    _check_two_threads(*_two_threads_in_and_out())


def test_blas_limit_restored_in_a_fresh_process():
    """The same five times in a fresh interpreter, where it failed most often: OpenBLAS ignored the
    second thread's restore of a limit the first had set, and the count stayed at one (before the
    limit was set and restored on one helper thread: in 5 of 6 fresh processes on the first try,
    in this test 2 of 6 runs)."""
    import json
    import subprocess
    import sys

    code = ("import json, numpy, scipy.linalg, sys; sys.path.insert(0, sys.argv[1]); import test_synthesis as t; "
            "rs = [t._two_threads_in_and_out() for _ in range(5)]; "
            "print(json.dumps([[sorted(r[0]), [sorted(x) for x in r[1]], sorted(r[2])] for r in rs]))")
    out = subprocess.run([sys.executable, "-c", code, str(Path(__file__).parent)], capture_output=True, text=True,
                         timeout=300, check=True).stdout
    for before, seen, after in json.loads(out.splitlines()[-1]):
        _check_two_threads(set(before), [set(x) for x in seen], set(after))


def test_blas_limit_set_and_restored_on_one_thread(monkeypatch):
    """Whichever Python threads enter and leave, the limit is set and restored on one and the same
    thread (OpenBLAS may ignore a raise from another thread than the one that lowered the count):
    a stand-in controller records the threads."""
    import threading

    from stabflow.waves import synthesis

    calls = []

    class Limiter:
        def restore_original_limits(self):
            calls.append(("restore", threading.get_ident()))

    class Controller:
        def limit(self, limits, user_api):
            calls.append(("limit", threading.get_ident()))
            return Limiter()

    monkeypatch.setattr(synthesis, "_blas_controller", Controller)
    entered, a_left, b_in = threading.Event(), threading.Event(), threading.Event()

    def a():
        with synthesis.one_blas_thread():
            entered.set()
            b_in.wait()
        a_left.set()

    def b():
        entered.wait()
        with synthesis.one_blas_thread():
            b_in.set()
            a_left.wait()

    ta, tb = threading.Thread(target=a), threading.Thread(target=b)
    ta.start(), tb.start()
    ta.join(120), tb.join(120)
    with synthesis.one_blas_thread():  # and from the main thread
        pass
    assert [c for c, _ in calls] == ["limit", "restore", "limit", "restore"]
    assert len({t for _, t in calls}) == 1 and calls[0][1] not in (ta.ident, tb.ident, threading.get_ident())


def test_blas_limit_in_a_forked_child_and_at_exit():
    """A forked child (the helper thread is not copied) and an atexit handler (the helper accepts no
    work at shutdown) still enter and leave the context, and the count comes back."""
    import subprocess
    import sys

    code = """
import atexit, os, signal
import numpy, scipy.linalg
from threadpoolctl import threadpool_info
from stabflow.waves.synthesis import one_blas_thread
def n(): return sorted({d["num_threads"] for d in threadpool_info() if d["user_api"] == "blas"})
with one_blas_thread(): pass
before = n()
pid = os.fork()
if pid == 0:
    signal.alarm(60)
    with one_blas_thread():
        inside = n()
    print("child", inside == [1] or not before, n() == before, flush=True)
    os._exit(0)
os.waitpid(pid, 0)
def late():
    with one_blas_thread():
        inside = n()
    print("atexit", inside == [1] or not before, n() == before, flush=True)
atexit.register(late)
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split("\n")[:2] == ["child True True", "atexit True True"], out.stdout + out.stderr[-2000:]


def test_station_table_curvature_column_is_dS_dxi():
    """curvature=True appends eta_xixi = dS/dxi, here against central differences of S along x
    (d/dx = cos(beta) d/dxi, heading 30 deg) over +-1 mm, and a zero d2phi/dzdt column without
    depths."""
    from stabflow.waves.synthesis import station_wave_table

    rng = np.random.default_rng(3)
    amp, w, ph = rng.uniform(0.1, 0.5, 12), rng.uniform(0.4, 1.6, 12), rng.uniform(-np.pi, np.pi, 12)
    xs = np.linspace(-40.0, 40.0, 9)
    t = np.arange(50) * 0.37
    beta = 30.0
    tab = station_wave_table(amp, w, ph, xs, beta, 3.0, t, curvature=True)
    assert tab.shape == (50, 9, 4) and np.all(tab[:, :, 2] == 0.0)
    h = 1e-3
    sp = station_wave_table(amp, w, ph, xs + h, beta, 3.0, t)[:, :, 1]
    sm = station_wave_table(amp, w, ph, xs - h, beta, 3.0, t)[:, :, 1]
    assert np.allclose(np.cos(np.radians(beta)) * tab[:, :, 3], (sp - sm) / (2 * h), rtol=1e-5, atol=1e-8)
    assert np.allclose(tab[:, :, :2], station_wave_table(amp, w, ph, xs, beta, 3.0, t), rtol=1e-12, atol=1e-12)


def test_equally_spaced_decides_as_numpy_allclose():
    """The line tables' check of equally spaced points (``_equally_spaced``, numba) takes numpy's
    ``allclose(diff(x), x[1] - x[0], rtol=1e-12, atol=0)`` decision on points near and far from the
    origin (a far drift loses the spacing's last bits), perturbed at and around the tolerance."""
    from stabflow.waves._kernels import _equally_spaced

    rng = np.random.default_rng(3)
    cases = []
    for x0 in (0.0, -19.5, 1.0e3, 4.0e4, 3.0e6):
        x = x0 + 0.6 * np.arange(65)
        cases.append(x)
        for eps in (1e-13, 1e-12, 3e-12, 1e-9):
            y = x.copy()
            y[rng.integers(1, 65)] += eps * 0.6
            cases.append(y)
    cases += [np.array([0.0, 1.0]), np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0, np.nan])]
    decisions = set()
    for x in cases:
        ref = len(x) > 2 and bool(np.allclose(np.diff(x), x[1] - x[0], rtol=1e-12, atol=0.0))
        assert _equally_spaced(x, 1e-12) == ref
        decisions.add(ref)
    assert decisions == {True, False}
