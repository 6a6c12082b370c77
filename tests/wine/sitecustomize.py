"""Copied into the Wine test environments' site-packages by tests/wine/run.sh (site imports it in every Python
process there, Blender's extension installer's too): Wine's gaps filled in before anything else runs."""

import wine_gaps

wine_gaps.patch()
