#!/usr/bin/env python3
"""Regenerates assets/fonts/PpoTutorSansSC-Regular.otf, the font Chinese plots are set in.

It keeps, from Noto Sans CJK SC Regular (SIL OFL 1.1), only the characters the plots can
show: printable ASCII, every non-ASCII character of crates/ppo-engine/src/plot/labels.rs, the Chinese terms
of lessons/glossary.toml and the characters of assets/fonts/extra-chars.txt. The subset is
a Modified Version under the OFL, so it is renamed (no "Noto", no "Source").

    pip install fonttools==4.68.0
    apt-get download fonts-noto-cjk && dpkg-deb -x fonts-noto-cjk_*.deb noto
    python3 assets/fonts/make_subset.py noto/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc

Run it from the repository root after changing a Chinese plot label; tests/plot_zh.rs
fails while a label has a character the font lacks.
"""

import sys
import tomllib
from pathlib import Path

from fontTools import subset
from fontTools.ttLib import TTCollection, TTFont

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "assets/fonts/PpoTutorSansSC-Regular.otf"
FAMILY = "PPO Tutor Sans SC"
POSTSCRIPT = "PpoTutorSansSC-Regular"


def characters() -> str:
    chars = {chr(c) for c in range(0x20, 0x7F)}
    chars |= {c for c in (ROOT / "crates/ppo-engine/src/plot/labels.rs").read_text("utf-8") if ord(c) > 0x7F}
    glossary = tomllib.loads((ROOT / "lessons/glossary.toml").read_text("utf-8"))
    chars |= {c for term in glossary["term"] for c in term["zh"] if ord(c) > 0x7F}
    for line in (ROOT / "assets/fonts/extra-chars.txt").read_text("utf-8").splitlines():
        if not line.startswith("#"):
            chars |= {c for c in line if not c.isspace()}
    return "".join(sorted(chars))


def source_font(path: str) -> TTFont:
    """Noto Sans CJK SC from the collection (or an .otf of it given directly)."""
    if path.endswith(".ttc"):
        for font in TTCollection(path).fonts:
            if font["name"].getDebugName(6) == "NotoSansCJKsc-Regular":
                return font
        sys.exit(f"{path}: no NotoSansCJKsc-Regular in the collection")
    return TTFont(path)


def main() -> None:
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    font = source_font(sys.argv[1])
    text = characters()
    options = subset.Options()
    options.layout_features = ["kern", "palt"]  # plotters uses kerning only
    options.name_IDs = [0, 7, 8, 9, 11, 12, 13, 14]  # copyright, trademark, credits, licence
    options.hinting = False
    options.drop_tables += ["BASE", "VORG", "vhea", "vmtx"]  # vertical text: unused
    options.desubroutinize = False
    subsetter = subset.Subsetter(options)
    subsetter.populate(text=text)
    subsetter.subset(font)
    name = font["name"]
    version = "Version 2.004-ppo-tutor-subset"
    for name_id, value in [
        (1, FAMILY),
        (2, "Regular"),
        (3, f"{POSTSCRIPT};{version}"),
        (4, f"{FAMILY} Regular"),
        (5, version),
        (6, POSTSCRIPT),
        (
            10,
            "A subset of Noto Sans CJK SC Regular 2.004 with the characters of "
            "ppo-tutor's plot labels (assets/fonts/make_subset.py).",
        ),
    ]:
        name.setName(value, name_id, 3, 1, 0x409)
    cff = font["CFF "].cff
    cff.fontNames = [POSTSCRIPT]
    top = cff.topDictIndex[0]
    for key, value in [("FullName", f"{FAMILY} Regular"), ("FamilyName", FAMILY)]:
        if hasattr(top, key):
            setattr(top, key, value)
    for fd in getattr(top, "FDArray", []):
        # NotoSansCJKjp-Regular-Ideographs and so on: keep the part after the font's name.
        part = getattr(fd, "FontName", "").rsplit("-", 1)[-1]
        fd.FontName = f"{POSTSCRIPT}-{part}"
    font.recalcTimestamp = False  # the same input gives the same bytes
    font.save(OUT)
    print(f"{OUT.relative_to(ROOT)}: {len(text)} characters, {OUT.stat().st_size} bytes")


if __name__ == "__main__":
    main()
