#!/usr/bin/env python3
"""Generates the bundled ROS map_server maps (YAML + binary PGM) next to this script.

Standard library only.  Run:  python3 maps/generate_maps.py [--ascii]

Conventions: pixel 0 = occupied, 254 = free, 205 = unknown; image row 0 is the top
(largest y); the YAML origin is the world position of the lower-left pixel corner.
Every map is drawn in *room-local* metres: (0, 0) is the lower-left corner of the
interior (the inner face of the outer walls), which sits MARGIN + WALL from the origin.
"""
import os
import sys
from collections import deque

RES = 0.05        # m per pixel
WALL = 0.15       # outer walls: 3 px
INNER = 0.10      # interior walls: 2 px
MARGIN = 0.50     # unknown band outside the outer walls
OCC, FREE, UNKNOWN = 0, 254, 205
HERE = os.path.dirname(os.path.abspath(__file__))


def px(m):
    """Metres -> whole pixels (all coordinates below are multiples of 0.05 m)."""
    return int(round(m / RES))


class Map:
    def __init__(self, name, desc, width_m, height_m, origin):
        """width_m/height_m: interior bounding box; the canvas adds walls and margin."""
        self.name, self.desc, self.origin = name, desc, origin
        self.off = MARGIN + WALL                      # local (0,0) -> canvas metres
        self.w = px(width_m + 2 * self.off)
        self.h = px(height_m + 2 * self.off)
        self.rows = [bytearray([UNKNOWN]) * self.w for _ in range(self.h)]  # rows[0] = bottom

    def rect(self, x0, y0, x1, y1, v=OCC):
        """Fills the local rectangle [x0,x1] x [y0,y1] (metres) with value v."""
        c0, c1 = max(0, px(x0 + self.off)), min(self.w, px(x1 + self.off))
        r0, r1 = max(0, px(y0 + self.off)), min(self.h, px(y1 + self.off))
        for r in range(r0, r1):
            self.rows[r][c0:c1] = bytes([v]) * (c1 - c0)

    def disc(self, cx, cy, radius, v=OCC):
        """Fills every pixel whose centre lies within radius of (cx, cy)."""
        for r in range(px(cy - radius + self.off) - 1, px(cy + radius + self.off) + 1):
            for c in range(px(cx - radius + self.off) - 1, px(cx + radius + self.off) + 1):
                x, y = (c + 0.5) * RES - self.off, (r + 0.5) * RES - self.off
                if (x - cx) ** 2 + (y - cy) ** 2 <= radius ** 2:
                    self.rows[r][c] = v

    def rooms(self, boxes):
        """Walled free space made of the union of the interior boxes (x0, y0, x1, y1):
        all outer walls first, then all interiors, so joined boxes share no wall."""
        for x0, y0, x1, y1 in boxes:
            self.rect(x0 - WALL, y0 - WALL, x1 + WALL, y1 + WALL, OCC)
        for box in boxes:
            self.rect(*box, v=FREE)

    def wall(self, x0, y0, x1, y1, doors=()):
        """Interior wall (a thin rectangle) with door openings given as (start, end)
        along its long axis; openings are free."""
        self.rect(x0, y0, x1, y1, OCC)
        horizontal = (x1 - x0) >= (y1 - y0)
        for a, b in doors:
            self.rect(a, y0, b, y1, FREE) if horizontal else self.rect(x0, a, x1, b, FREE)

    def door(self, x0, y0, x1, y1):
        """Opening in an outer wall: the wall pixels become free, outside stays unknown."""
        self.rect(x0, y0, x1, y1, FREE)

    # ---- checks and output -------------------------------------------------------
    def free_components(self):
        seen, sizes = set(), []
        for r in range(self.h):
            for c in range(self.w):
                if self.rows[r][c] != FREE or (r, c) in seen:
                    continue
                seen.add((r, c))
                q, n = deque([(r, c)]), 0
                while q:
                    y, x = q.popleft()
                    n += 1
                    for dy, dx in ((1, 0), (-1, 0), (0, 1), (0, -1)):
                        ny, nx = y + dy, x + dx
                        if 0 <= ny < self.h and 0 <= nx < self.w and \
                                self.rows[ny][nx] == FREE and (ny, nx) not in seen:
                            seen.add((ny, nx))
                            q.append((ny, nx))
                sizes.append(n)
        return sizes

    def rot180_mismatch(self):
        """Fraction of pixels that differ from the map turned by 180 degrees."""
        diff = sum(a != b for row, rrow in zip(self.rows, reversed(self.rows))
                   for a, b in zip(row, reversed(rrow)))
        return diff / (self.w * self.h)

    def ascii(self, step=4):
        """Thumbnail of step x step blocks: '#' if any pixel is occupied (so thin walls
        show), else '.' if any is free, else ' ' (unknown)."""
        def cell(r, c):
            block = [v for row in self.rows[max(0, r - step + 1):r + 1] for v in row[c:c + step]]
            return "#" if OCC in block else "." if FREE in block else " "
        return "\n".join("".join(cell(r, c) for c in range(0, self.w, step))
                         for r in range(self.h - 1, -1, -step))

    def save(self):
        with open(os.path.join(HERE, self.name + ".pgm"), "wb") as f:
            f.write(b"P5\n%d %d\n255\n" % (self.w, self.h))
            for row in reversed(self.rows):          # image row 0 = top of the map
                f.write(row)
        with open(os.path.join(HERE, self.name + ".yaml"), "w") as f:
            f.write("# %s\n" % self.desc)
            f.write("image: %s.pgm\nresolution: %g\n" % (self.name, RES))
            f.write("origin: [%.1f, %.1f, 0.0]\n" % self.origin)
            f.write("negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n")


