"""`lightsolver sun`, `lightsolver weather` and their bindings, lightsolver.sun_position and
lightsolver.read_weather (docs/daylight.md): SPA's worked example through every front end, the
scene-frame direction, flags named in errors, the EPW file's location and median."""
import json
import math
import subprocess

import lightsolver
import pytest

from conftest import SOURCE_DIR

CHICAGO = SOURCE_DIR / "Tests/native/sun/data/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw"
# Reda & Andreas 2004 (NREL/TP-560-34302), the worked example: topocentric zenith and azimuth.
SPA_ARGS = ["--lat", "39.742476", "--lon", "-105.1786", "--time", "2003-10-17T12:30:30",
            "--tz", "-7", "--elevation-m", "1830.14", "--pressure-mbar", "820",
            "--temperature-c", "11", "--delta-t-s", "67"]


def run(cli: str, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([cli, *args], capture_output=True, text=True, timeout=60)


def test_sun_json_matches_spa_worked_example(cli):
    r = run(cli, "sun", *SPA_ARGS, "--json")
    assert r.returncode == 0, r.stderr
    p = json.loads(r.stdout)
    assert p["zenith_deg"] == pytest.approx(50.111622, abs=1e-4)
    assert p["azimuth_deg"] == pytest.approx(194.340241, abs=1e-4)
    assert p["elevation_deg"] == pytest.approx(90 - p["zenith_deg"], abs=1e-12)
    assert p["utc_offset_h"] == -7.0 and p["refraction"] is True
    assert math.hypot(*p["direction"]) == pytest.approx(1.0, abs=1e-12)


def test_sun_text_names_the_convention(cli):
    r = run(cli, "sun", *SPA_ARGS)
    assert r.returncode == 0, r.stderr
    assert "zenith     50.1116" in r.stdout
    assert "azimuth    194.340" in r.stdout and "from north, clockwise" in r.stdout


def test_sun_direction_turns_with_north(cli):
    """The sun due south at noon on the equinox, seen in a model whose north is 90° from +y
    counter-clockwise (north along −x): south is +x."""
    base = ["--lat", "45", "--lon", "0", "--time", "2026-03-20T12:07Z", "--no-refraction"]
    plain = json.loads(run(cli, "sun", *base, "--json").stdout)
    turned = json.loads(run(cli, "sun", *base, "--north-deg", "90", "--json").stdout)
    assert plain["azimuth_deg"] == pytest.approx(180.0, abs=0.5)
    assert plain["direction"][1] < -0.6 and turned["direction"][0] > 0.6
    assert turned["direction"][2] == pytest.approx(plain["direction"][2], abs=1e-12)


@pytest.mark.parametrize("args, flag", [
    (["--lat", "91", "--lon", "0", "--time", "2026-01-01T00:00Z"], "--lat:"),
    (["--lat", "10", "--lon", "nan", "--time", "2026-01-01T00:00Z"], "--lon:"),
    (["--lat", "10", "--lon", "0", "--time", "2026-13-01T00:00Z"], "month 13"),
    (["--lat", "10", "--lon", "0", "--time", "2026-01-01T00:00"], "no time zone"),
    (["--lat", "10", "--lon", "0", "--time", "2026-01-01T00:00Z", "--tz", "2"], "disagrees"),
    (["--lat", "10", "--lon", "0", "--time", "2026-01-01T00:00Z", "--pressure-mbar", "0"],
     "--pressure-mbar:"),
])
def test_sun_bad_input_names_the_flag(cli, args, flag):
    r = run(cli, "sun", *args)
    assert r.returncode != 0 and r.stdout == ""
    assert flag in r.stderr, r.stderr


def test_sun_position_binding_agrees_with_cli(cli):
    p = lightsolver.sun_position(39.742476, -105.1786, "2003-10-17T12:30:30-07:00",
                                 elevation_m=1830.14, pressure_mbar=820, temperature_c=11,
                                 delta_t_s=67)
    c = json.loads(run(cli, "sun", *SPA_ARGS, "--json").stdout)
    for key in ("zenith_deg", "azimuth_deg", "julian_day", "declination_deg"):
        assert p[key] == c[key]
    assert list(p["direction"]) == c["direction"]
    with pytest.raises(lightsolver.InputError, match="latitude_deg"):
        lightsolver.sun_position(91, 0, "2026-01-01T00:00Z")


def test_weather_command_and_binding():
    w = lightsolver.read_weather(str(CHICAGO))
    assert w["location"]["city"] == "Chicago Ohare Intl Ap"
    assert w["location"]["utc_offset_h"] == -6.0 and len(w["hours"]) == 8760
    # EN 17037's E_v,d,med: checked outside the solver by sorting column 19 (tests in sun_tests).
    assert w["median_diffuse_illuminance_lx"] == 15900.0


def test_weather_cli(cli, tmp_path):
    r = run(cli, "weather", str(CHICAGO))
    assert r.returncode == 0, r.stderr
    assert "Chicago Ohare Intl Ap" in r.stdout and "15900 lx" in r.stdout
    j = json.loads(run(cli, "weather", str(CHICAGO), "--json").stdout)
    assert j["median_diffuse_illuminance_lx"] == 15900.0 and j["hours"] == 8760
    bad = tmp_path / "cut.epw"
    bad.write_text("\n".join(CHICAGO.read_text().splitlines()[:100]) + "\n")
    r = run(cli, "weather", str(bad))
    assert r.returncode == 1 and "cut.epw: line 100" in r.stderr and "92 hourly rows" in r.stderr


def test_a_sun_luminaire_from_python_takes_its_position():
    """Scene.add_light(..., 'sun', site=..., time=...) passes the keys to the scene reader: the
    beam's flux is E · opening area · sin(elevation) for a horizontal opening."""
    import numpy as np

    s = lightsolver.Scene()
    s.add_material("grey", "diffuse", reflectance=0.5)
    s.add_mesh("floor", np.array([[-9, -9, 0], [9, -9, 0], [9, 9, 0], [-9, 9, 0]], float),
               np.array([[0, 1, 2], [0, 2, 3]]), "grey")
    site = {"latitude_deg": 48.85, "longitude_deg": 2.35}
    s.add_light("sun", "sun", illuminance_lx=85000, site=site, time="2026-06-21T14:00+02:00",
                corner=[-3, -3, 3], edge1=[0, 6, 0], edge2=[6, 0, 0])
    s.add_target("floor", "surface", mesh="floor")
    s.validate()
    elevation = lightsolver.sun_position(48.85, 2.35, "2026-06-21T14:00+02:00")["elevation_deg"]
    assert s.total_flux_lm == pytest.approx(85000 * 36 * math.sin(math.radians(elevation)),
                                            rel=1e-9)
    s.add_light("bad", "sun", illuminance_lx=1, site={"latitude_deg": 98, "longitude_deg": 0},
                time="2026-06-21T14:00Z", corner=[0, 0, 3], edge1=[0, 1, 0], edge2=[1, 0, 0])
    with pytest.raises(lightsolver.InputError, match=r"luminaires\[1\]\.site\.latitude_deg"):
        s.validate()
