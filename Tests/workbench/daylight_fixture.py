"""A hand-written daylight-factor result in docs/scene-format.md, "Results"'s layout, for testing the
workbench's display before the solver writes them (the headless suite and the GUI scenario
workbench_gui_daylight use it). Its numbers are made up, not a computation: a DF falling
with the distance from the window, intervals +-5 %."""
from typing import Any, Dict, List


def cells(nu: int, nv: int, near: float = 5.0, far: float = 0.5) -> List[float]:
    """Row-by-row cell DF in %, from ``near`` at the grid's v = 0 edge to ``far`` at v = 1."""
    out = []
    for iv in range(nv):
        t = (iv + 0.5) / nv
        for iu in range(nu):
            side = 1.0 - 0.3 * abs((iu + 0.5) / nu - 0.5)  # darker toward the side walls
            out.append(round((near * (far / near) ** t) * side, 4))
    return out


def _interval(value: float) -> Dict[str, float]:
    return {"percent": value, "ci_low_percent": round(value * 0.95, 4),
            "ci_high_percent": round(value * 1.05, 4)}


def daylight_factor(sky: str, values: List[float]) -> Dict[str, Any]:
    """The ``daylight_factor`` object of a grid with these cell values."""
    ordered = sorted(values, reverse=True)
    p50 = ordered[(len(ordered) - 1) // 2]
    p95 = ordered[min(len(ordered) - 1, int(0.95 * len(ordered)))]
    mean = sum(values) / len(values)
    low = min(values)
    return {"sky": sky, "outside_illuminance_lx": 10000.0,
            "mean_percent": mean, "ci_low_percent": mean * 0.98, "ci_high_percent": mean * 1.02,
            "min_percent": low, "min_ci_low_percent": low * 0.9, "min_ci_high_percent": low * 1.1,
            "p50_percent": p50, "p50_ci_low_percent": p50 * 0.95,
            "p50_ci_high_percent": p50 * 1.05,
            "p95_percent": p95, "p95_ci_low_percent": p95 * 0.9,
            "p95_ci_high_percent": p95 * 1.1,
            "cells": [_interval(v) for v in values]}


def add_to_results(data: Dict[str, Any], grid: str, sky: str, nu: int, nv: int) -> Dict[str, Any]:
    """``data`` with the grid's entry given a DF result, EN 17037 medium requirements (Chicago's
    15 900 lx) and their verdicts: D_T passes, D_TM is undecided."""
    values = cells(nu, nv)
    df = daylight_factor(sky, values)
    for entry in data["targets"]:
        if entry["name"] != grid:
            continue
        entry["daylight_factor"] = df
        entry["requirements"] = {"en17037": "medium", "median_diffuse_lx": 15900,
                                 "df_target_percent": 500 / 159, "df_minimum_percent": 300 / 159,
                                 "source": "EN 17037:2018, daylight factor method, medium"}
        entry["verdicts"] = {
            "df_target": {"verdict": "pass", "value": df["p50_percent"],
                          "ci_low": df["p50_ci_low_percent"], "ci_high": df["p50_ci_high_percent"],
                          "required": 500 / 159, "relation": ">="},
            "df_minimum": {"verdict": "undecided", "value": df["p95_percent"],
                           "ci_low": df["p95_ci_low_percent"],
                           "ci_high": df["p95_ci_high_percent"], "required": 300 / 159,
                           "relation": ">="}}
        entry["verdict"] = "undecided"
    return data
