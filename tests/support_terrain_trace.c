/* support_terrain_trace.c — the sphere-tracing tests' rays, device probe and judge against the
 * double-precision brute-force march (testterrain.h; the oracle and the classes of error are
 * described in tests/test_terrain_trace.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/plan_terrain.h"
#include "atmo/terrain_ref.h"
#include "testlib.h"
#include "testscene.h"
#include "testterrain.h"

const char test_trace_probe_src[] =
    "__kernel void trace(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                    __global const float4 *o, __global const float4 *d,\n"
    "                    __global float4 *out, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  float t = 0.0f; int used = 0;\n"
    "  int hit = terrain_trace(s, heightmap, o[i].xyz, d[i].xyz, 0.0f, d[i].w, s->terrain.steps,\n"
    "                          &t, &used);\n"
    "  out[i] = (float4)(hit ? t : -1.0f, (float)used, 0.0f, 0.0f);\n"
    "}\n";

void test_trace_plan_above_site(test_trace_setup *u, const char *extra1, const char *extra2,
                                const char *extra3)
{
    double cam[3] = {TEST_TRACE_SITE_X, 0.0, TEST_TRACE_SITE_Z}, p[3], n[3];
    test_trace_plan_at3(u, cam, extra1, extra2, extra3); /* for the field */
    const atmo_gpu_terrain_field f = u->plan.gpu.terrain.field;
    test_trace_surface_point(&f, NULL, 0.0, TEST_TRACE_SITE_X, TEST_TRACE_SITE_Z, p, n);
    atmo_plan_free(&u->plan);
    for (int k = 0; k < 3; k++)
        cam[k] = p[k] + 300.0 * n[k];
    test_trace_plan_at3(u, cam, extra1, extra2, extra3);
}

double test_trace_urand(unsigned *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (*state >> 8) / 16777216.0;
}

double test_trace_R_m;

void test_trace_plan_at(test_trace_setup *u, const double cam[3], const char *extra1,
                        const char *extra2)
{
    test_trace_plan_at3(u, cam, extra1, extra2, NULL);
}

void test_trace_plan_at3(test_trace_setup *u, const double cam[3], const char *extra1,
                         const char *extra2, const char *extra3)
{
    char buf[160];
    test_scene_preset(&u->scene, "sky-noon");
    test_scene_set(&u->scene, "atmosphere.method=single");
    test_scene_set(&u->scene, "terrain.enabled=true");
    test_scene_set(&u->scene, "terrain.seed=46");
    snprintf(buf, sizeof buf, "camera.position_m=%.17g,%.17g,%.17g", cam[0], cam[1], cam[2]);
    test_scene_set(&u->scene, buf);
    if (extra1)
        test_scene_set(&u->scene, extra1);
    if (extra2)
        test_scene_set(&u->scene, extra2);
    if (extra3)
        test_scene_set(&u->scene, extra3);
    test_plan(&u->scene, &u->plan);
    memcpy(u->cam, cam, sizeof u->cam);
    u->heightmap = NULL;
    test_trace_R_m = u->scene.atmosphere.bottom_radius_m;
}

/* The surface point above planar (x, z) and its vertical, world coordinates. */
void test_trace_surface_point(const atmo_gpu_terrain_field *f, const float *hm, double sea,
                              double x, double z, double p[3], double n[3])
{
    double h = fmax(terrain_ref_height_map(f, hm, x, z), sea);
    double rho2 = (x * x + z * z) / (test_trace_R_m * test_trace_R_m);
    n[0] = x / test_trace_R_m, n[1] = sqrt(1 - rho2), n[2] = z / test_trace_R_m;
    for (int k = 0; k < 3; k++)
        p[k] = n[k] * (test_trace_R_m + h) - (k == 1 ? test_trace_R_m : 0);
}

void test_trace_make_ray(test_trace_ray *r, const double cam[3], const double origin_world[3],
                         const double d[3],
                     double t_max)
{
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    float df[3];
    for (int k = 0; k < 3; k++)
        df[k] = (float)(d[k] / len);
    len = sqrt((double)df[0] * df[0] + (double)df[1] * df[1] + (double)df[2] * df[2]);
    for (int k = 0; k < 3; k++) {
        r->o[k] = (double)(float)(origin_world[k] - cam[k]);
        r->d[k] = (double)df[k] / len;
    }
    r->t_max = t_max;
}

