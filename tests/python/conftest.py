import os
import sys

import pytest

# The full module (reads files too) is built into build/python; the add-on carries portable builds of it.
BUILD = os.environ.get("PROBELIGHTS_BUILD", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
# PROBELIGHTS_MODULE_DIR puts another build's _probelights first: the Windows module's under Wine
# (tests/wine/module_tests.sh), where the tests that read files or run the CLI are skipped (full_only).
sys.path.insert(0, os.environ.get("PROBELIGHTS_MODULE_DIR") or os.path.join(BUILD, "python"))
# The add-on's bpy-free rules (world_graph, conversion) are imported as plain modules too.
sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "addon", "probe_lights"))


@pytest.fixture
def bundled_probe():
    return os.path.join(os.path.dirname(__file__), "..", "..", "assets", "noon_grass_1k.hdr")
