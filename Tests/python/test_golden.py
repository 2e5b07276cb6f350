"""Golden results (Tests/golden/README.md): the CLI commands in Tests/golden/commands.json give
bit-identical numbers to the committed results files. Only the timing fields listed there are
skipped, and in the results' provenance the facts of the run and the build listed there (time,
host, command line, device, threads, source commit, build type); every other number, string
and list is compared exactly (Python's float parsing of the JSON round-trips the doubles the CLI
wrote, so == on them is == on the bits): the scene's hash, its files' hashes, the solver
version, backend, MPI ranks and every resolved option.

The manifest's `per_backend` goldens (every luminaire, material and target type, a rescale,
verdicts near their bounds) are recorded once per tracing backend and each run is compared with
its own backend's file: Embree here, Vulkan on lavapipe where the build has it."""
import functools
import json
import math
import os
import subprocess
from pathlib import Path

import pytest

from conftest import SOURCE_DIR

GOLDEN = SOURCE_DIR / "Tests" / "golden"
MANIFEST = json.loads((GOLDEN / "commands.json").read_text())
TIMING_FIELDS = frozenset(MANIFEST["timing_fields"])
#: Skipped in the top-level "provenance" object only: they differ between machines and runs.
PROVENANCE_RUN_FIELDS = frozenset(MANIFEST["provenance_run_fields"])
PER_BACKEND = MANIFEST["per_backend"]
#: (name, backend) of every per-backend golden, in manifest order.
BACKEND_GOLDENS = [(name, backend) for backend in PER_BACKEND["backends"]
                   for name in PER_BACKEND["commands"]]


def golden_path(name, backend=None):
    """The committed results file of a golden (a per-backend one when `backend` is given)."""
    return GOLDEN / (f"{name}.{backend}.results.json" if backend else f"{name}.results.json")


def all_golden_files():
    """Every committed golden results file the manifest names."""
    return ([golden_path(n) for n in MANIFEST["commands"]]
            + [golden_path(n, b) for n, b in BACKEND_GOLDENS])


def backend_env(backend):
    """The environment of a backend's golden runs (Vulkan: the lavapipe driver)."""
    return {**os.environ, **PER_BACKEND["backends"][backend]["env"]}


@functools.lru_cache(maxsize=None)
def backend_available(cli, backend):
    """Whether `lightsolver backends` lists the backend as available in its golden environment
    (a build without Vulkan, or without lavapipe installed, skips the Vulkan goldens)."""
    r = subprocess.run([cli, "backends"], capture_output=True, text=True, timeout=120,
                       env=backend_env(backend))
    return any(line.split()[:1] == [backend] and " available" in line
               and "not available" not in line for line in r.stdout.splitlines())


def differences(expected, actual, path="", found=None):
    """Paths where `actual` differs from `expected` (timing fields skipped, and the provenance's
    run facts), with both values."""
    found = [] if found is None else found
    if isinstance(expected, dict) and isinstance(actual, dict):
        for key in sorted(set(expected) | set(actual)):
            if key in TIMING_FIELDS or (path == ".provenance" and key in PROVENANCE_RUN_FIELDS):
                continue
            if key not in expected or key not in actual:
                found.append(f"{path}.{key}: only in {'golden' if key in expected else 'new'}")
            else:
                differences(expected[key], actual[key], f"{path}.{key}", found)
    elif isinstance(expected, list) and isinstance(actual, list):
        if len(expected) != len(actual):
            found.append(f"{path}: {len(expected)} items in the golden, {len(actual)} now")
        for i, (e, a) in enumerate(zip(expected, actual)):
            differences(e, a, f"{path}[{i}]", found)
    elif type(expected) is not type(actual) or not same_value(expected, actual):
        found.append(f"{path}: golden {expected!r}, now {actual!r}")
    return found


def same_value(a, b):
    if isinstance(a, float):
        return a.hex() == b.hex() or (math.isnan(a) and math.isnan(b))
    return a == b


