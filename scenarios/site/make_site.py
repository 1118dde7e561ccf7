#!/usr/bin/env python3
"""Make the example site of scenarios/site/site.yaml: a terrain raster and a forest inventory.

Writes, next to this script:
- dem.tif: a digital elevation model, 90 x 90 pixels of 5 m (450 m x 450 m), float32 elevations in metres,
  in WGS 84 / UTM zone 32N (EPSG:32632), covering x 512000 .. 512450, y 5401000 .. 5401450. The ground is a
  gentle valley side: 420 m at the south edge, rising 3 m per 100 m toward the north, with a hill of 25 m
  centred on x 512300, y 5401250 (a Gaussian, e-folding radius 90 m).
- trees.csv: a forest inventory (id, x, y, species, height, dbh), as a survey or a LiDAR segmentation gives
  one: Norway spruce in the west, beech in the east, on a jittered grid 5.6 m apart, heights from a clipped
  normal and dbh from a slenderness (height over dbh) drawn per tree. The last 6 trees stand east of the
  scenario's domain, still on the raster, so that a check has trees outside the domain to report.

It writes the GeoTIFF by hand rather than through GDAL: Debian's minimal install used here has no GDAL
Python bindings (nor numpy), and the format is small: a baseline TIFF (one float32 band, uncompressed, in
strips of rows) plus three GeoTIFF tags (the pixel scale, the tie point and the GeoKey directory) and GDAL's
nodata tag. Python 3's standard library only; the output is the same on every run (fixed seed).

Run it from anywhere: python3 scenarios/site/make_site.py
"""

import math
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
SEED = 2024

# The raster: north-up, row 0 the north row.
PIXEL = 5.0  # m, square
COLUMNS = 90
ROWS = 90
WEST = 512000.0  # x of the west edge
NORTH = 5401450.0  # y of the north edge
NODATA = -9999.0
EPSG = 32632  # WGS 84 / UTM zone 32N
ROWS_PER_STRIP = 16  # 16 x 90 x 4 bytes = 5,760 bytes a strip (TIFF advises strips of about 8 kB)

# The ground.
BASE = 420.0  # m at the south edge
SLOPE = 0.03  # rise per metre toward the north
HILL_HEIGHT = 25.0
HILL_X, HILL_Y = 512300.0, 5401250.0
HILL_RADIUS = 90.0  # e-folding: the hill is HILL_HEIGHT / e high this far from its centre

# The domain of site.yaml (south-west corner and size), for the summary: the floor must lie at or below
# the lowest ground that the run's terrain reads.
DOMAIN_X, DOMAIN_Y = 512040.0, 5401040.0
DOMAIN_W, DOMAIN_D = 360.0, 320.0
PROBES = {"upwind": (30.0, 160.0), "stand": (200.0, 160.0)}  # local x, y of site.yaml's probes

# The stand: a block of GRID_COLUMNS x GRID_ROWS grid points SPACING apart, its x from STAND_WEST to
# STAND_EAST, its rows centred on STAND_Y; the westmost SPRUCE_COLUMNS columns spruce, the rest beech.
STAND_WEST, STAND_EAST = 512090.0, 512370.0
STAND_Y = 5401200.0
SPACING = 5.6
GRID_COLUMNS = 50  # 50 x 5.6 = 280 m: STAND_WEST .. STAND_EAST
GRID_ROWS = 10  # 56 m; 46 rows would fill y 5401070 .. 5401330 (about 2,300 trees)
SPRUCE_COLUMNS = 30
JITTER = 1.0  # m, uniform in x and y
MISSING = 0.02  # chance that a grid point holds no tree (a gap)
MIN_DISTANCE = 2.5  # m between any two trees

# Per species: height (mean, sd, min, max) in m, slenderness H/dbh (min, max).
SPECIES = {
    "spruce": {"height": (22.0, 2.5, 16.0, 28.0), "slenderness": (60.0, 85.0)},
    "beech": {"height": (19.0, 2.0, 14.0, 24.0), "slenderness": (50.0, 70.0)},
}

