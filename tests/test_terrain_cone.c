/* test_terrain_cone — the terrain's cone start (kernels/terrain/terrain.h's terrain_cone_start,
 * where the denoiser's guide rays of one pixel start their march) on the device, against the
 * brute-force double-precision march.
 * labels: kernel
 *
 * Claim: every ray from the cone's origin whose unit direction lies within the chord `spread`
 * of the axis keeps a clearance above the tracer's hit tolerance eps(t) = 0.01 m + tolerance t
 * over [0, t_s], t_s the cone start.
 * Oracle: terrain_ref_hit (host/terrain/terrain_ref.c: the same height field in double, marched
 * in steps of at most 2 m and bisected), as in test_terrain_trace. For each cone, the axis and
 * 8 rays on the cone's rim (chord exactly `spread` from the axis, at 8 azimuths) are checked:
 *   - the reference finds no hit on (0, t_s];
 *   - the reference clearance at its 2 m sample points t <= t_s is at least eps(t) - delta(t),
 *     delta the float rounding bound of test_terrain_trace (the height field's and the ray's
 *     float position's).
 * Rays: test_terrain_trace's three kinds (from a camera 300 m above thesis-1's site downward;
 * grazing from 2..50 m above the surface; skimming a surface point), 100 of each, as axes of
 * cones of spread 1e-3 (a guide pixel's pattern at 320 x 180 is ~3e-3 across) and 1e-2, over
 * test_terrain_trace's field (seed 46, warped) and the thesis presets' mountains (seed 7, first
 * octave 1e-4 /m, no warp). And walls, the case where the bound's lateral term (1 + L) spread t
 * is what stops the walk in time, on the mountains at four times the frequency (slopes to 10.4
 * over 20000 points around the site; the two fields above reach 0.17 and 2.6 there, which the
 * walk's stopping rule alone would cover): at surface points q of slope s = |grad h| >
 * WALL_SLOPE, a horizontal axis along the contour, passing q WALL_DISTANCE_M on at q's
 * altitude, displaced downhill so that its clearance there is WALL_CLEARANCE x (spread t +
 * eps); a ray of the cone tilted toward the wall (checked beside the rim's 8) enters it near q,
 * as (WALL_CLEARANCE / s) (spread t + eps) < spread t. 100 such cones at spread 1e-2. A walk
 * that took the lateral term as spread t, without the slope (it stops at an axis clearance of 2
 * (spread t + eps)), passes them: that mutation fails the test.
 * Asserted: no violation. And that the start is of use (a start of 0 would pass the claim):
 * over the downward axes of spread 1e-3, the mean of t_s over the reference's hit distance is
 * at least 0.5 (printed). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/plan_terrain.h"
#include "atmo/terrain_ref.h"
#include "testlib.h"
#include "testscene.h"
#include "testterrain.h"

#define N_KIND 100
#define N_AXES (4 * N_KIND) /* the three kinds of rays, then the walls */
#define N_RIM 8
#define WALL_SLOPE 2.6      /* |grad h| at a wall's point */
#define WALL_DISTANCE_M 300.0
#define WALL_CLEARANCE 2.2  /* the axis's clearance at the wall, in (spread t + eps) */
#define WALL_TRIES 100000   /* points drawn for the walls (one in eight is steep enough) */

/* The probe: the cone start of the axis o + t d with the spread in d.w (test_trace_run's
 * t_max slot). */
static const char probe_src[] =
    "__kernel void trace(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                    __global const float4 *o, __global const float4 *d,\n"
    "                    __global float4 *out, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  out[i] = (float4)(terrain_cone_start(s, heightmap, o[i].xyz, d[i].xyz, d[i].w,\n"
    "                                       s->terrain.steps), 0.0f, 0.0f, 0.0f);\n"
    "}\n";

/* Direction k of the cone's rim: chord `spread` from the unit axis d, at azimuth 2 pi k / N_RIM. */
static void rim_direction(const double d[3], double spread, int k, double out[3])
{
    double a[3] = {fabs(d[0]) < 0.9 ? 1.0 : 0.0, fabs(d[0]) < 0.9 ? 0.0 : 1.0, 0.0};
    double e1[3] = {d[1] * a[2] - d[2] * a[1], d[2] * a[0] - d[0] * a[2], d[0] * a[1] - d[1] * a[0]};
    double l = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int c = 0; c < 3; c++)
        e1[c] /= l;
    double e2[3] = {d[1] * e1[2] - d[2] * e1[1], d[2] * e1[0] - d[0] * e1[2],
                    d[0] * e1[1] - d[1] * e1[0]};
    double theta = 2.0 * asin(0.5 * spread), phi = 2.0 * M_PI * k / N_RIM;
    for (int c = 0; c < 3; c++)
        out[c] = d[c] * cos(theta) + (e1[c] * cos(phi) + e2[c] * sin(phi)) * sin(theta);
}

