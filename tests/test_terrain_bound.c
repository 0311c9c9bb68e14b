/* test_terrain_bound — the height's cheap forms that the tracer steps by (kernels/terrain/
 * noise.h): the value-only height and the early upper bound of terrain_height_direct_capped.
 * labels: unit
 *
 * Oracles (the kernels' float code compiled on the host, at 40000 random points of the thesis
 * site's 60 km square and 4000 out to 3000 km, each with a random cap in [0, H]):
 *  1. The value-only height (terrain_height_direct_value) against the full evaluation's
 *     (terrain_height_direct): the same sums in the same order, so they agree to the float
 *     rounding of the last operations, bound 1e-6 H.
 *  2. Where the capped form returns a bound, it lies at or above the float height and at or
 *     above the double-precision reference (host/terrain/terrain_ref.c) less the float
 *     rounding bound of test_terrain_noise (4 (L N 2^-24 max(|u|, |v|, 1 km) + N 2^-24 H)), and
 *     at or below the cap (what the tracer relies on: the bound is a height no surface
 *     exceeds, and it is offered only where it clears the hit tolerance). The closed form
 *     behind it: after m octaves |e - e_m| <= k R_m, since each eroded term lies in
 *     [-b_i, b_i] and tanh has slope <= 1.
 *  3. The bound is taken at least once in 20 at caps far above the surface (else it would
 *     save nothing): a statistical floor, not a speed claim. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "atmo/plan.h"
#include "atmo/terrain_ref.h"
#include "terrain/terrain.h"
#include "testlib.h"
#include "testscene.h"

static double urand(unsigned *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (*state >> 8) / 16777216.0;
}

int main(void)
{
    atmo_scene s;
    atmo_plan p;
    test_scene_preset(&s, "thesis-1");
    test_plan(&s, &p);
    const atmo_gpu_terrain_field *f = &p.gpu.terrain.field;
    double H = f->max_height_m, L = p.gpu.terrain.slope_bound, N = f->octaves;
    unsigned rng = 12345u;
    int taken = 0, far_caps = 0, far_taken = 0, bad_value = 0, bad_bound = 0;
    double worst_value = 0.0, worst_below = -1e30;
    for (int i = 0; i < 44000; i++) {
        double span = i < 40000 ? 30000.0 : 3e6;
        double u = 23796.0 + (urand(&rng) * 2 - 1) * span, v = 16636.0 + (urand(&rng) * 2 - 1) * span;
        float cap = (float)(urand(&rng) * H);
        int bound;
        float hv = terrain_height_direct_value(f, (float)u, (float)v);
        terrain_height full = terrain_height_direct(f, (float)u, (float)v);
        double dv = fabs((double)hv - (double)full.h);
        worst_value = fmax(worst_value, dv);
        bad_value += dv > 1e-6 * H;
        float hb = terrain_height_direct_capped(f, (float)u, (float)v, cap, &bound, NULL);
        double ref = terrain_ref_height(f, u, v, NULL, NULL);
        double tol = 4.0 * (L * N * ldexp(1.0, -24) * fmax(fmax(fabs(u), fabs(v)), 1000.0) +
                            N * ldexp(1.0, -24) * H);
        if (cap > ref + 0.5 * H) {
            far_caps++;
            far_taken += bound;
        }
        if (!bound)
            continue;
        taken++;
        worst_below = fmax(worst_below, (double)hv - (double)hb);
        if (hb < hv || (double)hb < ref - tol || hb > cap) {
            if (bad_bound < 5)
                fprintf(stderr, "bound %.4f at (%.1f, %.1f): float %.4f, double %.4f, cap %.1f\n",
                        (double)hb, u, v, (double)hv, ref, (double)cap);
            bad_bound++;
        }
    }
    printf("value-only height: worst %.3g m from the full evaluation (bound %.3g)\n", worst_value,
           1e-6 * H);
    printf("bound taken at %d of 44000 points (%d of %d caps > 0.5 H above the surface); "
           "height - bound at most %.4g m\n",
           taken, far_taken, far_caps, worst_below);
    CHECK(bad_value == 0);
    CHECK(bad_bound == 0);
    CHECK(far_caps > 0 && far_taken * 20 >= far_caps);
    atmo_plan_free(&p);
    return test_finish();
}
