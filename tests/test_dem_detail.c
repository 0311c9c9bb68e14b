/* test_dem_detail — the fBm's detail below a DEM's cells (kernels/terrain/terrain_detail.h,
 * terrain.heightmap_detail) under a heightmap: its heights and normals, its spectrum, and the
 * sphere tracer over it.
 * labels: kernel
 *
 * Setup: thesis-1's terrain (seed 46) with a 512-texel heightmap over 65536 m (128 m texels)
 * whose base grid is that terrain itself sampled at the texel centres (double reference rounded
 * to float: a DEM with the fBm's slopes), and atmo_plan_terrain_detail for 128 m cells: the
 * octaves 10 .. 13 (lattice periods 32.6 .. 4.1 m, at most half a cell), first amplitude
 * H 1.2 / sum b 2^-10 = 2.35 m.
 *
 * Oracles:
 *  1. The kernels' float detail (terrain_detail_height, the header compiled on the host)
 *     against its double reference (terrain_ref_detail) at 4000 points up to 30 km out: the
 *     lattice coordinates' rounding, relative (i0 + K) 2^-24, moves the point by that times
 *     max(|u|, |v|, 1 km), the height by the detail's slope bound L_d times it; the sum adds
 *     K 2^-24 of the amplitude bound. Bound 4 (L_d (i0 + K) 2^-24 max(|u|, |v|, 1 km)
 *     + K 2^-24 2 A) (the factor 4 for the fractions' and the fades' rounding), and for the
 *     gradient 4 L_d (i0 + K) 2^-24 (max(|u|, |v|, 1 km) / P_last + 1). The double gradient
 *     against central differences (step 1e-3 m; truncation h^2/6 |d'''| < 1e-6 with
 *     |d'''| <= sum A_i 2 60 / P_i^3 ~ 2): bound 1e-6 + 1e-5 |grad|.
 *  2. The lookups (terrain_height_at, terrain_height_value) over a base grid that is a plane,
 *     h = 500 + 0.05 u + 0.03 v (bilinear interpolation and the central differences reproduce a
 *     plane exactly): the height is the plane plus the double detail and the gradient (the
 *     normal's input) (0.05, 0.03) plus the detail's, within bound 1 plus the float rounding of
 *     the plane's heights (2^-24 2000 m per texel, 4 texels).
 *  3. Spectrum: the difference (DEM + detail) - DEM is the detail; its mean over a cell of side
 *     C = 128 m at 400 random places has variance at most B = sum_i A_i^2 / 3 (P_i / C)^2
 *     (terrain_detail.h: averaged interpolation weights sum to 1 and are each at most
 *     (P_i / C)^2; independent lattice values of variance 1/3), so the mean square of the 400
 *     cell means (128 x 128 midpoint samples each) must lie below B (1 + 4 sqrt(2 / 400)): the
 *     chi-square spread of a mean of 400 squares of near-normal means, 4 sigma. Their mean lies
 *     within 4 sqrt(B / 400) of 0. The same sum started one octave coarser (periods up to a
 *     whole cell) must exceed that bound, so the test sees a detail that reaches the cells'
 *     wavelengths.
 *  4. Sphere tracing over the DEM with detail on the device: the rays of test_terrain_trace
 *     (400 downward from 300 m above the site, 600 grazing, 500 skimming at 0.05..3 m) against
 *     the brute-force double march over the same float heightmap plus the double detail
 *     (terrain_ref_hit_map, 2 m steps, shorter near the surface: no 4 m lattice cell is
 *     stepped over), classes of error as in test_terrain_trace: none asserted (a rate below
 *     3 / hits at 95 % confidence; test_dem_detail_miss_rate, slow, takes it below 1e-4), the
 *     steps per ray printed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/plan_terrain.h"
#include "atmo/terrain_ref.h"
#include "terrain/terrain.h"
#include "testlib.h"
#include "testscene.h"
#include "testterrain.h"

#define MAP TEST_TRACE_DEM_MAP
#define EXTENT TEST_TRACE_DEM_EXTENT_M
#define CELLS 400
#define QUAD 128

static double urand(unsigned *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (*state >> 8) / 16777216.0;
}

/* The mean of the detail of field f over the square [x, x + C] x [z, z + C]. */
static double cell_mean(const atmo_gpu_terrain_field *f, double x, double z, double C)
{
    double sum = 0;
    for (int j = 0; j < QUAD; j++)
        for (int i = 0; i < QUAD; i++)
            sum += terrain_ref_detail(f, x + (i + 0.5) * C / QUAD, z + (j + 0.5) * C / QUAD, NULL);
    return sum / (QUAD * QUAD);
}

