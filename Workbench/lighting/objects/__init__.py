# SPDX-License-Identifier: LGPL-2.1-or-later
"""Document objects (App side, headless): luminaire, target, placement domain, analysis."""
