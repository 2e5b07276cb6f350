"""lightsolver.sky_patches, lightsolver.sky_vectors and `lightsolver skymtx` (docs/daylight.md,
"Sky patches and sky vectors"): Radiance's numbering seen from numpy, the year's arrays, the
.npz the command writes read back by numpy, errors named."""
import math
import subprocess

import lightsolver
import numpy as np
import pytest

from conftest import SOURCE_DIR

CHICAGO = SOURCE_DIR / "Tests/native/sun/data/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw"


@pytest.fixture(scope="module")
def year() -> dict:
    return lightsolver.sky_vectors(str(CHICAGO), mf=1)


def test_patches_as_radiance_numbers_them():
    for mf, n in ((1, 146), (2, 578), (4, 2306)):
        p = lightsolver.sky_patches(mf)
        assert p["count"] == n and p["centre"].shape == (n, 3)
        assert p["solid_angle_sr"][1:].sum() == pytest.approx(2 * math.pi, abs=1e-12)
        assert (p["solid_angle_sr"][1:] * p["mean_cos_zenith"][1:]).sum() == pytest.approx(
            math.pi, abs=1e-12)
        assert p["row"][0] == -1 and p["row"][-1] == 7 * mf
    p = lightsolver.sky_patches(1)
    # Patch 1 centred on north (+y) at 6° altitude; patch 9 at 96° (east of north); zenith last.
    assert p["centre"][1] == pytest.approx([0, math.cos(math.radians(6)), math.sin(math.radians(6))])
    assert p["azimuth_deg"][9] == pytest.approx(96.0)
    assert p["centre"][145] == pytest.approx([0, 0, 1])
    turned = lightsolver.sky_patches(1, north_deg=90)  # north is -x
    assert turned["centre"][1] == pytest.approx(
        [-math.cos(math.radians(6)), 0, math.sin(math.radians(6))], abs=1e-12)


def test_year_arrays(year):
    sky = year["sky"]
    assert sky.shape == (8760, 146) and sky.dtype == np.float32
    assert np.isfinite(sky).all() and (sky >= 0).all()
    assert year["sun_direction"].shape == (8760, 3)
    dark = year["status"] != 2
    assert (sky[dark] == 0).all() and (year["sun_direct_normal_lx"][dark] == 0).all()
    assert year["bytes"] > sky.nbytes
    # The global horizontal illuminance rebuilt from the vectors and the sun, against the
    # file's column (docs: +1.7 % over the year with Perez' efficacies).
    p = lightsolver.sky_patches(1)
    rebuilt = sky[:, 1:] @ p["mean_cos_zenith"][1:] + (
        year["sun_direct_normal_lx"] * year["sun_direction"][:, 2])
    ghi = np.array([h["global_horizontal_lx"] or 0.0
                    for h in lightsolver.read_weather(str(CHICAGO))["hours"]])
    assert abs(rebuilt.sum() / ghi.sum() - 1) < 0.03


def test_radiance_sun_moves_the_sun_into_patches(year):
    smeared = lightsolver.sky_vectors(str(CHICAGO), mf=1, radiance_sun=True)
    assert (smeared["sun_direct_normal_lx"] == 0).all()
    added = smeared["sky"].astype(np.float64).sum(axis=1) - year["sky"].astype(np.float64).sum(axis=1)
    assert added == pytest.approx(year["sun_direct_normal_lx"], rel=1e-4, abs=1.0)


def test_errors_are_named():
    with pytest.raises(lightsolver.InputError, match="mf"):
        lightsolver.sky_patches(0)
    with pytest.raises(lightsolver.InputError, match="ground_reflectance"):
        lightsolver.sky_vectors(str(CHICAGO), ground_reflectance=2.0)
    with pytest.raises(lightsolver.InputError, match="cannot open"):
        lightsolver.sky_vectors(str(CHICAGO) + ".missing")


def test_skymtx_writes_an_npz_numpy_reads(cli, tmp_path, year):
    out = tmp_path / "chicago.npz"
    r = subprocess.run([cli, "skymtx", str(CHICAGO), "--mf", "1", "--out", str(out)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert "patches    146" in r.stdout and "written" in r.stdout
    with np.load(out) as z:
        assert z["sky"].shape == (8760, 146) and z["sky"].dtype == np.float32
        np.testing.assert_array_equal(z["sky"], year["sky"])
        np.testing.assert_array_equal(z["sun_direct_normal_lx"], year["sun_direct_normal_lx"])
        assert z["month_day_hour"][0].tolist() == [1, 1, 1]
        assert z["patch_solid_angle_sr"].sum() == pytest.approx(4 * math.pi)
    bad = tmp_path / "none" / "x.npz"
    r = subprocess.run([cli, "skymtx", str(CHICAGO), "--mf", "0", "--out", str(bad)],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode != 0 and "mf" in r.stderr and not bad.parent.exists()
