/* plan_terrain.c — the procedural terrain in the plan (atmo/plan_terrain.h).
 *
 * Fills gpu.terrain: the height field's inputs (field: what the heightmap pass reads, so its
 * cache key), the camera's placement over it (world position and altitude above the ground
 * sphere in double, so the kernels' camera-relative floats keep metre precision at 6360 km;
 * this part follows the view), the sphere tracer's slope bound, tolerance and budget, and the
 * shadow and shaft settings.
 *
 * Slope bound. Value noise's gradient has norm at most 15/4 (lattice units): the gradient is
 * linear in the corner values, so its norm (convex in them) is largest at corner values of
 * +-1; over the 16 sign patterns and a 2001^2-point grid of the cell the largest norm is 15/4,
 * at edge midpoints (one of n_x, n_y reaches (15/8) 2 where the other vanishes), against the
 * (15/8) 2 sqrt 2 that bounding each axis apart gives. Octave i of the
 * eroded fBm then contributes to e = (1 + tanh(2 relief a / sum b)) / 2 a slope of at most
 *     b_i 2^i f (15/4) relief / sum b = f (15/4) relief / sum b
 * (tanh' <= 1, the erosion denominator >= 1 only lowering it), N of them H f N (15/4) relief /
 * sum b with H the maximum height (relief TERRAIN_RELIEF, noise.h). That sum is reached only
 * where every octave's steepest point lines up, which the erosion prevents: steep coarse
 * octaves damp the fine ones. The largest slopes of the double reference sampled over the
 * land of the 120 km square around the thesis' sites (2^21 points for each of seeds 1, 7 and 46
 * at N = 9, 5 10^5 of seed 46 for the other N) are, in units of H f relief / sum b, 8.9,
 * 12.9, 16.9, 15.1 and 15.7 for N = 3, 6, 9, 12 and 15, against the sum's 11, 23, 34, 45 and
 * 56. The tracer takes
 *     L = H f (relief / sum b) min((15/4) N, TERRAIN_SLOPE_ENVELOPE sqrt N),
 * TERRAIN_SLOPE_ENVELOPE = 6: above every sampled maximum (18 at N = 9), so L is the
 * steepest slope the field shows rather than one it cannot reach; about 1.3 for the default
 * terrain (H 4 km, f 3e-5 /m, 9 octaves, relief 1.2) and 4.3 for the thesis presets' (f 1e-4
 * /m). The domain warp (noise.h) evaluates the fBm at x = x0 + A w(x0) with Jacobian
 * J = I + A sum_o 2^-o F_o G_o R_o (G_o the rows grad n_a, grad n_b of warp octave o, each of
 * norm at most 15/4; R_o a rotation; F_o = F 2^o), so the slope in x0 is at most ||J|| times
 * the slope in x, and
 *     ||J|| <= 1 + A sum_o 2^-o F_o ||G_o|| <= 1 + TERRAIN_WARP_OCTAVES A F (15/4) sqrt 2
 * (||G||_2 <= its Frobenius norm, reached where both noises of an octave peak along one
 * direction; every octave's term is A F (15/4) sqrt 2): L takes that factor, 7.6 for the
 * default warp (A 1.25 cells, F 1/2, two octaves), 1 without one. The slopes sampled over
 * the land stay far below it (1.8 against the warped L of 9.9 for the default terrain,
 * tests/test_terrain_noise.c): the worst case needs all four warp noises' steepest points and
 * the fBm's at one spot. tests/test_terrain_noise.c samples the slopes against L (the
 * erosion's second term and the warp included); the coverage's slope, at coasts only, is left
 * out. terrain.optimism and the tracer's back-stepping
 * answer for steps longer than L allows; tests/test_terrain_trace.c measures the misses.
 *
 * Local bound under the warp. Over the direct fBm the tracer knows ||J(x0)|| at each step's
 * start (the warp's Jacobian comes with the warped point), so its slope there is at most
 * L_F ||J(x0)||, L_F = L without the warp's factor (stretch_slope). Along the step ||J|| can
 * grow only as fast as the warp's gradients turn: value noise's Hessian has spectral norm at most
 * C = 225/16 (lattice units; linear in the corner values, so largest at +-1; over the 16 sign
 * patterns and a 601^2 grid of the cell the largest is (15/8)^2 4, at the centre with corners
 * -1, 1, 1, -1, where n_xy = k3 q'x q'y alone), so each row of G_o moves by at most C F_o per
 * lattice unit of x0, G_o by sqrt 2 C F_o (Frobenius), and
 *     ||J(x0')|| <= ||J(x0)|| + A sqrt 2 C sum_o 2^-o F_o^2 |x0' - x0|
 *                 = ||J(x0)|| + A sqrt 2 C F^2 (2^O - 1) |x0' - x0|   (O warp octaves).
 * A ray's foot (u, v) = R (X, Z) / r moves at most 2 m per metre along it (R / r <= 1 in the
 * terrain's shell; the change of R / r adds at most |(X, Z)| / r <= 1), and x0 = f (u, v), so
 * the slope bound grows along the ray by at most
 *     slope_growth = L_F 2 A sqrt 2 C F^2 (2^O - 1) f   per metre
 * (4.7e-4 for the default terrain: the bound at the start of a 1 km step rises by at most 0.47
 * over it), and never past L. The tracer sizes its steps by that (kernels/terrain/terrain.h).
 *
 * The detail below a DEM's cells (kernels/terrain/terrain_detail.h) adds
 *     L_d = K A_i0 2^i0 f (15/4)
 * (K octaves, A_i 2^i constant), about 1.1 for the default terrain whatever the cell size
 * (A_i0 2^i0 = H relief / sum b).
 *
 * A digital elevation model (terrain.heightmap_file, atmo/dem.h) becomes the heightmap's base
 * height grid (plan_dem below); with terrain.heightmap_detail the fBm's octaves finer than the
 * cells it is drawn at (the larger of the file's cell and the heightmap's texel) are added at
 * lookup time, with twice terrain.steps for the tracer (TERRAIN_DETAIL_STEPS_FACTOR), else the
 * procedural fBm adds nothing.
 *
 * Tolerance: half a pixel's footprint per metre of distance (tan(fov / 2) / height, the pixel
 * angle), so a hit is as exact as the image can show.
 *
 * Surface height for placing objects and cameras (atmo_plan_terrain_surface_y): the surface
 * lies at radius r = R + S(u, v), S = max(h, sea level), with u = R x / r, v = R z / r (the
 * foot of world (x, z) on the ground sphere: kernels/terrain/terrain.h's placement), solved by
 * fixed-point iteration from r = R + S(x, z) (the foot moves by x (r - R) / R, a few metres,
 * so the slope's change of S shrinks each step by ~(r - R) / R < 1e-3); Y_s = sqrt(r^2 - x^2 -
 * z^2) - R. S is the renderer's own height: a DEM's heightmap texels read back as the kernels
 * read them, the procedural field in double (its float evaluation differs by < 1 mm,
 * test_terrain_noise). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/dem.h"
#include "atmo/plan_terrain.h"
#include "atmo/terrain_ref.h"
#include "terrain/terrain.h"

/* texels per side of the heightmap a DEM is resampled into when terrain.heightmap_size is 0 */
#define TERRAIN_DEM_HEIGHTMAP_SIZE 1024
/* octaves of the detail below a DEM's cells: periods C/2 .. C/16 (C the cell) */
#define TERRAIN_DETAIL_OCTAVES 4
/* the finest octave the detail may start at (lattice coordinates stay well inside float) */
#define TERRAIN_DETAIL_MAX_OCTAVE 24
/* the sphere tracer's step budget over the detail, times terrain.steps: grazing rays over its
 * metre-scale relief run out of 300 steps about once in 5000 hits and the fallback then steps
 * over bumps (6 errors in 32356 hits, test_dem_detail_miss_rate); twice the budget leaves none,
 * and the mean steps per ray grow by 1 % (the few rays that need them) */
