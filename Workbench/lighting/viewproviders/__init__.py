# SPDX-License-Identifier: LGPL-2.1-or-later
"""View providers (GUI only): symbols, false colours, legend."""