/* Up to n cones along walls (see the top of the file) for `spread`, from at most
 * WALL_TRIES points drawn: their axes in rays[], the horizontal unit vector toward each wall
 * in toward[]; returns how many. */
static int make_walls(const test_trace_setup *u, double spread, int n, unsigned *rng,
                      test_trace_ray *rays, double (*toward)[3])
{
    const atmo_gpu_terrain_field *f = &u->plan.gpu.terrain.field;
    double tol = (double)u->plan.gpu.terrain.tolerance;
    int i = 0;
    for (int tries = 0; i < n && tries < WALL_TRIES; tries++) {
        double x = TEST_TRACE_SITE_X + (test_trace_urand(rng) - 0.5) * 4000;
        double z = TEST_TRACE_SITE_Z + (test_trace_urand(rng) - 0.5) * 4000;
        double grad[2], q[3], up[3];
        terrain_ref_height(f, x, z, grad, NULL);
        double slope = hypot(grad[0], grad[1]);
        test_trace_surface_point(f, NULL, 0.0, x, z, q, up);
        if (slope < WALL_SLOPE || q[1] <= 1.0) /* gentle, or the sea */
            continue;
        /* uphill and along the contour, horizontal at q */
        double g[3] = {grad[0] / slope, 0.0, grad[1] / slope}, k = g[0] * up[0] + g[2] * up[2];
        for (int c = 0; c < 3; c++)
            g[c] -= k * up[c];
        double lg = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        double along[3] = {up[1] * g[2] - up[2] * g[1], up[2] * g[0] - up[0] * g[2],
                           up[0] * g[1] - up[1] * g[0]};
        double la = sqrt(along[0] * along[0] + along[1] * along[1] + along[2] * along[2]);
        double t = WALL_DISTANCE_M, eps = 0.01 + tol * t;
        double off = WALL_CLEARANCE * (spread * t + eps) / slope, o[3];
        for (int c = 0; c < 3; c++) {
            g[c] /= lg;
            along[c] /= la;
            o[c] = q[c] - off * g[c] - t * along[c];
        }
        if (terrain_ref_clearance(f, test_trace_R_m, 0.0, o) < 1.0)
            continue; /* the contour bends: the axis would start in the ground */
        test_trace_make_ray(&rays[i], u->cam, o, along, 20000.0);
        memcpy(toward[i], g, sizeof toward[i]);
        i++;
    }
    return i;
}

/* Checks one ray of a cone from world point o along unit d over [0, t_s]: returns 1 on a
 * violation of the claim (see the top of the file). */
static int check_ray(const test_trace_setup *u, double L, const double o[3], const double d[3],
                     double t_s)
{
    const atmo_gpu_terrain *tr = &u->plan.gpu.terrain;
    double t_ref, min_clear;
    if (t_s <= 0.0)
        return 0;
    if (terrain_ref_hit_map(&tr->field, u->heightmap, test_trace_R_m, tr->sea_level_m, o, d, t_s,
                            TEST_TRACE_REF_STEP_M, &t_ref, &min_clear)) {
        fprintf(stderr, "  the reference hits at %.3f m, before the cone start %.3f m\n", t_ref,
                t_s);
        return 1;
    }
    for (double t = 0.0; t <= t_s; t += TEST_TRACE_REF_STEP_M) {
        double w[3];
        for (int c = 0; c < 3; c++)
            w[c] = o[c] + t * d[c];
        double g = terrain_ref_clearance_map(&tr->field, u->heightmap, test_trace_R_m,
                                             tr->sea_level_m, w);
        double eps = 0.01 + (double)tr->tolerance * t, delta = test_trace_delta_m(&tr->field, L, w, t);
        if (g < eps - delta) {
            fprintf(stderr, "  clearance %.4f m at %.3f m (eps %.4f, delta %.4f), cone start "
                            "%.3f m\n", g, t, eps, delta, t_s);
            return 1;
        }
    }
    return 0;
}

