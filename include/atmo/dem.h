/* dem.h — digital elevation models: a height file read into a metric grid, and its resampling.
 *
 * atmo_dem_load reads one of
 *   - GeoTIFF (or another raster GDAL reads), when atmo is built with GDAL (libgdal-dev):
 *     band 1 with the band's scale and offset applied, heights in metres (a band unit of feet is
 *     converted), the extent from the geotransform: a projected CRS's linear unit converted to
 *     metres (metres used as is), a geographic CRS's degrees converted at the grid's centre
 *     latitude on the CRS's ellipsoid; no CRS, a local/engineering CRS, a CRS neither projected
 *     nor geographic, or a rotated geotransform is refused;
 *   - 16-bit (or 8-bit) greyscale PNG: height = offset_m + scale_m * v / vmax (vmax = 65535 or
 *     255), extent from the options;
 *   - OpenEXR with one channel (float, half or uint): heights in metres, extent from the options.
 * The format is told by the file's first bytes, not its name.
 *
 * The grid: width x height samples at the centres of square-or-not cells ("pixel is area"),
 * row 0 the northern edge, column 0 the western edge; heights_m[row * width + col] in metres
 * above sea level. In the world (Y up) the grid lies in the X-Z plane with +X east and +Z north,
 * the camera's frame (kernels/common/camera.h: right x up = forward), so a camera looking north
 * (camera.yaw_deg = 0) has east on its right and sun.azimuth_deg is a compass bearing; its
 * centre at the scene's terrain.heightmap_center_m.
 *
 * Missing samples (GDAL's nodata value, alpha 0 in a PNG, or a non-finite value in any format)
 * are filled, as the options say (terrain.heightmap_nodata):
 *   - from their neighbours (the default, for voids in the data such as SRTM's): layer by layer
 *     from the rim of each hole inward, each sample the mean of its known 8-neighbours, so a
 *     hole takes the heights around it;
 *   - with sea level, 0 m (for DEMs whose sea is nodata, e.g. coastal tiles).
 * A grid with no known sample is refused, and so is a known sample beyond +-ATMO_DEM_MAX_HEIGHT_M
 * (100 km: ten times Everest's height or the Mariana Trench's depth), which is a wrong scale,
 * offset or an undeclared no-data value rather than a height; the message names the sample.
 *
 * Limits: each side at most ATMO_DEM_MAX_SIDE and the grid at most ATMO_DEM_MAX_SAMPLES
 * samples (256 MiB of floats on the host); larger files are refused with one line naming the
 * size and the limit before their data are read. (The device's limit applies to the resampled
 * heightmap, which the plan checks against the device's maximum allocation.)
 *
 * Errors are one line (status.h): what, which file, how to fix; ATMO_ERR_USAGE for every
 * problem of the file or the options, ATMO_ERR_RUNTIME for out of memory. */
#ifndef ATMO_DEM_H
#define ATMO_DEM_H
#include <stddef.h>
#include "atmo/scene.h"
#include "atmo/status.h"

#define ATMO_DEM_MAX_SIDE 32768
#define ATMO_DEM_MAX_HEIGHT_M 1e5
#define ATMO_DEM_MAX_SAMPLES ((size_t)1 << 26)

typedef enum { ATMO_DEM_GEOTIFF = 0, ATMO_DEM_PNG = 1, ATMO_DEM_EXR = 2 } atmo_dem_format;

typedef enum { ATMO_DEM_NODATA_NEIGHBOURS = 0, ATMO_DEM_NODATA_SEA_LEVEL = 1 } atmo_dem_nodata;

typedef struct atmo_dem {
    int width, height;         /* samples along X (east) and -Z (south) */
    float *heights_m;          /* width * height, row 0 north; malloc'd, atmo_dem_free */
    double extent_m[2];        /* size of the whole grid along X and Z, metres */
    double min_m, max_m;       /* lowest and highest height after filling */
    int format;                /* atmo_dem_format */
    char format_name[32];      /* "GeoTIFF", "PNG 16-bit", "EXR half" ... (GDAL: its driver) */
    char projection[256];      /* the CRS's name and how the extent was found */
    int geographic;            /* 1: extent converted from degrees at centre_lat_deg */
    double centre_lat_deg;     /* geographic only */
    size_t nodata_filled;      /* samples that were missing and were filled */
} atmo_dem;

/* How to read the heights of formats that carry no georeference (PNG, EXR). */
typedef struct atmo_dem_options {
    double extent_m;           /* X extent of a PNG/EXR grid (Z: extent_m * height / width);
                                  0 = not given (PNG/EXR refused; GeoTIFF uses its own) */
    double scale_m, offset_m;  /* PNG: height = offset_m + scale_m * v / vmax */
    int nodata;                /* atmo_dem_nodata: how missing samples are filled */
    size_t max_samples;        /* 0: ATMO_DEM_MAX_SAMPLES */
} atmo_dem_options;

/* The options a scene gives (its terrain.heightmap_* keys). */
void atmo_dem_options_from_scene(const atmo_scene *s, atmo_dem_options *o);

/* Read path into dem (zeroed first; on failure nothing is left to release). */
int atmo_dem_load(const char *path, const atmo_dem_options *o, atmo_dem *dem, atmo_err *e);
void atmo_dem_free(atmo_dem *dem);

/* Whether atmo was built with GDAL (GeoTIFF). */
int atmo_dem_have_gdal(void);

typedef enum { ATMO_DEM_BILINEAR = 0, ATMO_DEM_BICUBIC = 1 } atmo_dem_filter;

/* A target grid in the DEM's own frame (metres from the DEM's centre, +X east, +Z north):
 * sample (i, j) at (x0_m + i * dx_m, z0_m + j * dz_m), written to out[j * width + i], or with
 * `derivatives` to out[3 (j * width + i) + 0, 1, 2] = h, dh/dx, dh/dz (the layout of a height
 * + derivatives heightmap). */
typedef struct atmo_dem_grid {
    int width, height;
    double x0_m, z0_m;
    double dx_m, dz_m;
    int derivatives;
} atmo_dem_grid;

/* The height at (x_m, z_m) of the DEM's frame, interpolated between the sample centres:
 * bilinear, or bicubic (Keys' cubic convolution, a = -1/2: third-order accurate, C1). Outside
 * the outermost sample centres the edge samples are extended (indices clamped). */
double atmo_dem_sample(const atmo_dem *dem, double x_m, double z_m, int filter);
/* The same height and its gradient (dh/dx, dh/dz, dimensionless) from the interpolant's
 * derivative: bilinear's is constant across each cell's x or z, bicubic's continuous. */
double atmo_dem_sample_gradient(const atmo_dem *dem, double x_m, double z_m, int filter,
                                double gradient[2]);

/* Fill out (grid->width * grid->height floats, three times that with derivatives) with
 * atmo_dem_sample_gradient at the grid's points. */
int atmo_dem_resample(const atmo_dem *dem, const atmo_dem_grid *grid, int filter, float *out,
                      atmo_err *e);

#endif
