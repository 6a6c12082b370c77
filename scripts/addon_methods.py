"""Writes addon/probe_lights/methods.json, the add-on's menu of methods, from the core's registry (methodMenu,
cut_choice.h: the cut choices auto and both, then every registered placement method) through the built module.
The add-on registers before its native module loads, so it reads its menu from this file;
tests/python/test_manifest.py fails until the file matches the core.

    PYTHONPATH=build/python python3 scripts/addon_methods.py
"""
import json
import os

import _probelights

PATH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "addon", "probe_lights", "methods.json")


def menu():
    return {"written_by": "scripts/addon_methods.py", "methods": [list(m) for m in _probelights.method_menu]}


if __name__ == "__main__":
    text = json.dumps(menu(), indent=1) + "\n"
    tmp = PATH + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, PATH)
    print("wrote", os.path.normpath(PATH))
