"""The luminaire UGR table (CIE 190 tabular method) through the module and the CLI."""
import math
import subprocess

import lightsolver
import pytest
from conftest import SOURCE_DIR

DOWNLIGHT = SOURCE_DIR / "Resources/luminaires/downlight.ies"


def test_module_table_matches_cli_text(cli: str) -> None:
    """ugr_table() returns the 19 standard rooms; the CLI prints the same table text."""
    t = lightsolver.ugr_table(str(DOWNLIGHT))
    assert len(t["rows"]) == 19 and len(t["reflectances"]) == 5
    assert t["reflectances"][0] == (0.7, 0.5, 0.2)
    for row in t["rows"]:
        for cross, end in zip(row["crosswise"], row["endwise"]):
            assert math.isfinite(cross) and abs(cross - end) < 0.02  # rotational symmetry
        assert 0.0 < row["direct_floor_fraction"] < 1.0
    r = subprocess.run([cli, "photometry", str(DOWNLIGHT), "--ugr-table"], capture_output=True,
                       text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    assert t["text"] in r.stdout


def test_spacing_changes_the_table_and_bad_files_raise(tmp_path) -> None:
    """A wider spacing gives a different table; a file without luminous area is refused."""
    a = lightsolver.ugr_table(str(DOWNLIGHT))
    b = lightsolver.ugr_table(str(DOWNLIGHT), spacing_to_height=1.0)
    assert a["rows"][10]["crosswise"][0] != pytest.approx(b["rows"][10]["crosswise"][0], abs=0.05)
    point = tmp_path / "point.ies"
    text = DOWNLIGHT.read_text().splitlines()
    # Line after TILT: lamps, lumens, multiplier, angles, planes, type, units, width, length, height.
    i = next(k for k, line in enumerate(text) if line.startswith("TILT=")) + 1
    f = text[i].split()
    f[7:10] = ["0", "0", "0"]
    text[i] = " ".join(f)
    point.write_text("\n".join(text) + "\n")
    with pytest.raises(lightsolver.InputError, match="luminous area"):
        lightsolver.ugr_table(str(point))
