"""NetCDF output: atomic, and bit-identical whatever the Python process."""

import hashlib
import subprocess
import sys

SCRIPT = """
import sys
import numpy as np
import xarray as xr
from stabflow.io import write_netcdf
# a dataset read back from a file that had zero-length (unlimited) dimensions: xarray keeps them
# in encoding as a set, whose order follows the per-process string hash
ds = xr.Dataset({n: (n, np.zeros(0)) for n in ("crossing", "peak", "envelope_peak", "extra_a", "extra_b")},
                attrs={"ship": "s"})
ds["record"] = ("record", np.arange(3))
ds.encoding["unlimited_dims"] = {"crossing", "peak", "envelope_peak", "extra_a", "extra_b"}
write_netcdf(ds, sys.argv[1])
"""


def test_zero_length_dimensions_do_not_depend_on_the_hash_seed(tmp_path):
    """Same dataset, different PYTHONHASHSEED: identical bytes (xarray orders declared unlimited
    dimensions by a set; stabflow declares none)."""
    digests = set()
    for seed in ("1", "2", "3", "4"):
        out = tmp_path / f"f{seed}.nc"
        r = subprocess.run([sys.executable, "-c", SCRIPT, str(out)], capture_output=True, text=True,
                           env={"PYTHONHASHSEED": seed, "PATH": "/usr/bin:/bin"})
        assert r.returncode == 0, r.stderr
        digests.add(hashlib.sha256(out.read_bytes()).hexdigest())
    assert len(digests) == 1


def test_atomic_write_leaves_nothing_on_failure(tmp_path):
    """A write that fails half-way leaves neither the file nor a temporary beside it."""
    import pytest

    from stabflow.io import atomic_path

    target = tmp_path / "out" / "x.nc"
    with pytest.raises(RuntimeError):
        with atomic_path(target) as tmp:
            open(tmp, "w").write("partial")
            raise RuntimeError("boom")
    assert not target.exists() and list(target.parent.iterdir()) == []


def test_annotate_sets_the_table_attributes_on_variables_and_coordinates():
    """CF attributes from the one table on data variables, dimension coordinates and scalars; other
    variables and attributes left as they are; the dataset's own variables are changed."""
    import numpy as np
    import xarray as xr

    from stabflow.io import CF_ATTRS, annotate

    named = [n for n in ("roll_std", "lag", "frequency", "exposure_hours") if n in CF_ATTRS]
    assert len(named) == 4
    ds = xr.Dataset({"roll_std": ((), 1.0), "exposure_hours": ((), 2.0), "acov_sum": ("lag", np.zeros(3)),
                     "not_in_table": ("frequency", np.zeros(2), {"note": "kept"})},
                    coords={"lag": [0.0, 0.5, 1.0], "frequency": [0.1, 0.2]})
    ds["roll_std"].attrs["extra"] = "kept"
    out = annotate(ds)
    assert out is ds
    for n in named:
        units, long_name = CF_ATTRS[n]
        assert ds[n].attrs["units"] == units and ds[n].attrs["long_name"] == long_name
    assert ds["roll_std"].attrs["extra"] == "kept"
    assert ds["not_in_table"].attrs == {"note": "kept"}
