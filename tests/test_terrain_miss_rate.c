/* test_terrain_miss_rate — the sphere tracer's miss rate below 1e-4, demonstrated: over 3e4
 * rays that hit, none may be missed or mistraced.
 * labels: kernel slow
 *
 * Oracle: the brute-force double-precision march terrain_ref_hit (host/terrain/terrain_ref.c),
 * with the classes of error of test_terrain_trace (miss, pass-through, false hit, bad hit;
 * tests/support_terrain_trace.c). Rays: the same three kinds in the same proportions as
 * test_terrain_trace but 15 times as many and from another seed: 12000 downward from a camera
 * 300 m above thesis-1's site, 18000 grazing (cosine to the vertical -0.05..0.02, 2..50 m above
 * the surface) and 15000 skimming a surface point at 0.05..3 m, at the default steps and
 * optimism. Statistics: with k errors among n reference hits, the rate's one-sided 95 % upper
 * bound is the chi-square quantile chi2_{0.95}(2k + 2) / (2n): 3.0 / n for k = 0, so 0 errors
 * in n >= 30000 hits bound the rate below 1e-4. Asserted: at least 30000 reference hits, 0
 * errors, over the default field (with the default domain warp) at the default optimism,
 * over the thesis presets' mountains (seed 7, first octave 1e-4 /m, no warp) at theirs (4),
 * and over the same mountains with the default warp at optimism 4 (slopes to 6, the worst-case
 * bound 33: the tracer's local bound under the warp, kernels/terrain/terrain.h, keeps its
 * rays within the 600 steps). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "atmo/terrain_ref.h"
#include "testlib.h"
#include "testscene.h"
#include "testterrain.h"

#define N_DOWN 12000
#define N_GRAZE 18000
#define N_SKIM 15000
#define N_RAYS (N_DOWN + N_GRAZE + N_SKIM)
/* the thesis presets' terrain.optimism (host/scene/scene_presets.c) */
#define THESIS_OPTIMISM 4.0f

/* The rays over one field (the scene's terrain keys extra1, extra2; optimism > 0 replaces the
 * default's): prints the tally, returns the errors and adds the reference hits to *hits. */
static int miss_rate(atmo_cl *cl, const char *label, const char *extra1, const char *extra2,
                     const char *extra3, float optimism, int *hits)
{
    test_trace_setup u;
    test_trace_plan_above_site(&u, extra1, extra2, extra3);
    const atmo_gpu_terrain_field f = u.plan.gpu.terrain.field;
    if (optimism > 0.0f)
        u.plan.gpu.terrain.optimism = optimism;
    cl_program prog = test_plan_program(cl, &u.plan, test_trace_probe_src);
    test_trace_ray *rays = calloc(N_RAYS, sizeof *rays);
    float4 *out = calloc(N_RAYS, sizeof *out);
    unsigned rng = 20261201u;
    test_trace_make_rays(&f, NULL, u.cam, N_DOWN, N_GRAZE, N_SKIM, &rng, rays);
    test_trace_run(cl, prog, &u.plan, rays, N_RAYS, out);
    static const char *const names[3] = {"downward", "grazing", "ridge-skimming"};
    const int first[4] = {0, N_DOWN, N_DOWN + N_GRAZE, N_RAYS};
    int all_hits = 0, all_bad = 0;
    for (int g = 0; g < 3; g++) {
        test_trace_tally y = test_trace_judge(&u, rays + first[g], first[g + 1] - first[g],
                                              out + first[g], 1);
        printf("%s (optimism %.1f, slope L %.2f): %-14s %5d rays, %5d hits (reference %5d): %d "
               "misses, %d pass-throughs, %d false, %d bad; worst clearance %.3f of its bound; "
               "%.1f steps per ray\n",
               label, (double)u.plan.gpu.terrain.optimism, (double)u.plan.gpu.terrain.slope_bound,
               names[g], first[g + 1] - first[g], y.hits, y.ref_hits, y.misses, y.through,
               y.false_hits, y.bad, y.worst_clear, y.mean_steps);
        all_hits += y.ref_hits;
        all_bad += y.misses + y.through + y.false_hits + y.bad;
    }
    printf("%s: %d errors in %d reference hits: rate < %.3g at 95 %% confidence\n", label,
           all_bad, all_hits, 3.0 / all_hits);
    *hits = all_hits;
    atmo_plan_free(&u.plan);
    free(rays);
    free(out);
    clReleaseProgram(prog);
    return all_bad;
}

int main(void)
{
    test_require_opencl();
    atmo_cl cl;
    test_cl_open(&cl);
    int hits = 0, bad = miss_rate(&cl, "default field", NULL, NULL, NULL, 0.0f, &hits);
    CHECK(hits >= 30000);
    CHECK(bad == 0);
    bad = miss_rate(&cl, "thesis mountains", "terrain.seed=7", "terrain.frequency_per_m=1e-4",
                    "terrain.warp=0", THESIS_OPTIMISM, &hits);
    CHECK(hits >= 30000);
    CHECK(bad == 0);
    hits = 0;
    bad = miss_rate(&cl, "warped mountains", "terrain.seed=7", "terrain.frequency_per_m=1e-4",
                    "terrain.warp=1.25", THESIS_OPTIMISM, &hits);
    CHECK(hits >= 30000);
    CHECK(bad == 0);
    atmo_cl_close(&cl);
    return test_finish();
}
