/* dem_resample.c — heights of a DEM between its samples: bilinear and bicubic interpolation,
 * and the resampling of a whole grid (what the heightmap pass uploads as a host table).
 *
 * Sample (col, row) of a W x H grid with extent (X, Z) sits at the centre of its cell:
 *   x = (col + 1/2) X / W - X / 2,   z = Z / 2 - (row + 1/2) Z / H   (DEM frame, dem.h: row 0
 * north at +Z), so a point's continuous index is u = (x + X/2) W / X - 1/2 and
 * v = (Z/2 - z) H / Z - 1/2, and with
 * i = floor(u), t = u - i:
 *   bilinear  h = sum over the 2 x 2 samples i..i+1 of (1 - t, t) x (1 - s, s) weights;
 *             error <= (dx^2 / 8) max |h_xx| + (dz^2 / 8) max |h_zz| (tensor-product linear
 *             interpolation of a C2 surface);
 *   bicubic   Keys' cubic convolution (R. Keys, "Cubic convolution interpolation for digital
 *             image processing", IEEE Trans. ASSP 29(6), 1981, eq. 15 with a = -1/2) over the
 *             4 x 4 samples i-1..i+2, weights for offset t:
 *               w-1 = (-t^3 + 2t^2 - t)/2,  w0 = (3t^3 - 5t^2 + 2)/2,
 *               w1 = (-3t^3 + 4t^2 + t)/2,  w2 = (t^3 - t^2)/2;
 *             it reproduces quadratics, so its error falls as the cube of the cell size
 *             (Keys, section IV), and is C1 across cells.
 * Indices beyond the grid are clamped to its edge, so the outermost half cell (and anything
 * beyond) takes the edge samples: the interpolation never reads outside the grid. The gradient
 * is the interpolant's own derivative (t's weights differentiated, times W / X samples per
 * metre; along z times -H / Z, rows running south): bicubic's, with weights w-1' = (-3t^2 + 4t - 1)/2, w0' = (9t^2 - 10t)/2,
 * w1' = (-9t^2 + 8t + 1)/2, w2' = (3t^2 - 2t)/2, is continuous and second-order accurate.
 * Arithmetic is in double; the heights come out as float. */
#include <math.h>
#include "atmo/dem.h"

static double at(const atmo_dem *dem, long col, long row)
{
    col = col < 0 ? 0 : col >= dem->width ? dem->width - 1 : col;
    row = row < 0 ? 0 : row >= dem->height ? dem->height - 1 : row;
    return dem->heights_m[(size_t)row * (size_t)dem->width + (size_t)col];
}

/* Keys' weights for offset t and their derivatives d/dt. */
static void keys_weights(double t, double w[4], double dw[4])
{
    double t2 = t * t, t3 = t2 * t;
    w[0] = (-t3 + 2 * t2 - t) / 2;
    w[1] = (3 * t3 - 5 * t2 + 2) / 2;
    w[2] = (-3 * t3 + 4 * t2 + t) / 2;
    w[3] = (t3 - t2) / 2;
    dw[0] = (-3 * t2 + 4 * t - 1) / 2;
    dw[1] = (9 * t2 - 10 * t) / 2;
    dw[2] = (-9 * t2 + 8 * t + 1) / 2;
    dw[3] = (3 * t2 - 2 * t) / 2;
}

double atmo_dem_sample(const atmo_dem *dem, double x_m, double z_m, int filter)
{
    double gradient[2];
    return atmo_dem_sample_gradient(dem, x_m, z_m, filter, gradient);
}

double atmo_dem_sample_gradient(const atmo_dem *dem, double x_m, double z_m, int filter,
                                double gradient[2])
{
    double per_x = dem->width / dem->extent_m[0], per_z = -dem->height / dem->extent_m[1];
    double u = (x_m / dem->extent_m[0] + 0.5) * dem->width - 0.5;
    double v = (0.5 - z_m / dem->extent_m[1]) * dem->height - 0.5;
    /* far outside, clamp before floor so the index stays a small long */
    u = fmin(fmax(u, -2.0), dem->width + 1.0);
    v = fmin(fmax(v, -2.0), dem->height + 1.0);
    double fu = floor(u), fv = floor(v);
    long i = (long)fu, j = (long)fv;
    double t = u - fu, s = v - fv;
    if (filter == ATMO_DEM_BILINEAR) {
        double h00 = at(dem, i, j), h10 = at(dem, i + 1, j), h01 = at(dem, i, j + 1),
               h11 = at(dem, i + 1, j + 1);
        gradient[0] = ((1 - s) * (h10 - h00) + s * (h11 - h01)) * per_x;
        gradient[1] = ((1 - t) * (h01 - h00) + t * (h11 - h10)) * per_z;
        return (1 - s) * ((1 - t) * h00 + t * h10) + s * ((1 - t) * h01 + t * h11);
    }
    double wx[4], wz[4], dwx[4], dwz[4], h = 0, hx = 0, hz = 0;
    keys_weights(t, wx, dwx);
    keys_weights(s, wz, dwz);
    for (int b = 0; b < 4; b++) {
        double row = 0, row_x = 0;
        for (int a = 0; a < 4; a++) {
            double sample = at(dem, i - 1 + a, j - 1 + b);
            row += wx[a] * sample;
            row_x += dwx[a] * sample;
        }
        h += wz[b] * row;
        hx += wz[b] * row_x;
        hz += dwz[b] * row;
    }
    gradient[0] = hx * per_x;
    gradient[1] = hz * per_z;
    return h;
}

int atmo_dem_resample(const atmo_dem *dem, const atmo_dem_grid *grid, int filter, float *out,
                      atmo_err *e)
{
    if (grid->width < 1 || grid->height < 1 || !isfinite(grid->x0_m) || !isfinite(grid->z0_m) ||
        !isfinite(grid->dx_m) || !isfinite(grid->dz_m))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "heightmap resampling: the target grid %d x %d from (%g, %g) m by (%g, "
                         "%g) m is not a grid",
                         grid->width, grid->height, grid->x0_m, grid->z0_m, grid->dx_m,
                         grid->dz_m);
    if (filter != ATMO_DEM_BILINEAR && filter != ATMO_DEM_BICUBIC)
        return atmo_fail(e, ATMO_ERR_USAGE, "heightmap resampling: unknown filter %d", filter);
    for (int j = 0; j < grid->height; j++) {
        double z = grid->z0_m + j * grid->dz_m;
        for (int i = 0; i < grid->width; i++) {
            size_t k = (size_t)j * (size_t)grid->width + (size_t)i;
            double g[2], h = atmo_dem_sample_gradient(dem, grid->x0_m + i * grid->dx_m, z,
                                                      filter, g);
            if (grid->derivatives) {
                out[3 * k] = (float)h;
                out[3 * k + 1] = (float)g[0];
                out[3 * k + 2] = (float)g[1];
            } else {
                out[k] = (float)h;
            }
        }
    }
    return ATMO_OK;
}
