/* dem.c — atmo_dem_load: a digital elevation model from a file into a metric height grid.
 *
 * The format is told by the first bytes (PNG's signature 89 50 4E 47 0D 0A 1A 0A, OpenEXR's
 * magic 76 2F 31 01, TIFF's "II*\0", "MM\0*" and BigTIFF's "II+\0", "MM\0+"); anything else goes
 * to GDAL when atmo has it (SRTM .hgt, ASCII grids, ...) and is refused otherwise. The readers
 * (dem_png.c, dem_exr.c, dem_gdal.c) give heights with missing samples as NaN; this file then
 * fills them from their neighbours and finds the range.
 *
 * Filling (dem.h): layer k holds every missing sample that has a known sample among its 8
 * neighbours once the layers before it are filled, and gives it the mean of those; a layer reads
 * only the values of the layers before, so the result does not depend on the order of the
 * samples. Layer k + 1 is found among the neighbours of layer k, so each sample is visited a
 * bounded number of times: linear in the grid, however large the holes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/dem.h"
#include "atmo/fileio.h"
#include "dem_read.h"

void atmo_dem_options_from_scene(const atmo_scene *s, atmo_dem_options *o)
{
    memset(o, 0, sizeof *o);
    o->extent_m = s->dem.extent_m;
    o->scale_m = s->dem.scale_m;
    o->offset_m = s->dem.offset_m;
    o->nodata = s->dem.nodata;
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
                         "terrain.heightmap_file_extent_m (metres)",
                         path, format);
    dem->extent_m[0] = o->extent_m;
    dem->extent_m[1] = o->extent_m * dem->height / dem->width;
    snprintf(dem->projection, sizeof dem->projection,
             "none (extent from terrain.heightmap_file_extent_m)");
    return ATMO_OK;
}

/* The missing samples that have a known 8-neighbour, each once (state 1 -> 2), appended to
 * order[*n...]; of the neighbours of order[from, to) or, with from == to == 0 and *n == 0, of
 * every known sample's missing neighbours (the first layer). */
static void next_layer(const atmo_dem *dem, unsigned char *state, size_t *order, size_t from,
                       size_t to, size_t *n)
{
    long w = dem->width, h = dem->height;
    for (size_t k = from; k < to; k++) {
        long x = (long)(order[k] % (size_t)w), z = (long)(order[k] / (size_t)w);
        for (long dz = -1; dz <= 1; dz++)
            for (long dx = -1; dx <= 1; dx++) {
                long xx = x + dx, zz = z + dz;
                size_t q = (size_t)zz * (size_t)w + (size_t)xx;
                if (xx >= 0 && xx < w && zz >= 0 && zz < h && state[q] == 1) {
                    state[q] = 2;
                    order[(*n)++] = q;
                }
            }
    }
}

/* Missing samples (non-finite) filled as the options say: from their neighbours (dem.h: layer
 * by layer from the known samples inward, each the mean of its known 8-neighbours; every sample
 * is visited once per layer it borders, so the work is linear in the grid) or with sea level.
 * ATMO_ERR_USAGE when no sample is known. */
