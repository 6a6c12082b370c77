"""Wrapping panel text to its width (the add-on's text_fit.py, no Blender needed)."""

import text_fit


def measure(text):
    return 7 * len(text)  # a monospaced stand-in for the interface font


def test_lines_fit_and_keep_every_word():
    text = ("no count met the tolerance of 0.05%: using 32 lights, the lowest error found (0.98%); "
            "a_very_long_identifier_without_spaces_that_needs_breaking_inside")
    for width in (70, 140, 280, 1000):
        lines = text_fit.wrap(text, width, measure)
        assert all(text_fit.fits(line, width, measure) for line in lines), (width, lines)
        assert "".join(lines).replace(" ", "") == text.replace(" ", "")
    assert text_fit.wrap(text, 10000, measure) == [text]


def test_empty_and_tiny_widths():
    assert text_fit.wrap("", 100, measure) == [""]
    assert text_fit.wrap("abc", 1, measure) == ["a", "b", "c"]
