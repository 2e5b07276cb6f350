# SPDX-License-Identifier: LGPL-2.1-or-later
"""A year of daylight for a 300-cell side-lit room (docs/BENCHMARKS.md, "A year of daylight"):
`lightsolver annual` on Examples/daylight/annual_side_lit_room.scene.json with the Chicago TMY3
file at MF 1 and 2 and several photon counts, in one run: the wall time of each stage (sky
matrix, trace, hours and metrics), the peak memory of the process, the coefficients' and hours'
bytes, and the widths the photons buy (sDA's interval, the mean DA's, the mean UDI's). Prints a
Markdown table.

    /usr/bin/python3 Tests/benchmarks/annual_bench.py build/NativeSolver/cli/lightsolver
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "Examples/daylight/annual_side_lit_room.scene.json"
WEATHER = ROOT / "Tests/native/sun/data/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw"


def run(cli: str, mf: int, photons: int, folder: str) -> dict:
    """One annual run in its own process; its summary and the process' peak RSS (MB, GNU time's
    %M)."""
    out = os.path.join(folder, f"mf{mf}-{photons}")
    done = subprocess.run(["/usr/bin/time", "-f", "%M", cli, "annual", str(SCENE), "--weather",
                           str(WEATHER), "--mf", str(mf), "--photons", str(photons), "--out-dir",
                           out], check=True, capture_output=True, text=True)
    summary = json.loads(Path(out, "annual.json").read_text())
    summary["peak_mb"] = int(done.stderr.strip().splitlines()[-1]) / 1024.0  # KiB
    summary["npz_mb"] = Path(out, "annual.npz").stat().st_size / 1e6
    return summary


def width(m: dict, scale: float = 1.0) -> str:
    return f"{scale * m['estimate']:.1f} [{scale * m['low']:.1f}, {scale * m['high']:.1f}]"


def main() -> None:
    cli = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "build/NativeSolver/cli/lightsolver")
    print("| MF | photons | sky matrix | direct sun | photons traced | hours + metrics | total | "
          "peak memory | coefficients | annual.npz | sDA300/50 % | mean DA300 | "
          "mean UDI 100–2000 |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as folder:
        for mf, photons in ((1, 2_000_000), (1, 20_000_000), (1, 80_000_000), (2, 20_000_000)):
            s = run(cli, mf, photons, folder)
            sec, m = s["seconds"], s["grids"][0]["metrics"]
            print(f"| {mf} | {photons:.0e} | {sec['sky_matrix']:.2f} s | "
                  f"{sec['of_which_direct_sun']:.2f} s | {sec['of_which_photons']:.2f} s | "
                  f"{sec['hours_and_metrics']:.2f} s | {sec['total']:.2f} s | "
                  f"{s['peak_mb']:.0f} MB | {s['trace']['coefficient_bytes'] / 1e6:.1f} MB | "
                  f"{s['npz_mb']:.1f} MB | {width(m['sda_percent'])} % | "
                  f"{width(m['da_fraction'], 100)} % | {width(m['udi_useful_fraction'], 100)} % |",
                  flush=True)


if __name__ == "__main__":
    main()
