#!/usr/bin/env python3
"""Checks a testbed screenshot against its --dump-projections sidecar (no PIL: PNG read with zlib).

check_render.py PICTURE.png SIDECAR.json [--same]
  - the picture is not blank;
  - each view's top-left corner has the background colour;
  - every dynamic body on screen has, at its projected origin, its own colour under the
    testbed's shading (colour * s, one s for all three channels);
  - the views differ only inside the projected bounds of bodies whose states differ between the
    views (--same: the views must be identical, pixel for pixel).
"""
import json
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: not a PNG"
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour == 2 and interlace == 0, "expected 8-bit RGB, not interlaced"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride, bpp = width * 3, 3
    rows, prev = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if kind == 1:
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 255
        elif kind == 2:
            for i in range(stride):
                line[i] = (line[i] + prev[i]) & 255
        elif kind == 3:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 255
        elif kind == 4:
            for i in range(stride):
                a = line[i - bpp] if i >= bpp else 0
                b = prev[i]
                c = prev[i - bpp] if i >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        rows.append(bytes(line))
        prev = line
    return width, height, rows


def pixel(rows, x, y):
    r = rows[y]
    return r[3 * x], r[3 * x + 1], r[3 * x + 2]


def main():
    png, sidecar = sys.argv[1], sys.argv[2]
    same = "--same" in sys.argv[3:]
    width, height, rows = read_png(png)
    meta = json.load(open(sidecar))
    assert (width, height) == (meta["width"], meta["height"]), (width, height)
    background = tuple(meta["background"])
    ambient, diffuse = meta["shading"]["ambient"], meta["shading"]["diffuse"]

    # Not blank: many colours, and a good share of the pixels are not background.
    colours = set()
    not_background = 0
    for y in range(0, height, 2):
        for x in range(0, width, 2):
            p = pixel(rows, x, y)
            colours.add(p)
            not_background += p != background
    share = not_background / ((height // 2) * (width // 2))
    assert len(colours) >= 4 and share > 0.05, f"blank picture: {len(colours)} colours, {share:.1%} not background"
    print(f"ok not blank: {len(colours)} colours, {share:.0%} of the pixels not background")

    views = meta["views"]
    for v in views:
        assert not v["error"], f"{v['backend']}: {v['error']}"
        x, y, w, h = v["rect"]
        assert pixel(rows, x + 3, y + 3) == background, f"{v['backend']}: corner {pixel(rows, x + 3, y + 3)} is not background"
        checked = 0
        for b in v["bodies"]:
            if b["type"] != "dynamic" or not b.get("onScreen") or "color" not in b:
                continue
            px, py = int(b["screen"][0]), int(b["screen"][1])
            got = pixel(rows, px, py)
            want = [255 * c for c in b["color"]]
            scales = [g / c for g, c in zip(got, want)]
            assert ambient - 0.02 <= min(scales) and max(scales) <= ambient + diffuse + 0.02, \
                f"{v['backend']} {b['name']}: pixel {got} at {(px, py)} is not its colour {b['color']} shaded"
            assert max(scales) - min(scales) <= 0.03, \
                f"{v['backend']} {b['name']}: pixel {got} at {(px, py)} has other colour ratios than {b['color']}"
            checked += 1
        assert checked > 0, f"{v['backend']}: no dynamic body on screen"
        print(f"ok {v['backend']}: background corner, {checked} bodies in their colour where they project")

    # The views differ only where the bodies' states differ.
    for i in range(1, len(views)):
        a, b = views[0], views[i]
        assert a["rect"][2:] == b["rect"][2:], "views of different sizes"
        moved = []
        for ba, bb in zip(a["bodies"], b["bodies"]):
            differ = any(abs(p - q) > 1e-12 for p, q in zip(ba["position"] + ba["orientation"], bb["position"] + bb["orientation"]))
            if differ:
                # Where the body is in either view (view-local pixels), 2 px of edge allowed.
                for body, view in ((ba, a), (bb, b)):
                    if "boundsScreen" in body:
                        x0, y0, x1, y1 = body["boundsScreen"]
                        rx, ry = view["rect"][:2]
                        moved.append((x0 - rx - 2, y0 - ry - 2, x1 - rx + 2, y1 - ry + 2))
        ax, ay, w, h = a["rect"]
        bx, by = b["rect"][:2]
        different = outside = 0
        for y in range(h):
            ra, rb = rows[ay + y], rows[by + y]
            sa, sb = ra[3 * ax:3 * (ax + w)], rb[3 * bx:3 * (bx + w)]
            if sa == sb:
                continue
            for x in range(w):
                if sa[3 * x:3 * x + 3] != sb[3 * x:3 * x + 3]:
                    different += 1
                    if not any(x0 <= x <= x1 and y0 <= y <= y1 for x0, y0, x1, y1 in moved):
                        outside += 1
        if same:
            assert different == 0, f"{a['backend']} and {b['backend']} views differ in {different} pixels"
            print(f"ok {a['backend']} vs {b['backend']}: identical views")
        else:
            assert outside == 0, f"{outside} of {different} differing pixels lie outside every body whose state differs"
            print(f"ok {a['backend']} vs {b['backend']}: {different} pixels differ, all where {len(moved) // 2} bodies' states differ")


if __name__ == "__main__":
    main()
