"""The one error the add-on reports to the user (no bpy, so the rules and the native facade share it)."""


class ProbeError(Exception):
    """A problem the user can fix, said in one line."""