def run_golden(cli, name, tmp_path, extra=()):
    out = tmp_path / f"{name}.results.json"
    args = [cli, *MANIFEST["commands"][name], *extra, "--out", str(out)]
    # From the repository root: the committed paths (and the optimizer's scene_file) are
    # relative to it.
    r = subprocess.run(args, cwd=SOURCE_DIR, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return json.loads(out.read_text())


def run_backend_golden(cli, name, backend, tmp_path, extra=(), env=None):
    """Runs a per-backend golden's command on `backend` and returns its results."""
    if not backend_available(cli, backend):
        pytest.skip(f"the {backend} backend is not available here")
    out = tmp_path / f"{name}.{backend}.results.json"
    args = [a.replace("{backend}", backend) for a in PER_BACKEND["commands"][name]]
    r = subprocess.run([cli, *args, *extra, "--out", str(out)], cwd=SOURCE_DIR,
                       capture_output=True, text=True, timeout=300,
                       env={**backend_env(backend), **(env or {})})
    assert r.returncode == 0, r.stderr
    return json.loads(out.read_text())


def assert_same_as_golden(golden_file, new):
    """Fails with the first differing fields when `new` is not `golden_file` bit for bit."""
    diff = differences(json.loads(golden_file.read_text()), new)
    assert not diff, (f"{len(diff)} field(s) differ from {golden_file.relative_to(SOURCE_DIR)} "
                      "(regenerate deliberately with Tests/golden/regenerate.sh):\n"
                      + "\n".join(diff[:20]))


@pytest.mark.parametrize("name,backend", BACKEND_GOLDENS)
def test_each_backend_reproduces_its_own_golden(cli, name, backend, tmp_path):
    assert_same_as_golden(golden_path(name, backend),
                          run_backend_golden(cli, name, backend, tmp_path))


@pytest.mark.parametrize("backend,extra,env", [
    ("embree", ["--threads", "1"], {}),
    ("embree", ["--threads", "3"], {}),
    ("vulkan", [], {"LP_NUM_THREADS": "1"}),  # lavapipe's own worker threads
])
def test_thread_counts_do_not_move_a_golden(cli, backend, extra, env, tmp_path):
    # The goldens are recorded with the default threads; photon i is photon i and the tallies
    # are integers, so any other count gives the same bits.
    assert_same_as_golden(golden_path("lamps", backend),
                          run_backend_golden(cli, "lamps", backend, tmp_path, extra, env))


def test_per_backend_goldens_cover_every_type():
    """The per-backend goldens hold every luminaire, material and target type the solver
    reads, a rescaled file and verdicts of every outcome (pass, fail, undecided)."""
    import lightsolver  # noqa: PLC0415 (the build's module; conftest puts it on the path)

    scenes = [json.loads((SOURCE_DIR / args[1]).read_text())
              for args in PER_BACKEND["commands"].values() if args[0] == "run"]
    luminaires = {lum["type"] for s in scenes for lum in s["luminaires"]}
    assert luminaires == {"point", "spot", "area", "directional", "photometric"}
    files = {Path(lum["file"]).suffix.lower() for s in scenes for lum in s["luminaires"]
             if lum["type"] == "photometric"}
    assert files == {".ies", ".ldt"}
    assert any("TILT=INCLUDE" in (GOLDEN / "scenes" / lum["file"]).read_text()
               for s in scenes for lum in s["luminaires"] if lum["type"] == "photometric"
               and (GOLDEN / "scenes" / lum["file"]).exists())
    materials = {m["type"] for s in scenes for m in s["materials"].values()}
    assert materials == set(lightsolver.material_defaults())
    assert any(m.get("thin") for s in scenes for m in s["materials"].values())
    targets = {t["type"] for s in scenes for t in s["targets"]}
    assert targets == {"surface", "grid", "observer", "observer_grid"}
    for backend in PER_BACKEND["backends"]:
        rescaled = json.loads(golden_path("lamps_rescaled", backend).read_text())
        assert set(rescaled["rescaled"].values()) >= {0, 0.5}
        verdicts = {v["verdict"] for t in rescaled["targets"] + json.loads(
            golden_path("lamps", backend).read_text())["targets"]
            for v in t.get("verdicts", {}).values()}
        assert verdicts == {"pass", "fail", "undecided"}
        # Near their bounds: every traced verdict's bound lies within a quarter of its interval's
        # width of the interval (a small change to the numbers flips it).
        for t in json.loads(golden_path("lamps", backend).read_text())["targets"]:
            for kind, v in t.get("verdicts", {}).items():
                gap = max(v["ci_low"] - v["required"], v["required"] - v["ci_high"], 0.0)
                assert gap <= 0.25 * (v["ci_high"] - v["ci_low"]), (t["name"], kind, v)


@pytest.mark.parametrize("name", sorted(MANIFEST["commands"]))
def test_results_are_bit_identical_to_the_golden(cli, name, tmp_path):
    golden = json.loads((GOLDEN / f"{name}.results.json").read_text())
    new = run_golden(cli, name, tmp_path)
    diff = differences(golden, new)
    assert not diff, (f"{name}: {len(diff)} field(s) differ from Tests/golden/{name}.results.json "
                      "(regenerate deliberately with Tests/golden/regenerate.sh):\n"
                      + "\n".join(diff[:20]))


def test_timing_fields_are_the_only_ones_skipped():
    # Every skipped name is a timing that the golden files really hold, so the list cannot
    # silently hide a number.
    present = set()

    def walk(x):
        if isinstance(x, dict):
            present.update(x)
            for v in x.values():
                walk(v)
        elif isinstance(x, list):
            for v in x:
                walk(v)

    for path in all_golden_files():
        walk(json.loads(path.read_text()))
    assert TIMING_FIELDS <= present
    assert all(f.endswith("seconds") for f in TIMING_FIELDS)
    assert "max_seconds" not in TIMING_FIELDS  # a setting, not a timing


def test_provenance_skips_only_run_facts():
    # The run facts skipped are in every golden a run wrote, and what makes results belong to
    # a scene (its hash and files) or reproducible (options, version, backend) is compared.
    for path in all_golden_files():
        doc = json.loads(path.read_text())
        if doc.get("format") == "lightsolver.results/1":
            assert PROVENANCE_RUN_FIELDS < set(doc["provenance"]), path.name
    assert not PROVENANCE_RUN_FIELDS & {"scene_sha256", "files", "options", "solver_version",
                                        "backend", "mpi_ranks"}
    golden = json.loads(golden_path("lamps", "embree").read_text())
    for key, value in [("scene_sha256", "0" * 64), ("options", {}), ("mpi_ranks", 2)]:
        changed = json.loads(json.dumps(golden))
        changed["provenance"][key] = value
        diff = differences(golden, changed)
        assert diff and all(d.startswith(f".provenance.{key}") for d in diff), diff
    changed = json.loads(json.dumps(golden))
    changed["provenance"]["files"][0]["sha256"] = "0" * 64
    assert differences(golden, changed)
    for key in PROVENANCE_RUN_FIELDS:
        changed = json.loads(json.dumps(golden))
        changed["provenance"][key] = "elsewhere"
        assert differences(golden, changed) == []


def test_a_changed_number_is_caught(cli, tmp_path):
    # Another seed moves the numbers; the comparison must say so (else it could not fail).
    golden = json.loads((GOLDEN / "office.results.json").read_text())
    new = run_golden(cli, "office", tmp_path, extra=["--seed", "2"])
    diff = differences(golden, new)
    assert any(d.startswith(".seed:") for d in diff)
    assert any(".mean_lux:" in d for d in diff) and any(".hits:" in d for d in diff)
    # One ulp is a difference too.
    nudged = json.loads(json.dumps(golden))
    nudged["targets"][0]["mean_lux"] = math.nextafter(nudged["targets"][0]["mean_lux"], math.inf)
    assert differences(golden, nudged) == [".targets[0].mean_lux: golden "
                                           f"{golden['targets'][0]['mean_lux']!r}, now "
                                           f"{nudged['targets'][0]['mean_lux']!r}"]
