#!/usr/bin/python3
"""Draws a GeoTIFF written by `sonarmap map --geotiff [--mosaic]` on a chart: latitude and longitude
axes with a graticule, every pixel placed by GDAL's own reading of the file (its CRS and
geotransform, projected to WGS 84 by GDAL's OSR/PROJ), the occupancy classes on the left and, when
the file has it, the echo-intensity mosaic on the right; a metre scale bar and the file's UTM zone.

Usage: /usr/bin/python3 scripts/geotiff_chart.py MAP.tif OUT.png [--mark LAT,LON]...
Needs Debian's python3-gdal and python3-matplotlib (scripts/install-deps.sh test).
"""

import argparse
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from osgeo import gdal, osr  # noqa: E402

gdal.UseExceptions()


def dms(value, positive, negative):
    hemisphere = positive if value >= 0 else negative
    value = abs(value)
    degrees = int(value)
    minutes = (value - degrees) * 60
    return f"{degrees}°{minutes:06.3f}'{hemisphere}"


def corners_lonlat(dataset):
    """Longitude and latitude of every pixel corner, (rows + 1, cols + 1) each, by GDAL/PROJ."""
    transform = dataset.GetGeoTransform()
    cols, rows = dataset.RasterXSize, dataset.RasterYSize
    source = dataset.GetSpatialRef()
    wgs84 = osr.SpatialReference()
    wgs84.ImportFromEPSG(4326)
    wgs84.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)  # (lon, lat)
    to_wgs84 = osr.CoordinateTransformation(source, wgs84)
    col, row = np.meshgrid(np.arange(cols + 1), np.arange(rows + 1))
    easting = transform[0] + col * transform[1] + row * transform[2]
    northing = transform[3] + col * transform[4] + row * transform[5]
    points = np.column_stack([easting.ravel(), northing.ravel()])
    lonlat = np.array(to_wgs84.TransformPoints(points))[:, :2]
    return lonlat[:, 0].reshape(easting.shape), lonlat[:, 1].reshape(easting.shape)


def decorate(ax, lon, lat, marks, title):
    ax.set_title(title, fontsize=10)
    mid_lat = float(np.mean(lat))
    ax.set_aspect(1.0 / math.cos(math.radians(mid_lat)))  # a chart's aspect at this latitude
    ax.grid(True, color="#3070c0", linewidth=0.6, alpha=0.7)
    ax.xaxis.set_major_formatter(plt.FuncFormatter(lambda v, _: dms(v, "E", "W")))
    ax.yaxis.set_major_formatter(plt.FuncFormatter(lambda v, _: dms(v, "N", "S")))
    ax.tick_params(labelsize=7)
    for label in ax.get_xticklabels():
        label.set_rotation(30)
    for lat_deg, lon_deg, text in marks:
        ax.plot(lon_deg, lat_deg, marker="+", color="red", markersize=12, mew=2)
        ax.annotate(text, (lon_deg, lat_deg), textcoords="offset points", xytext=(6, 6), color="red", fontsize=8)
    # scale bar: 10 m along the parallel, at the lower left
    metres_per_degree_lon = 111320.0 * math.cos(math.radians(mid_lat))
    length_m = 10.0
    x0 = float(lon.min()) + 0.05 * float(lon.max() - lon.min())
    y0 = float(lat.min()) + 0.06 * float(lat.max() - lat.min())
    ax.plot([x0, x0 + length_m / metres_per_degree_lon], [y0, y0], color="black", linewidth=3)
    ax.annotate(f"{length_m:g} m", (x0, y0), textcoords="offset points", xytext=(0, 5), fontsize=8)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("geotiff")
    parser.add_argument("png")
    parser.add_argument("--mark", action="append", default=[], help="LAT,LON[,TEXT]: a point to mark")
    args = parser.parse_args()
    dataset = gdal.Open(args.geotiff)
    lon, lat = corners_lonlat(dataset)
    occupancy = dataset.GetRasterBand(1).ReadAsArray()
    epsg = dataset.GetSpatialRef().GetAuthorityCode(None)
    marks = []
    for mark in args.mark:
        parts = mark.split(",")
        marks.append((float(parts[0]), float(parts[1]), parts[2] if len(parts) > 2 else ""))
    panels = 2 if dataset.RasterCount > 1 else 1
    fig, axes = plt.subplots(panels, 1, figsize=(11, 5.2 * panels), squeeze=False)
    classes = np.ma.masked_equal(occupancy, 0)  # no data: unknown, left blank (the chart shows through)
    ax = axes[0][0]
    ax.set_facecolor("#dfeaf5")  # the chart's water
    ax.pcolormesh(lon, lat, classes, cmap=ListedColormap(["#ffffff", "#000000"]), vmin=1, vmax=2, shading="flat")
    decorate(ax, lon, lat, marks,
             f"occupancy (band 1): white free, black occupied, blank unknown  |  EPSG:{epsg}, "
             f"{dataset.GetGeoTransform()[1]:g} m pixels")
    if panels == 2:
        intensity = np.ma.masked_equal(dataset.GetRasterBand(2).ReadAsArray(), 0)
        ax = axes[1][0]
        ax.set_facecolor("#dfeaf5")
        mesh = ax.pcolormesh(lon, lat, intensity, cmap="copper", vmin=1, vmax=255, shading="flat")
        fig.colorbar(mesh, ax=ax, shrink=0.8, label="echo intensity (0..255)")
        decorate(ax, lon, lat, marks, "echo-intensity mosaic (band 2): the loudest bin heard in each pixel")
    fig.suptitle(f"{args.geotiff.split('/')[-1]} laid on a latitude / longitude chart (WGS 84)", fontsize=11)
    fig.tight_layout()
    fig.savefig(args.png, dpi=110)


if __name__ == "__main__":
    main()
