#!/usr/bin/env python3
"""A contact sheet of rendered figures: one PNG mosaic, each figure a captioned tile, so a
reader scans every figure of the main job at once; and, with --thumbnails, small copies
for docs/figures.md.

    contact_sheet.py FOLDER [FOLDER ...] --out results/contact_sheet.png
                     [--thumbnails docs/figures/contact --width 520]

Takes every *.png in the folders (in folder order, then by name), except an earlier
contact sheet. Debian's python3-pil (a dependency of python3-matplotlib) and matplotlib's fonts."""
import argparse
import glob
import math
import os
import sys

import matplotlib.font_manager
from PIL import Image, ImageDraw, ImageFont

TILE = 560  # px, width and height of a tile of the mosaic
CAPTION = 22  # px under each tile for its file name


def figures(folders, out):
    found = []
    for folder in folders:
        names = sorted(glob.glob(os.path.join(folder, "*.png")))
        found += [n for n in names if os.path.abspath(n) != os.path.abspath(out) and "contact_sheet" not in n]
    return found


def fitted(image, box):
    """`image` scaled down to fit a box x box square, keeping its proportions."""
    scale = min(box / image.width, box / image.height, 1.0)
    return image.resize((max(1, round(image.width * scale)), max(1, round(image.height * scale))), Image.LANCZOS)


def mosaic(paths, out):
    columns = math.ceil(math.sqrt(len(paths)))
    rows = math.ceil(len(paths) / columns)
    sheet = Image.new("RGB", (columns * TILE, rows * (TILE + CAPTION)), "white")
    draw = ImageDraw.Draw(sheet)
    # matplotlib's own DejaVu Sans: PIL's built-in font is 11 px high and hard to read.
    font = ImageFont.truetype(matplotlib.font_manager.findfont("DejaVu Sans"), CAPTION - 4)
    for i, path in enumerate(paths):
        x, y = (i % columns) * TILE, (i // columns) * (TILE + CAPTION)
        with Image.open(path) as image:
            tile = fitted(image.convert("RGB"), TILE - 8)
        sheet.paste(tile, (x + (TILE - tile.width) // 2, y + (TILE - tile.height) // 2))
        draw.text((x + 6, y + TILE + 1), os.path.basename(path), fill="black", font=font)
    sheet.save(out, optimize=True)


def thumbnails(paths, folder, width):
    os.makedirs(folder, exist_ok=True)
    for path in paths:
        with Image.open(path) as image:
            image = image.convert("RGB")
            # A wide figure (three panels in a row) would be a strip too thin to read at `width`.
            wide = round(width * 1.7) if image.width > 2 * image.height else width
            small = image.resize((wide, round(image.height * wide / image.width)), Image.LANCZOS)
        # 256 colours: a figure has few, and the thumbnails stay a few tens of kB each.
        small.quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(
            os.path.join(folder, os.path.basename(path)), optimize=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folders", nargs="+", help="folders of rendered PNG figures")
    parser.add_argument("--out", required=True, help="the mosaic PNG to write")
    parser.add_argument("--thumbnails", help="also write each figure scaled to --width into this folder")
    parser.add_argument("--width", type=int, default=520,
                        help="thumbnail width [px], 1.7 x that for figures over twice as wide as high (default %(default)s)")
    args = parser.parse_args()
    paths = figures(args.folders, args.out)
    if not paths:
        print(f"no PNG figures in {', '.join(args.folders)}", file=sys.stderr)
        sys.exit(2)
    mosaic(paths, args.out)
    print(f"contact sheet: {args.out} ({len(paths)} figures)")
    if args.thumbnails:
        thumbnails(paths, args.thumbnails, args.width)
        print(f"thumbnails: {args.thumbnails}/ ({len(paths)})")


if __name__ == "__main__":
    main()
