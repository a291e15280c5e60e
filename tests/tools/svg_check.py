#!/usr/bin/env python3
"""Parses a clpc plot as XML and prints what it holds, one fact per line, for the plot test.

    python3 svg_check.py plot.svg
"""
import re
import sys
import xml.etree.ElementTree as ET

NS = "{http://www.w3.org/2000/svg}"
root = ET.parse(sys.argv[1]).getroot()
assert root.tag == NS + "svg", root.tag
width, height = float(root.get("width")), float(root.get("height"))
print("size", int(width), int(height))
views = [g for g in root.iter(NS + "g") if g.get("class") == "view"]
print("views", ",".join(v.get("id") for v in views))
for v in views:
    paths = {p.get("class"): p.get("d") for p in v.iter(NS + "path")}
    feed, rapid = paths.get("feed", ""), paths.get("rapid", "")
    # Every path is well formed: commands with their numbers, all on the canvas.
    for d in (feed, rapid):
        for cmd, args in re.findall(r"([MLA])([^MLA]*)", d):
            n = [float(x) for x in args.split()]
            assert len(n) == {"M": 2, "L": 2, "A": 7}[cmd], (cmd, args)
            x, y = n[-2], n[-1]
            assert -1 <= x <= width + 1 and -1 <= y <= height + 1, (cmd, args)
    arcs = len(re.findall(r"A", feed))
    markers = [t.text for t in v.iter(NS + "text") if t.text and re.fullmatch(r"T\d+", t.text)]
    print(v.get("id"), "feed" if feed else "-", "rapid" if rapid else "-", "arcs", arcs, "tools", " ".join(markers))