def room_rect():
    m = Map("room_rect", "Rectangular room 6.0 x 4.5 m (interior): desk on the north wall, "
            "cupboard on the east wall, door in the south wall", 6.0, 4.5, (-0.5, -0.5))
    m.rooms([(0, 0, 6.0, 4.5)])
    m.rect(0.5, 3.8, 1.9, 4.5)            # desk 1.4 x 0.7 against the north wall
    m.rect(5.5, 0.6, 6.0, 1.8)            # cupboard 0.5 x 1.2 against the east wall
    m.door(1.0, -WALL, 1.9, 0)            # 0.9 m door, south wall, west of centre
    return m


def room_l():
    m = Map("room_l", "L-shaped room 7.0 x 6.0 m, 3 m wide arms: table in the north arm, "
            "pillar in the east arm, door in the south wall", 7.0, 6.0, (-1.0, -0.5))
    m.rooms([(0, 0, 7.0, 3.0), (0, 0, 3.0, 6.0)])   # inner corner at (3, 3)
    m.rect(0.6, 4.4, 1.8, 5.2)            # table 1.2 x 0.8 in the north arm
    m.disc(5.5, 1.8, 0.15)                # pillar, 0.3 m diameter, 2.8 m from the corner
    m.door(4.5, -WALL, 5.4, 0)            # 0.9 m door, south wall of the east arm
    return m


def room_furnished():
    m = Map("room_furnished", "Bedroom 6.5 x 5.0 m: bed, wardrobe, free-standing table and "
            "chair, 1.2 m niche in the north wall, door in the east wall", 6.5, 5.4, (0.0, 0.0))
    m.rooms([(0, 0, 6.5, 5.0), (4.6, 5.0, 5.8, 5.4)])  # niche 1.2 wide, 0.4 deep
    m.rect(0, 3.2, 2.0, 4.6)              # bed 2.0 x 1.4, head against the west wall
    m.rect(3.8, 0, 5.6, 0.6)              # wardrobe 1.8 x 0.6 against the south wall
    m.rect(2.6, 2.0, 3.4, 2.8)            # table 0.8 x 0.8, >= 2 m from every wall
    m.rect(3.6, 2.15, 4.05, 2.6)          # chair 0.45 x 0.45 next to the table
    m.door(6.5, 1.2, 6.5 + WALL, 2.1)     # 0.9 m door, east wall
    return m


def apartment_small():
    m = Map("apartment_small", "Small apartment 10 x 7 m: living room, kitchen, bedroom and "
            "bathroom joined by 0.9 m doors, entrance in the south wall", 9.7, 6.7, (-0.5, -0.5))
    m.rooms([(0, 0, 9.7, 6.7)])
    m.wall(5.5, 0, 5.6, 6.7, doors=[(0.8, 1.7), (2.9, 3.8)])  # west | east; bath, bedroom
    m.wall(0, 4.0, 5.5, 4.1, doors=[(1.0, 1.9)])              # living | kitchen
    m.wall(5.6, 2.5, 9.7, 2.6)                                 # bathroom | bedroom
    m.door(3.5, -WALL, 4.4, 0)            # entrance, south wall of the living room
    m.rect(0, 1.0, 0.9, 3.0)              # living: sofa 0.9 x 2.0 against the west wall
    m.rect(2.0, 1.6, 3.0, 2.2)            # living: coffee table
    m.rect(1.5, 6.1, 4.5, 6.7)            # kitchen: counter 3.0 x 0.6 on the north wall
    m.rect(7.7, 4.5, 9.7, 6.1)            # bedroom: bed 2.0 x 1.6 against the east wall
    m.rect(6.0, 6.1, 7.2, 6.7)            # bedroom: wardrobe on the north wall
    m.rect(8.0, 0, 9.7, 0.75)             # bathroom: bathtub on the south wall
    m.rect(9.3, 1.4, 9.7, 2.0)            # bathroom: toilet block on the east wall
    return m


def room_symmetric():
    # The one deliberately symmetric map: turned by 180 degrees about its centre it is the
    # same room, so every pose has a twin that reads the same (the ambiguity tests need it).
    m = Map("room_symmetric", "Symmetric room 6.0 x 4.0 m: two doors and two cupboards placed "
            "so that the room is the same turned by 180 degrees", 6.0, 4.0, (-0.5, -0.5))
    m.rooms([(0, 0, 6.0, 4.0)])
    m.door(1.0, -WALL, 1.9, 0)            # 0.9 m door, south wall, west of centre
    m.door(4.1, 4.0, 5.0, 4.0 + WALL)     # its twin, north wall, east of centre
    m.rect(0, 2.6, 0.6, 3.6)              # cupboard 0.6 x 1.0 against the west wall
    m.rect(5.4, 0.4, 6.0, 1.4)            # its twin against the east wall
    return m


SYMMETRIC = ("room_symmetric",)


def main():
    show = "--ascii" in sys.argv
    ok = True
    for build in (room_rect, room_l, room_furnished, apartment_small, room_symmetric):
        m = build()
        m.save()
        comps = m.free_components()
        asym = m.rot180_mismatch()
        print("%-16s %4d x %4d px  (%.2f x %.2f m)  free regions: %d  rot180 mismatch: %.1f%%"
              % (m.name, m.w, m.h, m.w * RES, m.h * RES, len(comps), 100 * asym))
        symmetric = m.name in SYMMETRIC
        if len(comps) != 1 or (asym < 0.01) != symmetric:
            print("  ERROR: free space must be one connected region, and 180-degree symmetric "
                  "exactly when the map is meant to be")
            ok = False
        if show:
            print(m.ascii())
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
