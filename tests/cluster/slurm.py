"""A throwaway single-node SLURM cluster with job accounting, on localhost, for the executor tests.

Snakemake's SLURM executor reads job states with `sacct` (or `squeue`) and checks the user's account
with `sacctmgr`, so the cluster needs slurmdbd and a database, not only slurmctld and slurmd (without
accounting the executor cannot read the states and hangs after the last job). `LocalSlurm` brings
up, in a temporary folder and on free local ports:

    munged (own key) -> MariaDB (own data folder, unix socket in the folder, no networking) ->
    slurmdbd -> cluster / account / user in the accounting database -> slurmctld -> slurmd

with the node's CPUs and memory read from this machine (scheduler affinity; MemTotal or the cgroup
limit), waits until `sinfo` shows the node idle and stops every daemon it started, by PID, at the
end (also when the start fails half-way: then the configs and logs stay for a look). Outside its
folder it uses munged's default socket /run/munge/munge.socket.2 (a munged already serving there
is used instead of starting one) and slurmd's link /run/slurm/conf (why: see MUNGE_SOCKET), both
removed at the end, and it installs the Debian packages when missing (slurm-wlm, slurmdbd, munge,
mariadb-server; apt-get with service start-up suppressed). It needs root: the daemons run as root
and so do the jobs (SlurmUser=root). No cgroups are used (proctrack/linuxproc, task/none), so it
also runs in containers without cgroup delegation.

Stand-alone use (stdlib only, runs a command against the cluster and stops it afterwards):

    sudo python3 tests/cluster/slurm.py -- snakemake --workflow-profile workflow/profiles/slurm ...
    sudo python3 tests/cluster/slurm.py --keep-running      # prints SLURM_CONF, Ctrl-C stops it
"""

from __future__ import annotations

import argparse
import fcntl
import getpass
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

# executables that must exist, and the package that provides each
BINARIES = {"munged": "munge", "slurmctld": "slurm-wlm", "slurmd": "slurm-wlm", "slurmdbd": "slurmdbd",
            "sbatch": "slurm-wlm", "sacct": "slurm-wlm", "sacctmgr": "slurm-wlm", "sinfo": "slurm-wlm",
            "squeue": "slurm-wlm", "scancel": "slurm-wlm", "mariadbd": "mariadb-server",
            "mariadb-install-db": "mariadb-server", "mariadb": "mariadb-server"}


# munged's default socket. The daemons and commands could use another one (AuthInfo=socket=...,
# AccountingStoragePass=... for slurmdbd), but srun inside a job cannot: the executor's job step
# clears SLURM_CONF, so srun reads the configuration that slurmd fetched from slurmctld
# ("configless", linked at /run/slurm/conf) and slurmd can only fetch it with the default socket.
MUNGE_SOCKET = Path("/run/munge/munge.socket.2")
# ... and since that socket and /run/slurm/conf are machine-wide, one throwaway cluster at a time:
# a second one (another test session on the same machine) waits for this lock.
LOCK_FILE = Path("/run/lock/stabflow-slurm.lock")