/* Runs the probe over the rays: out[i] = (t or -1, steps used). */
void test_trace_run(atmo_cl *cl, cl_program prog, const atmo_plan *p, const test_trace_ray *rays,
                    int n,
                      float4 *out)
{
    cl_int err;
    float4 *o = calloc((size_t)n, sizeof *o), *d = calloc((size_t)n, sizeof *d);
    for (int i = 0; i < n; i++) {
        o[i].x = (float)rays[i].o[0], o[i].y = (float)rays[i].o[1], o[i].z = (float)rays[i].o[2];
        d[i].x = (float)rays[i].d[0], d[i].y = (float)rays[i].d[1], d[i].z = (float)rays[i].d[2];
        d[i].w = (float)rays[i].t_max;
    }
    cl_mem scene = clCreateBuffer(cl->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                  sizeof p->gpu, (void *)&p->gpu, &err);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    test_precompute(cl, prog, scene, p, luts);
    cl_mem bo = test_cl_buffer(cl, sizeof *o * (size_t)n, o);
    cl_mem bd = test_cl_buffer(cl, sizeof *d * (size_t)n, d);
    cl_mem bout = test_cl_buffer(cl, sizeof *out * (size_t)n, NULL);
    cl_kernel k = clCreateKernel(prog, "trace", &err);
    clSetKernelArg(k, 0, sizeof scene, &scene);
    int a = test_bind_buffers(k, luts);
    cl_uint nn = (cl_uint)n;
    clSetKernelArg(k, a++, sizeof bo, &bo);
    clSetKernelArg(k, a++, sizeof bd, &bd);
    clSetKernelArg(k, a++, sizeof bout, &bout);
    clSetKernelArg(k, a++, sizeof nn, &nn);
    test_cl_run_1d(cl, k, (size_t)n);
    test_cl_read(cl, bout, sizeof *out * (size_t)n, out);
    clReleaseKernel(k);
    clReleaseMemObject(bout);
    clReleaseMemObject(bd);
    clReleaseMemObject(bo);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    free(o);
    free(d);
}

double test_trace_delta_m(const atmo_gpu_terrain_field *f, double L, const double w[3], double t)
{
    double eps = ldexp(1.0, -24) * f->octaves;
    double reach = fmax(fmax(fabs(w[0]), fabs(w[2])), 1000.0);
    return 4.0 * (L * eps * reach + eps * (double)f->max_height_m) + 2e-7 * t;
}

void test_trace_world_at(const test_trace_setup *u, const test_trace_ray *r, double t,
                         double w[3])
{
    for (int k = 0; k < 3; k++)
        w[k] = u->cam[k] + r->o[k] + t * r->d[k];
}

test_trace_tally test_trace_judge(const test_trace_setup *u, const test_trace_ray *rays, int n,
                                  const float4 *out, int verbose)
{
    const atmo_gpu_terrain *tr = &u->plan.gpu.terrain;
    double L = atmo_terrain_slope_bound(&tr->field), sea = tr->sea_level_m;
    test_trace_tally y;
    memset(&y, 0, sizeof y);
    for (int i = 0; i < n; i++) {
        const test_trace_ray *r = &rays[i];
        double o[3], t_ref = 0, min_clear = INFINITY;
        test_trace_world_at(u, r, 0.0, o);
        int ref = terrain_ref_hit_map(&tr->field, u->heightmap, test_trace_R_m, sea, o, r->d,
                                      r->t_max, TEST_TRACE_REF_STEP_M, &t_ref, &min_clear);
        int hit = out[i].x >= 0.0f;
        double t = out[i].x, w[3];
        y.ref_hits += ref;
        y.hits += hit;
        y.mean_steps += out[i].y / n;
        if (ref && !hit) {
            y.misses++;
            if (verbose)
                fprintf(stderr, "  ray %d: missed a hit at %.3f m (%d steps)\n", i, t_ref,
                        (int)out[i].y);
            continue;
        }
        if (!hit)
            continue;
        test_trace_world_at(u, r, t, w);
        double eps = 0.01 + (double)tr->tolerance * t, delta = test_trace_delta_m(&tr->field, L, w, t);
        double g = terrain_ref_clearance_map(&tr->field, u->heightmap, test_trace_R_m, sea, w);
        y.worst_clear = fmax(y.worst_clear, g > 0 ? g / (eps + delta) : -g / delta);
        if (g < -delta || g > eps + delta) {
            y.bad++;
            if (verbose)
                fprintf(stderr, "  ray %d: hit at %.3f m has clearance %.4f m (eps %.3f, delta "
                                "%.3f)\n", i, t, g, eps, delta);
        }
        if (!ref && min_clear > eps + delta) {
            y.false_hits++;
            if (verbose)
                fprintf(stderr, "  ray %d: hit at %.3f m, reference clears by %.3f m\n", i, t,
                        min_clear);
        }
        if (ref && t > t_ref) { /* how deep the reference goes between the two hits */
            double deepest = 0;
            for (int k = 1; k < 64; k++) {
                double q[3];
                test_trace_world_at(u, r, t_ref + (t - t_ref) * k / 64.0, q);
                deepest = fmin(deepest, terrain_ref_clearance_map(&tr->field, u->heightmap,
                                                                  test_trace_R_m, sea, q));
            }
            if (deepest < -(delta + 0.5)) {
                y.through++;
                if (verbose)
                    fprintf(stderr, "  ray %d: passed %.3f m deep through the terrain (hits "
                                    "%.3f / %.3f m, %d steps)\n", i, -deepest, t_ref, t,
                            (int)out[i].y);
            }
        }
    }
    return y;
}

