#!/usr/bin/env python3
"""Cut Noto Sans CJK SC down to the characters shadowlab's own text uses.

The page has no system fonts, and a machine without fonts-noto-cjk has none either: the app
embeds this subset for Chinese in its panels, diagrams and slides. It holds every character
outside ASCII that appears in the shipped text (src/ outside its tests, lessons/*.toml,
assets/**/*.toml) and that the full face has, so the subset draws that text exactly as the
full face does. Run it again whenever Chinese text changes; `cargo test` fails until then.

    pip install fonttools
    python3 assets/tools/subset_cjk_font.py [--font /usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc]
"""

import argparse
import pathlib
import sys

from fontTools import subset
from fontTools.ttLib import TTCollection, TTFont

ROOT = pathlib.Path(__file__).resolve().parents[2]
OUT = ROOT / "assets/fonts/NotoSansCJKsc-Regular-subset.otf"
FAMILY = "Noto Sans CJK SC"


def code_of(path: pathlib.Path) -> str:
    """A Rust file's code without its unit tests (as tests/structure.rs reads it)."""
    if path.name == "tests.rs" or path.name.endswith("_tests.rs"):
        return ""
    text = path.read_text(encoding="utf-8")
    return text.split("#[cfg(test)]\nmod tests", 1)[0]


def shipped_text() -> str:
    parts = [code_of(p) for p in sorted(ROOT.glob("src/**/*.rs"))]
    for pattern in ("lessons/*.toml", "assets/**/*.toml"):
        parts += [p.read_text(encoding="utf-8") for p in sorted(ROOT.glob(pattern))]
    return "".join(parts)


def open_face(path: str) -> TTFont:
    """The Simplified Chinese face: from a collection (.ttc) by its family name, else the file.
    Its timestamp is kept, so the same text and font give the same bytes."""
    if path.endswith(".ttc"):
        for font in TTCollection(path, recalcTimestamp=False).fonts:
            if font["name"].getDebugName(1) == FAMILY:
                return font
        sys.exit(f"{path}: no face named {FAMILY!r}")
    font = TTFont(path, recalcTimestamp=False)
    if font["name"].getDebugName(1) != FAMILY:
        sys.exit(f"{path}: its family is {font['name'].getDebugName(1)!r}, not {FAMILY!r}")
    return font


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--font", default="/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc",
                        help="Noto Sans CJK (a .ttc holding the SC face, or NotoSansCJKsc-Regular.otf)")
    parser.add_argument("--out", default=str(OUT))
    args = parser.parse_args()

    font = open_face(args.font)
    has = font.getBestCmap()
    wanted = sorted({c for c in shipped_text() if ord(c) >= 0x80})
    kept = [c for c in wanted if ord(c) in has]

    options = subset.Options()
    # Copyright, names, version, trademark, licence and its address: the OFL asks for the notice.
    options.name_IDs = [0, 1, 2, 3, 4, 5, 6, 7, 13, 14]
    options.name_languages = [0x409]
    options.notdef_outline = True
    # Hints kept: egui hints glyphs (sharper small text); the diagrams ask for none.
    subsetter = subset.Subsetter(options)
    subsetter.populate(unicodes=[ord(c) for c in kept])
    subsetter.subset(font)
    font.save(args.out)

    size = pathlib.Path(args.out).stat().st_size
    cjk = sum(1 for c in kept if ord(c) >= 0x2E80)
    print(f"{args.out}: {len(kept)} characters ({cjk} CJK and full-width), {size} bytes")
    skipped = "".join(c for c in wanted if ord(c) not in has)
    if skipped:
        print(f"not in {FAMILY} (drawn by the other fonts): {skipped}")


if __name__ == "__main__":
    main()
