/* dem_gdal.c — a GeoTIFF (or any raster GDAL reads: SRTM .hgt, ASCII grids, ...) as heights in
 * metres with its extent in metres, through GDAL's C API. Built only with GDAL (ATMO_HAVE_GDAL).
 *
 * A file with more than one band is refused (which band holds heights is the user's to say),
 * and so are terrain.heightmap_file_extent_m and terrain.heightmap_offset_m, which only PNG
 * and EXR heightmaps use: the file's georeference and band scale would silently override them.
 * Heights: band 1 as float, h = v * scale + offset with the band's scale and offset (1 and 0
 * when it has none), times 0.3048 when the band's unit is the foot (1200/3937 for the US survey
 * foot); a unit other than metres or feet is refused. The band's nodata value marks missing
 * samples (dem.c fills them from their neighbours).
 *
 * Extent: from the geotransform (x = gt0 + col gt1 + row gt2, y = gt3 + col gt4 + row gt5).
 * gt2 or gt4 non-zero (a rotated or sheared grid) is refused; a negative gt1 or a positive gt5
 * flips the columns or rows so that column 0 is west and row 0 north. Then
 *   - a projected CRS: extent = size * |cell| * the CRS's linear unit in metres (1 for metres);
 *   - a geographic CRS (x longitude, y latitude, GeoTIFF's order): the cell in degrees times
 *     the length of a degree at the grid's centre latitude phi on the CRS's ellipsoid
 *     (semi-major axis a, eccentricity e^2 = f (2 - f)):
 *       north-south  M(phi) pi/180,        M = a (1 - e^2) / (1 - e^2 sin^2 phi)^(3/2)
 *       east-west    N(phi) cos(phi) pi/180, N = a / (1 - e^2 sin^2 phi)^(1/2)
 *     (the meridional and prime-vertical radii of curvature; e.g. Torge & Mueller, Geodesy,
 *     4th ed., eq. 4.15 and 4.20). A grid spanning many degrees is flattened at its centre,
 *     so distances at its northern and southern edges are off by the change of cos(phi).
 *   - no CRS, a local (engineering) CRS, or one neither projected nor geographic (geocentric):
 *     refused, since the grid cannot be placed in metres.
 * GDAL's messages are collected into the one-line error instead of being printed. */
#ifdef ATMO_HAVE_GDAL
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>
#include "dem_read.h"

#define PI 3.14159265358979323846

typedef struct {
    char msg[256];
} gdal_log;

/* Keep the first failure's message; warnings are not shown. */
static void on_error(CPLErr level, CPLErrorNum code, const char *msg)
{
    gdal_log *log = CPLGetErrorHandlerUserData();
    if (log && level >= CE_Failure && log->msg[0] == '\0')
        snprintf(log->msg, sizeof log->msg, "%s", msg ? msg : "unknown GDAL error");
    (void)code;
}

/* Metres per unit of the band's heights, or 0 for a unit atmo does not know. */
static double height_unit_m(const char *unit)
{
    if (!unit || !unit[0] || !strcmp(unit, "m") || !strcmp(unit, "metre") ||
        !strcmp(unit, "meter") || !strcmp(unit, "metres") || !strcmp(unit, "meters"))
        return 1;
    if (!strcmp(unit, "ft") || !strcmp(unit, "foot") || !strcmp(unit, "feet"))
        return 0.3048;
    if (!strcmp(unit, "US survey foot") || !strcmp(unit, "ft_US") || !strcmp(unit, "us-ft"))
        return 1200.0 / 3937.0;
    return 0;
}

/* "EPSG:32633 WGS 84 / UTM zone 33N" */
static void crs_name(OGRSpatialReferenceH srs, char *buf, size_t n)
{
    const char *auth = OSRGetAuthorityName(srs, NULL), *code = OSRGetAuthorityCode(srs, NULL);
    const char *name = OSRGetName(srs);
    if (auth && code)
        snprintf(buf, n, "%s:%s %s", auth, code, name ? name : "");
    else
        snprintf(buf, n, "%s", name ? name : "unnamed CRS");
}

