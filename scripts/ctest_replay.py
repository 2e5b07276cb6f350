#!/usr/bin/python3
"""Replays CTest's parallel scheduler over measured entry times (docs/testing.md, "CI time").

    /usr/bin/python3 scripts/ctest_replay.py ORDER.json TIMES.log [-j 2] [--assume NAME=SECONDS]

ORDER.json is ``ctest --test-dir build --show-only=json-v1``: the entries in registration order
with their RUN_SERIAL, RESOURCE_LOCK, COST and PROCESSORS. TIMES.log is the output of a CTest
run ("Test #N: NAME ...... Passed X sec"; the log's first run only). It prints the wall time
`ctest -j N` takes when every entry takes as long as in that log and the build has no timings of
its own (a fresh clone): entries start in COST order (stable), a RUN_SERIAL entry starts only
when nothing runs and starts nothing beside it, an entry waits while another holds one of its
locks. An entry missing from the log takes 0 s unless --assume gives its seconds."""
import json
import re
import sys
from typing import Dict, List, Tuple


def times_from_log(path: str) -> Dict[str, float]:
    """Entry name -> seconds, from the first CTest run in the log."""
    out: Dict[str, float] = {}
    with open(path, errors="replace") as stream:
        for line in stream:
            if "Total Test time" in line:
                break
            m = re.search(r"Test\s+#\d+: (.+?) \.{3,}.*?([\d.]+) sec", line)
            if m:
                out[m.group(1)] = float(m.group(2))
    return out


def _entries(order: dict, times: Dict[str, float]) -> List[dict]:
    entries = []
    for index, test in enumerate(order["tests"]):
        props = {p["name"]: p["value"] for p in test.get("properties", [])}
        entries.append({"name": test["name"], "index": index, "cost": float(props.get("COST", 0)),
                        "serial": bool(props.get("RUN_SERIAL")),
                        "locks": set(props.get("RESOURCE_LOCK", [])),
                        "procs": int(props.get("PROCESSORS", 1)),
                        "seconds": times.get(test["name"], 0.0)})
    return entries


def replay(order: dict, times: Dict[str, float], jobs: int) -> Tuple[float, Dict[str, float]]:
    """The wall time of the run and each entry's start."""
    pending = sorted(_entries(order, times), key=lambda e: (-e["cost"], e["index"]))
    running: List[Tuple[float, dict]] = []
    now, serial, starts = 0.0, False, {}
    while pending or running:
        free = jobs - sum(min(e["procs"], jobs) for _, e in running)
        held = set().union(*(e["locks"] for _, e in running))
        for entry in [] if serial else list(pending):
            if (entry["serial"] and running) or entry["locks"] & held:
                continue
            need = min(entry["procs"], jobs)
            if need > free:
                if free == 0:
                    break
                continue
            pending.remove(entry)
            running.append((now + entry["seconds"], entry))
            starts[entry["name"]] = now
            free -= need
            held |= entry["locks"]
            if entry["serial"]:
                serial = True
                break
        running.sort(key=lambda r: r[0])
        now, done = running.pop(0)
        serial = serial and not done["serial"]
    return now, starts


def main(args: List[str]) -> int:
    jobs, assumed = 2, {}
    while "-j" in args:
        k = args.index("-j")
        jobs = int(args[k + 1])
        del args[k:k + 2]
    while "--assume" in args:
        k = args.index("--assume")
        name, seconds = args[k + 1].split("=")
        assumed[name] = float(seconds)
        del args[k:k + 2]
    if len(args) != 2:
        print(__doc__)
        return 2
    with open(args[0]) as stream:
        order = json.load(stream)
    times = {**times_from_log(args[1]), **assumed}
    names = [t["name"] for t in order["tests"]]
    wall, _ = replay(order, times, jobs)
    missing = [n for n in names if n not in times]
    print(f"{len(names)} entries ({len(missing)} without a time), "
          f"{sum(times.get(n, 0.0) for n in names):.0f} s in all; "
          f"ctest -j {jobs} replayed: {wall:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