# The trees outside the domain: x east of it (it ends at 512400), y and species.
OUTSIDE = [(512420.0, 5401180.0, "beech"), (512430.0, 5401190.0, "beech"), (512440.0, 5401200.0, "spruce"),
           (512420.0, 5401210.0, "beech"), (512430.0, 5401220.0, "spruce"), (512440.0, 5401230.0, "beech")]


def elevation(x, y):
    r2 = (x - HILL_X) ** 2 + (y - HILL_Y) ** 2
    return BASE + SLOPE * (y - (NORTH - ROWS * PIXEL)) + HILL_HEIGHT * math.exp(-r2 / HILL_RADIUS ** 2)


def pixel_centre(column, row):
    return WEST + (column + 0.5) * PIXEL, NORTH - (row + 0.5) * PIXEL


def make_dem():
    """The elevations, row by row from the north, rounded to the centimetre and to float32."""
    grid = []
    for row in range(ROWS):
        values = []
        for column in range(COLUMNS):
            z = round(elevation(*pixel_centre(column, row)), 2)
            values.append(struct.unpack("<f", struct.pack("<f", z))[0])
        grid.append(values)
    return grid


# TIFF field types.
SHORT, LONG, RATIONAL, DOUBLE, ASCII = 3, 4, 5, 12, 2
TYPE_SIZE = {SHORT: 2, LONG: 4, RATIONAL: 8, DOUBLE: 8, ASCII: 1}
TYPE_CODE = {SHORT: "H", LONG: "I", DOUBLE: "d"}


def write_geotiff(path, grid):
    """A little-endian baseline TIFF, one float32 band in strips of rows, with the GeoTIFF tags."""
    strips = []
    for first in range(0, ROWS, ROWS_PER_STRIP):
        rows = grid[first:first + ROWS_PER_STRIP]
        strips.append(b"".join(struct.pack("<%df" % COLUMNS, *row) for row in rows))

    geokeys = [1, 1, 0, 4,  # version 1, revision 1.0, 4 keys
               1024, 0, 1, 1,  # GTModelTypeGeoKey: projected
               1025, 0, 1, 1,  # GTRasterTypeGeoKey: PixelIsArea
               3072, 0, 1, EPSG,  # ProjectedCSTypeGeoKey
               3076, 0, 1, 9001]  # ProjLinearUnitsGeoKey: metre
    count = len(strips)
    # (tag, type, values); the strip offsets are filled in once the layout is known.
    entries = [
        (256, SHORT, [COLUMNS]),  # ImageWidth
        (257, SHORT, [ROWS]),  # ImageLength
        (258, SHORT, [32]),  # BitsPerSample
        (259, SHORT, [1]),  # Compression: none
        (262, SHORT, [1]),  # PhotometricInterpretation: BlackIsZero
        (273, LONG, [0] * count),  # StripOffsets
        (277, SHORT, [1]),  # SamplesPerPixel
        (278, SHORT, [ROWS_PER_STRIP]),  # RowsPerStrip
        (279, LONG, [len(s) for s in strips]),  # StripByteCounts
        (282, RATIONAL, [(1, 1)]),  # XResolution
        (283, RATIONAL, [(1, 1)]),  # YResolution
        (284, SHORT, [1]),  # PlanarConfiguration: chunky
        (296, SHORT, [1]),  # ResolutionUnit: none
        (339, SHORT, [3]),  # SampleFormat: IEEE floating point
        (33550, DOUBLE, [PIXEL, PIXEL, 0.0]),  # ModelPixelScaleTag
        (33922, DOUBLE, [0.0, 0.0, 0.0, WEST, NORTH, 0.0]),  # ModelTiepointTag
        (34735, SHORT, geokeys),  # GeoKeyDirectoryTag
        (42113, ASCII, "%d" % NODATA),  # GDAL_NODATA
    ]
    entries.sort(key=lambda entry: entry[0])  # TIFF wants the IFD's entries in ascending tag order

    def pack(kind, values):
        if kind == ASCII:
            return values.encode("ascii") + b"\0"
        if kind == RATIONAL:
            return b"".join(struct.pack("<II", n, d) for n, d in values)
        return struct.pack("<%d%s" % (len(values), TYPE_CODE[kind]), *values)

    def layout(entries):
        """The file: header, IFD, the values too long for their entries, then the strips."""
        ifd_offset = 8
        ifd_size = 2 + 12 * len(entries) + 4
        extra = bytearray()
        extra_offset = ifd_offset + ifd_size
        ifd = bytearray(struct.pack("<H", len(entries)))
        for tag, kind, values in entries:
            data = pack(kind, values)
            n = len(values) + 1 if kind == ASCII else len(values)
            if len(data) <= 4:
                ifd += struct.pack("<HHI", tag, kind, n) + data.ljust(4, b"\0")
            else:
                if (extra_offset + len(extra)) % 2:
                    extra += b"\0"  # values start on a word boundary
                ifd += struct.pack("<HHII", tag, kind, n, extra_offset + len(extra))
                extra += data
        ifd += struct.pack("<I", 0)  # no next IFD
        data_offset = extra_offset + len(extra)
        data_offset += data_offset % 2
        return bytes(ifd), bytes(extra), data_offset

    _, _, data_offset = layout(entries)
    offsets, at = [], data_offset
    for strip in strips:
        offsets.append(at)
        at += len(strip)
    entries = [(tag, kind, offsets if tag == 273 else values) for tag, kind, values in entries]
    ifd, extra, data_offset_again = layout(entries)
    assert data_offset_again == data_offset

    header = b"II" + struct.pack("<HI", 42, 8)
    body = header + ifd + extra
    body += b"\0" * (data_offset - len(body))
    with open(path, "wb") as file:
        file.write(body + b"".join(strips))


