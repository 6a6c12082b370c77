"""Render settings the add-on offers to change (cycles_settings.py, eevee_settings.py), each change remembered on
the scene (once: a second click keeps the first values) so Restore world can put the user's values back."""


def set_remembering(scene, key, settings, wanted):
    """Sets `wanted` ({name: value}) on `settings` (scene.cycles, scene.eevee), remembering under scene[key] the
    value each name had before the first change."""
    before = dict(scene.get(key, {}))
    for name, value in wanted.items():
        before.setdefault(name, getattr(settings, name))
        setattr(settings, name, value)
    if before:
        scene[key] = before


def put_back(scene, key, settings, convert):
    """Puts back what set_remembering() replaced; convert(name, stored) turns a stored ID-property value back into
    the setting's type. Returns the names restored, sorted."""
    before = scene.get(key)
    if not before:
        return []
    values = before.to_dict() if hasattr(before, "to_dict") else dict(before)
    for name, value in values.items():
        setattr(settings, name, convert(name, value))
    del scene[key]
    return sorted(values)
