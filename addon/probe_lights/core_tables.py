"""The core's tables the panel shows (no bpy), read once from core_tables.json, which scripts/addon_tables.py
writes from the native module (the add-on registers before its module loads, and registers without one): the menu
of methods (methodMenu, cut_choice.h), the kinds of light (lightKinds, light_export.h) and the point lamps'
default distance."""
import json
import os

with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "core_tables.json")) as _f:
    _TABLES = json.load(_f)

METHODS = [tuple(m) for m in _TABLES["methods"]]  # (name, label, what it does): EnumProperty's items
LIGHT_KINDS = _TABLES["light_kinds"]  # name, label, description, fitted_angle, on_dome
DEFAULT_DISTANCE = _TABLES["default_distance"]  # metres from the origin
