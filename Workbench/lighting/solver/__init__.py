# SPDX-License-Identifier: LGPL-2.1-or-later
"""Run stages Check -> Prepare -> Solve -> Results (like FEM's solver framework)."""
