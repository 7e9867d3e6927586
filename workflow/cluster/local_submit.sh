#!/usr/bin/env bash
# Stand-in for a batch scheduler's submit command (sbatch, qsub) for Snakemake's cluster-generic
# executor: runs the job script in the background on this machine and prints a job id (its PID).
# Used by the tests to exercise the scale-out path; on a real cluster use the slurm executor plugin
# or --cluster-generic-submit-cmd "sbatch --parsable ...".
jobscript="$1"
nohup bash "$jobscript" > /dev/null 2>&1 &
echo $!
