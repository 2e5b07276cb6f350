# SPDX-License-Identifier: LGPL-2.1-or-later
"""Scene export: object collection, tessellation, materials, scene and PLY files."""
