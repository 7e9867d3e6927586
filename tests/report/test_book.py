"""The report's number formats (``stabflow.report.book``)."""

import math

from stabflow.report.book import _fmt, _rate


def test_rate_prints_an_underflowed_rate_from_log_space():
    """A rate that underflowed to 0 prints its order of magnitude from its log10, never a bare 0; a
    representable rate prints as every other number; a rate with no finite log10 stays as it is."""
    assert _rate(0.0, -412.5).startswith("3.2e-413 ")
    assert "log space" in _rate(0.0, -412.5)
    assert _rate(2.5e-3, math.log10(2.5e-3)) == _fmt(2.5e-3) == "0.0025"
    assert _rate(0.0, -math.inf) == "0"
    assert _rate(math.inf, math.inf) == "–"
