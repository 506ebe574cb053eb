#!/usr/bin/env python3
"""Writes the two hidden spaces of the object-search experiment (map_server YAML + PGM).

12 x 8 m at 0.05 m, walls all round. The miniUGV starts at (1, 4) facing +x
(examples/experiments/paper.yaml). 'sparse' holds a few boxes; 'dense' adds an
inner wall, more boxes and two pillars that hide parts of zones 2 and 4 from the
start (the paper's cluttered map, where the camera sees the object less often).
Run from anywhere: python3 examples/maps/make_maps.py (python3 standard library only).
"""
import os

RES = 0.05
W_M, H_M = 12.0, 8.0
FREE, OCC = 254, 0

SPARSE = [  # boxes: x0, y0, x1, y1 in metres
    (5.6, 5.6, 6.4, 6.4),
    (5.6, 1.6, 6.4, 2.4),
    (8.5, 3.5, 9.3, 4.5),
    (9.5, 6.0, 10.5, 6.6),
    (9.5, 1.4, 10.5, 2.0),
]
DENSE = SPARSE + [
    (7.0, 2.6, 7.2, 5.4),    # inner wall, open at both ends
    (2.0, 6.6, 2.6, 7.2),
    (2.0, 0.8, 2.6, 1.4),
    (4.8, 6.8, 5.4, 7.6),
    (4.8, 0.4, 5.4, 1.2),
    (8.2, 6.2, 8.8, 7.0),
    (8.2, 1.0, 8.8, 1.8),
    (10.2, 3.0, 10.8, 5.0),
    (11.0, 6.8, 11.6, 7.4),
    (6.2, 6.8, 6.8, 7.4),
    (6.2, 0.6, 6.8, 1.2),
    (2.5, 5.0, 2.7, 5.2),    # pillars between the start and zones 2 and 4
    (2.5, 2.8, 2.7, 3.0),
    (4.6, 5.9, 4.8, 6.1),
    (4.6, 1.9, 4.8, 2.1),
]
WALL_M = 0.1


def grid(boxes):
    w, h = round(W_M / RES), round(H_M / RES)
    cells = [[FREE] * w for _ in range(h)]  # cells[j][i], j = 0 at the bottom
    wall = round(WALL_M / RES)
    for j in range(h):
        for i in range(w):
            if i < wall or j < wall or i >= w - wall or j >= h - wall:
                cells[j][i] = OCC
    for x0, y0, x1, y1 in boxes:
        for j in range(round(y0 / RES), round(y1 / RES)):
            for i in range(round(x0 / RES), round(x1 / RES)):
                cells[j][i] = OCC
    return w, h, cells


def write(name, boxes, out_dir):
    w, h, cells = grid(boxes)
    pgm = os.path.join(out_dir, name + ".pgm")
    with open(pgm, "wb") as f:
        f.write(b"P5\n# ferret hidden space '%s', made by make_maps.py\n%d %d\n255\n" % (name.encode(), w, h))
        for j in reversed(range(h)):  # the image's first row is the map's top
            f.write(bytes(cells[j]))
    with open(os.path.join(out_dir, name + ".yaml"), "w") as f:
        f.write("# %s hidden space, 12 x 8 m (examples/maps/make_maps.py)\n" % name)
        f.write("image: %s.pgm\nresolution: %.2f\norigin: [0.0, 0.0, 0.0]\n" % (name, RES))
        f.write("negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n")


if __name__ == "__main__":
    here = os.path.dirname(os.path.abspath(__file__))
    write("sparse", SPARSE, here)
    write("dense", DENSE, here)
