# SPDX-License-Identifier: LGPL-2.1-or-later
"""Number formatting for the report (Jinja2 filters): the same value always prints the same
text, so equal inputs give byte-identical HTML."""
from __future__ import annotations

import math
from typing import Any, Optional

#: Unicode superscripts for powers of ten (10⁶).
_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")
DASH = "–"


def finite(value: Any) -> Optional[float]:
    """A JSON value as a finite float, or None (missing, not a number, a bool, inf or NaN)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def lux(value: Optional[float]) -> str:
    """Illuminance with four significant digits and at most two decimals: 404.5, 1234, 8.35."""
    if value is None or not math.isfinite(value):
        return DASH
    magnitude = abs(value)
    if magnitude >= 1000:
        return f"{value:.0f}"
    if magnitude >= 100:
        return f"{value:.1f}"
    if magnitude >= 1 or magnitude == 0:
        return f"{value:.2f}"
    return f"{value:.3g}"


def ratio(value: Optional[float]) -> str:
    """A ratio such as U0 or a reflectance: three decimals (0.849)."""
    if value is None or not math.isfinite(value):
        return DASH
    return f"{value:.3f}"


def ratio2(value: Optional[float]) -> str:
    """A required ratio or a material factor: two decimals (0.60)."""
    if value is None or not math.isfinite(value):
        return DASH
    return f"{value:.2f}"


def number(value: Optional[float], digits: int = 3) -> str:
    """A general number with ``digits`` significant digits (no exponent below 10⁶)."""
    if value is None or not math.isfinite(value):
        return DASH
    if value != 0 and (abs(value) >= 1e6 or abs(value) < 1e-3):
        return sci(value, digits)
    text = f"{value:.{digits}g}"
    return f"{float(text):.0f}" if "e" in text else text


def sci(value: Optional[float], digits: int = 2) -> str:
    """Scientific notation with a proper power of ten: 2.0·10⁶."""
    if value is None or not math.isfinite(value):
        return DASH
    if value == 0:
        return "0"
    exponent = math.floor(math.log10(abs(value)))
    mantissa = value / 10.0 ** exponent
    if round(abs(mantissa), digits - 1) >= 10.0:
        mantissa /= 10.0
        exponent += 1
    if exponent == 0:
        return f"{mantissa:.{digits - 1}f}"
    return f"{mantissa:.{digits - 1}f}·10{str(exponent).translate(_SUPERSCRIPT)}"


def count(value: Optional[float]) -> str:
    """A count with thin-space thousands separators below 10⁷ (2 000 000), else 1.2·10⁸."""
    if value is None or not math.isfinite(value):
        return DASH
    if abs(value) >= 1e7:
        return sci(value, 3)
    return f"{round(value):,}".replace(",", "\u202f")


def seconds(value: Optional[float]) -> str:
    """A duration that does not break across lines: 0.81 s, 45 s, 4 min 10 s, 3 h 20 min."""
    return _seconds(value).replace(" ", "\u00a0")


def _seconds(value: Optional[float]) -> str:
    if value is None or not math.isfinite(value):
        return DASH
    if value < 10:
        return f"{value:.2g} s"
    if value < 59.5:
        return f"{value:.0f} s"
    if value < 3600:
        total = round(value)
        return f"{total // 60} min {total % 60} s"
    if value < 86400:
        minutes = round(value / 60)
        return f"{minutes // 60} h {minutes % 60} min"
    return f"{value / 86400:.3g} days"


def percent(value: Optional[float]) -> str:
    """A fraction as a percentage without trailing zeros: 0.95 -> 95 %."""
    if value is None or not math.isfinite(value):
        return DASH
    return f"{100.0 * value:.6g}\u202f%"


def metres(value: Optional[float]) -> str:
    """A length in metres with two decimals."""
    if value is None or not math.isfinite(value):
        return DASH
    return f"{value:.2f}"


def ugr(value: Optional[float]) -> str:
    """A UGR as data sheets print it, one decimal: 25.8; "–" where no luminaire counts."""
    value = finite(value)
    return "–" if value is None else f"{value:.1f}"


def azimuth(direction: Any) -> Optional[float]:
    """A line of sight seen from above, in degrees from +x toward +y (0 … 360); None for a
    vertical or missing one."""
    try:
        x, y = float(direction[0]), float(direction[1])
    except (TypeError, ValueError, IndexError):
        return None
    if not (math.isfinite(x) and math.isfinite(y)) or (x == 0 and y == 0):
        return None
    # Rounded first: a direction one ulp off an axis (the workbench's 2.2e-16) reads 90°.
    angle = round(math.degrees(math.atan2(y, x)), 6) % 360.0
    return angle + 0.0  # no "-0"


def df(value: Optional[float]) -> str:
    """A daylight factor in percent (the number only): 2.03, 12.4."""
    value = finite(value)
    if value is None:
        return DASH
    return f"{value:.2f}" if abs(value) < 10 else f"{value:.1f}"


def sunhours(hours: Optional[float]) -> str:
    """Hours of sunlight as "3 h 12 min"."""
    hours = finite(hours)
    if hours is None:
        return DASH
    minutes = round(hours * 60.0)
    return f"{minutes // 60}\u00a0h {minutes % 60:02d}\u00a0min"


def stopped(reason: Optional[str]) -> str:
    """How the calculation ended, for a client (the results' ``stop_reason``)."""
    from lightsolver_report.wording import stopped as worded

    return worded(reason)


def frac(value: Optional[float]) -> str:
    """A fraction of hours or of an area in percent, one decimal (the number only): 82.0."""
    value = finite(value)
    return DASH if value is None else f"{100.0 * value:.1f}"


def pct(value: Optional[float]) -> str:
    """A value already in percent, one decimal (the number only): 99.3."""
    value = finite(value)
    return DASH if value is None else f"{value:.1f}"


FILTERS = {"frac": frac, "pct": pct, "ugr": ugr, "lux": lux, "ratio": ratio, "ratio2": ratio2,
           "number": number, "sci": sci,
           "count": count, "seconds": seconds, "percent": percent, "metres": metres,
           "azimuth": azimuth, "stopped": stopped, "df": df,
           "sunhours": sunhours}
