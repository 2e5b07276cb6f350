"""Golden results (Tests/golden/README.md): the CLI commands in Tests/golden/commands.json give
bit-identical numbers to the committed results files. Only the timing fields listed there are
skipped; every other number, string and list is compared exactly (Python's float parsing of
the JSON round-trips the doubles the CLI wrote, so == on them is == on the bits)."""
import json
import math
import subprocess

import pytest

from conftest import SOURCE_DIR

GOLDEN = SOURCE_DIR / "Tests" / "golden"
MANIFEST = json.loads((GOLDEN / "commands.json").read_text())
TIMING_FIELDS = frozenset(MANIFEST["timing_fields"])


def differences(expected, actual, path="", found=None):
    """Paths where `actual` differs from `expected` (timing fields skipped), with both values."""
    found = [] if found is None else found
    if isinstance(expected, dict) and isinstance(actual, dict):
        for key in sorted(set(expected) | set(actual)):
            if key in TIMING_FIELDS:
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

    for name in MANIFEST["commands"]:
        walk(json.loads((GOLDEN / f"{name}.results.json").read_text()))
    assert TIMING_FIELDS <= present
    assert all(f.endswith("seconds") for f in TIMING_FIELDS)
    assert "max_seconds" not in TIMING_FIELDS  # a setting, not a timing


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
