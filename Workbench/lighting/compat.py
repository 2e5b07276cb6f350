# SPDX-License-Identifier: LGPL-2.1-or-later
"""Differences between FreeCAD 0.20, 0.21 and 1.0 (Arch -> BIM rename, IFC type names)."""
from __future__ import annotations

from typing import Any, Optional



def import_arch() -> Any:
    """The Arch API module: ``Arch`` in 0.20/0.21, still ``Arch`` (inside the BIM workbench) in 1.0."""
    try:
        import Arch  # noqa: F401  (0.20, 0.21, 1.0 keep this name)
        return Arch
    except ImportError:  # pragma: no cover - only if a future version drops the alias
        import BIM  # type: ignore
        return BIM


def ifc_type(obj: Any) -> str:
    """Normalised IFC class of an Arch/BIM object: lower case, no spaces, no "Ifc" prefix,
    no "Standard Case" suffix ("Wall", "IfcWallStandardCase" -> "wall"). Empty if none."""
    value = ""
    for prop in ("IfcType", "IfcRole", "Role"):
        if prop in getattr(obj, "PropertiesList", []):
            value = str(getattr(obj, prop) or "")
            if value:
                break
    if not value:
        proxy_type = getattr(getattr(obj, "Proxy", None), "Type", "")
        value = proxy_type if isinstance(proxy_type, str) else ""
    value = value.replace(" ", "").replace("_", "").lower()
    if value.startswith("ifc"):
        value = value[3:]
    if value.endswith("standardcase"):
        value = value[: -len("standardcase")]
    return value


def has_property(obj: Any, name: str) -> bool:
    """True when ``obj`` is a document object with a property ``name``."""
    return name in getattr(obj, "PropertiesList", ())


def get_property(obj: Any, name: str, default: Optional[Any] = None) -> Any:
    """Value of property ``name`` of ``obj`` or ``default``."""
    return getattr(obj, name) if has_property(obj, name) else default


def is_group(obj: Any) -> bool:
    """True for containers (groups, App::Part, Arch building parts, sites, floors)."""
    for ext in ("App::GroupExtension", "App::GeoFeatureGroupExtension"):
        try:
            if obj.hasExtension(ext):
                return True
        except Exception:  # noqa: BLE001 - very old objects without hasExtension
            pass
    return ifc_type(obj) in ("buildingstorey", "building", "site", "buildingpart", "project")
