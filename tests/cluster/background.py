"""The SLURM executor runs of the test suite, in a background thread started at session start.

One `SlurmRuns` per pytest session (`SlurmRuns.shared()`): it brings up the throwaway cluster
(tests/cluster/slurm.py), then, one after the other,

1. ``dag``:  the whole config/test.yaml DAG through `snakemake --workflow-profile
   workflow/profiles/slurm` (the real SLURM executor plugin), into its own results folder;
2. ``kill``: the test ensemble (3 shard jobs + merge) again into a new folder; once a shard's SLURM
   job runs, it is cancelled with `scancel`; the workflow must stop with an error naming the job;
3. ``rerun``: the same command again, which must complete.

The tests (tests/test_workflow.py, tests/cluster/test_slurm.py) wait for the stage they check and
compare the files with the local -j2 run. Running these beside the unit tests keeps the suite inside
its time budget on 2 cores. tests/cluster/conftest.py starts it when the session has tests that
use the `slurm_runs` fixture and stops everything at the end of the session.

STABFLOW_NO_SLURM=1 skips these tests (machines without root); otherwise a cluster that cannot be
started fails them with the reason.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from .slurm import LocalSlurm, SlurmUnavailable

ROOT = Path(__file__).resolve().parents[2]
OPT_OUT = "STABFLOW_NO_SLURM"
ENS = "ensemble/barge_beam"          # the test profile's ensemble (3 shards of 8 records)
STAGES = ("cluster", "dag", "kill", "rerun")
# Status checks: the executor's first check after init seconds, then +10 s per round in which no job
# finished (reset when one did). The profile keeps the plugin's default for real clusters (40 s);
# on this one-node cluster the jobs take seconds, so check after 1 s.
STATUS_ARGS = ["--slurm-init-seconds-before-status-checks", "1", "--seconds-between-status-checks", "1"]


def opted_out() -> str | None:
    if os.environ.get(OPT_OUT, "").strip() not in ("", "0"):
        return (f"{OPT_OUT}={os.environ[OPT_OUT]}: the SLURM executor tests are skipped on this machine "
                "(they need root to start a throwaway SLURM cluster)")
    return None


@dataclass
class Run:
    """One snakemake invocation: command, exit status, output and wall time."""
    cmd: list[str]
    out: Path                                   # its results folder
    returncode: int | None = None
    output: str = ""
    seconds: float = 0.0
    notes: dict = field(default_factory=dict)

    def tail(self, n: int = 6000) -> str:
        return f"$ {' '.join(self.cmd)}\n(status {self.returncode}, {self.seconds:.0f} s)\n{self.output[-n:]}"


class SlurmRuns:
    _shared: "SlurmRuns | None" = None

    @classmethod
    def shared(cls) -> "SlurmRuns":
        if cls._shared is None:
            cls._shared = cls()
            cls._shared.start()
        return cls._shared

    @classmethod
    def stop_shared(cls) -> None:
        if cls._shared is not None:
            cls._shared.stop()

    def __init__(self):
        self.dir = Path(tempfile.mkdtemp(prefix="stabflow-slurm-runs-"))
        self.messages: list[str] = []
        self.cluster = LocalSlurm(log=self.messages.append)
        self.done = {s: threading.Event() for s in STAGES}
        self.error: dict[str, str] = {}
        self.runs: dict[str, Run] = {}
        self.cluster_seconds = 0.0
        self.probe: dict = {}
        self._proc: subprocess.Popen | None = None
        self._stopping = False
        self._lock = threading.Lock()
        self._thread = threading.Thread(target=self._main, name="slurm-runs", daemon=True)

    # --- public --------------------------------------------------------------------------------
    def start(self) -> None:
        self._thread.start()

    def wait(self, stage: str, timeout: float = 1200) -> Run | None:
        """Wait for a stage; fail the calling test with the reason if the cluster or a stage broke."""
        order = STAGES[: STAGES.index(stage) + 1]
        t0 = time.monotonic()
        for s in order:
            if not self.done[s].wait(max(0.0, timeout - (time.monotonic() - t0))):
                pytest.fail(f"SLURM stage {s!r} not finished after {timeout:.0f} s\n" + "\n".join(self.messages[-20:]))
            if s in self.error:
                what = "SLURM could not be started" if s == "cluster" else f"SLURM stage {s!r} broke"
                pytest.fail(f"{what}: {self.error[s]}\n" + "\n".join(self.messages[-5:]), pytrace=False)
        return self.runs.get(stage)

    def stop(self) -> None:
        """Stop the running snakemake (its process group), then the cluster; remove the folder."""
        with self._lock:
            self._stopping = True
            p = self._proc
        if p is not None and p.poll() is None:
            try:
                os.killpg(p.pid, signal.SIGTERM)  # snakemake cancels its SLURM jobs
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
            except ProcessLookupError:
                pass
        if self._thread.is_alive() and threading.current_thread() is not self._thread:
            self._thread.join(timeout=180)  # a bring-up in progress ends within its own timeouts
        self.cluster.stop()
        shutil.rmtree(self.dir, ignore_errors=True)

    def summary(self) -> str:
        parts = [f"cluster up in {self.cluster_seconds:.0f} s"] if "cluster" not in self.error else ["cluster FAILED"]
        for stage in ("dag", "kill", "rerun"):
            r = self.runs.get(stage)
            if r is not None and r.returncode is not None:
                jobs = r.output.count("submitted with SLURM jobid")
                parts.append(f"{stage} {jobs} jobs in {r.seconds:.0f} s (status {r.returncode})")
        return "SLURM executor: " + ", ".join(parts)

    # --- the background thread -----------------------------------------------------------------
    def _main(self) -> None:
        stage = "cluster"
        try:
            t0 = time.monotonic()
            self.cluster.start()
            self.cluster_seconds = time.monotonic() - t0
            self._probe()
            self.done["cluster"].set()
            for stage, step in (("dag", self._dag), ("kill", self._kill), ("rerun", self._rerun)):
                if self._stopping:
                    raise RuntimeError("stopped (end of session)")
                step()
                self.done[stage].set()
        except SlurmUnavailable as e:
            self.error[stage] = str(e)
        except BaseException:  # noqa: BLE001 - reported to the waiting test
            self.error[stage] = traceback.format_exc()
        finally:
            for s in STAGES:
                if not self.done[s].is_set():
                    self.error.setdefault(s, f"not run: stage {stage!r} failed")
                    self.done[s].set()

    def _probe(self) -> None:
        """A one-line batch job, submitted and followed to its final state in accounting (sacct)."""
        r = self.cluster.run("sbatch", "--parsable", "-J", "stabflow-probe", "-o", "/dev/null", "--wrap", "true")
        jobid, state = r.stdout.strip().split(";")[0], ""
        t0 = time.monotonic()
        while time.monotonic() - t0 < 60:
            state = self.cluster.run("sacct", "-X", "-n", "-P", "-j", jobid, "-o", "State", check=False).stdout.strip()
            if state and not state.startswith(("RUNNING", "PENDING", "COMPLETING")):
                break
            time.sleep(0.2)
        self.probe = {"jobid": jobid, "state": state, "seconds": time.monotonic() - t0}

    def _command(self, out: Path, *targets: str) -> list[str]:
        # targets first: --configfile takes several values
        return [sys.executable, "-m", "snakemake", *targets, "--workflow-profile", "workflow/profiles/slurm",
                "--configfile", "config/test.yaml", "--config", f"results={out}", "--nolock",
                "--max-threads", str(self.cluster.cpus), *STATUS_ARGS,
                "--slurm-logdir", str(out.parent / "slurm_logs")]

    def _snakemake(self, stage: str, out: Path, *targets: str, on_start=None, timeout: float = 600) -> Run:
        run = Run(self._command(out, *targets), out)
        self.runs[stage] = run
        log = out.parent / f"{stage}.log"
        out.parent.mkdir(parents=True, exist_ok=True)
        t0 = time.monotonic()
        with open(log, "w") as f:
            with self._lock:
                if self._stopping:
                    raise RuntimeError("stopped (end of session)")
                self._proc = subprocess.Popen(run.cmd, cwd=ROOT, env=self.cluster.env, stdout=f,
                                              stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                              start_new_session=True)
            try:
                if on_start is not None:
                    on_start(self._proc, run)
                self._proc.wait(timeout=max(1.0, timeout - (time.monotonic() - t0)))
            except subprocess.TimeoutExpired:
                os.killpg(self._proc.pid, signal.SIGKILL)
                self._proc.wait()
                run.notes["timeout"] = timeout
        run.seconds = time.monotonic() - t0
        run.returncode = self._proc.returncode
        run.output = log.read_text(errors="replace")
        if "timeout" in run.notes:
            run.output += f"\n[test harness] killed after {timeout:.0f} s"
        return run

    def _dag(self) -> None:
        # a guard against a hung run, not a speed target: the 36 SLURM jobs share the 2 cores with the
        # unit tests and the local -j2 run (two CI runs on 2026-12-01 were killed at 600 s, 82 % done)
        run = self._snakemake("dag", self.dir / "dag" / "results", timeout=1000)
        # each job's rule, queue wait and run time, for a failing test's message and for timing
        run.notes["sacct"] = self.cluster.run("sacct", "-X", "-P", "-o", "JobID,Comment%80,State,Submit,Start,End",
                                              check=False).stdout

    def _kill(self) -> None:
        out = self.dir / "kill" / "results"
        self._snakemake("kill", out, f"{out}/{ENS}/ensemble.nc", on_start=self._cancel_a_running_shard, timeout=240)

    def _cancel_a_running_shard(self, proc: subprocess.Popen, run: Run) -> None:
        """Once a shard's job runs, scancel it; if it finished first (lost race), try another."""
        tried: set[str] = set()
        t0 = time.monotonic()
        while proc.poll() is None and time.monotonic() - t0 < 240:
            q = self.cluster.run("squeue", "-h", "-t", "RUNNING", "-o", "%i|%k", check=False, timeout=20)
            jobs = [line.split("|", 1) for line in q.stdout.split() if "|rule_ensemble_shard" in line]
            jobs = [(j, c) for j, c in jobs if j not in tried]
            if not jobs:
                time.sleep(0.2)
                continue
            jobid, comment = jobs[0]
            tried.add(jobid)
            time.sleep(1.0)                                          # mid-run, not at its first instant
            self.cluster.run("scancel", jobid, check=False, timeout=20)
            state = ""
            for _ in range(100):                                   # its final state, from accounting
                s = self.cluster.run("sacct", "-X", "-n", "-P", "-j", jobid, "-o", "State", check=False, timeout=20)
                state = s.stdout.strip()
                if state and not state.startswith(("RUNNING", "PENDING", "COMPLETING")):
                    break
                time.sleep(0.2)
            run.notes.setdefault("attempts", []).append((jobid, comment, state))
            if state.startswith("CANCELLED"):
                run.notes.update(jobid=jobid, shard=int(comment.rsplit("_", 1)[1]), state=state)
                return

    def _rerun(self) -> None:
        out = self.runs["kill"].out
        shards = {p.name: p.stat().st_mtime_ns for p in (out / ENS).glob("shard_*.nc")}
        run = self._snakemake("rerun", out, f"{out}/{ENS}/ensemble.nc", timeout=240)
        run.notes["kept_before"] = shards


@pytest.fixture(scope="session")
def slurm_runs():
    """The session's SLURM runs (started at session start by tests/cluster/conftest.py, or here)."""
    reason = opted_out()
    if reason:
        pytest.skip(reason)
    yield SlurmRuns.shared()
    SlurmRuns.stop_shared()
