"""A Radiance .hdr (RGBE) reader in numpy, for the tests alone: it gives every platform's module the same float32
pixels of the bundled probe without OpenImageIO (the add-on's modules take pixels, not files). Reads the
"-Y H +X W" orientation with new-style run-length scanlines, as assets/noon_grass_1k.hdr has (Ward, Graphics Gems
II, "Real pixels"): a pixel is (R, G, B) * 2^(E - 136) for E > 0, black for E = 0."""

import numpy as np


def read_hdr(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"\n\n") + 2
    header, rest = data[:end], data[end:]
    if b"FORMAT=32-bit_rle_rgbe" not in header:
        raise ValueError("%s: not a 32-bit RGBE file" % path)
    size_line, rest = rest.split(b"\n", 1)
    y, height, x, width = size_line.split()
    if (y, x) != (b"-Y", b"+X"):
        raise ValueError("%s: orientation %s not read here" % (path, size_line))
    height, width = int(height), int(width)
    buf = np.frombuffer(rest, np.uint8)
    rgbe = np.empty((height, width, 4), np.uint8)
    pos = 0
    for row in range(height):
        if buf[pos] != 2 or buf[pos + 1] != 2 or (int(buf[pos + 2]) << 8 | int(buf[pos + 3])) != width:
            raise ValueError("%s: row %d is not a new-style run-length scanline" % (path, row))
        pos += 4
        for channel in range(4):
            column = 0
            while column < width:
                count = int(buf[pos])
                if count > 128:  # a run of one value
                    count -= 128
                    rgbe[row, column:column + count, channel] = buf[pos + 1]
                    pos += 2
                else:  # count literal values
                    rgbe[row, column:column + count, channel] = buf[pos + 1:pos + 1 + count]
                    pos += 1 + count
                column += count
    exponent = rgbe[..., 3].astype(np.int32)
    scale = np.where(exponent > 0, np.ldexp(1.0, exponent - 136), 0.0)
    return (rgbe[..., :3] * scale[..., None]).astype(np.float32)


def write_hdr(path, pixels):
    """Writes H x W x 3 linear pixels (top row first) as a flat (not run-length) RGBE file, which Radiance
    readers take for any width: each pixel's largest channel m = f * 2^e (f in [0.5, 1)) sets the shared exponent
    e + 128, its channels stored as c * 256 / 2^e."""
    a = np.maximum(np.asarray(pixels, np.float64)[..., :3], 0.0)
    height, width = a.shape[:2]
    peak = a.max(axis=-1)
    mantissa, exponent = np.frexp(peak)
    lit = peak > 1e-32
    rgbe = np.zeros((height, width, 4), np.uint8)
    scale = np.where(lit, 256.0 / np.ldexp(1.0, exponent), 0.0)
    rgbe[..., :3] = np.minimum(a * scale[..., None], 255).astype(np.uint8)
    rgbe[..., 3] = np.where(lit, exponent + 128, 0)
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (height, width))
        f.write(rgbe.tobytes())
