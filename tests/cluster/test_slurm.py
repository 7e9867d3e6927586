"""The throwaway SLURM cluster of tests/cluster/slurm.py, as the executor tests use it."""

import os

import pytest

from .background import slurm_runs  # noqa: F401  (session fixture)

pytestmark = pytest.mark.slurm


def test_cluster_node_account_and_job_accounting(slurm_runs):  # noqa: F811
    """Node idle with this machine's CPUs, the user's account in the accounting database, and a
    batch job followed to COMPLETED in sacct (the executor's account check and job states use these)."""
    slurm_runs.wait("cluster")
    c = slurm_runs.cluster
    assert c.cpus == len(os.sched_getaffinity(0)) and c.memory_mb >= 1000
    node = c.run("sinfo", "-h", "-N", "-o", "%N|%c|%m").stdout.split()
    assert node == [f"{c.node}|{c.cpus}|{c.memory_mb}"], node
    assoc = c.run("sacctmgr", "-n", "-P", "show", "assoc", f"user={c.user}", "format=cluster,account,user").stdout
    assert f"{c.cluster}|{c.account}|{c.user}" in assoc.split(), assoc
    assert slurm_runs.probe["state"] == "COMPLETED", slurm_runs.probe