#define TERRAIN_DETAIL_STEPS_FACTOR 2
/* the eroded fBm's slope envelope in units of H f relief / sum b, times sqrt(octaves) (above) */
#define TERRAIN_SLOPE_ENVELOPE 6.0
/* value noise's largest gradient norm and Hessian spectral norm, lattice units (above) */
#define TERRAIN_NOISE_SLOPE (15.0 / 4.0)
#define TERRAIN_NOISE_CURVATURE (225.0 / 16.0)

/* L_F: the eroded fBm's slope bound in metres per metre of its lattice point (above) */
static double terrain_fbm_slope(const atmo_gpu_terrain_field *f)
{
    double norm = 2.0 * (1.0 - pow(0.5, f->octaves));
    double octaves = fmin(f->octaves * TERRAIN_NOISE_SLOPE,
                          TERRAIN_SLOPE_ENVELOPE * sqrt(f->octaves));
    return (double)f->max_height_m * (double)f->frequency_per_m * octaves *
           (double)TERRAIN_RELIEF / norm;
}

double atmo_terrain_slope_bound(const atmo_gpu_terrain_field *f)
{
    double detail = f->detail_octaves * (double)f->detail_amplitude_m *
                    ldexp((double)f->frequency_per_m, f->detail_octave0) * TERRAIN_NOISE_SLOPE;
    double warp = 1.0 + TERRAIN_WARP_OCTAVES * (double)f->warp * (double)TERRAIN_WARP_FREQUENCY *
                            TERRAIN_NOISE_SLOPE * sqrt(2.0);
    return terrain_fbm_slope(f) * warp + detail;
}

