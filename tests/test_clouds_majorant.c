/* test_clouds_majorant — the fBm cloud layer's majorant grid (kernels/clouds/cloud_majorant.h,
 * its pass cloud_majorant.cl) bounds the density in every cell, and the reference's ratio
 * tracking through it (media_walk.h's media_walk_sun_transmittance: the one majorant walk over
 * the grid's cells, majorant_walk.h, with Russian roulette) estimates the transmittance
 * without bias. Scene: thesis-6 (the camera inside the layer, the sun 28 degrees high) with
 * method reference.
 * labels: kernel stat
 *
 * Oracles:
 *   - the bound: the density (cloud_layer.h's clouds_density, host build, bitwise the device's:
 *     test_cloud_noise) at 16 uniform random points of each of 16384 random cells, and at 256
 *     points of each of the 64 cells with the largest bounds, with the altitude of each point
 *     computed in double from its camera-relative position, must never exceed the cell's bound
 *     as the device's pass wrote it (a bound is a bound: no tolerance). The bound's tightness
 *     (the largest sampled density over the bound in the cells that have cloud) and the share
 *     of the layer's cells the grid proves clear are printed;
 *   - ratio tracking: along 4 sun rays whose transmittances lie in [0.03, 0.25), [0.25, 0.5),
 *     [0.5, 0.75) and [0.75, 0.9], chosen among random points in and below the layer, the mean of 4096 walks must lie within 4.5
 *     standard errors (sample standard deviation / sqrt(4096)) plus the quadrature's error of
 *     a double-precision midpoint quadrature of the same extinction (the air's
 *     atmosphere_extinction_at and the layer's clouds_density, host builds, at the walk's
 *     points p + t sun with the altitudes of geometry_altitude_at) with 2^17 steps to the top
 *     of the atmosphere; the quadrature's error is taken as its difference from 2^16 steps
 *     (midpoint: the error falls 4 times per halving, so that difference is 3 times it);
 *   - determinism: the pass run twice gives the same grid bit for bit, and the walks run in
 *     reverse order give the same floats bit for bit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/geometry.h"
#include "clouds/cloud_majorant.h"
#include "media/ray.h"
#include "testlib.h"
#include "testscene.h"

#define CELLS (CLOUDS_GRID_NX * CLOUDS_GRID_NY * CLOUDS_GRID_NZ)
#define RAYS 4
#define WALKS 4096
#define CANDIDATES 512
#define Z_MAX 4.5

static const char probe[] =
    "__kernel void walks(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                    __global const float4 *origins, __global const uint *order,\n"
    "                    __global float *out, uint n, uint walks) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  uint item = order[i];\n"
    "  float4 o = origins[item / walks];\n"
    "  medium_ray m = medium_ray_make(s, v3(o.x, o.y, o.z), v3_from4(s->sun_direction));\n"
    "  medium_point q = medium_ray_at(&m, 0.0f, s->atmosphere.bottom_radius);\n"
    "  rng_stream g = rng_stream_stage(11u, item, 0u, 0u);\n"
    "  out[item] = media_walk_sun_transmittance(s, ATMO_LUT_ARGS, &q, MEDIA_WALK_SHADOW, &g).y;\n"
    "}\n";

/* The green extinction at the point t along the sun's ray from q (what the walk sees). */
static double extinction(const atmo_gpu_scene *s, const medium_point *q, double t)
{
    const atmo_gpu_atmosphere *a = &s->atmosphere;
    float h = geometry_altitude_at(q->r, q->mu_s, (float)t, a->bottom_radius);
    vec3 p = v3_add(q->p, v3_scale(v3_from4(s->sun_direction), (float)t));
    double air = atmosphere_extinction_at(a, h, expf(-h / a->rayleigh_scale_height),
                                          expf(-h / a->mie_scale_height)).y;
    return air + (double)clouds_density(&s->clouds, p, h) * s->clouds.extinction.y;
}

/* The optical depth to the top of the atmosphere by the midpoint rule with n steps. */
static double depth(const atmo_gpu_scene *s, const medium_point *q, int n)
{
    float d = geometry_distance_to_top(q->r, q->mu_s, s->atmosphere.top_radius);
    double dt = (double)d / n, tau = 0.0;
    for (int j = 0; j < n; j++)
        tau += extinction(s, q, (j + 0.5) * dt) * dt;
    return tau;
}

