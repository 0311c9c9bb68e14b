/* dem_read.h — the format readers of atmo_dem_load (dem.c), private to host/terrain/.
 *
 * Each reader fills dem->width, height, heights_m (malloc'd, row 0 north, metres; a missing
 * sample as NaN, which dem.c fills from its neighbours), extent_m, format, format_name and
 * projection, after checking the size with dem_check_size before reading any data. On failure
 * it releases what it allocated and returns the status with the one-line error. */
#ifndef ATMO_DEM_READ_H
#define ATMO_DEM_READ_H
#include "atmo/dem.h"

/* ATMO_ERR_USAGE unless 1 <= width, height <= ATMO_DEM_MAX_SIDE and width * height <= the
 * options' limit; the message names the file, its size and the limit. */
int dem_check_size(const char *path, const char *format, long width, long height,
                   const atmo_dem_options *o, atmo_err *e);
/* The X and Z extent of a grid without a georeference: options' extent_m, Z by the aspect. */
int dem_extent_from_options(const char *path, const char *format, const atmo_dem_options *o,
                            atmo_dem *dem, atmo_err *e);

int dem_read_png(const char *path, const atmo_dem_options *o, atmo_dem *dem, atmo_err *e);
int dem_read_exr(const char *path, const atmo_dem_options *o, atmo_dem *dem, atmo_err *e);
/* Only where atmo is built with GDAL (ATMO_HAVE_GDAL). */
int dem_read_gdal(const char *path, const atmo_dem_options *o, atmo_dem *dem, atmo_err *e);

#endif