/* The extent in metres from the geotransform and the CRS; fills dem->extent_m, projection. */
static int extent_m(const char *path, GDALDatasetH ds, const double gt[6], atmo_dem *dem,
                    atmo_err *e)
{
    OGRSpatialReferenceH srs = GDALGetSpatialRef(ds);
    char name[128];
    if (!srs)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s has no coordinate reference system, so its extent in metres is "
                         "unknown; assign one (gdal_edit.py -a_srs EPSG:...) or convert it to a "
                         "16-bit PNG with terrain.heightmap_file_extent_m",
                         path);
    crs_name(srs, name, sizeof name);
    if (OSRIsLocal(srs) || (!OSRIsProjected(srs) && !OSRIsGeographic(srs)))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s: its coordinate reference system '%s' is %s, not projected or "
                         "geographic; reproject it (gdalwarp -t_srs EPSG:...)",
                         path, name,
                         OSRIsLocal(srs)        ? "a local (engineering) one"
                         : OSRIsGeocentric(srs) ? "geocentric"
                                                : "of a kind atmo cannot place");
    double cell_x = fabs(gt[1]), cell_z = fabs(gt[5]);
    if (OSRIsProjected(srs)) {
        char *unit = NULL;
        double to_m = OSRGetLinearUnits(srs, &unit);
        if (!(to_m > 0))
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "%s: the projected CRS '%s' has no linear unit; reproject it", path,
                             name);
        dem->extent_m[0] = dem->width * cell_x * to_m;
        dem->extent_m[1] = dem->height * cell_z * to_m;
        snprintf(dem->projection, sizeof dem->projection, "%s (projected, %s)", name,
                 unit ? unit : "?");
        return ATMO_OK;
    }
    char *unit = NULL;
    double rad = OSRGetAngularUnits(srs, &unit);
    OGRErr err_a = OGRERR_NONE, err_f = OGRERR_NONE;
    double a = OSRGetSemiMajor(srs, &err_a), inv_f = OSRGetInvFlattening(srs, &err_f);
    if (!(rad > 0) || err_a != OGRERR_NONE || err_f != OGRERR_NONE || !(a > 0))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s: the geographic CRS '%s' lacks its angular unit or ellipsoid; "
                         "reproject it (gdalwarp -t_srs EPSG:4326)",
                         path, name);
    double deg = rad * 180.0 / PI; /* degrees per unit */
    double lat = (gt[3] + gt[5] * dem->height / 2.0) * deg;
    if (!(fabs(lat) <= 90))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s: its centre latitude %.9g deg is not within -90 .. 90; is the "
                         "geotransform right?",
                         path, lat);
    double f = inv_f > 0 ? 1.0 / inv_f : 0.0; /* inv_f 0: a sphere */
    double e2 = f * (2.0 - f), s = sin(lat * PI / 180.0), w = 1.0 - e2 * s * s;
    double per_deg_ns = a * (1.0 - e2) / (w * sqrt(w)) * PI / 180.0;
    double per_deg_ew = a / sqrt(w) * cos(lat * PI / 180.0) * PI / 180.0;
    dem->extent_m[0] = dem->width * cell_x * deg * per_deg_ew;
    dem->extent_m[1] = dem->height * cell_z * deg * per_deg_ns;
    dem->geographic = 1;
    dem->centre_lat_deg = lat;
    snprintf(dem->projection, sizeof dem->projection,
             "%s (geographic, degrees converted at latitude %.6f)", name, lat);
    return ATMO_OK;
}

/* Band 1 into dem->heights_m, flipped to row 0 north and column 0 west, nodata as NaN. On
 * failure dem->heights_m may hold a block, which atmo_dem_load releases. */
static int read_heights(const char *path, GDALDatasetH ds, const double gt[6], atmo_dem *dem,
                        gdal_log *log, atmo_err *e)
{
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    double to_m = height_unit_m(GDALGetRasterUnitType(band));
    if (to_m == 0)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s: band 1's heights are in '%s', which atmo does not know; give them "
                         "in metres (gdal_translate -scale)",
                         path, GDALGetRasterUnitType(band));
    int has_scale = 0, has_offset = 0, has_nodata = 0;
    double scale = GDALGetRasterScale(band, &has_scale);
    double offset = GDALGetRasterOffset(band, &has_offset);
    double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
    if (!has_scale)
        scale = 1;
    if (!has_offset)
        offset = 0;
    size_t w = (size_t)dem->width, h = (size_t)dem->height;
    float *z = malloc(w * h * sizeof *z);
    if (!z)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading %s (%zu x %zu)", path, w, h);
    dem->heights_m = z; /* released by atmo_dem_load on failure */
    if (GDALRasterIO(band, GF_Read, 0, 0, dem->width, dem->height, z, dem->width, dem->height,
                     GDT_Float32, 0, 0) != CE_None)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s: its heights cannot be read: %s; is the file "
                         "complete?", path, log->msg[0] ? log->msg : "GDAL gave no reason");
    float missing = (float)nodata; /* compared as GDAL stored it: in the band's float values */
    for (size_t i = 0; i < w * h; i++) {
        int is_missing = has_nodata && (z[i] == missing || (isnan(missing) && isnan(z[i])));
        z[i] = is_missing ? NAN : (float)(((double)z[i] * scale + offset) * to_m);
    }
    /* in place, so a grid needs its own size in memory and no more */
    if (gt[5] > 0)
        for (size_t r = 0; r < h / 2; r++)
            for (size_t c = 0; c < w; c++) {
                float t = z[r * w + c];
                z[r * w + c] = z[(h - 1 - r) * w + c];
                z[(h - 1 - r) * w + c] = t;
            }
    if (gt[1] < 0)
        for (size_t r = 0; r < h; r++)
            for (size_t c = 0; c < w / 2; c++) {
                float t = z[r * w + c];
                z[r * w + c] = z[r * w + w - 1 - c];
                z[r * w + w - 1 - c] = t;
            }
    return ATMO_OK;
}

