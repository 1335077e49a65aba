#!/usr/bin/python3
"""figures.py's own PNG writer (png_bytes in compare/figure_files.py, docs/compare.md "Figures"): a known file byte for byte,
and any image read back by PIL (which checks every chunk's CRC) as the same pixels, dpi and text.

    /usr/bin/python3 tests/compare/test_png_bytes.py SOURCE_DIR
"""
import io
import os
import struct
import sys
import zlib

sys.path.insert(0, os.path.join(sys.argv[1], "compare"))
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402
from figure_files import png_bytes  # noqa: E402

checks = failures = 0


def check(name, ok, detail=""):
    global checks, failures
    checks += 1
    if not ok:
        failures += 1
        print(f"FAIL {name}: {detail}")


# One red pixel. Its IHDR chunk is the well-known one of every 1 x 1 8-bit RGB PNG, CRC 0x907753DE
# included; its image data is the row's filter byte (0) and the pixel.
red = png_bytes(np.array([[[255, 0, 0]]], np.uint8), 150, "x")
check("signature", red[:8] == b"\x89PNG\r\n\x1a\n", red[:8])
check("ihdr", red[8:33] == bytes.fromhex("0000000d4948445200000001000000010802000000907753de"), red[8:33].hex())
idat = red.index(b"IDAT")
length = struct.unpack(">I", red[idat - 4:idat])[0]
check("idat", zlib.decompress(red[idat + 4:idat + 4 + length]) == b"\x00\xff\x00\x00", red[idat + 4:idat + 4 + length])
check("iend", red[-12:] == bytes.fromhex("0000000049454e44ae426082"), red[-12:].hex())  # IEND's fixed CRC

# An image with every value in each channel, odd sizes, read back by PIL.
rng = np.random.default_rng(7)
rgb = rng.integers(0, 256, size=(37, 53, 3), dtype=np.uint8)
rgb[0, :, 0] = np.arange(53) * 4  # a ramp: rows are not all alike
back = Image.open(io.BytesIO(png_bytes(rgb, 150, "Matplotlib version3.6.3, https://matplotlib.org/")))
back.load()
check("mode and size", (back.mode, back.size) == ("RGB", (53, 37)), (back.mode, back.size))
check("pixels", np.array_equal(np.asarray(back), rgb), "the pixels differ")
check("dpi", np.allclose(back.info["dpi"], (150, 150), atol=0.02), back.info.get("dpi"))
check("text", back.info.get("Software") == "Matplotlib version3.6.3, https://matplotlib.org/", back.info.get("Software"))
# A view with strides (figures.py passes the RGBA canvas without its alpha channel).
rgba = np.dstack([rgb, np.full(rgb.shape[:2], 255, np.uint8)])
check("strided view", png_bytes(rgba[:, :, :3], 150, "t") == png_bytes(rgb, 150, "t"), "a view gives other bytes")

print(f"{checks - failures} passed, {failures} failed")
sys.exit(1 if failures else 0)
