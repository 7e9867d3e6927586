# stabflow: ship dynamic stability in irregular seas.
# The whole pipeline on one screen: config -> hull -> statics -> waves / early-stage metric -> rao -> ensemble -> extremes / splittime (+ the 1-DOF capsize case, the 6-DOF broaching scenario, the derivative model) -> criteria / dsa -> validation -> report.
# Scheduling on few cores: rules with a `priority:` start first among the jobs that are ready, longest
# chains first (capsize_1dof 50; the 6-DOF chain's radiation 40; ensembles, extremes, split-time and
# their validation 30; broaching 20; DSA and derivative model 10; the rest 0), so that no long job is
# left to run alone at the end. Every job has one thread by default (`ensemble_threads`).


configfile: "config/config.yaml"


include: "workflow/rules/common.smk"
include: "workflow/rules/hull.smk"
include: "workflow/rules/statics.smk"
include: "workflow/rules/waves.smk"
include: "workflow/rules/rao.smk"
include: "workflow/rules/roll_decay.smk"
include: "workflow/rules/ensemble.smk"
include: "workflow/rules/extremes.smk"
include: "workflow/rules/splittime.smk"
include: "workflow/rules/capsize_1dof.smk"
include: "workflow/rules/broaching.smk"
include: "workflow/rules/derivative.smk"
include: "workflow/rules/criteria.smk"
include: "workflow/rules/dsa.smk"
include: "workflow/rules/validate.smk"
include: "workflow/rules/report.smk"


rule all:
    input:
        all_outputs(),