def clipped_normal(rng, mean, sd, low, high):
    while True:
        value = rng.gauss(mean, sd)
        if low <= value <= high:
            return value


def make_trees(rng):
    """Rows (x, y, species, height, dbh): the stand west to east, then the trees outside the domain."""
    placed = []
    y0 = STAND_Y - 0.5 * GRID_ROWS * SPACING
    for i in range(GRID_COLUMNS):
        species = "spruce" if i < SPRUCE_COLUMNS else "beech"
        for j in range(GRID_ROWS):
            if rng.random() < MISSING:
                continue
            x = STAND_WEST + (i + 0.5) * SPACING + rng.uniform(-JITTER, JITTER)
            y = y0 + (j + 0.5) * SPACING + rng.uniform(-JITTER, JITTER)
            placed.append((x, y, species))
    placed += OUTSIDE
    trees = []
    for x, y, species in placed:
        mean, sd, low, high = SPECIES[species]["height"]
        height = round(clipped_normal(rng, mean, sd, low, high), 2)
        slenderness = rng.uniform(*SPECIES[species]["slenderness"])
        trees.append((round(x, 2), round(y, 2), species, height, round(height / slenderness, 3)))
    for a in range(len(trees)):
        for b in range(a + 1, len(trees)):
            d = math.hypot(trees[a][0] - trees[b][0], trees[a][1] - trees[b][1])
            assert d >= MIN_DISTANCE, "trees %d and %d are %.2f m apart" % (a + 1, b + 1, d)
    return trees


def write_trees(path, trees):
    with open(path, "w", newline="\n") as file:
        file.write("id,x,y,species,height,dbh\n")
        for n, (x, y, species, height, dbh) in enumerate(trees, 1):
            file.write("T%04d,%.2f,%.2f,%s,%.2f,%.3f\n" % (n, x, y, species, height, dbh))