double atmo_terrain_stretch_slope(const atmo_gpu_terrain_field *f)
{
    return f->warp > 0.0f ? terrain_fbm_slope(f) : 0.0;
}

double atmo_terrain_slope_growth(const atmo_gpu_terrain_field *f)
{
    double F = (double)TERRAIN_WARP_FREQUENCY;
    double stretch_rate = (double)f->warp * sqrt(2.0) * TERRAIN_NOISE_CURVATURE * F * F *
                          (ldexp(1.0, TERRAIN_WARP_OCTAVES) - 1.0) * (double)f->frequency_per_m;
    return atmo_terrain_stretch_slope(f) * 2.0 * stretch_rate;
}

/* The scene's DEM (p->dem, read by the plan) as the heightmap's base: resampled bicubically
 * onto the heightmap's own texel centres, so the pass's bilinear lookup of the base returns the
 * bicubic values there. The heightmap covers [-E/2, E/2]^2 of world X, Z (E its extent); the
 * DEM's frame is centred on terrain.heightmap_center_m. */
static int plan_dem(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    const atmo_gpu_terrain_field *f = &p->gpu.terrain.field;
    int n = f->heightmap_size;
    double extent = f->heightmap_extent_m, texel = extent / n, first = -0.5 * extent + 0.5 * texel;
    atmo_dem_grid g = {n, n, first - s->dem.center_m[0], first - s->dem.center_m[1], texel, texel,
                       0};
    float *grid = malloc(sizeof(float) * (size_t)n * (size_t)n);
    if (!grid)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for a %dx%d heightmap", n, n);
    int rc = atmo_plan_own(p, grid, e);
    if (rc) {
        free(grid);
        return rc;
    }
    if ((rc = atmo_dem_resample(&p->dem, &g, ATMO_DEM_BICUBIC, grid, e)) ||
        (rc = atmo_plan_terrain_base(p, grid, n, n, first, first, texel, texel, 0.0, e)))
        return rc;
    if (!s->dem.detail)
        return ATMO_OK;
    double cell = fmax(fmax(p->dem.extent_m[0] / p->dem.width, p->dem.extent_m[1] / p->dem.height),
                       texel);
    return atmo_plan_terrain_detail(p, cell, e);
}

