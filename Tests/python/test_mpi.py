"""MPI (docs/cluster.md): `mpirun -np K lightsolver ...` and `solve(comm=...)` give results bit
for bit equal to one process's, for K that divide the photon count and K that do not; a rank
that dies or hangs makes the job fail within a time limit, writing no results file."""
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from conftest import without_run_facts

lightsolver = pytest.importorskip("lightsolver")

MPIRUN = shutil.which("mpirun")
pytestmark = pytest.mark.skipif(MPIRUN is None or not lightsolver.mpi_built(),
                                reason="no mpirun, or a lightsolver built without MPI")
#: Fields that differ between two runs of the same scene and seed (the clock's).
RUN_FACTS = ("seconds",)
#: A job that fails must end within this many seconds.
FAIL_LIMIT_S = 60.0


def mpirun(k: int, *args: str, env: dict = None) -> subprocess.CompletedProcess:
    command = [MPIRUN, "--allow-run-as-root", "--oversubscribe", "-np", str(k), *args]
    return subprocess.run(command, capture_output=True, text=True, timeout=300, env=env)


def results(path: Path) -> dict:
    """The results without what differs between runs: timings, and the provenance's run facts,
    MPI ranks and rank 0's threads (the scene's hash, files and options must agree)."""
    data = json.loads(path.read_text())
    for key in RUN_FACTS:
        data.pop(key, None)
    return without_run_facts(data, also=("mpi_ranks", "threads"))


def ranks(path: Path) -> int:
    return json.loads(path.read_text())["provenance"]["mpi_ranks"]


@pytest.fixture(scope="module")
def decided_scene(tmp_path_factory, room_scene) -> Path:
    """The room with requirements on its workplane, close enough to its Em to take a few looks."""
    scene = json.loads(room_scene.read_text())
    for target in scene["targets"]:
        if target["name"] == "workplane":
            target["requirements"] = {"em_lux": 400.0, "u0": 0.6}
    path = tmp_path_factory.mktemp("mpi") / "room_decide.json"
    path.write_text(json.dumps(scene))
    return path


@pytest.mark.parametrize("extra", [["--photons", "300001"], ["--accuracy", "0.03"],
                                   ["--decide", "--photons", "2000000"]],
                         ids=["photons", "accuracy", "decide"])
def test_cli_run_is_bit_identical_for_any_process_count(cli, room_scene, decided_scene, tmp_path,
                                                         extra):
    scene = str(decided_scene if "--decide" in extra else room_scene)
    alone = tmp_path / "alone.json"
    subprocess.run([cli, "run", scene, "-q", "--seed", "3", "--out", str(alone), *extra],
                   check=True, timeout=300)
    for k in (2, 3):
        shared = tmp_path / f"np{k}.json"
        done = mpirun(k, cli, "run", scene, "-q", "--seed", "3", "--out", str(shared), *extra)
        assert done.returncode == 0, done.stderr
        assert results(shared) == results(alone), f"-np {k} differs from one process"
        assert (ranks(shared), ranks(alone)) == (k, 1)
    if "--decide" in extra:
        assert results(alone)["stop_reason"] in ("decided", "photons")


def test_cli_study_and_cost_are_bit_identical(cli, room_scene, tmp_path):
    alone, shared = tmp_path / "study1.json", tmp_path / "study2.json"
    subprocess.run([cli, "study", str(room_scene), "--max-photons", "80000", "--json",
                    str(alone)], check=True, capture_output=True, timeout=300)
    done = mpirun(2, cli, "study", str(room_scene), "--max-photons", "80000", "--json",
                  str(shared))
    assert done.returncode == 0, done.stderr
    strip = lambda d: [{k: v for k, v in row.items() if "second" not in k and k != "rate"}
                       for row in d["rows"]]
    assert strip(json.loads(shared.read_text())) == strip(json.loads(alone.read_text()))
    cost1 = tmp_path / "cost1.json"
    cost2 = tmp_path / "cost2.json"
    subprocess.run([cli, "cost", str(room_scene), "--max-photons", "40000", "--out", str(cost1)],
                   check=True, capture_output=True, timeout=300)
    done = mpirun(3, cli, "cost", str(room_scene), "--max-photons", "40000", "--out", str(cost2))
    assert done.returncode == 0, done.stderr
    assert results(cost2) == results(cost1)
    assert done.stdout.count("photons/s") == 1  # rank 0 alone prints


def test_optimizer_is_bit_identical(cli, tmp_path):
    scene = Path(os.environ.get("LIGHTSOLVER_SOURCE_DIR", Path(__file__).resolve().parents[2])) / \
        "Examples" / "optimization" / "small_room" / "small_room.json"
    alone, shared = tmp_path / "opt1.json", tmp_path / "opt2.json"
    subprocess.run([cli, "optimize", str(scene), "-q", "--iterations", "8", "--out", str(alone)],
                   check=True, capture_output=True, timeout=300)
    done = mpirun(2, cli, "optimize", str(scene), "-q", "--iterations", "8", "--out", str(shared))
    assert done.returncode == 0, done.stderr

    def strip(x):
        if isinstance(x, dict):
            return {k: strip(v) for k, v in x.items() if "second" not in k}
        return [strip(v) for v in x] if isinstance(x, list) else x

    # The search's provenance: the scene, block, domain and options the same, the ranks counted.
    assert (ranks(alone), ranks(shared)) == (1, 2)
    assert strip(results(shared)) == strip(results(alone))


