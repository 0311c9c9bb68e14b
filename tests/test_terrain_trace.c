/* test_terrain_trace — sphere tracing the terrain (kernels/terrain/terrain.h) on the device
 * against a brute-force double-precision march, and its precision at planet scale.
 * labels: kernel
 *
 * Oracle: terrain_ref_hit (host/terrain/terrain_ref.c): the same height field in double,
 * marched in steps of at most 2 m (shorter near the surface, so no feature of the 130 m finest
 * octave is stepped over) and bisected to 1e-9. With eps(t) = 0.01 m + tolerance t the
 * tracer's acceptance distance and delta(t) = the float rounding bound of the height field
 * (test_terrain_noise's bound 2) plus 2e-7 t for the ray's float position, a ray is counted as
 *   - a miss: the reference hits, the tracer does not;
 *   - a pass-through: both hit, but the reference's clearance goes more than delta + 0.5 m
 *     below the surface between its hit and the tracer's (the tracer stepped over solid
 *     ground);
 *   - a false hit: the tracer hits, the reference does not, and the reference ray's smallest
 *     clearance exceeds eps + delta;
 *   - a bad hit: the double clearance at the tracer's hit point lies outside
 *     [-delta, eps + delta].
 * Rays: from a camera 300 m above thesis-1's site, 800 downward rays; 1200 grazing rays
 * (cosine to the vertical in [-0.05, 0.02]) from 2..50 m above the surface; 1000 rays that
 * skim a random surface point horizontally at 0.05..3 m, started on the line back from it
 * where that is at least 1 m above the terrain. Asserted: no miss, pass-through, false
 * or bad hit among them (at most 3 / hits at 95 % confidence for the rate), at the default
 * steps and optimism. With 8 steps the fallback resolves every downward ray (a hit within the
 * bound: never sky) and the others' errors are printed. The same rays (their own draw) over the
 * thesis presets' mountains (seed 7, first octave 1e-4 /m: slopes to 75 degrees) at the
 * default steps and the presets' optimism 4: no error either.
 *
 * Precision: one target point on the surface seen at 45 degrees from cameras 1 m, 10 m, ...,
 * 100 km and 2000 km away (each its own camera-relative frame, image 16384 px high with a 1
 * degree field, so eps(t) ~ 5e-7 t): the double clearance at the hit within [-delta, eps +
 * delta] and the hit point within (eps + delta) / |dg/dt| + 1e-6 t of the reference's, dg/dt
 * the rate the reference's clearance falls along the ray. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/plan_terrain.h"
#include "atmo/terrain_ref.h"
#include "testlib.h"
#include "testscene.h"
#include "testterrain.h"

#define N_DOWN 800
#define N_GRAZE 1200
#define N_SKIM 1000
#define N_RAYS (N_DOWN + N_GRAZE + N_SKIM)


int main(void)
{
    test_require_opencl();
    atmo_cl cl;
    test_cl_open(&cl);
    test_trace_setup u;
    double cam[3] = {TEST_TRACE_SITE_X, 0.0, TEST_TRACE_SITE_Z}, p[3], n[3];
    test_trace_plan_at(&u, cam, NULL, NULL); /* for the field */
    const atmo_gpu_terrain_field f = u.plan.gpu.terrain.field;
    test_trace_surface_point(&f, NULL, 0.0, TEST_TRACE_SITE_X, TEST_TRACE_SITE_Z, p, n);
    atmo_plan_free(&u.plan);
    for (int k = 0; k < 3; k++)
        cam[k] = p[k] + 300.0 * n[k];
    test_trace_plan_at(&u, cam, NULL, NULL);
    cl_program prog = test_plan_program(&cl, &u.plan, test_trace_probe_src);

    test_trace_ray *rays = calloc(N_RAYS, sizeof *rays);
    float4 *out = calloc(N_RAYS, sizeof *out);
    unsigned rng = 777u;
    test_trace_make_rays(&f, NULL, cam, N_DOWN, N_GRAZE, N_SKIM, &rng, rays);
    static const char *const names[3] = {"downward", "grazing", "ridge-skimming"};
    const int first[4] = {0, N_DOWN, N_DOWN + N_GRAZE, N_RAYS};

    test_trace_run(&cl, prog, &u.plan, rays, N_RAYS, out);
    int all_hits = 0, all_bad = 0;
    for (int g = 0; g < 3; g++) {
        test_trace_tally y = test_trace_judge(&u, rays + first[g], first[g + 1] - first[g], out + first[g], 1);
        printf("default (steps %d, optimism %.2f): %-14s %4d rays, %4d hits (reference %4d): "
               "%d misses, %d pass-throughs, %d false, %d bad; worst clearance %.3f of its "
               "bound; %.1f steps per ray\n",
               u.plan.gpu.terrain.steps, (double)u.plan.gpu.terrain.optimism, names[g],
               first[g + 1] - first[g], y.hits, y.ref_hits, y.misses, y.through, y.false_hits,
               y.bad, y.worst_clear, y.mean_steps);
        all_hits += y.ref_hits;
        all_bad += y.misses + y.through + y.false_hits + y.bad;
    }
    CHECK(all_bad == 0);
    printf("  %d errors in %d reference hits: rate < %.2g at 95 %% confidence\n", all_bad,
           all_hits, 3.0 / all_hits);
    atmo_plan_free(&u.plan);

    /* the fallback: 8 steps */
    test_trace_plan_at(&u, cam, "terrain.steps=8", NULL);
    test_trace_run(&cl, prog, &u.plan, rays, N_RAYS, out);
    for (int g = 0; g < 3; g++) {
        test_trace_tally y = test_trace_judge(&u, rays + first[g], first[g + 1] - first[g], out + first[g], 0);
        printf("8 steps + fallback: %-14s %4d hits (reference %4d): %d misses, %d "
               "pass-throughs, %d false, %d bad; %.1f steps per ray\n",
               names[g], y.hits, y.ref_hits, y.misses, y.through, y.false_hits, y.bad,
               y.mean_steps);
        if (g == 0)
            CHECK(y.misses == 0 && y.through == 0 && y.bad == 0);
    }
    atmo_plan_free(&u.plan);

    /* the thesis presets' mountains (seed 7, first octave 1e-4 /m, no warp) at the default
     * steps */
    static const char *const mountains[3] = {"terrain.seed=7", "terrain.frequency_per_m=1e-4",
                                             "terrain.warp=0"};
    double cam_m[3] = {TEST_TRACE_SITE_X, 0.0, TEST_TRACE_SITE_Z};
    test_trace_plan_at3(&u, cam_m, mountains[0], mountains[1], mountains[2]);
    const atmo_gpu_terrain_field fm = u.plan.gpu.terrain.field;
    test_trace_surface_point(&fm, NULL, 0.0, TEST_TRACE_SITE_X, TEST_TRACE_SITE_Z, p, n);
    atmo_plan_free(&u.plan);
    for (int k = 0; k < 3; k++)
        cam_m[k] = p[k] + 300.0 * n[k];
    test_trace_plan_at3(&u, cam_m, mountains[0], mountains[1], mountains[2]);
    u.plan.gpu.terrain.optimism = 4.0f; /* the thesis presets' */
    rng = 778u;
    test_trace_make_rays(&fm, NULL, cam_m, N_DOWN, N_GRAZE, N_SKIM, &rng, rays);
    test_trace_run(&cl, prog, &u.plan, rays, N_RAYS, out);
    int m_hits = 0, m_bad = 0;
    for (int g = 0; g < 3; g++) {
        test_trace_tally y = test_trace_judge(&u, rays + first[g], first[g + 1] - first[g], out + first[g], 1);
        printf("mountains (steps %d, optimism 4, slope bound %.2f): %-14s %4d hits (reference %4d): %d "
               "misses, %d pass-throughs, %d false, %d bad; %.1f steps per ray\n",
               u.plan.gpu.terrain.steps, (double)u.plan.gpu.terrain.slope_bound, names[g], y.hits,
               y.ref_hits, y.misses, y.through, y.false_hits, y.bad, y.mean_steps);
        m_hits += y.ref_hits;
        m_bad += y.misses + y.through + y.false_hits + y.bad;
    }
    CHECK(m_bad == 0);
    printf("  %d errors in %d reference hits: rate < %.2g at 95 %% confidence\n", m_bad, m_hits,
           3.0 / m_hits);
    atmo_plan_free(&u.plan);

    /* precision: one target, cameras from 1 m to 2000 km away at 45 degrees */
    double target[3], tn[3];
    test_trace_surface_point(&f, NULL, 0.0, TEST_TRACE_SITE_X + 1234.5, TEST_TRACE_SITE_Z - 987.25, target, tn);
    double east[3] = {tn[1], -tn[0], 0}, el = hypot(east[0], east[1]);
    static const double dist[] = {1, 10, 100, 1e3, 1e4, 1e5, 2e6};
    for (size_t k = 0; k < sizeof dist / sizeof dist[0]; k++) {
        double c[3], d[3];
        for (int i = 0; i < 3; i++) {
            d[i] = -(tn[i] + east[i] / el) / sqrt(2.0);
            c[i] = target[i] - dist[k] * sqrt(2.0) * d[i] * 0.5 * sqrt(2.0);
        }
        test_trace_plan_at(&u, c, "image.height=16384", "camera.fov_deg=1");
        test_trace_ray r;
        test_trace_make_ray(&r, c, c, d, 2.0 * dist[k] + 1e4);
        float4 res;
        test_trace_run(&cl, prog, &u.plan, &r, 1, &res);
        const atmo_gpu_terrain *tr = &u.plan.gpu.terrain;
        double L = atmo_terrain_slope_bound(&tr->field);
        /* the reference from where the ray comes below the highest terrain */
        double start = fmax(0.0, dist[k] - 6000.0), o[3], t_ref, mc;
        test_trace_world_at(&u, &r, start, o);
        int ref = terrain_ref_hit(&tr->field, test_trace_R_m, 0.0, o, r.d, dist[k] + 1e4 - start, TEST_TRACE_REF_STEP_M,
                                  &t_ref, &mc);
        t_ref += start;
        double w[3], wr[3], a[3], b[3];
        test_trace_world_at(&u, &r, res.x, w);
        test_trace_world_at(&u, &r, t_ref, wr);
        test_trace_world_at(&u, &r, t_ref - 0.5, a);
        test_trace_world_at(&u, &r, t_ref + 0.5, b);
        double rate = fabs(terrain_ref_clearance(&tr->field, test_trace_R_m, 0.0, b) -
                           terrain_ref_clearance(&tr->field, test_trace_R_m, 0.0, a));
        double t = res.x, eps = 0.01 + (double)tr->tolerance * t;
        double delta = test_trace_delta_m(&tr->field, L, w, t);
        double g = terrain_ref_clearance(&tr->field, test_trace_R_m, 0.0, w);
        double err = sqrt((w[0] - wr[0]) * (w[0] - wr[0]) + (w[1] - wr[1]) * (w[1] - wr[1]) +
                          (w[2] - wr[2]) * (w[2] - wr[2]));
        double bound = (eps + delta) / fmax(rate, 0.05) + 1e-6 * t;
        CHECK(ref && res.x >= 0.0f);
        CHECK(g >= -delta && g <= eps + delta);
        CHECK(err <= bound);
        printf("camera %8.0f m from the target: hit %.4f m from the reference's (bound %.3f), "
               "clearance %+.4f m (eps %.3f, delta %.3f)\n",
               dist[k], err, bound, g, eps, delta);
        atmo_plan_free(&u.plan);
    }
    free(rays);
    free(out);
    clReleaseProgram(prog);
    atmo_cl_close(&cl);
    return test_finish();
}