class SlurmUnavailable(RuntimeError):
    """The cluster could not be brought up; the message says why (with the daemon's log tail)."""


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _memory_mb() -> int:
    """Usable memory of this machine in MB: MemTotal, or the cgroup limit when lower."""
    total = 0
    for line in Path("/proc/meminfo").read_text().splitlines():
        if line.startswith("MemTotal:"):
            total = int(line.split()[1]) // 1024
    for limit in ("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"):
        try:
            value = Path(limit).read_text().strip()
        except OSError:
            continue
        if value.isdigit():
            total = min(total, int(value) // 2**20)
    return total


def _tail(path: Path, n: int = 15) -> str:
    try:
        lines = path.read_text(errors="replace").splitlines()
    except OSError:
        return f"({path.name}: no log)"
    return f"--- last lines of {path} ---\n" + "\n".join(lines[-n:])


def install_packages(log=print) -> None:
    """Install the Debian packages that provide missing executables (apt-get, as root)."""
    missing = sorted({pkg for exe, pkg in BINARIES.items() if shutil.which(exe) is None})
    if not missing:
        return
    if shutil.which("apt-get") is None:
        raise SlurmUnavailable(f"missing {', '.join(missing)} and no apt-get to install them")
    log(f"installing {' '.join(missing)} (apt-get)")
    # keep the packages' init scripts from starting system-wide daemons (we start our own)
    policy = Path("/usr/sbin/policy-rc.d")
    added_policy = not policy.exists()
    if added_policy:
        policy.write_text("#!/bin/sh\nexit 101\n")
        policy.chmod(0o755)
    try:
        env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
        out = ""
        for cmd in (["apt-get", "update", "-qq"],
                    ["apt-get", "install", "-y", "-qq", "--no-install-recommends", *missing]):
            r = subprocess.run(cmd, env=env, capture_output=True, text=True)
            out += r.stdout + r.stderr
            if r.returncode != 0:
                raise SlurmUnavailable(f"{' '.join(cmd)} failed (status {r.returncode}):\n{out[-3000:]}")
    finally:
        if added_policy:
            policy.unlink(missing_ok=True)
    still = sorted(exe for exe in BINARIES if shutil.which(exe) is None)
    if still:
        raise SlurmUnavailable(f"after installing {' '.join(missing)}, still missing: {', '.join(still)}")


class LocalSlurm:
    """Single-node SLURM with slurmdbd accounting in a temporary folder; a context manager.

    `env` is os.environ plus SLURM_CONF: pass it to sbatch, sinfo, snakemake, ....
    """

    def __init__(self, cluster: str = "stabflow", account: str = "stabflow", partition: str = "debug",
                 root: str | os.PathLike | None = None, keep: bool = False, log=print):
        self.cluster, self.account, self.partition = cluster, account, partition
        self.user = getpass.getuser()
        self.node = socket.gethostname().split(".")[0]
        self._root_arg, self.keep, self.log = root, keep, log
        self.dir: Path | None = None
        self.procs: dict[str, subprocess.Popen] = {}
        self._made: list[Path] = []  # folders created outside self.dir (/run/munge, /run/slurm)
        self._lock_fd: int | None = None
        self.cpus = len(os.sched_getaffinity(0))
        self.memory_mb = 0
        self.env = dict(os.environ)

    # --- public --------------------------------------------------------------------------------
    def __enter__(self):
        self.start()
        return self

    def __exit__(self, *exc):
        self.stop()

    def start(self, timeout: float = 120.0, lock_timeout: float = 1200.0) -> "LocalSlurm":
        """Bring the cluster up; on any failure stop what was started and raise SlurmUnavailable."""
        t0 = time.monotonic()
        if os.geteuid() != 0:
            raise SlurmUnavailable("needs root (the SLURM daemons and the jobs run as root); "
                                   "set STABFLOW_NO_SLURM=1 to skip the SLURM tests on this machine")
        try:
            self._lock(lock_timeout)
            install_packages(self.log)
            self._configure()
            self._start_munge()
            self._start_mariadb(timeout)
            self._start_slurmdbd(timeout)
            self._add_associations()
            self._start_slurmctld_slurmd(timeout)
        except BaseException:
            keep = self.keep
            self.keep = True  # keep the configs and logs of a failed start (not the database)
            try:
                self.stop()
            finally:
                self.keep = keep
            if self.dir is not None:
                shutil.rmtree(self.dir / "mysql", ignore_errors=True)
                self.log(f"configs and logs of the failed start kept in {self.dir}")
                self.dir = None  # a later stop() leaves them alone
            raise
        self.log(f"SLURM up in {time.monotonic() - t0:.1f} s: node {self.node} ({self.cpus} CPUs, "
                 f"{self.memory_mb} MB), partition {self.partition}, account {self.account}, "
                 f"SLURM_CONF={self.conf}")
        return self

    def stop(self) -> None:
        """Cancel the cluster's jobs, stop every daemon this object started (by PID), remove the folder."""
        if self.procs.get("slurmctld") and self.procs["slurmctld"].poll() is None:
            self._cancel_all_jobs()
        for name in ("slurmd", "slurmctld", "slurmdbd", "mariadbd", "munged"):
            p = self.procs.pop(name, None)
            if p is None or p.poll() is not None:
                continue
            p.send_signal(signal.SIGTERM)
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
        # slurmd's link to its fetched configuration, and the folders this object created in /run
        link = Path("/run/slurm/conf")
        if self.dir is not None and link.is_symlink() and str(os.readlink(link)).startswith(str(self.dir)):
            link.unlink()
        for folder in reversed(self._made):
            try:
                folder.rmdir()
            except OSError:
                pass
        self._made = []
        if self.dir is not None and not self.keep:
            shutil.rmtree(self.dir, ignore_errors=True)
            self.dir = None
        if self._lock_fd is not None:
            os.close(self._lock_fd)  # releases the lock
            self._lock_fd = None

    def run(self, *cmd: str, check: bool = True, timeout: float = 60) -> subprocess.CompletedProcess:
        """Run a SLURM client command against this cluster."""
        r = subprocess.run(list(cmd), env=self.env, capture_output=True, text=True, timeout=timeout)
        if check and r.returncode != 0:
            raise SlurmUnavailable(f"{' '.join(cmd)} failed (status {r.returncode}): {r.stdout}{r.stderr}")
        return r

    def node_state(self) -> str:
        r = self.run("sinfo", "-h", "-N", "-n", self.node, "-o", "%t", check=False, timeout=20)
        return r.stdout.strip() if r.returncode == 0 else f"(sinfo failed: {r.stderr.strip()})"

    # --- bring-up steps ------------------------------------------------------------------------
    def _lock(self, timeout: float) -> None:
        lock = LOCK_FILE if LOCK_FILE.parent.is_dir() else Path(tempfile.gettempdir()) / LOCK_FILE.name
        fd = os.open(lock, os.O_RDWR | os.O_CREAT, 0o644)
        t0, said = time.monotonic(), False
        while True:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                holder = os.pread(fd, 64, 0).decode(errors="replace").strip()
                if time.monotonic() - t0 > timeout:
                    os.close(fd)
                    raise SlurmUnavailable(f"another throwaway cluster (pid {holder}) held {lock} for {timeout:.0f} s")
                if not said:
                    self.log(f"waiting for the throwaway cluster of pid {holder} to stop ({lock})")
                    said = True
                time.sleep(1.0)
        os.ftruncate(fd, 0)
        os.pwrite(fd, str(os.getpid()).encode(), 0)
        self._lock_fd = fd

    def _configure(self) -> None:
        base = self._root_arg or tempfile.gettempdir()
        # unix socket paths must stay below 108 characters
        if len(str(base)) > 60:
            base = "/tmp"
        self.dir = Path(tempfile.mkdtemp(prefix="stabflow-slurm-", dir=base))
        self.dir.chmod(0o755)  # the job steps read the config; the folder holds nothing secret
        for sub in ("state", "spool", "mysql", "log"):
            (self.dir / sub).mkdir()
        self.conf = self.dir / "slurm.conf"
        self.munge_socket = MUNGE_SOCKET
        self.mysql_socket = self.dir / "mysql.sock"
        self.dbd_port, self.ctld_port, self.slurmd_port = _free_port(), _free_port(), _free_port()
        self.memory_mb = max(1000, int(0.9 * _memory_mb()))  # leave room for the daemons themselves
        d = self.dir
        common = "AuthType=auth/munge\n"  # munged's default socket: see _start_munge
        self.conf.write_text(f"""# throwaway single-node cluster of tests/cluster/slurm.py
ClusterName={self.cluster}
SlurmctldHost={self.node}(127.0.0.1)
SlurmctldPort={self.ctld_port}
SlurmdPort={self.slurmd_port}
SlurmUser=root
SlurmdUser=root
{common}CredType=cred/munge
StateSaveLocation={d}/state
SlurmdSpoolDir={d}/spool
SlurmctldPidFile={d}/slurmctld.pid
SlurmdPidFile={d}/slurmd.pid
SlurmctldLogFile={d}/log/slurmctld.log
SlurmdLogFile={d}/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/slurmdbd
AccountingStorageHost=127.0.0.1
AccountingStoragePort={self.dbd_port}
AccountingStoreFlags=job_comment
JobCompType=jobcomp/none
MpiDefault=none
MailProg=/bin/true
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SlurmdParameters=config_overrides
# configless: slurmd fetches this file from slurmctld and links it at /run/slurm/conf, where srun
# inside a job finds it (the executor's job step clears SLURM_CONF before calling srun)
SlurmctldParameters=enable_configless
ReturnToService=2
MinJobAge=300
KillWait=5
InactiveLimit=0
NodeName={self.node} NodeAddr=127.0.0.1 CPUs={self.cpus} RealMemory={self.memory_mb} State=UNKNOWN
PartitionName={self.partition} Nodes={self.node} Default=YES MaxTime=INFINITE State=UP
""")
        dbd = self.dir / "slurmdbd.conf"
        dbd.write_text(f"""{common}DbdHost={self.node}
DbdAddr=127.0.0.1
DbdPort={self.dbd_port}
SlurmUser=root
PidFile={d}/slurmdbd.pid
LogFile={d}/log/slurmdbd.log
DebugLevel=info
StorageType=accounting_storage/mysql
StorageHost=localhost
StorageUser=root
StorageLoc=slurm_acct_db
""")
        dbd.chmod(0o600)  # slurmdbd refuses a config others can read
        self.env = dict(os.environ, SLURM_CONF=str(self.conf))
        for var in [k for k in self.env if k.startswith(("SLURM_", "SBATCH_", "SALLOC_", "SRUN_"))]:
            if var != "SLURM_CONF":  # we may run inside another allocation: do not inherit it
                del self.env[var]

    def _spawn(self, name: str, cmd: list[str], env: dict | None = None) -> subprocess.Popen:
        """Start a daemon in the foreground of its own session, output to log/<name>.out."""
        out = open(self.dir / "log" / f"{name}.out", "wb")
        p = subprocess.Popen(cmd, env=env or self.env, stdout=out, stderr=subprocess.STDOUT,
                             stdin=subprocess.DEVNULL, start_new_session=True, cwd=self.dir)
        out.close()
        self.procs[name] = p
        return p

    def _mkdir(self, folder: Path) -> None:
        if not folder.exists():
            folder.mkdir(mode=0o755, parents=True)
            self._made.append(folder)

    def _wait(self, what: str, ready, timeout: float, name: str, logs: list[str]) -> None:
        t0 = time.monotonic()
        while time.monotonic() - t0 < timeout:
            if ready():
                return
            p = self.procs.get(name)
            if p is not None and p.poll() is not None:
                break
            time.sleep(0.2)
        p = self.procs.get(name)
        state = f"exited with status {p.returncode}" if p is not None and p.poll() is not None else \
            f"not ready after {timeout:.0f} s"
        raise SlurmUnavailable(f"{what}: {name} {state}\n" +
                               "\n".join(_tail(self.dir / "log" / f) for f in logs))

    def _munge_ok(self) -> bool:
        if not self.munge_socket.exists():
            return False
        r = subprocess.run(f"munge -n --socket={self.munge_socket} | unmunge --socket={self.munge_socket}",
                           shell=True, capture_output=True)
        return r.returncode == 0

    def _start_munge(self) -> None:
        if self._munge_ok():  # this machine's munged is running: use it (any key will do on one node)
            self.log(f"using the running munged at {self.munge_socket}")
            return
        key = self.dir / "munge.key"
        key.write_bytes(os.urandom(1024))
        key.chmod(0o400)
        self._mkdir(self.munge_socket.parent)
        self._spawn("munged", ["munged", "--foreground", "--force", f"--key-file={key}",
                               f"--socket={self.munge_socket}", f"--pid-file={self.dir}/munged.pid",
                               f"--log-file={self.dir}/log/munged.log", f"--seed-file={self.dir}/munged.seed"])
        self._wait("munge", self._munge_ok, 20, "munged", ["munged.out", "munged.log"])

    def _mysql_ok(self) -> bool:
        r = subprocess.run(["mariadb", "--no-defaults", f"--socket={self.mysql_socket}", "-uroot", "-e", "select 1"],
                           capture_output=True, text=True)
        return r.returncode == 0

    def _start_mariadb(self, timeout: float) -> None:
        data = self.dir / "mysql"
        r = subprocess.run(["mariadb-install-db", "--no-defaults", f"--datadir={data}", "--user=root",
                            "--auth-root-authentication-method=normal", "--skip-test-db"],
                           capture_output=True, text=True)
        if r.returncode != 0:
            raise SlurmUnavailable(f"mariadb-install-db failed (status {r.returncode}):\n{(r.stdout + r.stderr)[-3000:]}")
        self._spawn("mariadbd", ["mariadbd", "--no-defaults", f"--datadir={data}", f"--socket={self.mysql_socket}",
                                 "--skip-networking", "--user=root", f"--pid-file={self.dir}/mariadbd.pid",
                                 f"--log-error={self.dir}/log/mariadbd.log", "--innodb-buffer-pool-size=64M",
                                 "--innodb-flush-log-at-trx-commit=0", "--skip-log-bin"])
        self._wait("MariaDB", self._mysql_ok, timeout, "mariadbd", ["mariadbd.out", "mariadbd.log"])

    def _start_slurmdbd(self, timeout: float) -> None:
        # slurmdbd connects to "localhost", i.e. the client library's default socket: point it at ours
        env = dict(self.env, MYSQL_UNIX_PORT=str(self.mysql_socket))
        self._spawn("slurmdbd", ["slurmdbd", "-D"], env=env)

        def ready():
            return self.run("sacctmgr", "-n", "list", "cluster", check=False, timeout=20).returncode == 0
        self._wait("slurmdbd", ready, timeout, "slurmdbd", ["slurmdbd.out", "slurmdbd.log"])

    def _add_associations(self) -> None:
        self.run("sacctmgr", "-i", "add", "cluster", self.cluster)
        self.run("sacctmgr", "-i", "add", "account", self.account, f"Cluster={self.cluster}",
                 "Description=stabflow tests", "Organization=stabflow")
        self.run("sacctmgr", "-i", "add", "user", self.user, f"Account={self.account}",
                 f"DefaultAccount={self.account}", f"Cluster={self.cluster}")

    def _start_slurmctld_slurmd(self, timeout: float) -> None:
        self._spawn("slurmctld", ["slurmctld", "-D", "-i"])
        self._wait("slurmctld", lambda: self.run("sinfo", "-h", check=False, timeout=20).returncode == 0,
                   timeout, "slurmctld", ["slurmctld.out", "slurmctld.log"])
        self._mkdir(Path("/run/slurm"))
        env = {k: v for k, v in self.env.items() if k != "SLURM_CONF"}
        self._spawn("slurmd", ["slurmd", "-D", "-N", self.node, "--conf-server", f"127.0.0.1:{self.ctld_port}"],
                    env=env)
        self._wait("node idle", lambda: self.node_state() == "idle", timeout, "slurmd",
                   ["slurmd.out", "slurmd.log", "slurmctld.log"])

    def _cancel_all_jobs(self) -> None:
        """Cancel this cluster's jobs and wait (up to 30 s) until they are gone from the node."""
        r = self.run("squeue", "-h", "-o", "%i", check=False, timeout=20)
        jobs = r.stdout.split() if r.returncode == 0 else []
        if not jobs:
            return
        self.run("scancel", *jobs, check=False, timeout=20)
        t0 = time.monotonic()
        while time.monotonic() - t0 < 30:
            r = self.run("squeue", "-h", "-t", "RUNNING,COMPLETING", "-o", "%i", check=False, timeout=20)
            if r.returncode != 0 or not r.stdout.strip():
                return
            time.sleep(0.5)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 epilog="example: python3 tests/cluster/slurm.py -- sbatch --wrap hostname")
    ap.add_argument("--keep-running", action="store_true", help="stay up until interrupted (Ctrl-C / SIGTERM)")
    ap.add_argument("--keep-dir", action="store_true", help="keep the temporary folder (configs, logs)")
    ap.add_argument("command", nargs=argparse.REMAINDER, help="command to run with SLURM_CONF set (after --)")
    args = ap.parse_args(argv)
    cmd = args.command[1:] if args.command[:1] == ["--"] else args.command
    # SIGTERM / SIGHUP stop the cluster like Ctrl-C does
    for sig in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, lambda *_: sys.exit(128 + 15))
    cluster = LocalSlurm(keep=args.keep_dir, log=lambda m: print(f"[slurm] {m}", file=sys.stderr, flush=True))
    try:
        cluster.start()
    except SlurmUnavailable as e:
        print(f"[slurm] cannot start SLURM: {e}", file=sys.stderr)
        return 3
    try:
        if cmd:
            return subprocess.run(cmd, env=cluster.env).returncode
        print(f"export SLURM_CONF={cluster.conf}", flush=True)
        if args.keep_running:
            while True:
                time.sleep(3600)
        return 0
    except KeyboardInterrupt:
        return 130
    finally:
        cluster.stop()
        if args.keep_dir:
            print(f"[slurm] kept {cluster.conf.parent}", file=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