int dem_read_gdal(const char *path, const atmo_dem_options *o, atmo_dem *dem, atmo_err *e)
{
    int rc = ATMO_OK;
    gdal_log log = {""};
    GDALAllRegister();
    CPLPushErrorHandlerEx(on_error, &log);
    GDALDatasetH ds = GDALOpenEx(path, GDAL_OF_RASTER | GDAL_OF_READONLY, NULL, NULL, NULL);
    if (!ds) {
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "%s is not an elevation model GDAL can read (%s); give a GeoTIFF, a "
                       "16-bit PNG or an EXR",
                       path, log.msg[0] ? log.msg : "no GDAL driver recognises it");
        goto cleanup;
    }
    const char *driver = GDALGetDriverShortName(GDALGetDatasetDriver(ds));
    if (strcmp(driver, "GTiff") == 0)
        driver = "GeoTIFF";
    long width = GDALGetRasterXSize(ds), height = GDALGetRasterYSize(ds);
    if (GDALGetRasterCount(ds) < 1) {
        rc = atmo_fail(e, ATMO_ERR_USAGE, "%s (%s) has no raster band; is it a DEM?", path,
                       driver);
        goto cleanup;
    }
    if (GDALGetRasterCount(ds) > 1) {
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "%s (%s) has %d bands; a heightmap is one band of heights (take the one "
                       "you mean: gdal_translate -b N)",
                       path, driver, GDALGetRasterCount(ds));
        goto cleanup;
    }
    if (o->extent_m > 0.0 || o->offset_m != 0.0) {
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "%s (%s) carries its own extent and heights; terrain.heightmap_file_%s "
                       "is for PNG and EXR heightmaps, leave it out",
                       path, driver, o->extent_m > 0.0 ? "extent_m" : "offset_m");
        goto cleanup;
    }
    rc = dem_check_size(path, driver, width, height, o, e);
    if (rc)
        goto cleanup;
    double gt[6];
    if (GDALGetGeoTransform(ds, gt) != CE_None) {
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "%s (%s) has no geotransform, so its extent is unknown; georeference it "
                       "or convert it to a 16-bit PNG with terrain.heightmap_file_extent_m",
                       path, driver);
        goto cleanup;
    }
    if (gt[2] != 0 || gt[4] != 0) {
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "%s: its geotransform is rotated (terms %.9g, %.9g); resample it north "
                       "up (gdalwarp)",
                       path, gt[2], gt[4]);
        goto cleanup;
    }
    if (gt[1] == 0 || gt[5] == 0 || !isfinite(gt[1]) || !isfinite(gt[5])) {
        rc = atmo_fail(e, ATMO_ERR_USAGE, "%s: its geotransform has a cell size of %.9g x %.9g; "
                       "georeference it again", path, gt[1], gt[5]);
        goto cleanup;
    }
    dem->width = (int)width;
    dem->height = (int)height;
    rc = extent_m(path, ds, gt, dem, e);
    if (rc == ATMO_OK)
        rc = read_heights(path, ds, gt, dem, &log, e);
    if (rc == ATMO_OK) {
        dem->format = ATMO_DEM_GEOTIFF;
        snprintf(dem->format_name, sizeof dem->format_name, "%s", driver);
    }
cleanup:
    if (ds)
        GDALClose(ds);
    CPLPopErrorHandler();
    return rc;
}
#endif
