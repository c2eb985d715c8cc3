#!/usr/bin/env python3
"""Convert the Stanford bunny from the npm package `bunny` into a Wavefront OBJ.

Usage:
    python3 assets/tools/bunny_to_obj.py PATH/TO/package/index.js assets/meshes/bunny.obj

The npm package `bunny` (public domain) ships the mesh as JavaScript:

    exports.positions=[[x,y,z],...];
    exports.cells=[[i,j,k],...];

The parser below does not evaluate JavaScript. It looks for the names
`positions` and `cells` followed by `=` or `:` (so `exports.positions = ...`,
`module.exports = {positions: ...}` and a plain JSON file
`{"positions": ..., "cells": ...}` all work) and reads the nested array
literal that follows, accepting JS number syntax, comments and trailing
commas.

The output mesh:
  * sits on y = 0 (minimum y is exactly 0),
  * is centred in x and z (bounding-box centre at x = 0, z = 0),
  * is scaled uniformly so its height (y extent) is exactly 1.0,
  * has smooth per-vertex normals (area-weighted face normals, normalised),
  * has faces wound counter-clockwise seen from outside (checked, and
    flipped if the source winding is inward),
  * writes floats with 6 significant digits.

Python 3 standard library only.
"""

import argparse
import math
import os
import re
import sys


# --------------------------------------------------------------------------
# Parsing
# --------------------------------------------------------------------------

class ParseError(Exception):
    pass


_NUMBER_RE = re.compile(
    r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"
)


def _skip_ws_and_comments(text, i):
    n = len(text)
    while i < n:
        c = text[i]
        if c in " \t\r\n\f\v":
            i += 1
        elif text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j + 1
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            if j < 0:
                raise ParseError("unterminated /* comment")
            i = j + 2
        else:
            break
    return i


def _parse_array(text, i):
    """Parse a (possibly nested) array literal of numbers starting at text[i] == '['.

    Returns (value, index_after_closing_bracket)."""
    if text[i] != "[":
        raise ParseError("expected '[' at offset %d" % i)
    i += 1
    out = []
    while True:
        i = _skip_ws_and_comments(text, i)
        if i >= len(text):
            raise ParseError("unterminated array")
        c = text[i]
        if c == "]":
            return out, i + 1
        if c == ",":
            # Tolerate trailing/duplicate commas.
            i += 1
            continue
        if c == "[":
            value, i = _parse_array(text, i)
            out.append(value)
            continue
        m = _NUMBER_RE.match(text, i)
        if not m:
            snippet = text[i:i + 30].replace("\n", " ")
            raise ParseError("unexpected text at offset %d: %r" % (i, snippet))
        tok = m.group(0)
        if re.fullmatch(r"[+-]?\d+", tok):
            out.append(int(tok))
        else:
            out.append(float(tok))
        i = m.end()


def extract_array(text, name):
    """Find `name = [...]` / `name: [...]` / `"name": [...]` and parse the array."""
    pattern = re.compile(
        r"""(?<![A-Za-z0-9_$])["']?%s["']?\s*[=:]\s*""" % re.escape(name)
    )
    for m in pattern.finditer(text):
        i = _skip_ws_and_comments(text, m.end())
        if i < len(text) and text[i] == "[":
            value, _ = _parse_array(text, i)
            return value
    raise ParseError("could not find an array named %r" % name)


def load_bunny(path):
    with open(path, "r", encoding="utf-8") as f:
        text = f.read()
    positions = extract_array(text, "positions")
    cells = extract_array(text, "cells")

    verts = []
    for k, p in enumerate(positions):
        if not isinstance(p, list) or len(p) != 3:
            raise ParseError("position %d is not [x, y, z]: %r" % (k, p))
        verts.append(tuple(float(c) for c in p))
    faces = []
    for k, c in enumerate(cells):
        if not isinstance(c, list) or len(c) != 3:
            raise ParseError("cell %d is not a triangle [i, j, k]: %r" % (k, c))
        tri = tuple(int(v) for v in c)
        for v in tri:
            if v < 0 or v >= len(verts):
                raise ParseError("cell %d references vertex %d (have %d)" % (k, v, len(verts)))
        faces.append(tri)
    return verts, faces


# --------------------------------------------------------------------------
# Geometry
# --------------------------------------------------------------------------

def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def normalize(a):
    length = math.sqrt(dot(a, a))
    if length == 0.0:
        return None
    return (a[0] / length, a[1] / length, a[2] / length)


def bbox(verts):
    lo = [min(v[i] for v in verts) for i in range(3)]
    hi = [max(v[i] for v in verts) for i in range(3)]
    return lo, hi


def normalise_placement(verts):
    """Centre in x/z, put min y on 0, scale so height is exactly 1."""
    lo, hi = bbox(verts)
    height = hi[1] - lo[1]
    if height <= 0.0:
        raise ValueError("mesh has zero height")
    s = 1.0 / height
    cx = 0.5 * (lo[0] + hi[0])
    cz = 0.5 * (lo[2] + hi[2])
    out = []
    for x, y, z in verts:
        out.append(((x - cx) * s, (y - lo[1]) * s, (z - cz) * s))
    return out


