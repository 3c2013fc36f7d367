#!/usr/bin/env python3
"""Regenerates the two subsets of Noto Sans CJK SC Regular (SIL OFL 1.1) in assets/fonts/.

- PpoTutorSansSC-Regular.otf, the font Chinese plots are set in (compiled into the engine, so
  kept small): printable ASCII, every non-ASCII character of
  crates/ppo-engine/src/plot/labels.rs, the Chinese terms of lessons/glossary.toml and the
  characters of assets/fonts/extra-chars.txt.
- PpoTutorSansSCScreens-Regular.otf, the font the Chinese screenshots are drawn with
  (`ppo-tutor dev screenshots`, read from the checkout, never compiled in): every non-ASCII
  character of the Chinese course (lessons/**/*.zh.*, lessons/glossary.toml) and of the
  program's source (src/, crates/: every interface string), the CJK punctuation and
  full-width forms, and the 3,755 common characters of GB 2312's first level, so that a
  changed screen rarely needs a new subset.

Each subset is a Modified Version under the OFL, so it is renamed (no "Noto", no "Source").

    pip install fonttools==4.68.0
    apt-get download fonts-noto-cjk && dpkg-deb -x fonts-noto-cjk_*.deb noto
    python3 assets/fonts/make_subset.py noto/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc [plots|screens]

With `plots` or `screens` it writes only that subset (both by default).

Run it from the repository root after changing a Chinese plot label (tests/plot_zh.rs
fails while a label has a character the font lacks), or when `dev screenshots` names a
character the screen font lacks.
"""

import sys
import tomllib
from pathlib import Path

from fontTools import subset
from fontTools.ttLib import TTCollection, TTFont

ROOT = Path(__file__).resolve().parents[2]
PLOTS = (
    "PPO Tutor Sans SC",
    "PpoTutorSansSC-Regular",
    "A subset of Noto Sans CJK SC Regular 2.004 with the characters of "
    "ppo-tutor's plot labels (assets/fonts/make_subset.py).",
)
SCREENS = (
    "PPO Tutor Sans SC Screens",
    "PpoTutorSansSCScreens-Regular",
    "A subset of Noto Sans CJK SC Regular 2.004 with the characters of "
    "ppo-tutor's Chinese screens and GB 2312's first level (assets/fonts/make_subset.py).",
)


def plot_characters() -> str:
    chars = {chr(c) for c in range(0x20, 0x7F)}
    chars |= {c for c in (ROOT / "crates/ppo-engine/src/plot/labels.rs").read_text("utf-8") if ord(c) > 0x7F}
    glossary = tomllib.loads((ROOT / "lessons/glossary.toml").read_text("utf-8"))
    chars |= {c for term in glossary["term"] for c in term["zh"] if ord(c) > 0x7F}
    for line in (ROOT / "assets/fonts/extra-chars.txt").read_text("utf-8").splitlines():
        if not line.startswith("#"):
            chars |= {c for c in line if not c.isspace()}
    return "".join(sorted(chars))


def screen_characters() -> str:
    chars = {chr(c) for c in range(0x20, 0x7F)}
    files = sorted(ROOT.glob("lessons/**/*.zh.*")) + [ROOT / "lessons/glossary.toml"]
    files += sorted(ROOT.glob("src/**/*.rs")) + sorted(ROOT.glob("crates/**/*.rs"))
    for path in files:
        chars |= {c for c in path.read_text("utf-8") if ord(c) > 0x7F}
    chars |= {chr(c) for c in range(0x3000, 0x3040)}  # CJK symbols and punctuation
    chars |= {chr(c) for c in range(0xFF01, 0xFF5F)}  # full-width forms
    for row in range(0xB0, 0xD8):  # GB 2312, first level: rows 16-55
        for cell in range(0xA1, 0xFF):
            try:
                chars.add(bytes([row, cell]).decode("gb2312"))
            except UnicodeDecodeError:
                pass  # row 55 ends at 0xF9
    return "".join(sorted(chars))


def source_font(path: str) -> TTFont:
    """Noto Sans CJK SC from the collection (or an .otf of it given directly)."""
    if path.endswith(".ttc"):
        for font in TTCollection(path).fonts:
            if font["name"].getDebugName(6) == "NotoSansCJKsc-Regular":
                return font
        sys.exit(f"{path}: no NotoSansCJKsc-Regular in the collection")
    return TTFont(path)


def make(path: str, text: str, out: Path, naming: tuple[str, str, str]) -> None:
    family, postscript, description = naming
    font = source_font(path)
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
        (1, family),
        (2, "Regular"),
        (3, f"{postscript};{version}"),
        (4, f"{family} Regular"),
        (5, version),
        (6, postscript),
        (10, description),
    ]:
        name.setName(value, name_id, 3, 1, 0x409)
    cff = font["CFF "].cff
    cff.fontNames = [postscript]
    top = cff.topDictIndex[0]
    for key, value in [("FullName", f"{family} Regular"), ("FamilyName", family)]:
        if hasattr(top, key):
            setattr(top, key, value)
    for fd in getattr(top, "FDArray", []):
        # NotoSansCJKjp-Regular-Ideographs and so on: keep the part after the font's name.
        part = getattr(fd, "FontName", "").rsplit("-", 1)[-1]
        fd.FontName = f"{postscript}-{part}"
    font.recalcTimestamp = False  # the same input gives the same bytes
    font.save(out)
    print(f"{out.relative_to(ROOT)}: {len(text)} characters, {out.stat().st_size} bytes")


def main() -> None:
    which = sys.argv[2:] or ["plots", "screens"]
    if len(sys.argv) < 2 or not set(which) <= {"plots", "screens"}:
        sys.exit(__doc__)
    fonts = ROOT / "assets/fonts"
    if "plots" in which:
        make(sys.argv[1], plot_characters(), fonts / "PpoTutorSansSC-Regular.otf", PLOTS)
    if "screens" in which:
        out = fonts / "PpoTutorSansSCScreens-Regular.otf"
        make(sys.argv[1], screen_characters(), out, SCREENS)


if __name__ == "__main__":
    main()
