#!/usr/bin/env python3
"""make_test_dem.py — tests/data/jacksboro_fault_dem.tif from matplotlib's sample DEM.

usage: tools/make_test_dem.py MATPLOTLIB_WHEEL_OR_NPZ tests/data/jacksboro_fault_dem.tif

Reads mpl-data/sample_data/jacksboro_fault_dem.npz (from a matplotlib wheel, e.g. `pip download
--no-deps matplotlib==3.10.0`, or the .npz itself): 'elevation' (int16 metres, 344 x 403, rows
as stored), 'dx', 'dy' (degrees per sample) and the bounds 'xmin', 'xmax' (longitude) and
'ymin', 'ymax' (latitude; the file's 'ymin' is the larger, northern one). It writes the grid
unchanged as a GeoTIFF by hand (TIFF 6.0 with the GeoTIFF 1.0 keys: geographic model, pixel is
area, WGS 84 = EPSG:4326; ModelTiepoint at the north-west corner, ModelPixelScale dx, dy;
16-bit signed samples in deflate-compressed strips), so no GDAL tools are needed, and prints
the facts tests/data/README.md and tests/test_dem.c state: size, range, spot values. Needs only
Python's standard library (the .npy members are parsed directly).
"""
import ast
import io
import struct
import sys
import zipfile
import zlib


def npz_arrays(path):
    z = zipfile.ZipFile(path)
    names = z.namelist()
    if "elevation.npy" not in names:  # a wheel: the sample file inside it
        inner = [n for n in names if n.endswith("sample_data/jacksboro_fault_dem.npz")][0]
        z = zipfile.ZipFile(io.BytesIO(z.read(inner)))
    out = {}
    for n in z.namelist():
        b = z.read(n)
        assert b[:6] == b"\x93NUMPY", n
        if b[6] == 1:
            hl, off = struct.unpack("<H", b[8:10])[0], 10
        else:
            hl, off = struct.unpack("<I", b[8:12])[0], 12
        hdr = ast.literal_eval(b[off:off + hl].decode())
        data = b[off + hl:]
        code = {"<i2": "h", "<f8": "d"}[hdr["descr"]]
        count = len(data) // struct.calcsize(code)
        values = struct.unpack("<%d%s" % (count, code), data)
        out[n[:-4]] = (hdr["shape"], values if hdr["shape"] else values[0])
    return out


def geotiff(width, height, samples, west, north, dx, dy):
    rows_per_strip = 16
    strips = []
    for r in range(0, height, rows_per_strip):
        rows = samples[r * width:min(height, r + rows_per_strip) * width]
        strips.append(zlib.compress(struct.pack("<%dh" % len(rows), *rows), 9))
    geokeys = [1, 1, 0, 4,  # version 1.1.0, 4 keys
               1024, 0, 1, 2,     # GTModelTypeGeoKey = ModelTypeGeographic
               1025, 0, 1, 1,     # GTRasterTypeGeoKey = RasterPixelIsArea
               2048, 0, 1, 4326,  # GeographicTypeGeoKey = WGS 84
               2054, 0, 1, 9102]  # GeogAngularUnitsGeoKey = degree
    data = bytearray(b"II*\0" + struct.pack("<I", 0))
    def put(blob):
        while len(data) % 2:
            data.append(0)
        at = len(data)
        data.extend(blob)
        return at
    strip_at = [put(s) for s in strips]
    offsets_at = put(struct.pack("<%dI" % len(strips), *strip_at))
    counts_at = put(struct.pack("<%dI" % len(strips), *[len(s) for s in strips]))
    scale_at = put(struct.pack("<3d", dx, dy, 0.0))
    tie_at = put(struct.pack("<6d", 0.0, 0.0, 0.0, west, north, 0.0))
    keys_at = put(struct.pack("<%dH" % len(geokeys), *geokeys))
    entries = [  # tag, type (3 short, 4 long, 12 double), count, value or offset
        (256, 4, 1, width), (257, 4, 1, height), (258, 3, 1, 16), (259, 3, 1, 8),
        (262, 3, 1, 1), (273, 4, len(strips), offsets_at), (277, 3, 1, 1),
        (278, 4, 1, rows_per_strip), (279, 4, len(strips), counts_at), (284, 3, 1, 1),
        (339, 3, 1, 2), (33550, 12, 3, scale_at), (33922, 12, 6, tie_at),
        (34735, 3, len(geokeys), keys_at)]
    ifd = struct.pack("<H", len(entries))
    for tag, typ, count, value in entries:
        if typ == 3 and count == 1:
            ifd += struct.pack("<HHIHH", tag, typ, count, value, 0)
        else:
            ifd += struct.pack("<HHII", tag, typ, count, value)
    ifd += struct.pack("<I", 0)
    ifd_at = put(ifd)
    data[4:8] = struct.pack("<I", ifd_at)
    return bytes(data)


def main():
    a = npz_arrays(sys.argv[1])
    (height, width), z = a["elevation"]
    dx, dy = a["dx"][1], a["dy"][1]
    west, north = a["xmin"][1], max(a["ymin"][1], a["ymax"][1])
    assert abs(west + width * dx - a["xmax"][1]) < 1e-9
    assert abs(north - height * dy - min(a["ymin"][1], a["ymax"][1])) < 1e-9
    open(sys.argv[2], "wb").write(geotiff(width, height, z, west, north, dx, dy))
    print("%d x %d samples, %.9g deg cells, west %.9g, north %.9g, heights %d .. %d m" %
          (width, height, dx, west, north, min(z), max(z)))
    for r, c in [(0, 0), (height // 2, width // 2), (height - 1, width - 1), (100, 300)]:
        print("sample row %d col %d: %d m" % (r, c, z[r * width + c]))


if __name__ == "__main__":
    main()
