# SPDX-License-Identifier: LGPL-2.1-or-later
"""FreeCAD module "Lighting": App-side initialisation (runs in freecadcmd and in the GUI).

Nothing is imported here on purpose: the package ``lighting`` next to this file is importable
because FreeCAD puts every module folder on ``sys.path``, and it loads on first use
(``import lighting`` in a script, or the workbench's first activation in the GUI).
"""