/* The cones over one terrain (extra settings e1..e3, may be NULL; walls: the walls too at the
 * second spread): returns the violations. */
static int run_terrain(atmo_cl *cl, const char *name, const char *e1, const char *e2,
                       const char *e3, unsigned seed, int walls)
{
    test_trace_setup u;
    test_trace_plan_above_site(&u, e1, e2, e3);
    const atmo_gpu_terrain_field f = u.plan.gpu.terrain.field;
    cl_program prog = test_plan_program(cl, &u.plan, probe_src);
    double L = atmo_terrain_slope_bound(&u.plan.gpu.terrain.field);

    test_trace_ray *rays = calloc(N_AXES, sizeof *rays);
    float4 *out = calloc(N_AXES, sizeof *out);
    unsigned rng = seed;
    double(*toward)[3] = calloc(N_KIND, sizeof *toward);
    test_trace_make_rays(&f, NULL, u.cam, N_KIND, N_KIND, N_KIND, &rng, rays);
    static const double spreads[2] = {1e-3, 1e-2};
    static const char *const kinds[4] = {"downward", "grazing", "ridge-skimming", "wall"};
    int bad = 0;
    for (int s = 0; s < 2; s++) {
        int n_kinds = walls && s == 1 ? 4 : 3;
        if (n_kinds == 4)
            CHECK(make_walls(&u, spreads[s], N_KIND, &rng, rays + 3 * N_KIND, toward) == N_KIND);
        for (int i = 0; i < N_AXES; i++)
            rays[i].t_max = spreads[s]; /* the probe's spread */
        test_trace_run(cl, prog, &u.plan, rays, n_kinds * N_KIND, out);
        for (int kind = 0; kind < n_kinds; kind++) {
            int kind_bad = 0, hits = 0;
            double start = 0.0, ratio = 0.0;
            for (int i = kind * N_KIND; i < (kind + 1) * N_KIND; i++) {
                double o[3], d[3], t_s = out[i].x, t_hit, min_clear;
                test_trace_world_at(&u, &rays[i], 0.0, o);
                kind_bad += check_ray(&u, L, o, rays[i].d, t_s);
                for (int k = 0; k < N_RIM; k++) {
                    rim_direction(rays[i].d, spreads[s], k, d);
                    kind_bad += check_ray(&u, L, o, d, t_s);
                }
                if (kind == 3) { /* the ray tilted toward the wall */
                    double theta = 2.0 * asin(0.5 * spreads[s]);
                    for (int c = 0; c < 3; c++)
                        d[c] = rays[i].d[c] * cos(theta) + toward[i - 3 * N_KIND][c] * sin(theta);
                    kind_bad += check_ray(&u, L, o, d, t_s);
                }
                start += t_s / N_KIND;
                if (terrain_ref_hit_map(&f, NULL, test_trace_R_m, u.plan.gpu.terrain.sea_level_m,
                                        o, rays[i].d, 20000.0, TEST_TRACE_REF_STEP_M, &t_hit,
                                        &min_clear)) {
                    ratio += t_s / t_hit;
                    hits++;
                }
            }
            ratio = hits ? ratio / hits : 0.0;
            printf("%s, spread %.0e, %-14s %d cones x %d rays: %d violations; mean start "
                   "%.1f m, %.3f of the axis's hit distance (%d hits)\n",
                   name, spreads[s], kinds[kind], N_KIND, 1 + N_RIM + (kind == 3), kind_bad,
                   start, ratio, hits);
            if (s == 0 && kind == 0)
                CHECK(ratio >= 0.5);
            bad += kind_bad;
        }
    }
    free(toward);
    free(out);
    free(rays);
    clReleaseProgram(prog);
    atmo_plan_free(&u.plan);
    return bad;
}

int main(void)
{
    test_require_opencl();
    atmo_cl cl;
    test_cl_open(&cl);
    int bad = run_terrain(&cl, "seed 46, warped", NULL, NULL, NULL, 901u, 0);
    bad += run_terrain(&cl, "thesis mountains", "terrain.seed=7", "terrain.frequency_per_m=1e-4",
                       "terrain.warp=0", 902u, 0);
    bad += run_terrain(&cl, "steep mountains", "terrain.seed=7", "terrain.frequency_per_m=4e-4",
                       "terrain.warp=0", 903u, 1);
    CHECK(bad == 0);
    atmo_cl_close(&cl);
    return test_finish();
}