def winding_report(verts, faces):
    """Count faces whose normal points away from / towards the centroid,
    and compute the signed volume (positive for outward CCW winding)."""
    n = float(len(verts))
    centroid = (sum(v[0] for v in verts) / n,
                sum(v[1] for v in verts) / n,
                sum(v[2] for v in verts) / n)
    outward = inward = degenerate = 0
    volume6 = 0.0
    for a, b, c in faces:
        pa, pb, pc = verts[a], verts[b], verts[c]
        fn = cross(sub(pb, pa), sub(pc, pa))
        fc = ((pa[0] + pb[0] + pc[0]) / 3.0,
              (pa[1] + pb[1] + pc[1]) / 3.0,
              (pa[2] + pb[2] + pc[2]) / 3.0)
        d = dot(fn, sub(fc, centroid))
        if dot(fn, fn) == 0.0:
            degenerate += 1
        elif d > 0.0:
            outward += 1
        else:
            inward += 1
        volume6 += dot(pa, cross(pb, pc))
    return outward, inward, degenerate, volume6 / 6.0


def vertex_normals(verts, faces):
    acc = [[0.0, 0.0, 0.0] for _ in verts]
    for a, b, c in faces:
        pa, pb, pc = verts[a], verts[b], verts[c]
        # |cross| is twice the triangle area, so summing the raw cross
        # product gives area-weighted face normals.
        fn = cross(sub(pb, pa), sub(pc, pa))
        for v in (a, b, c):
            acc[v][0] += fn[0]
            acc[v][1] += fn[1]
            acc[v][2] += fn[2]
    normals = []
    fallback = 0
    for a in acc:
        nv = normalize(a)
        if nv is None:
            fallback += 1
            nv = (0.0, 1.0, 0.0)
        normals.append(nv)
    return normals, fallback


# --------------------------------------------------------------------------
# Output
# --------------------------------------------------------------------------

def fmt(x):
    """6 significant digits, no exponent, no trailing zeros, no '-0'.

    Magnitudes below 5e-7 are written as 0 (the mesh is about 1 unit big)."""
    if x == 0.0 or abs(x) < 5e-7:
        return "0"
    digits = 6 - 1 - int(math.floor(math.log10(abs(x))))
    r = round(x, digits)
    if r == 0.0:
        return "0"
    s = "%.*f" % (max(digits, 0), r)
    if "." in s:
        s = s.rstrip("0").rstrip(".")
    if s in ("-0", ""):
        s = "0"
    return s


def write_obj(path, verts, normals, faces, provenance):
    lines = []
    for p in provenance:
        lines.append("# " + p if p else "#")
    lines.append("o bunny")
    for v in verts:
        lines.append("v %s %s %s" % (fmt(v[0]), fmt(v[1]), fmt(v[2])))
    for nv in normals:
        lines.append("vn %s %s %s" % (fmt(nv[0]), fmt(nv[1]), fmt(nv[2])))
    for a, b, c in faces:
        a, b, c = a + 1, b + 1, c + 1
        lines.append("f %d//%d %d//%d %d//%d" % (a, a, b, b, c, c))
    out_dir = os.path.dirname(os.path.abspath(path))
    os.makedirs(out_dir, exist_ok=True)
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("input", help="data file of the npm package `bunny` (package/index.js)")
    ap.add_argument("output", help="output OBJ path, e.g. assets/meshes/bunny.obj")
    ap.add_argument("--package-version", default=None,
                    help="version for the header (default: read from package.json next to the input)")
    args = ap.parse_args(argv)

    version = args.package_version
    licence = None
    pkg_json = os.path.join(os.path.dirname(os.path.abspath(args.input)), "package.json")
    if os.path.isfile(pkg_json):
        import json
        with open(pkg_json, "r", encoding="utf-8") as f:
            meta = json.load(f)
        if version is None:
            version = meta.get("version")
        licence = meta.get("license")

    verts, faces = load_bunny(args.input)
    print("read %d vertices, %d triangles from %s" % (len(verts), len(faces), args.input))

    used = set()
    for f in faces:
        used.update(f)
    if len(used) != len(verts):
        print("note: %d vertices are not referenced by any face" % (len(verts) - len(used)))

    verts = normalise_placement(verts)

    outward, inward, degenerate, volume = winding_report(verts, faces)
    total = len(faces)
    print("winding (source): %d outward, %d inward, %d degenerate of %d faces; signed volume %.6f"
          % (outward, inward, degenerate, total, volume))
    flipped = False
    if inward > outward:
        faces = [(a, c, b) for a, b, c in faces]
        flipped = True
        outward, inward, degenerate, volume = winding_report(verts, faces)
        print("flipped all faces -> %d outward, %d inward; signed volume %.6f"
              % (outward, inward, volume))
    else:
        print("winding kept (counter-clockwise seen from outside)")
    if volume <= 0.0:
        print("warning: signed volume is not positive after winding check", file=sys.stderr)

    normals, fallback = vertex_normals(verts, faces)
    if fallback:
        print("note: %d vertices got a fallback normal (0, 1, 0)" % fallback)

    lo, hi = bbox(verts)
    print("bounding box: min (%s, %s, %s) max (%s, %s, %s)"
          % tuple(fmt(c) for c in lo + hi))

    provenance = [
        "Stanford Bunny",
        "Scanned by the Stanford Computer Graphics Laboratory",
        "(Stanford 3D Scanning Repository).",
        "Source: npm package `bunny`%s, licence field: %s."
        % (" " + version if version else "", licence or "Public Domain"),
        "Converted by assets/tools/bunny_to_obj.py:",
        "  placed on y=0, centred in x/z, scaled to height 1.0,",
        "  smooth area-weighted vertex normals, CCW winding seen from outside%s."
        % (" (source faces flipped)" if flipped else ""),
        "%d vertices, %d triangles." % (len(verts), len(faces)),
        "",
    ]
    write_obj(args.output, verts, normals, faces, provenance)
    print("wrote %s" % args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