int main(void)
{
    test_trace_setup u;
    double cam0[3] = {TEST_TRACE_SITE_X, 0.0, TEST_TRACE_SITE_Z};
    float *plane = test_trace_dem_plan(&u, cam0, 1);
    atmo_gpu_terrain_field f = u.plan.gpu.terrain.field;
    int i0 = f.detail_octave0, K = f.detail_octaves;
    double A = f.detail_amplitude_m, texel = EXTENT / MAP;
    double L = atmo_terrain_slope_bound(&f), Ld = L;
    {
        atmo_gpu_terrain_field g = f;
        g.detail_octaves = 0;
        Ld = L - atmo_terrain_slope_bound(&g);
    }
    double P_last = 1.0 / ldexp((double)f.frequency_per_m, i0 + K - 1);
    printf("detail: octaves %d..%d (periods %.2f..%.2f m), first amplitude %.3f m, slope bound "
           "%.3f (of %.3f)\n", i0, i0 + K - 1, 1.0 / ldexp((double)f.frequency_per_m, i0), P_last,
           A, Ld, L);
    CHECK(i0 == 10 && K == 4);
    CHECK(fabs(A - 4000.0 * 1.2 / (2.0 * (1.0 - pow(0.5, 9))) / 1024.0) < 1e-3);
    CHECK(1.0 / ldexp((double)f.frequency_per_m, i0) <= 0.5 * texel &&
          1.0 / ldexp((double)f.frequency_per_m, i0 - 1) > 0.5 * texel);

    /* 1: float against double, and the double gradient against finite differences */
    unsigned rng = 4242u;
    double worst_h = 0, worst_g = 0, worst_fd = 0, eps = ldexp(1.0, -24) * (i0 + K);
    for (int k = 0; k < 4000; k++) {
        double x = (double)(float)((2 * urand(&rng) - 1) * 3e4);
        double z = (double)(float)((2 * urand(&rng) - 1) * 3e4);
        double g[2], step = 1e-3, reach = fmax(fmax(fabs(x), fabs(z)), 1000.0);
        double d = terrain_ref_detail(&f, x, z, g);
        terrain_height df = terrain_detail_height(&f, (float)x, (float)z);
        double hb = 4.0 * (Ld * eps * reach + K * ldexp(1.0, -24) * 2 * A);
        double gb = 4.0 * Ld * eps * (reach / P_last + 1.0);
        worst_h = fmax(worst_h, fabs(df.h - d) / hb);
        worst_g = fmax(worst_g, fmax(fabs(df.du - g[0]), fabs(df.dv - g[1])) / gb);
        CHECK(fabs(df.h - d) <= hb);
        CHECK(fabs(df.du - g[0]) <= gb && fabs(df.dv - g[1]) <= gb);
        CHECK(fabs(terrain_detail_value(&f, (float)x, (float)z) - df.h) <= 1e-6 * A);
        double hx = (terrain_ref_detail(&f, x + step, z, NULL) -
                     terrain_ref_detail(&f, x - step, z, NULL)) / (2 * step);
        double hz = (terrain_ref_detail(&f, x, z + step, NULL) -
                     terrain_ref_detail(&f, x, z - step, NULL)) / (2 * step);
        double fd = fmax(fabs(hx - g[0]), fabs(hz - g[1])), fb = 1e-6 + 1e-5 * hypot(g[0], g[1]);
        worst_fd = fmax(worst_fd, fd / fb);
        CHECK(fd <= fb);
    }
    printf("float detail vs double: height worst %.3f, gradient worst %.3f of the bound; double "
           "gradient vs central differences worst %.3f of the bound\n", worst_h, worst_g, worst_fd);

    /* 2: the lookups over a plane */
    double worst_l = 0, worst_n = 0;
    for (int k = 0; k < 2000; k++) {
        double x = (double)(float)((urand(&rng) - 0.5) * (EXTENT - 4 * texel));
        double z = (double)(float)((urand(&rng) - 0.5) * (EXTENT - 4 * texel));
        double g[2], d = terrain_ref_detail(&f, x, z, g);
        terrain_height h = terrain_height_at(&f, plane, (float)x, (float)z);
        float hv = terrain_height_value(&f, plane, (float)x, (float)z);
        double hb = 4.0 * (Ld * eps * fmax(fmax(fabs(x), fabs(z)), 1000.0) +
                           K * ldexp(1.0, -24) * 2 * A) + 4 * ldexp(1.0, -24) * 2000.0;
        double gb = 4.0 * Ld * eps * (fmax(fabs(x), fabs(z)) / P_last + 1.0) +
                    4 * ldexp(1.0, -24) * 2000.0 / texel;
        double want = 500.0 + 0.05 * x + 0.03 * z + d;
        worst_l = fmax(worst_l, fmax(fabs(h.h - want), fabs(hv - want)) / hb);
        worst_n = fmax(worst_n, fmax(fabs(h.du - 0.05 - g[0]), fabs(h.dv - 0.03 - g[1])) / gb);
        CHECK(fabs(h.h - want) <= hb && fabs(hv - want) <= hb);
        CHECK(fabs(h.du - 0.05 - g[0]) <= gb && fabs(h.dv - 0.03 - g[1]) <= gb);
    }
    printf("lookups over a plane with detail: height worst %.3f, gradient worst %.3f of the "
           "bound\n", worst_l, worst_n);

    /* 3: no energy at the cells' wavelengths */
    double B = 0, C = texel, ms = 0, mean = 0, ms_coarse = 0, pointwise = 0;
    for (int k = 0; k < K; k++) {
        double Ak = ldexp(A, -k), Pk = 1.0 / ldexp((double)f.frequency_per_m, i0 + k);
        B += Ak * Ak / 3.0 * (Pk / C) * (Pk / C);
    }
    atmo_gpu_terrain_field coarse = f;
    coarse.detail_octave0 = i0 - 1;
    coarse.detail_amplitude_m = (float)(2 * A);
    for (int k = 0; k < CELLS; k++) {
        double x = (urand(&rng) - 0.5) * 6e4, z = (urand(&rng) - 0.5) * 6e4;
        double m = cell_mean(&f, x, z, C), mc = cell_mean(&coarse, x, z, C);
        double d = terrain_ref_detail(&f, x, z, NULL);
        ms += m * m / CELLS, mean += m / CELLS, ms_coarse += mc * mc / CELLS;
        pointwise += d * d / CELLS;
    }
    double limit = B * (1.0 + 4.0 * sqrt(2.0 / CELLS));
    printf("cell means of the detail over %d cells of %.0f m: mean %.2e m, mean square %.3e m^2 "
           "= %.3f of the bound B = %.3e (pointwise mean square %.3e: the cells keep %.4f of "
           "it); started one octave coarser: %.3e = %.1f B\n", CELLS, C, mean, ms, ms / B, B,
           pointwise, ms / pointwise, ms_coarse, ms_coarse / B);
    CHECK(ms <= limit);
    CHECK(fabs(mean) <= 4.0 * sqrt(B / CELLS));
    CHECK(ms_coarse > limit);
    atmo_plan_free(&u.plan);
    free(plane);

    /* 4: the tracer over the DEM with detail */
    test_require_opencl();
    atmo_cl cl;
    test_cl_open(&cl);
    int hits = 0, errors = test_trace_dem_run(&cl, 400, 600, 500, 9001u, &hits);
    CHECK(hits >= 1000);
    CHECK(errors == 0);
    atmo_cl_close(&cl);
    return test_finish();
}