int atmo_plan_terrain(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    const int method = s->atmosphere.method;
    if (method == ATMO_METHOD_REFERENCE)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "terrain.enabled works with atmosphere.method=single, march, fast or "
                         "lut (got reference); set one of those");
    atmo_gpu_terrain *t = &p->gpu.terrain;
    memset(t, 0, sizeof *t);
    t->field.max_height_m = (float)s->terrain.max_height_m;
    t->field.frequency_per_m = (float)s->terrain.frequency_per_m;
    t->field.coverage_frequency_per_m = (float)s->terrain.coverage_frequency_per_m;
    t->field.land_fraction = (float)s->terrain.land_fraction;
    t->field.warp = (float)s->terrain.warp;
    t->field.octaves = s->terrain.octaves;
    t->field.coverage_octaves = s->terrain.coverage_octaves;
    t->field.seed = (uint)s->terrain.seed;
    t->field.heightmap_size = s->terrain.heightmap_size;
    t->field.heightmap_format = s->terrain.heightmap_format;
    t->field.heightmap_extent_m = (float)s->terrain.heightmap_extent_m;
    if (p->dem.width > 0) {
        /* a DEM is resampled into the heightmap, so it needs one (4 MiB unless set), and the
         * heights, kept within [0, max_height_m], must reach its highest point */
        if (t->field.heightmap_size == 0)
            t->field.heightmap_size = TERRAIN_DEM_HEIGHTMAP_SIZE;
        if (p->dem.max_m > (double)t->field.max_height_m)
            t->field.max_height_m = (float)p->dem.max_m;
    }

    double R = s->atmosphere.bottom_radius_m;
    const double *c = s->camera.position_m;
    double r = sqrt(c[0] * c[0] + (c[1] + R) * (c[1] + R) + c[2] * c[2]);
    t->camera.x = (float)c[0];
    t->camera.y = (float)c[1];
    t->camera.z = (float)c[2];
    t->camera.w = (float)(r - R);
    t->sea_level_m = (float)s->terrain.sea_level_m;
    t->slope_bound = (float)atmo_terrain_slope_bound(&t->field);
    t->stretch_slope = (float)atmo_terrain_stretch_slope(&t->field);
    t->slope_growth_per_m = (float)atmo_terrain_slope_growth(&t->field);
    t->optimism = (float)s->terrain.optimism;
    double pixel = 2.0 * tan(0.5 * s->camera.fov_deg * M_PI / 180.0) / s->image.height;
    if (s->camera.kind == ATMO_CAMERA_PANORAMA)
        pixel = M_PI / s->image.height;
    t->pixel_angle = (float)pixel;
    t->tolerance = (float)(0.5 * pixel);
    t->steps = s->terrain.steps;
    t->shadow = s->terrain.shadow;
    t->shadow_rays = s->terrain.shadow_rays;
    t->shadow_steps = s->terrain.shadow_steps;
    t->shadow_far_m = (float)s->terrain.shadow_far_m;
    t->shafts = s->terrain.shafts;

    int n = t->field.heightmap_size;
    /* bytes per texel: 12 (derivatives), 2 (half; the buffer rounded up to whole floats), 4 */
    size_t texel = s->terrain.heightmap_format == ATMO_TERRAIN_FORMAT_DERIVATIVES ? 12
                   : s->terrain.heightmap_format == ATMO_TERRAIN_FORMAT_HALF  ? 2
                                                                              : 4;
    size_t bytes = (texel * (size_t)n * (size_t)n + 3) / 4 * 4;
    if (n == 1)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "terrain.heightmap_size=1 is no grid; use 0 (direct evaluation) or >= 2");
    if (bytes > ATMO_TERRAIN_HEIGHTMAP_MAX_BYTES)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "terrain.heightmap_size=%d needs %.0f MiB, over the %.0f MiB limit; use "
                         "a smaller size, the float or half format, or 0 (direct evaluation)",
                         n, bytes / 1048576.0, ATMO_TERRAIN_HEIGHTMAP_MAX_BYTES / 1048576.0);
    int rc = atmo_plan_add_buffer(p, "heightmap", "float", bytes, 0, NULL, e);
    if (!rc)
        rc = atmo_plan_add_buffer(p, "terrain_base", "float", 0, 0, NULL, e);
    if (!rc && n > 0)
        rc = atmo_plan_add_pass(p, "terrain_heightmap", n, n, 1, 0, e);
    if (!rc && s->dem.detail && p->dem.width == 0)
        rc = atmo_fail(e, ATMO_ERR_USAGE,
                       "terrain.heightmap_detail=true adds detail below a file's cells; set "
                       "terrain.heightmap_file or the detail to false");
    if (!rc && p->dem.width > 0)
        rc = plan_dem(s, p, e);
    return rc;
}

