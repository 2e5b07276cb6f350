# SPDX-License-Identifier: LGPL-2.1-or-later
"""GUI commands of the toolbar and menu."""
