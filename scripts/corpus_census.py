#!/usr/bin/env python3
"""The records of the CL files in ../shared/corpus, counted per CAM system: the table of
docs/cl-input.md ("Records per CAM system"). Continuations are joined first; $$ comments and
the lines NX's information window adds are not records.

    python3 scripts/corpus_census.py [CORPUS_DIR]
"""
import collections, os, re, sys

corpus = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..", "shared", "corpus")

def system(text):
    # As clpc recognises it (lower/prescan.cpp, recognise_cam_system).
    head = text[:65536]
    for sig, name in (("$$*CATIA0", "CATIA"), ("CATIA APT VERSION", "CATIA"), ("Pro/CLfile", "Creo"), ("$$->", "Creo"),
                      ("TOOL PATH/", "NX"), ("APTCL-SPEC,MAKINO-FF", "NX (Makino FFCAM)")):
        if sig in head:
            return name
    return "unknown"

counts = collections.defaultdict(collections.Counter)
files = collections.Counter()
for root, _, names in os.walk(corpus):
    if os.path.basename(root) == "licenses":
        continue
    for n in sorted(names):
        if n.startswith("LICENSE") or n.endswith(".md") or n.endswith(".tap"):
            continue
        text = open(os.path.join(root, n), encoding="latin-1").read().replace("\r", "")
        text = re.sub(r"\$[ \t]*\n", "", text)  # continuations, joined with nothing between
        sysname = system(text)
        files[sysname] += 1
        for line in text.split("\n"):
            s = line.strip()
            if not s or (s.startswith("$$") and not s.startswith("$$->")):
                continue
            if s.startswith("$$->"):
                s = s[4:].strip()
            m = re.match(r"([A-Za-z][A-Za-z0-9_-]*(?:[ \t]+[A-Za-z][A-Za-z0-9_-]*)*)\s*(,\s*[A-Za-z]+\s*/|/|$)", s)
            if not m:
                continue
            word = m.group(1).upper()
            first = word.split()[0]
            if first in ("PARTNO", "PPRINT", "INSERT", "REMARK", "TPRINT"):
                word = first
            if word.startswith(("INFORMATION LISTING", "DATE", "CURRENT WORK PART", "NODE NAME", "TOOL PATH LISTING")):
                continue
            if m.group(2).startswith(","):
                word = word + "," + m.group(2)[1:].strip(" /").upper()
            counts[sysname][word] += 1

for sysname in sorted(counts):
    print(f"### {sysname} ({files[sysname]} files)\n")
    print(" ".join(f"`{w}` {c}," for w, c in counts[sysname].most_common()).rstrip(","))
    print()
