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
