"""Stability criteria: the 2008 IS Code (general criteria and the weather criterion), the IMO
second-generation intact stability criteria (MSC.1/Circ.1627) levels 1 and 2, and the direct
stability assessment (DSA) over a wave scatter table.

Every standard value comes from ``resources/criteria/*.yaml`` with its source (:mod:`.standards`);
a value no readable source gave is null there, and a criterion that needs it is NOT EVALUATED with
the missing item named, never PASS.
"""
