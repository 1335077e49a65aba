"""What figures.py writes its figures with, apart from the drawing: the PNG file writer and the
fonts read from memory (docs/compare.md, "Figures"; docs/performance.md)."""
import functools
import io
import os
import struct
import zlib

import matplotlib
from matplotlib import font_manager, ft2font
import numpy as np


# Fonts from memory: matplotlib 3.6 hands FreeType a Python file object of the font, through which
# every glyph is read with a seek and a read (73,000 lseek and 33,000 read system calls for the
# seed study's figures); a BytesIO of the same bytes gives the same glyphs without them. As
# matplotlib's own font_manager._get_font, cached per font and process (its cache is emptied in a
# forked child: FreeType objects are not shared across a fork). For PNG figures only: the PDF
# backend embeds the font it finds by the FT2Font's file name (figures.py's main() installs it).
@functools.lru_cache(64)
def _font_bytes(path):
    with open(path, "rb") as f:
        return f.read()


@functools.lru_cache(64)
def _get_font_from_memory(font_filepaths, hinting_factor, *, _kerning_factor, thread_id):
    first, *rest = font_filepaths
    fallback = [ft2font.FT2Font(io.BytesIO(_font_bytes(p)), hinting_factor, _kerning_factor=_kerning_factor)
                for p in rest]
    return ft2font.FT2Font(io.BytesIO(_font_bytes(first)), hinting_factor, _fallback_list=fallback,
                           _kerning_factor=_kerning_factor)


def fonts_from_memory():
    font_manager._get_font = _get_font_from_memory
    os.register_at_fork(after_in_child=_get_font_from_memory.cache_clear)


def write_png(fig, path, dpi):
    """The figure as savefig draws it, in one draw, as an RGB PNG (the figure is opaque: the same
    pixels without the alpha channel); the figure is made at `dpi`."""
    fig.canvas.draw()  # as savefig draws it
    rgb = np.asarray(fig.canvas.buffer_rgba())[:, :, :3]
    with open(path, "wb") as f:
        f.write(png_bytes(rgb, dpi, f"Matplotlib version{matplotlib.__version__}, https://matplotlib.org/"))


def png_bytes(rgb, dpi, software):
    """A PNG file of `rgb` (height x width x 3, uint8) at `dpi`, with a Software text. Written here
    rather than by PIL, which tries all five PNG row filters on every row with no way to choose one:
    no filter and zlib level 3 take 0.45x its CPU for files 10-15 % larger (docs/performance.md)."""
    height, width, _ = rgb.shape
    rows = np.empty((height, 1 + 3 * width), np.uint8)
    rows[:, 0] = 0  # each row's filter: none
    rows[:, 1:] = rgb.reshape(height, -1)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    per_metre = round(dpi / 0.0254)
    return b"".join((b"\x89PNG\r\n\x1a\n",
                     chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)),  # 8-bit RGB
                     chunk(b"pHYs", struct.pack(">IIB", per_metre, per_metre, 1)),
                     chunk(b"tEXt", b"Software\0" + software.encode("latin-1")),
                     chunk(b"IDAT", zlib.compress(rows, 3)),
                     chunk(b"IEND", b"")))
