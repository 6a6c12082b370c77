"""Writes addon/probe_lights/core_tables.json, the core's tables the add-on shows, through the built module: the
menu of methods (methodMenu, cut_choice.h: the cut choices auto and both, then every registered placement method),
the kinds of light (lightKinds, light_export.h) and the point lights' default distance. The add-on registers
before its native module loads, so it reads them from this file; tests/python/test_manifest.py fails until the
file matches the core.

    PYTHONPATH=build/python python3 scripts/addon_tables.py
"""
import json
import os

import _probelights

PATH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "addon", "probe_lights", "core_tables.json")


def tables():
    return {"written_by": "scripts/addon_tables.py", "methods": [list(m) for m in _probelights.method_menu],
            "light_kinds": _probelights.light_kinds, "default_distance": _probelights.default_distance}


if __name__ == "__main__":
    text = json.dumps(tables(), indent=1) + "\n"
    tmp = PATH + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, PATH)
    print("wrote", os.path.normpath(PATH))