/* n_down rays from the camera downward, then n_graze grazing rays from 2..50 m above random
 * surface points within 2 km of the site, then n_skim ridge-skimming rays (see
 * test_terrain_trace.c), drawn from the generator state *rng. */
void test_trace_make_rays(const atmo_gpu_terrain_field *f, const float *hm, const double cam[3],
                          int n_down, int n_graze, int n_skim, unsigned *rng,
                          test_trace_ray *rays)
{
    for (int i = 0; i < n_down + n_graze + n_skim; i++) {
        double o[3], d[3], t_max;
        if (i < n_down) { /* from the camera, down */
            double mu = -0.02 - 0.98 * test_trace_urand(rng), phi = 2 * M_PI * test_trace_urand(rng);
            double s = sqrt(1 - mu * mu);
            memcpy(o, cam, sizeof o);
            d[0] = s * cos(phi), d[1] = mu, d[2] = s * sin(phi);
            t_max = 20000.0;
        } else {
            double x = TEST_TRACE_SITE_X + (test_trace_urand(rng) - 0.5) * 4000;
            double z = TEST_TRACE_SITE_Z + (test_trace_urand(rng) - 0.5) * 4000;
            double q[3], m[3], phi = 2 * M_PI * test_trace_urand(rng);
            test_trace_surface_point(f, hm, 0.0, x, z, q, m);
            /* a horizontal unit vector at q */
            double e1[3] = {cos(phi), 0, sin(phi)}, k = e1[0] * m[0] + e1[1] * m[1] + e1[2] * m[2];
            for (int c = 0; c < 3; c++)
                e1[c] -= k * m[c];
            double len = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
            if (i < n_down + n_graze) {
                double above = 2 + 48 * test_trace_urand(rng), mu = -0.05 + 0.07 * test_trace_urand(rng);
                for (int c = 0; c < 3; c++) {
                    o[c] = q[c] + above * m[c];
                    d[c] = e1[c] / len * sqrt(1 - mu * mu) + mu * m[c];
                }
                t_max = 8000.0;
            } else { /* started where the line back from q is above the terrain */
                double above = 0.05 + 2.95 * test_trace_urand(rng), back = 3000.0;
                for (int c = 0; c < 3; c++)
                    d[c] = e1[c] / len;
                do {
                    back *= 0.7;
                    for (int c = 0; c < 3; c++)
                        o[c] = q[c] + above * m[c] - back * d[c];
                } while (back > 1.0 && terrain_ref_clearance_map(f, hm, test_trace_R_m, 0.0, o) < 1.0);
                if (terrain_ref_clearance_map(f, hm, test_trace_R_m, 0.0, o) < 1.0) {
                    i--; /* a slope too steep to start 1 m above it: draw another point */
                    continue;
                }
                t_max = back + 3000.0;
            }
        }
        test_trace_make_ray(&rays[i], cam, o, d, t_max);
    }
}

