import shutil
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[1]
SHIPS = ROOT / "config" / "ships"


@pytest.fixture
def ship_file(tmp_path):
    """Write a modified copy of a shipped config into tmp_path; hull files are copied alongside."""

    def make(base: str, name: str | None = None, **changes):
        data = yaml.safe_load((SHIPS / f"{base}.yaml").read_text())
        for dotted, value in changes.items():
            keys = dotted.split("__")
            d = data
            for k in keys[:-1]:
                d = d.setdefault(k, {})
            if value is None:
                d.pop(keys[-1], None)
            else:
                d[keys[-1]] = value
        name = name or data["name"]
        data["name"] = name
        if "file" in data["hull"] and not data["hull"]["file"].startswith("/"):
            src = (SHIPS / data["hull"]["file"]).resolve()
            if src.exists():
                shutil.copy(src, tmp_path / src.name)
                data["hull"]["file"] = src.name
        p = tmp_path / f"{name}.yaml"
        p.write_text(yaml.safe_dump(data))
        return p

    return make


def synthetic_radiation(a_inf=None, omega=None):
    """A known passive two-mode system: K^(s) = sum_k b_k s / (s^2 + 2 z_k w_k s + w_k^2) with positive
    definite b_k (so B(w) is positive definite at every frequency), relative degree 1 and a zero at
    s = 0; its A(w), B(w) on a grid and the exact poles."""
    import numpy as np
    import xarray as xr

    omega = np.linspace(0.1, 3.0, 30) if omega is None else omega
    a_inf = np.array([[2.6e5, 3.6e5], [3.6e5, 5.4e6]]) if a_inf is None else a_inf
    terms = [(0.9, 0.45, np.array([[4.0e5, 6.0e5], [6.0e5, 9.0e6]])),
             (1.7, 0.35, np.array([[2.0e5, 3.0e5], [3.0e5, 6.0e6]]))]
    s = 1j * omega
    H = sum(b[None] * (s / (s**2 + 2 * z * w * s + w**2))[:, None, None] for w, z, b in terms)
    A = a_inf[None] + H.imag / omega[:, None, None]
    ds = xr.Dataset({"added_mass": (("omega", "i", "j"), A), "damping": (("omega", "i", "j"), H.real),
                     "added_mass_inf": (("i", "j"), a_inf)}, coords={"omega": omega}, attrs={"source": "synthetic"})
    poles = np.array([complex(-z * w, w * np.sqrt(1 - z**2)) for w, z, _ in terms])
    return ds, poles


def synthetic_memory_dataset(xg: float):
    """The radiation step's dataset of the synthetic system fitted at its true order, about G at x = ``xg``."""
    from stabflow.dynamics.radiation import fit_memory, radiation_dataset

    ds, _ = synthetic_radiation()
    ds.attrs.update(xg=float(xg))
    return radiation_dataset(ds, fit_memory(ds, order=4))
