#!/usr/bin/env python3
"""Make jacksboro_fault.asc, the terrain the slope search runs on, from
matplotlib's sample DEM `jacksboro_fault_dem.npz` (SRTM 3 arc-second
elevations, public domain; see README.md beside this script).

The sample DEM lies on a latitude/longitude grid (3" x 3", about 74 m
east-west by 93 m north-south there). The slope search needs square cells in
metres, so the script resamples it onto a square grid in UTM zone 16N
(EPSG:32616, WGS 84): 100 x 100 cells of 75 m, whose lower-left corner is
given below. Each cell's centre is taken back to longitude and latitude by
PROJ (pyproj) and its height interpolated bilinearly between the four
surrounding SRTM samples. Heights are in metres (SRTM: above the EGM96
geoid), written to the centimetre.

Usage (numpy and pyproj installed; the npz comes from matplotlib's wheel,
`pip download --no-deps matplotlib`, under matplotlib/mpl-data/sample_data/):

    python3 convert.py PATH/TO/jacksboro_fault_dem.npz

It writes jacksboro_fault.asc and jacksboro_fault.prj beside this script.
"""

import hashlib
import pathlib
import sys

import numpy as np
from pyproj import CRS, Transformer

# The file of matplotlib 3.11.2's wheel (unchanged since it was added to
# matplotlib in 2014, pull request #3291).
NPZ_SHA256 = "d493f50a33e82a4420494c54d1fca1539d177bdc27ab190bc5fe6e92f62fb637"

UTM = CRS.from_epsg(32616)  # WGS 84 / UTM zone 16N
CELL = 75.0  # m
COLUMNS, ROWS = 100, 100
# Lower-left corner of the grid (m, UTM 16N): around the place where the
# Jacksboro fault's straight valley meets the north-west face of Pine
# Mountain, south-west of Jellico, Tennessee.
XLL, YLL = 744_400.0, 4_051_200.0


def load(path):
    """Heights (m) and the longitudes and latitudes of their samples."""
    data = path.read_bytes()
    digest = hashlib.sha256(data).hexdigest()
    if digest != NPZ_SHA256:
        sys.exit(f"{path}: SHA-256 {digest}, expected {NPZ_SHA256}")
    with np.load(path) as dem:
        z = dem["elevation"].astype(float)
        dx, dy = float(dem["dx"]), float(dem["dy"])
        west, east = float(dem["xmin"]), float(dem["xmax"])
        # The file's `ymin` is the northern edge and `ymax` the southern
        # one: row 0 is the northernmost row (the fault trends north-west
        # and Pine Mountain north-east from it only that way up).
        north, south = float(dem["ymin"]), float(dem["ymax"])
    rows, columns = z.shape
    # The bounds are the outer edges of the cells: the samples lie half a
    # cell inside, on whole multiples of 3 arc-seconds, as SRTM's do.
    assert abs((east - west) / dx - columns) < 1e-6
    assert abs((north - south) / dy - rows) < 1e-6
    lon = west + (np.arange(columns) + 0.5) * dx
    lat = north - (np.arange(rows) + 0.5) * dy
    return z, lon, lat


def bilinear(z, lon, lat, x, y):
    """z interpolated at longitudes x and latitudes y (arrays)."""
    dlon, dlat = lon[1] - lon[0], lat[0] - lat[1]
    fc = (x - lon[0]) / dlon
    fr = (lat[0] - y) / dlat
    c0, r0 = np.floor(fc).astype(int), np.floor(fr).astype(int)
    if c0.min() < 0 or r0.min() < 0 or c0.max() + 1 >= len(lon) or r0.max() + 1 >= len(lat):
        sys.exit("the UTM grid reaches beyond the sample DEM")
    tc, tr = fc - c0, fr - r0
    return (
        z[r0, c0] * (1 - tc) * (1 - tr)
        + z[r0, c0 + 1] * tc * (1 - tr)
        + z[r0 + 1, c0] * (1 - tc) * tr
        + z[r0 + 1, c0 + 1] * tc * tr
    )


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    z, lon, lat = load(pathlib.Path(sys.argv[1]))
    here = pathlib.Path(__file__).resolve().parent
    # Cell centres, row 0 at the top (north), as the ESRI grid lists them.
    east = XLL + (np.arange(COLUMNS) + 0.5) * CELL
    north = YLL + (ROWS - np.arange(ROWS) - 0.5) * CELL
    e, n = np.meshgrid(east, north)
    to_geographic = Transformer.from_crs(UTM, CRS.from_epsg(4326), always_xy=True)
    x, y = to_geographic.transform(e, n)
    heights = bilinear(z, lon, lat, x, y)
    lines = [
        f"ncols {COLUMNS}",
        f"nrows {ROWS}",
        f"xllcorner {XLL:.1f}",
        f"yllcorner {YLL:.1f}",
        f"cellsize {CELL:.1f}",
        "NODATA_value -9999",
    ]
    lines += [" ".join(f"{v:.2f}" for v in row) for row in heights]
    (here / "jacksboro_fault.asc").write_text("\n".join(lines) + "\n")
    (here / "jacksboro_fault.prj").write_text(UTM.to_wkt("WKT1_ESRI") + "\n")
    print(
        f"jacksboro_fault.asc: {COLUMNS} x {ROWS} cells of {CELL} m, "
        f"lon {x.min():.4f}..{x.max():.4f}, lat {y.min():.4f}..{y.max():.4f}, "
        f"heights {heights.min():.1f}..{heights.max():.1f} m"
    )


if __name__ == "__main__":
    main()
