/* dem.c — atmo_dem_load: a digital elevation model from a file into a metric height grid.
 *
 * The format is told by the first bytes (PNG's signature 89 50 4E 47 0D 0A 1A 0A, OpenEXR's
 * magic 76 2F 31 01, TIFF's "II*\0", "MM\0*" and BigTIFF's "II+\0", "MM\0+"); anything else goes
 * to GDAL when atmo has it (SRTM .hgt, ASCII grids, ...) and is refused otherwise. The readers
 * (dem_png.c, dem_exr.c, dem_gdal.c) give heights with missing samples as NaN; this file then
 * fills them from their neighbours and finds the range.
 *
 * Filling (dem.h): pass k takes every missing sample that has at least one known sample among
 * its 8 neighbours after pass k-1 and gives it the mean of those; a pass reads only the values of
 * the pass before, so the result does not depend on the order of the samples. The passes end when
 * no sample is missing; a hole of radius r closes in about r passes, each visiting only the
 * samples still missing. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/dem.h"
#include "dem_read.h"

void atmo_dem_options_from_scene(const atmo_scene *s, atmo_dem_options *o)
{
    memset(o, 0, sizeof *o);
    o->extent_m = s->dem.extent_m;
    o->scale_m = s->dem.scale_m;
    o->offset_m = s->dem.offset_m;
}

int atmo_dem_have_gdal(void)
{
#ifdef ATMO_HAVE_GDAL
    return 1;
#else
    return 0;
#endif
}

void atmo_dem_free(atmo_dem *dem)
{
    free(dem->heights_m);
    memset(dem, 0, sizeof *dem);
}

int dem_check_size(const char *path, const char *format, long width, long height,
                   const atmo_dem_options *o, atmo_err *e)
{
    size_t limit = o->max_samples ? o->max_samples : ATMO_DEM_MAX_SAMPLES;
    if (width < 1 || height < 1)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s: the %s has no samples (%ld x %ld); is it a DEM?",
                         path, format, width, height);
    if (width > ATMO_DEM_MAX_SIDE || height > ATMO_DEM_MAX_SIDE ||
        (size_t)width * (size_t)height > limit)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s: the %s is %ld x %ld samples, beyond the limit of %d per side and "
                         "%zu samples in all; cut or downsample it (e.g. gdal_translate -outsize)",
                         path, format, width, height, ATMO_DEM_MAX_SIDE, limit);
    return ATMO_OK;
}

int dem_extent_from_options(const char *path, const char *format, const atmo_dem_options *o,
                            atmo_dem *dem, atmo_err *e)
{
    if (!(o->extent_m > 0))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s: the %s carries no georeference; give its east-west size with "
                         "terrain.heightmap_extent_m (metres)",
                         path, format);
    dem->extent_m[0] = o->extent_m;
    dem->extent_m[1] = o->extent_m * dem->height / dem->width;
    snprintf(dem->projection, sizeof dem->projection,
             "none (extent from terrain.heightmap_extent_m)");
    return ATMO_OK;
}

/* Missing samples (NaN) from their neighbours; ATMO_ERR_USAGE when there is no known one. */
static int fill_missing(const char *path, atmo_dem *dem, atmo_err *e)
{
    size_t n = (size_t)dem->width * (size_t)dem->height, missing = 0;
    float *h = dem->heights_m;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(h[i])) {
            h[i] = NAN;
            missing++;
        }
    dem->nodata_filled = missing;
    if (missing == 0)
        return ATMO_OK;
    if (missing == n)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s: every sample is nodata (or not finite); is it the right band/file?",
                         path);
    int rc = ATMO_OK;
    size_t *todo = malloc(missing * sizeof *todo);
    float *value = malloc(missing * sizeof *value);
    if (!todo || !value) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory filling the nodata samples of %s", path);
        goto cleanup;
    }
    size_t count = 0;
    for (size_t i = 0; i < n; i++)
        if (isnan(h[i]))
            todo[count++] = i;
    while (count > 0) {
        /* this pass's values, from the known samples of the passes before */
        for (size_t k = 0; k < count; k++) {
            long x = (long)(todo[k] % (size_t)dem->width), z = (long)(todo[k] / (size_t)dem->width);
            double sum = 0;
            int known = 0;
            for (long dz = -1; dz <= 1; dz++)
                for (long dx = -1; dx <= 1; dx++) {
                    long xx = x + dx, zz = z + dz;
                    if ((dx || dz) && xx >= 0 && xx < dem->width && zz >= 0 && zz < dem->height) {
                        float v = h[(size_t)zz * (size_t)dem->width + (size_t)xx];
                        if (!isnan(v)) {
                            sum += (double)v;
                            known++;
                        }
                    }
                }
            value[k] = known ? (float)(sum / known) : NAN;
        }
        size_t left = 0;
        for (size_t k = 0; k < count; k++) {
            if (isnan(value[k]))
                todo[left++] = todo[k];
            else
                h[todo[k]] = value[k];
        }
        count = left;
    }
cleanup:
    free(todo);
    free(value);
    return rc;
}

/* The reader for the file's first bytes. */
static int read_by_signature(const char *path, const atmo_dem_options *o, atmo_dem *dem,
                             atmo_err *e)
{
    unsigned char magic[8] = {0};
    FILE *f = fopen(path, "rb");
    if (!f)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "cannot open heightmap '%s' (terrain.heightmap_file); check the path",
                         path);
    size_t got = fread(magic, 1, sizeof magic, f);
    fclose(f);
    static const unsigned char png[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
    static const unsigned char exr[4] = {0x76, 0x2f, 0x31, 0x01};
    if (got == 8 && memcmp(magic, png, 8) == 0)
        return dem_read_png(path, o, dem, e);
    if (got >= 4 && memcmp(magic, exr, 4) == 0)
        return dem_read_exr(path, o, dem, e);
    int tiff = got >= 4 && ((magic[0] == 'I' && magic[1] == 'I' && magic[3] == 0 &&
                             (magic[2] == 42 || magic[2] == 43)) ||
                            (magic[0] == 'M' && magic[1] == 'M' && magic[2] == 0 &&
                             (magic[3] == 42 || magic[3] == 43)));
#ifdef ATMO_HAVE_GDAL
    (void)tiff;
    return dem_read_gdal(path, o, dem, e);
#else
    if (tiff)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s is a TIFF, and this atmo was built without GDAL; install libgdal-dev "
                         "and rebuild (cmake finds it), or convert the DEM to a 16-bit PNG",
                         path);
    return atmo_fail(e, ATMO_ERR_USAGE,
                     "%s is not a PNG or EXR heightmap (and this atmo was built without GDAL, "
                     "which reads GeoTIFF and other DEM formats: install libgdal-dev and rebuild)",
                     path);
#endif
}

int atmo_dem_load(const char *path, const atmo_dem_options *o, atmo_dem *dem, atmo_err *e)
{
    memset(dem, 0, sizeof *dem);
    int rc = read_by_signature(path, o, dem, e);
    if (rc == ATMO_OK)
        rc = fill_missing(path, dem, e);
    if (rc != ATMO_OK) {
        atmo_dem_free(dem);
        return rc;
    }
    size_t n = (size_t)dem->width * (size_t)dem->height;
    dem->min_m = dem->max_m = dem->heights_m[0];
    for (size_t i = 1; i < n; i++) {
        double h = dem->heights_m[i];
        if (h < dem->min_m)
            dem->min_m = h;
        if (h > dem->max_m)
            dem->max_m = h;
    }
    return ATMO_OK;
}
