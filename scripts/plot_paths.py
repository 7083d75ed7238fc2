#!/usr/bin/env python3
"""Plots one body's path from `anyphys run`-format CSVs (the demos' --out) as an SVG, one line
per file: python3 scripts/plot_paths.py --body chassis --x px --y pz --out path.svg native=a.csv ode=b.csv
Pure Python (no plotting package), so the pictures in docs/ can be remade anywhere."""
import argparse
import csv
import sys

COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd"]


def read_path(path, body, xcol, ycol, flip_y):
    points = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            if row["body"] == body:
                y = float(row[ycol])
                points.append((float(row[xcol]), -y if flip_y else y))
    if not points:
        sys.exit(f"plot_paths.py: {path}: no rows for body {body!r}")
    return points


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--body", required=True)
    p.add_argument("--x", default="px")
    p.add_argument("--y", default="py")
    p.add_argument("--flip-y", action="store_true", help="plot -y (e.g. -pz, so a left turn goes up)")
    p.add_argument("--title", default="")
    p.add_argument("--xlabel", default="")
    p.add_argument("--ylabel", default="")
    p.add_argument("--out", required=True)
    p.add_argument("runs", nargs="+", help="label=file.csv")
    a = p.parse_args()
    runs = []
    for item in a.runs:
        label, _, path = item.partition("=")
        runs.append((label, read_path(path, a.body, a.x, a.y, a.flip_y)))
    xs = [x for _, pts in runs for x, _ in pts]
    ys = [y for _, pts in runs for _, y in pts]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    span = max(x1 - x0, y1 - y0, 1e-9)  # equal scales: a circle stays round
    x0, y0 = (x0 + x1 - span) / 2, (y0 + y1 - span) / 2
    size, margin = 420, 50
    sx = lambda x: margin + (x - x0) / span * size
    sy = lambda y: margin + size - (y - y0) / span * size
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{size + 2 * margin + 120}" height="{size + 2 * margin}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect width="100%" height="100%" fill="white"/>',
           f'<rect x="{margin}" y="{margin}" width="{size}" height="{size}" fill="none" stroke="#999"/>',
           f'<text x="{margin}" y="{margin - 15}" font-size="14">{a.title}</text>',
           f'<text x="{margin + size / 2}" y="{margin + size + 35}" text-anchor="middle">{a.xlabel}</text>',
           f'<text x="15" y="{margin + size / 2}" transform="rotate(-90 15 {margin + size / 2})" text-anchor="middle">{a.ylabel}</text>']
    for i in range(5):  # ticks
        v = x0 + span * i / 4
        out.append(f'<text x="{sx(v):.1f}" y="{margin + size + 15}" text-anchor="middle">{v:.1f}</text>')
        w = y0 + span * i / 4
        out.append(f'<text x="{margin - 5}" y="{sy(w) + 4:.1f}" text-anchor="end">{w:.1f}</text>')
    for k, (label, pts) in enumerate(runs):
        colour = COLOURS[k % len(COLOURS)]
        line = " ".join(f"{sx(x):.1f},{sy(y):.1f}" for x, y in pts)
        out.append(f'<polyline points="{line}" fill="none" stroke="{colour}" stroke-width="1.5"/>')
        out.append(f'<text x="{margin + size + 15}" y="{margin + 20 + 18 * k}" fill="{colour}">{label}</text>')
    out.append("</svg>")
    with open(a.out, "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