float *test_trace_dem_plan(test_trace_setup *u, const double cam[3], int plane)
{
    test_trace_plan_at(u, cam, "terrain.heightmap_size=512", "terrain.heightmap_extent_m=65536");
    atmo_plan *p = &u->plan;
    const atmo_gpu_terrain_field *f = &p->gpu.terrain.field;
    float *grid = malloc(sizeof(float) * TEST_TRACE_DEM_MAP * TEST_TRACE_DEM_MAP);
    double texel = TEST_TRACE_DEM_EXTENT_M / TEST_TRACE_DEM_MAP, first = -0.5 * TEST_TRACE_DEM_EXTENT_M + 0.5 * texel;
    for (int j = 0; j < TEST_TRACE_DEM_MAP; j++)
        for (int i = 0; i < TEST_TRACE_DEM_MAP; i++) {
            double x = (double)(float)(first + i * texel), z = (double)(float)(first + j * texel);
            grid[j * TEST_TRACE_DEM_MAP + i] = (float)(plane ? 500.0 + 0.05 * x + 0.03 * z
                                              : terrain_ref_height(f, x, z, NULL, NULL));
        }
    atmo_err e;
    CHECK(atmo_plan_terrain_base(p, grid, TEST_TRACE_DEM_MAP, TEST_TRACE_DEM_MAP, first, first, texel, texel, 0.0, &e) ==
          ATMO_OK);
    CHECK(atmo_plan_terrain_detail(p, texel, &e) == ATMO_OK);
    return grid;
}


int test_trace_dem_run(atmo_cl *cl, int n_down, int n_graze, int n_skim, unsigned seed,
                       int *ref_hits)
{
    test_trace_setup u;
    double cam0[3] = {TEST_TRACE_SITE_X, 0.0, TEST_TRACE_SITE_Z};
    int nm = TEST_TRACE_DEM_MAP;
    float *grid = test_trace_dem_plan(&u, cam0, 0);
    atmo_gpu_terrain_field f = u.plan.gpu.terrain.field;
    cl_program prog = test_plan_program(cl, &u.plan, test_trace_probe_src);
    cl_int err;
    cl_mem scene = clCreateBuffer(cl->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                  sizeof u.plan.gpu, &u.plan.gpu, &err);
    CHECK(err == CL_SUCCESS);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    test_precompute(cl, prog, scene, &u.plan, luts);
    float *map = malloc(sizeof(float) * (size_t)nm * (size_t)nm);
    test_cl_read(cl, test_plan_buffer(&u.plan, luts, "heightmap"),
                 sizeof(float) * (size_t)nm * (size_t)nm, map);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    clReleaseProgram(prog);
    double p[3], n[3], cam[3];
    test_trace_surface_point(&f, map, 0.0, TEST_TRACE_SITE_X, TEST_TRACE_SITE_Z, p, n);
    for (int k = 0; k < 3; k++)
        cam[k] = p[k] + 300.0 * n[k];
    atmo_plan_free(&u.plan);
    free(grid);
    grid = test_trace_dem_plan(&u, cam, 0);
    u.heightmap = map;
    prog = test_plan_program(cl, &u.plan, test_trace_probe_src);
    int n_rays = n_down + n_graze + n_skim;
    test_trace_ray *rays = calloc((size_t)n_rays, sizeof *rays);
    float4 *out = calloc((size_t)n_rays, sizeof *out);
    test_trace_make_rays(&f, map, cam, n_down, n_graze, n_skim, &seed, rays);
    test_trace_run(cl, prog, &u.plan, rays, n_rays, out);
    static const char *const names[3] = {"downward", "grazing", "ridge-skimming"};
    const int first[4] = {0, n_down, n_down + n_graze, n_rays};
    int all_hits = 0, all_bad = 0;
    for (int g = 0; g < 3; g++) {
        test_trace_tally y = test_trace_judge(&u, rays + first[g], first[g + 1] - first[g],
                                              out + first[g], 1);
        printf("DEM + detail, %-14s %5d rays, %5d hits (reference %5d): %d misses, %d "
               "pass-throughs, %d false, %d bad; worst clearance %.3f of its bound; %.1f steps "
               "per ray\n", names[g], first[g + 1] - first[g], y.hits, y.ref_hits, y.misses,
               y.through, y.false_hits, y.bad, y.worst_clear, y.mean_steps);
        all_hits += y.ref_hits;
        all_bad += y.misses + y.through + y.false_hits + y.bad;
    }
    printf("%d errors in %d reference hits: rate < %.3g at 95 %% confidence\n", all_bad, all_hits,
           3.0 / all_hits);
    free(rays);
    free(out);
    free(map);
    free(grid);
    clReleaseProgram(prog);
    atmo_plan_free(&u.plan);
    *ref_hits = all_hits;
    return all_bad;
}