def bilinear(grid, x, y):
    """The elevation at (x, y) as the run reads it: bilinear between pixel centres."""
    c = (x - WEST) / PIXEL - 0.5
    r = (NORTH - y) / PIXEL - 0.5
    c0, r0 = int(math.floor(c)), int(math.floor(r))
    fc, fr = c - c0, r - r0
    z = lambda i, j: grid[min(max(j, 0), ROWS - 1)][min(max(i, 0), COLUMNS - 1)]
    return ((1 - fc) * (1 - fr) * z(c0, r0) + fc * (1 - fr) * z(c0 + 1, r0) + (1 - fc) * fr * z(c0, r0 + 1)
            + fc * fr * z(c0 + 1, r0 + 1))


def summary(grid, trees):
    values = [v for row in grid for v in row]
    print("dem.tif: %d x %d pixels of %g m, EPSG:%d, x %.1f .. %.1f, y %.1f .. %.1f, elevation %.2f .. %.2f m"
          % (COLUMNS, ROWS, PIXEL, EPSG, WEST, WEST + COLUMNS * PIXEL, NORTH - ROWS * PIXEL, NORTH,
             min(values), max(values)))
    # The pixels whose centres bilinear interpolation over the domain reads (as the run's terrain does).
    first_c = int(math.floor((DOMAIN_X - WEST) / PIXEL - 0.5))
    last_c = int(math.ceil((DOMAIN_X + DOMAIN_W - WEST) / PIXEL - 0.5))
    first_r = int(math.floor((NORTH - DOMAIN_Y - DOMAIN_D) / PIXEL - 0.5))
    last_r = int(math.ceil((NORTH - DOMAIN_Y) / PIXEL - 0.5))
    under = [grid[r][c] for r in range(first_r, last_r + 1) for c in range(first_c, last_c + 1)]
    floor = math.floor(min(under))
    print("  under the domain x %.0f .. %.0f, y %.0f .. %.0f (pixels read): %.2f .. %.2f m; "
          "floor at most %d m"
          % (DOMAIN_X, DOMAIN_X + DOMAIN_W, DOMAIN_Y, DOMAIN_Y + DOMAIN_D, min(under), max(under), floor))
    for name, (lx, ly) in PROBES.items():
        print("  probe %s at local (%g, %g): ground %.2f m, %.2f m above a floor of %d m"
              % (name, lx, ly, bilinear(grid, DOMAIN_X + lx, DOMAIN_Y + ly),
                 bilinear(grid, DOMAIN_X + lx, DOMAIN_Y + ly) - floor, floor))
    print("trees.csv: %d trees" % len(trees))
    for species in SPECIES:
        rows = [t for t in trees if t[2] == species]
        print("  %s: %d, height %.2f .. %.2f m (mean %.2f), dbh %.3f .. %.3f m (mean %.3f)"
              % (species, len(rows), min(t[3] for t in rows), max(t[3] for t in rows),
                 sum(t[3] for t in rows) / len(rows), min(t[4] for t in rows), max(t[4] for t in rows),
                 sum(t[4] for t in rows) / len(rows)))
    outside = [t for t in trees if not (DOMAIN_X <= t[0] <= DOMAIN_X + DOMAIN_W
                                        and DOMAIN_Y <= t[1] <= DOMAIN_Y + DOMAIN_D)]
    print("  outside the domain: %d (the last %d rows)" % (len(outside), len(OUTSIDE)))


def main():
    rng = random.Random(SEED)
    grid = make_dem()
    assert all(math.isfinite(v) and v >= 415.0 for row in grid for v in row)
    write_geotiff(os.path.join(HERE, "dem.tif"), grid)
    trees = make_trees(rng)
    write_trees(os.path.join(HERE, "trees.csv"), trees)
    summary(grid, trees)


if __name__ == "__main__":
    main()