static medium_point start(const atmo_gpu_scene *s, vec3 origin)
{
    medium_ray m = medium_ray_make(s, origin, v3_from4(s->sun_direction));
    return medium_ray_at(&m, 0.0f, s->atmosphere.bottom_radius);
}

static float uniform(uint i, uint d) { return rng_uniform(5u, i, 0u, d); }

/* Samples n points of cell c: counts those above its bound, raises *ratio to the largest
 * density / bound. */
static int check_cell(const atmo_gpu_scene *s, const clouds_grid_frame *f, const float *grid,
                      int c, int n, double *ratio)
{
    int i = c % CLOUDS_GRID_NX, j = (c / CLOUDS_GRID_NX) % CLOUDS_GRID_NY;
    int k = c / (CLOUDS_GRID_NX * CLOUDS_GRID_NY), bad = 0;
    double r_c = s->camera.local_up.w, R = s->atmosphere.bottom_radius;
    for (int m = 0; m < n; m++) {
        uint id = (uint)c * 4096u + (uint)m;
        vec3 p = v3_add(f->corner,
                        v3_add(v3_add(v3_scale(f->ax, ((float)i + uniform(id, 0)) * f->cell.x),
                                      v3_scale(f->ay, ((float)j + uniform(id, 1)) * f->cell.y)),
                               v3_scale(f->az, ((float)k + uniform(id, 2)) * f->cell.z)));
        double x = r_c * s->camera.local_up.x + p.x, y = r_c * s->camera.local_up.y + p.y;
        double z = r_c * s->camera.local_up.z + p.z;
        float h = (float)(sqrt(x * x + y * y + z * z) - R);
        float d = clouds_density(&s->clouds, p, h);
        if (d > grid[c]) {
            if (bad++ < 3)
                printf("cell (%d, %d, %d): density %.6g above its bound %.6g at h %.1f m\n", i, j,
                       k, d, grid[c], h);
        }
        if (grid[c] > 0.0f)
            *ratio = fmax(*ratio, d / grid[c]);
    }
    return bad;
}

static const float *sort_grid; /* qsort's comparator has no context argument */
static int cmp_cells(const void *a, const void *b)
{
    float x = sort_grid[*(const int *)a], y = sort_grid[*(const int *)b];
    return (x < y) - (x > y); /* largest bound first */
}

