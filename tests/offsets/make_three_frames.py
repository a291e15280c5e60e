#!/usr/bin/env python3
"""Writes three_frames.cls: a part machined in three SET/CAMERA frames, two of them used twice.

The frames are the seed paper's kind, R = Rz(C) Rx(A): the top (identity, SET/54), side A
(A45 C90, SET/55) and side B (A90 C180, SET/56). Points are in the part (model) frame, as
CAMERA frames give them; each operation's tool axis is its frame's Z. Run it again after
changing it: python3 tests/offsets/make_three_frames.py > tests/offsets/three_frames.cls
"""
import math


def rz(c):
    c = math.radians(c)
    return [[math.cos(c), -math.sin(c), 0], [math.sin(c), math.cos(c), 0], [0, 0, 1]]


def rx(a):
    a = math.radians(a)
    return [[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]]


def mul(p, q):
    return [[sum(p[i][k] * q[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def clean(v):
    return 0.0 if abs(v) < 1e-12 else v


class Frame:
    def __init__(self, a, c, origin):
        self.r = mul(rz(c), rx(a))
        self.o = origin

    def point(self, x, y, z):
        return [clean(self.o[i] + self.r[i][0] * x + self.r[i][1] * y + self.r[i][2] * z) for i in range(3)]

    def z(self):
        return [clean(self.r[i][2]) for i in range(3)]

    def camera(self):
        vals = []
        for i in range(3):
            vals += [clean(self.r[i][0]), clean(self.r[i][1]), clean(self.r[i][2]), self.o[i]]
        return "CAMERA/" + ",".join(f"{v:.10f}" for v in vals[:6]) + ", $\n" + ",".join(f"{v:.10f}" for v in vals[6:])


def goto(f, x, y, z):
    p = f.point(x, y, z)
    k = f.z()
    return "GOTO/" + ",".join(f"{v:.4f}" for v in p) + "," + ",".join(f"{v:.7f}" for v in k)


def pocket(f, depth, feed):
    """A 30 x 20 rectangle and a 10 mm radius arc, in the frame's XY plane at -depth."""
    out = ["RAPID", goto(f, 0, 0, 20), "RAPID", goto(f, 0, 0, 2), f"FEDRAT/MMPM,{feed/3:.1f}", goto(f, 0, 0, -depth),
           f"FEDRAT/MMPM,{feed:.1f}", goto(f, 30, 0, -depth), goto(f, 30, 20, -depth)]
    c = f.point(20, 20, -depth)
    k = [clean(-v) for v in f.z()]  # NX: the axis of clockwise rotation; this arc turns CCW about Z
    out.append("CIRCLE/" + ",".join(f"{v:.4f}" for v in c) + "," + ",".join(f"{v:.7f}" for v in k) +
               ",10.0000,0.0100,0.5000,10.0000,0.0000")
    out += [goto(f, 10, 20, -depth), goto(f, 0, 20, -depth), goto(f, 0, 0, -depth), "RAPID", goto(f, 0, 0, 20)]
    return out


def holes(f):
    out = ["RAPID", goto(f, 5, 5, 20), "CYCLE/DRILL,DEPTH,8.0,MMPM,90.0,CLEAR,2.0"]
    for x, y in [(5, 5), (25, 5), (25, 15)]:
        out.append(goto(f, x, y, 0))
    out += ["CYCLE/OFF", "RAPID", goto(f, 25, 15, 20)]
    return out


top = Frame(0, 0, [0.0, 0.0, 0.0])
side_a = Frame(45, 90, [50.0, 0.0, -10.0])
side_b = Frame(90, 180, [0.0, 40.0, -20.0])

ops = [
    ("TOP_ROUGH", 1, "EM10", 54, top, lambda f: pocket(f, 2, 600)),
    ("SIDE_A_ROUGH", 1, "EM10", 55, side_a, lambda f: pocket(f, 2, 600)),
    ("SIDE_B_DRILL", 2, "DRILL6", 56, side_b, holes),
    ("SIDE_A_FINISH", 3, "EM6", 55, side_a, lambda f: pocket(f, 2.5, 900)),
    ("TOP_FINISH", 3, "EM6", 54, top, lambda f: pocket(f, 2.5, 900)),
]
tools = {"EM10": (10, 0), "DRILL6": (6, 0), "EM6": (6, 0.5)}

print("$$ golden: ac-trunnion ac-trunnion-g10 ac-trunnion-none")
print("$$ Three SET/CAMERA frames, two used twice (tests/offsets/make_three_frames.py). Public domain.")
print("PARTNO/THREE FRAMES")
print("UNITS/MM")
for name, tool, tname, reg, f, body in ops:
    d, cr = tools[tname]
    print(f"TOOL PATH/{name},TOOL,{tname}")
    print(f"TLDATA/MILL,{d:.4f},{cr:.4f},50.0000,0.0000,0.0000")
    print(f"LOAD/TOOL,{tool},ADJUST,{tool}")
    print(f"SET/{reg}")
    print(f.camera())
    print("SPINDL/RPM,4000,CLW")
    print("COOLNT/FLOOD")
    for line in body(f):
        print(line)
    print("END-OF-PATH")
print("FINI")
