#!/usr/bin/env python3

# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

"""Writes real land for examples/dem/jacksboro.toml: the 3 arc-second DEM of
the Jacksboro fault in East Tennessee that Debian's python-matplotlib-data
ships (sample_data/jacksboro_fault_dem.npz, 403 x 344 cells of 1/1200
degree, 236..1076 m), as an ESRI ASCII grid with a WGS84 .prj: the form
USGS distributes, which GDAL reads with its place on the Earth.

    python3 examples/dem/jacksboro_dem.py [FOLDER]   (default: this folder)
"""

import os
import sys

import numpy as np

SOURCE = "/usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz"
WGS84 = ('GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],'
         'PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]]')


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    dem = np.load(SOURCE)
    heights = dem["elevation"]
    # The archive's xmin is the west edge; its "ymax" (36.446) is the south
    # edge and "ymin" the north one; row 0 is the northernmost.
    west, south, cell = float(dem["xmin"]), float(min(dem["ymin"], dem["ymax"])), float(dem["dx"])
    rows, columns = heights.shape
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "jacksboro.asc")
    with open(path + ".tmp", "w") as out:
        out.write(f"ncols {columns}\nnrows {rows}\nxllcorner {west!r}\nyllcorner {south!r}\n"
                  f"cellsize {cell!r}\nNODATA_value -9999\n")
        for row in heights:
            out.write(" ".join(str(int(v)) for v in row) + "\n")
    os.replace(path + ".tmp", path)
    with open(os.path.join(folder, "jacksboro.prj"), "w") as out:
        out.write(WGS84)
    print(f"{path}: {columns} x {rows} cells, {heights.min()}..{heights.max()} m, "
          f"west {west}, south {south}, cell {cell} degrees")


if __name__ == "__main__":
    main()