double atmo_plan_terrain_height(const atmo_plan *p, double u, double v)
{
    const atmo_gpu_terrain_field *f = &p->gpu.terrain.field;
    const atmo_plan_buffer *base = atmo_plan_buffer_find((atmo_plan *)p, "terrain_base");
    float gx, gy;
    if (p->dem.width > 0 && base && base->host_data &&
        terrain_in_heightmap(f, (float)u, (float)v, &gx, &gy)) {
        atmo_gpu_terrain_field heights = *f;
        heights.heightmap_format = ATMO_TERRAIN_FORMAT_FLOAT; /* the base holds heights alone */
        return terrain_height_at(&heights, (const float *)base->host_data, (float)u, (float)v).h;
    }
    return terrain_ref_height(f, u, v, NULL, NULL);
}

double atmo_plan_terrain_surface_y(const atmo_plan *p, double R, double x, double z)
{
    double sea = p->gpu.terrain.sea_level_m, r = R + fmax(atmo_plan_terrain_height(p, x, z), sea);
    for (int i = 0; i < 8; i++)
        r = R + fmax(atmo_plan_terrain_height(p, R * x / r, R * z / r), sea);
    return sqrt(r * r - x * x - z * z) - R;
}

int atmo_plan_terrain_base(atmo_plan *p, const float *heights, int nx, int nz, double x0,
                           double z0, double dx, double dz, double detail, atmo_err *e)
{
    atmo_plan_buffer *b = atmo_plan_buffer_find(p, "terrain_base");
    atmo_gpu_terrain_field *f = &p->gpu.terrain.field;
    if (!b || f->heightmap_size < 2)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "a height grid needs terrain.enabled and terrain.heightmap_size >= 2 "
                         "(the heightmap resamples it); set them");
    if (nx < 2 || nz < 2 || !(dx > 0.0) || !(dz > 0.0) || !isfinite(x0) || !isfinite(z0))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "a height grid needs at least 2 x 2 samples and positive spacing (got "
                         "%d x %d, %g x %g m)", nx, nz, dx, dz);
    b->bytes = sizeof(float) * (size_t)nx * (size_t)nz;
    b->host_data = heights;
    f->base_nx = nx, f->base_nz = nz;
    f->base_rect.x = (float)x0, f->base_rect.y = (float)z0;
    f->base_rect.z = (float)dx, f->base_rect.w = (float)dz;
    f->base_detail = (float)detail;
    return ATMO_OK;
}

int atmo_plan_terrain_detail(atmo_plan *p, double cell_m, atmo_err *e)
{
    atmo_gpu_terrain_field *f = &p->gpu.terrain.field;
    if (f->base_nx < 2)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "terrain.heightmap_detail needs a height grid under the heightmap; set "
                         "terrain.heightmap_file");
    /* the first octave i with lattice period 1 / (f 2^i) <= cell / 2 */
    int i0 = 0;
    while (i0 <= TERRAIN_DETAIL_MAX_OCTAVE &&
           1.0 / ldexp((double)f->frequency_per_m, i0) > 0.5 * cell_m)
        i0++;
    if (!(cell_m > 0.0) || i0 > TERRAIN_DETAIL_MAX_OCTAVE)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "terrain.heightmap_detail: cells of %g m are below the fBm's octave %d "
                         "(terrain.frequency_per_m=%g); raise the frequency or set the detail "
                         "to false",
                         cell_m, TERRAIN_DETAIL_MAX_OCTAVE, (double)f->frequency_per_m);
    /* the fBm's gain: H relief / sum b (noise.h's elevation slope) times 0.5^i0 */
    double norm = 2.0 * (1.0 - pow(0.5, f->octaves));
    f->detail_octave0 = i0;
    f->detail_octaves = TERRAIN_DETAIL_OCTAVES;
    f->detail_amplitude_m = (float)ldexp((double)f->max_height_m * (double)TERRAIN_RELIEF / norm, -i0);
    p->gpu.terrain.slope_bound = (float)atmo_terrain_slope_bound(f);
    p->gpu.terrain.steps *= TERRAIN_DETAIL_STEPS_FACTOR;
    return ATMO_OK;
}
