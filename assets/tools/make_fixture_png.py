#!/usr/bin/env python3
"""Write the tiny PNG used by the OBJ loader fixtures.

Usage (from the repository root):
    python3 assets/tools/make_fixture_png.py

Writes tests/data/obj/tex_2x2.png: a 2x2 RGBA image, top row red, green;
bottom row blue, white; all fully opaque. A tEXt "Comment" chunk says what
it tests. Python 3 standard library only (reuses the encoder in make_floor.py).
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_floor import write_png  # noqa: E402

RED = (255, 0, 0, 255)
GREEN = (0, 255, 0, 255)
BLUE = (0, 0, 255, 255)
WHITE = (255, 255, 255, 255)


def main():
    root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    path = os.path.join(root, "tests", "data", "obj", "tex_2x2.png")
    rows = [bytearray(RED + GREEN), bytearray(BLUE + WHITE)]
    write_png(path, 2, 2, rows, channels=4,
              text={"Comment": "Fixture: 2x2 RGBA map_Kd for multi_material.mtl; "
                               "top row red, green; bottom row blue, white"})
    print("wrote %s (%d bytes)" % (path, os.path.getsize(path)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
