"""Irregular-sea statistics: streamed ensembles (:mod:`.ensemble`), extreme roll by peaks over
threshold (:mod:`.extremes`), capsize rate by the split-time method (:mod:`.splittime`)."""
