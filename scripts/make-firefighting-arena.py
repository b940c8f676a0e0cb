#!/usr/bin/env python3
"""Writes scenes/firefighting_omni/arena.xml: the walls of the Fire-Fighting arena as static
cuboids, from the room list below (docs/tutorials/omni-localisation.md).

    scripts/make-firefighting-arena.py > scenes/firefighting_omni/arena.xml

Frame: the arena's inside is the square [0, 2.44] m x [0, 2.44] m, origin at its south-west
corner. Each room is a rectangle whose walls lie inside it along the sides that face a
hallway, so that the clear gap between two rooms (a hallway) is exactly what the rectangles
leave: 0.46 m. A door is a 0.46 m gap in one of those walls."""

ARENA_M = 2.44
HEIGHT_M = 0.33
THICK_M = 0.02
DOOR_M = 0.46

# name: (x0, y0, x1, y1, inner sides with walls, door: (side, start along that side))
ROOMS = {
    "room1": (0.00, 1.52, 0.92, 2.44, "east south", ("south", 0.30)),
    "room2": (1.38, 1.26, 2.44, 2.44, "west south", ("west", 1.80)),
    "room3": (0.00, 0.00, 1.06, 1.06, "north east", ("east", 0.30)),
    "room4": (1.52, 0.00, 2.44, 0.80, "north west", ("north", 1.90)),
}


def side_span(x0, y0, x1, y1, side):
    """The wall box of one side: (xa, ya, xb, yb) and whether it runs along x."""
    if side == "south":
        return (x0, y0, x1, y0 + THICK_M), True
    if side == "north":
        return (x0, y1 - THICK_M, x1, y1), True
    if side == "west":
        return (x0, y0, x0 + THICK_M, y1), False
    return (x1 - THICK_M, y0, x1, y1), False


def walls():
    t = THICK_M
    out = [("outer_south", (-t, -t, ARENA_M + t, 0.0)),
           ("outer_north", (-t, ARENA_M, ARENA_M + t, ARENA_M + t)),
           ("outer_west", (-t, 0.0, 0.0, ARENA_M)),
           ("outer_east", (ARENA_M, 0.0, ARENA_M + t, ARENA_M))]
    for name, (x0, y0, x1, y1, sides, door) in ROOMS.items():
        for side in sides.split():
            (xa, ya, xb, yb), along_x = side_span(x0, y0, x1, y1, side)
            if side != door[0]:
                out.append(("%s_%s" % (name, side), (xa, ya, xb, yb)))
                continue
            d0, d1 = door[1], door[1] + DOOR_M
            if along_x:
                pieces = [(xa, ya, d0, yb), (d1, ya, xb, yb)]
            else:
                pieces = [(xa, ya, xb, d0), (xa, d1, xb, yb)]
            for k, (pa, qa, pb, qb) in enumerate(pieces):
                if pb - pa > 1e-9 and qb - qa > 1e-9:
                    out.append(("%s_%s_%d" % (name, side, k), (pa, qa, pb, qb)))
    return out


def main():
    print("<?xml version='1.0' ?>")
    print("<!-- Written by scripts/make-firefighting-arena.py: edit the script, not this file.")
    print("     The Fire-Fighting arena's walls, 0.33 m high, 0.02 m thick; plain numbers, as")
    print("     python/examples/omni_tour.py reads them for its map. -->")
    print("<obstacles>")
    for name, (xa, ya, xb, yb) in walls():
        print("  <cuboid>")
        print("    <ID value='%s'/>" % name)
        print("    <size x='%.3f' y='%.3f' z='%.3f'/>" % (xb - xa, yb - ya, HEIGHT_M))
        print("    <pos x='%.3f' y='%.3f' z='%.3f'/>" % ((xa + xb) / 2, (ya + yb) / 2, HEIGHT_M / 2))
        print("    <color_rgb r='235' g='235' b='225'/>")
        print("  </cuboid>")
    print("</obstacles>")


if __name__ == "__main__":
    main()
