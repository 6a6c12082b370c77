"""Wrapping text to a width in pixels (no bpy: the measure is passed in), so panels never cut a line off."""


def fits(text, width, measure):
    return measure(text) <= width


def wrap(text, width, measure):
    """`text` in lines no wider than `width` by `measure` (text -> pixels), broken between words; a word wider than
    the width alone is broken inside. Always at least one line."""
    lines, line = [], ""
    for word in text.split():
        candidate = word if not line else line + " " + word
        if fits(candidate, width, measure):
            line = candidate
            continue
        if line:
            lines.append(line)
        line = ""
        while not fits(word, width, measure) and len(word) > 1:
            cut = len(word) - 1
            while cut > 1 and not fits(word[:cut], width, measure):
                cut -= 1
            lines.append(word[:cut])
            word = word[cut:]
        line = word
    if line or not lines:
        lines.append(line)
    return lines