int main(void)
{
    atmo_scene sc;
    test_scene_preset(&sc, "thesis-6");
    test_scene_set(&sc, "atmosphere.method=reference");
    test_scene_set(&sc, "image.width=8");
    test_scene_set(&sc, "image.height=8");
    atmo_plan p;
    test_plan(&sc, &p);
    const atmo_gpu_scene *s = &p.gpu;
    atmo_cl cl;
    test_cl_open(&cl);
    cl_program prog = test_plan_program(&cl, &p, probe);
    cl_mem scene = test_cl_buffer(&cl, sizeof p.gpu, &p.gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS] = {0}, again[ATMO_PLAN_MAX_BUFFERS] = {0};
    test_precompute(&cl, prog, scene, &p, luts);
    test_precompute(&cl, prog, scene, &p, again);
    float *grid = malloc(sizeof(float) * CELLS), *grid2 = malloc(sizeof(float) * CELLS);
    int *cells = malloc(sizeof(int) * CELLS);
    CHECK(grid && grid2 && cells);
    test_cl_read(&cl, test_plan_buffer(&p, luts, "clouds_majorant"), sizeof(float) * CELLS, grid);
    test_cl_read(&cl, test_plan_buffer(&p, again, "clouds_majorant"), sizeof(float) * CELLS,
                 grid2);
    CHECK(memcmp(grid, grid2, sizeof(float) * CELLS) == 0);

    /* the bound */
    clouds_grid_frame f = clouds_grid_frame_make(s);
    int bad = 0, in_layer = 0, clear = 0;
    double ratio = 0.0, mean_bound = 0.0;
    for (int c = 0; c < CELLS; c++) {
        cells[c] = c;
        CHECK(grid[c] >= 0.0f && grid[c] <= s->clouds.density * CLOUDS_GRID_ROUNDING);
        int j = (c / CLOUDS_GRID_NX) % CLOUDS_GRID_NY;
        float y = f.low.y + ((float)j + 0.5f) * f.cell.y;
        if (y > s->clouds.bottom_m && y < s->clouds.top_m) { /* the layer's middle cells */
            in_layer++;
            clear += grid[c] == 0.0f;
            mean_bound += grid[c];
        }
    }
    for (int m = 0; m < 16384; m++)
        bad += check_cell(s, &f, grid, (int)(uniform((uint)m, 3) * CELLS) % CELLS, 16, &ratio);
    sort_grid = grid;
    qsort(cells, CELLS, sizeof(int), cmp_cells);
    double hot_ratio = 0.0;
    for (int m = 0; m < 64; m++)
        bad += check_cell(s, &f, grid, cells[m], 256, &hot_ratio);
    printf("majorant grid %dx%dx%d, cells %.0f x %.0f x %.0f m: %d points above their bound; "
           "largest density / bound %.3f (random cells), %.3f (the 64 densest cells); of the "
           "cells between the layer's altitudes %.1f %% are proved clear, mean bound %.3f of "
           "the global %.3g\n",
           CLOUDS_GRID_NX, CLOUDS_GRID_NY, CLOUDS_GRID_NZ, f.cell.x, f.cell.y, f.cell.z, bad,
           ratio, hot_ratio, 100.0 * clear / in_layer, mean_bound / in_layer / s->clouds.density,
           s->clouds.density);
    CHECK(bad == 0);
    CHECK(hot_ratio > 0.0); /* the densest cells do hold cloud */

    /* ratio tracking along sun rays of useful transmittance */
    float4 origins[RAYS];
    double T_want[RAYS], T_err[RAYS];
    int found = 0, filled[RAYS] = {0};
    for (int m = 0; m < CANDIDATES && found < RAYS; m++) {
        float x = (uniform((uint)m, 10) - 0.5f) * 4e4f, z = (uniform((uint)m, 11) - 0.5f) * 4e4f;
        float y = 500.0f + uniform((uint)m, 12) * 5500.0f - (s->camera.local_up.w -
                                                              s->atmosphere.bottom_radius);
        vec3 o = v3_add(v3_add(v3_scale(f.ax, x), v3_scale(f.ay, y)), v3_scale(f.az, z));
        medium_point q = start(s, o);
        double T = exp(-depth(s, &q, 2048));
        int bin = T < 0.25 ? 0 : T < 0.5 ? 1 : T < 0.75 ? 2 : 3; /* one ray per quarter */
        if (T < 0.03 || T > 0.9 || filled[bin])
            continue;
        filled[bin] = 1;
        double fine = depth(s, &q, 1 << 17), coarse = depth(s, &q, 1 << 16);
        origins[found].x = o.x, origins[found].y = o.y, origins[found].z = o.z;
        origins[found].w = 0.0f;
        T_want[found] = exp(-fine);
        T_err[found] = fabs(exp(-fine) - exp(-coarse));
        found++;
    }
    CHECK(found == RAYS);
    uint n = RAYS * WALKS, walks = WALKS;
    float *out = malloc(sizeof(float) * n), *out2 = malloc(sizeof(float) * n);
    CHECK(out && out2);
    test_run_walks(&cl, prog, scene, luts, origins, sizeof origins, sizeof(float), n, walks, out,
                   out2);
    CHECK(memcmp(out, out2, sizeof(float) * n) == 0);
    for (int r = 0; r < RAYS; r++) {
        double sum = 0.0, sum2 = 0.0;
        for (int w = 0; w < WALKS; w++) {
            double v = out[r * WALKS + w];
            sum += v, sum2 += v * v;
        }
        double mean = sum / WALKS;
        double se = sqrt(fmax(sum2 / WALKS - mean * mean, 0.0) / (WALKS - 1));
        printf("sun ray %d: quadrature T %.5f (+- %.1e), ratio tracking %.5f +- %.5f (z %+.2f)\n",
               r, T_want[r], T_err[r], mean, se, (mean - T_want[r]) / se);
        CHECK_ABS(mean, T_want[r], Z_MAX * se + T_err[r]);
    }
    free(out2), free(out), free(cells), free(grid2), free(grid);
    test_release_luts(again);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    clReleaseProgram(prog);
    atmo_cl_close(&cl);
    atmo_plan_free(&p);
    return test_finish();
}
