"""Start the SLURM executor runs (tests/cluster/background.py) at session start, beside the unit
tests, when the session has tests that use them; stop the cluster at the end of the session."""

from .background import SlurmRuns, opted_out


def pytest_collection_finish(session):
    if session.config.option.collectonly or opted_out():
        return
    if any("slurm_runs" in getattr(item, "fixturenames", ()) for item in session.items):
        SlurmRuns.shared()


def pytest_sessionfinish(session, exitstatus):
    SlurmRuns.stop_shared()


def pytest_terminal_summary(terminalreporter):
    if SlurmRuns._shared is not None:
        terminalreporter.write_line(SlurmRuns._shared.summary())