static int fill_missing(const char *path, const atmo_dem_options *o, atmo_dem *dem, atmo_err *e)
{
    size_t n = (size_t)dem->width * (size_t)dem->height, missing = 0;
    long w = dem->width, hgt = dem->height;
    float *h = dem->heights_m;
    for (size_t i = 0; i < n; i++)
        missing += !isfinite(h[i]);
    dem->nodata_filled = missing;
    if (missing == 0)
        return ATMO_OK;
    if (missing == n)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s: every sample is nodata (or not finite); is it the right band/file?",
                         path);
    if (o->nodata == ATMO_DEM_NODATA_SEA_LEVEL) {
        for (size_t i = 0; i < n; i++)
            if (!isfinite(h[i]))
                h[i] = 0.0f;
        return ATMO_OK;
    }
    int rc = ATMO_OK;
    unsigned char *state = malloc(n); /* 0 known, 1 missing, 2 missing and in a layer */
    size_t *order = malloc(missing * sizeof *order);
    float *value = malloc(missing * sizeof *value);
    if (!state || !order || !value) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory filling the nodata samples of %s", path);
        goto cleanup;
    }
    size_t count = 0;
    for (size_t i = 0; i < n; i++)
        state[i] = !isfinite(h[i]);
    /* the first layer: missing samples next to a known one */
    for (size_t i = 0; i < n; i++) {
        if (state[i] != 1)
            continue;
        long x = (long)(i % (size_t)w), z = (long)(i / (size_t)w);
        int near_known = 0;
        for (long dz = -1; dz <= 1 && !near_known; dz++)
            for (long dx = -1; dx <= 1 && !near_known; dx++) {
                long xx = x + dx, zz = z + dz;
                near_known = xx >= 0 && xx < w && zz >= 0 && zz < hgt &&
                             state[(size_t)zz * (size_t)w + (size_t)xx] == 0;
            }
        if (near_known) {
            state[i] = 2;
            order[count++] = i;
        }
    }
    for (size_t begin = 0, end = count; begin < end; begin = end, end = count) {
        for (size_t k = begin; k < end; k++) { /* from the samples known before this layer */
            long x = (long)(order[k] % (size_t)w), z = (long)(order[k] / (size_t)w);
            double sum = 0;
            int known = 0;
            for (long dz = -1; dz <= 1; dz++)
                for (long dx = -1; dx <= 1; dx++) {
                    long xx = x + dx, zz = z + dz;
                    size_t q = (size_t)zz * (size_t)w + (size_t)xx;
                    if (xx >= 0 && xx < w && zz >= 0 && zz < hgt && state[q] == 0) {
                        sum += (double)h[q];
                        known++;
                    }
                }
            value[k] = (float)(sum / known);
        }
        for (size_t k = begin; k < end; k++) {
            h[order[k]] = value[k];
            state[order[k]] = 0;
        }
        next_layer(dem, state, order, begin, end, &count);
    }
cleanup:
    free(state);
    free(order);
    free(value);
    return rc;
}

/* The reader for the file's first bytes. */
static int read_by_signature(const char *path, const atmo_dem_options *o, atmo_dem *dem,
                             atmo_err *e)
{
    unsigned char magic[8] = {0};
    const char *why = NULL;
    FILE *f = atmo_open_regular(path, &why); /* a FIFO would block for ever */
    if (!f)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "cannot open heightmap '%s' (terrain.heightmap_file): %s; check the "
                         "path", path, why);
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

/* Every known (finite) sample within +-ATMO_DEM_MAX_HEIGHT_M. */
static int check_heights(const char *path, const atmo_dem *dem, atmo_err *e)
{
    size_t n = (size_t)dem->width * (size_t)dem->height;
    for (size_t i = 0; i < n; i++) {
        double h = dem->heights_m[i];
        if (isfinite(h) && fabs(h) > ATMO_DEM_MAX_HEIGHT_M)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "%s: the sample at column %zu, row %zu is %g m, beyond +-%g m; "
                             "check terrain.heightmap_scale_m and terrain.heightmap_offset_m, or "
                             "mark it as the file's no-data value",
                             path, i % (size_t)dem->width, i / (size_t)dem->width, h,
                             ATMO_DEM_MAX_HEIGHT_M);
    }
    return ATMO_OK;
}

int atmo_dem_load(const char *path, const atmo_dem_options *o, atmo_dem *dem, atmo_err *e)
{
    memset(dem, 0, sizeof *dem);
    int rc = read_by_signature(path, o, dem, e);
    if (rc == ATMO_OK)
        rc = check_heights(path, dem, e);
    if (rc == ATMO_OK)
        rc = fill_missing(path, o, dem, e);
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