def test_report_traces_with_every_rank(cli, room_scene, tmp_path):
    pytest.importorskip("mpi4py")
    pytest.importorskip("jinja2")
    args = ["report", str(room_scene), "--photons", "100001", "--date", "2026-01-01"]
    alone, shared = tmp_path / "alone", tmp_path / "shared"
    alone.mkdir(), shared.mkdir()
    subprocess.run([cli, *args, "--out", str(alone / "r.html"), "--save-results",
                    str(alone / "r.json")], check=True, capture_output=True, timeout=300)
    done = mpirun(2, cli, *args, "--out", str(shared / "r.html"), "--save-results",
                  str(shared / "r.json"))
    assert done.returncode == 0, done.stderr
    assert done.stdout.count("report written") == 1
    assert results(shared / "r.json") == results(alone / "r.json")
    assert sorted(p.name for p in shared.iterdir()) == ["r.html", "r.json"]


def test_python_solve_with_a_communicator_is_bit_identical(room_scene, tmp_path):
    script = tmp_path / "solve.py"
    script.write_text(
        "import json, sys\n"
        "from mpi4py import MPI\n"
        "import lightsolver\n"
        "scene = lightsolver.load_scene(sys.argv[1])\n"
        "comm = MPI.COMM_WORLD if sys.argv[3] == 'comm' else None\n"
        "r = lightsolver.solve(scene, photons=200001, seed=9, comm=comm)\n"
        "if comm is None or comm.Get_rank() == 0:\n"
        "    json.dump({t['name']: [t['mean_lux'], t['ci_low_lux'], t['ci_high_lux'], t['hits']]\n"
        "               for t in r['targets']}, open(sys.argv[2], 'w'))\n")
    pytest.importorskip("mpi4py")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    alone, shared = tmp_path / "alone.json", tmp_path / "shared.json"
    subprocess.run([sys.executable, str(script), str(room_scene), str(alone), "alone"],
                   check=True, timeout=300, env=env)
    done = mpirun(2, "-x", "PYTHONPATH", sys.executable, str(script), str(room_scene),
                  str(shared), "comm", env=env)
    assert done.returncode == 0, done.stderr
    assert json.loads(shared.read_text()) == json.loads(alone.read_text())


def _rank_pid(launcher: subprocess.Popen, rank: int, deadline_s: float = 30.0) -> int:
    """The pid of the lightsolver process of `rank` started by `launcher` (from /proc)."""
    end = time.monotonic() + deadline_s
    wanted = f"OMPI_COMM_WORLD_RANK={rank}".encode()
    while time.monotonic() < end:
        for entry in Path("/proc").iterdir():
            if not entry.name.isdigit():
                continue
            try:
                environ = (entry / "environ").read_bytes().split(b"\0")
                cmdline = (entry / "cmdline").read_bytes()
            except OSError:
                continue
            if wanted in environ and b"lightsolver" in cmdline and \
                    _descends_from(int(entry.name), launcher.pid):
                return int(entry.name)
        time.sleep(0.05)
    raise AssertionError(f"no rank {rank} process appeared")


def _descends_from(pid: int, ancestor: int) -> bool:
    while pid > 1:
        if pid == ancestor:
            return True
        try:
            stat = Path(f"/proc/{pid}/stat").read_text()
        except OSError:
            return False
        pid = int(stat.rsplit(")", 1)[1].split()[1])
    return False


@pytest.mark.parametrize("how", ["killed", "hangs"])
def test_a_failing_rank_fails_the_job_in_bounded_time(cli, room_scene, tmp_path, how):
    out = tmp_path / "results.json"
    env = dict(os.environ, LIGHTSOLVER_MPI_TIMEOUT_S="3")
    command = [MPIRUN, "--allow-run-as-root", "--oversubscribe", "-np", "2", "-x",
               "LIGHTSOLVER_MPI_TIMEOUT_S", cli, "run", str(room_scene), "-q", "--photons",
               "4000000000", "--out", str(out)]
    start = time.monotonic()
    launcher = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True, env=env)
    try:
        victim = _rank_pid(launcher, 1)
        time.sleep(1.0)  # inside the run's batches
        os.kill(victim, signal.SIGKILL if how == "killed" else signal.SIGSTOP)
        _, stderr = launcher.communicate(timeout=FAIL_LIMIT_S)
    finally:
        if launcher.poll() is None:
            launcher.kill()
            launcher.wait()
    assert launcher.returncode != 0
    assert time.monotonic() - start < FAIL_LIMIT_S + 30.0
    assert not out.exists(), "a failed job wrote a results file"
    if how == "hangs":
        assert "no answer from the other processes within 3 s" in stderr


def test_annual_under_mpirun_is_the_lone_processs_year(tmp_path):
    """`mpirun -np 2 lightsolver annual`: each rank traces a slice of every batch; rank 0 writes
    the same year a lone process writes (docs/daylight.md, "Daylight coefficients")."""
    root = Path(__file__).resolve().parents[2]
    scene = root / "Examples/daylight/annual_side_lit_room.scene.json"
    epw = root / "Tests/native/sun/data/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw"
    cli = os.environ["LIGHTSOLVER_CLI"]
    args = ["annual", str(scene), "--weather", str(epw), "--photons", "300000", "--seed", "5",
            "--backend", "embree"]
    alone = subprocess.run([cli, *args, "--out-dir", str(tmp_path / "alone")],
                           capture_output=True, text=True)
    assert alone.returncode == 0, alone.stderr
    done = mpirun(2, cli, *args, "--out-dir", str(tmp_path / "shared"))
    assert done.returncode == 0, done.stderr

    def year(folder: str) -> dict:
        data = json.loads((tmp_path / folder / "annual.json").read_text())
        data.pop("seconds")
        return data

    assert year("shared") == year("alone")
    a, b = (tmp_path / f / "annual.npz" for f in ("alone", "shared"))
    assert a.read_bytes() == b.read_bytes()
