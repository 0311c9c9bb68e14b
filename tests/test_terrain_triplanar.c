/* test_terrain_triplanar — the triplanar detail noise of the terrain's materials
 * (kernels/terrain/terrain_material.h: terrain_triplanar_weights, terrain_material_noise).
 * labels: unit
 *
 * Oracles:
 *  1. Closed form: the weights (h_u^4, 1, h_v^4) / (1 + h_u^4 + h_v^4) sum to 1 (within 4 float
 *     roundings, 2^-22) and lie in [0, 1] for 10000 gradients of slopes 0 to 1e6 in every
 *     direction; on flat ground they are exactly (0, 1, 0) and the detail is bitwise the planar
 *     noise D(u, v) (flat terrain renders as before).
 *  2. Statistics, on a cliff: the plane a = s u with s = 20 (87.1 degrees), 20000 random points
 *     over 10 km x 10 km, the footprint 1 cm (no fading). The increments of dn over 2 m along
 *     the fall line (du = 2 / sqrt(1 + s^2), da = s du) and along the strike (dv = 2) have
 *     mean squares m_f and m_s (variance per 2 m of the detail in each direction). Their
 *     difference, the mean of the paired differences x_f^2 - x_s^2 at each point, is compared
 *     with its standard error from those differences' own variance (sd / sqrt(n); the pairs
 *     share a point, so they are not independent of each other): |z| < 4 for the triplanar noise (the projection on (v, a)
 *     carries 1 - 6e-6 of the weight and moves 0.99875 m per metre along the fall line: a bias
 *     of 0.25 %, about 0.2 standard errors). The planar noise D(u, v) on the same cliff moves
 *     1 / sqrt(401) m per metre along the fall line: its z must lie below -4, with m_f / m_s
 *     near 1 / 401 (the stretch the triplanar blend removes; printed). */
#include <math.h>
#include <stdio.h>
#include "terrain/terrain_material.h"
#include "testlib.h"

#define N 20000
#define SLOPE 20.0
#define STEP_M 2.0
#define SEED 46u

static double urand(unsigned *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (*state >> 8) / 16777216.0;
}

/* The detail on the cliff a = SLOPE u at (u, v): triplanar or, with planar, D(u, v) alone. */
static double cliff(double u, double v, int planar)
{
    float a = (float)(SLOPE * u);
    if (planar)
        return terrain_material_noise_plane(SEED, (float)u, (float)v, 0.01f);
    return terrain_material_noise(SEED, (float)u, (float)v, a, (float)SLOPE, 0.0f, 0.01f);
}

/* z of m_f - m_s (see the top of the file), and the ratio m_f / m_s. */
static double stretch_z(int planar, double *ratio)
{
    unsigned rng = planar ? 31u : 17u;
    double sf = 0, ss = 0, sd = 0, sd2 = 0, du = STEP_M / sqrt(1.0 + SLOPE * SLOPE);
    for (int k = 0; k < N; k++) {
        double u = (urand(&rng) - 0.5) * 1e4 / SLOPE, v = (urand(&rng) - 0.5) * 1e4;
        double d0 = cliff(u, v, planar);
        double xf = cliff(u + du, v, planar) - d0, xs = cliff(u, v + STEP_M, planar) - d0;
        double d = xf * xf - xs * xs;
        sf += xf * xf, ss += xs * xs, sd += d, sd2 += d * d;
    }
    double mf = sf / N, ms = ss / N, md = sd / N, z = md / sqrt((sd2 / N - md * md) / N);
    *ratio = mf / ms;
    printf("%s on a %.0f:1 cliff: mean square of 2 m increments along the fall line %.4e, "
           "along the strike %.4e (ratio %.4f), z = %.2f\n", planar ? "planar    " : "triplanar",
           SLOPE, mf, ms, mf / ms, z);
    return z;
}

int main(void)
{
    /* 1 */
    unsigned rng = 5u;
    double worst = 0;
    for (int k = 0; k < 10000; k++) {
        double slope = pow(10.0, -3.0 + 9.0 * urand(&rng)), phi = 2 * M_PI * urand(&rng);
        float w[3];
        terrain_triplanar_weights((float)(slope * cos(phi)), (float)(slope * sin(phi)), w);
        double sum = (double)w[0] + w[1] + w[2];
        worst = fmax(worst, fabs(sum - 1.0));
        CHECK(fabs(sum - 1.0) <= ldexp(1.0, -22));
        CHECK(w[0] >= 0 && w[0] <= 1 && w[1] >= 0 && w[1] <= 1 && w[2] >= 0 && w[2] <= 1);
    }
    float flat[3];
    terrain_triplanar_weights(0.0f, 0.0f, flat);
    CHECK(flat[0] == 0.0f && flat[1] == 1.0f && flat[2] == 0.0f);
    int same = 1;
    for (int k = 0; k < 1000; k++) {
        float u = (float)((urand(&rng) - 0.5) * 1e5), v = (float)((urand(&rng) - 0.5) * 1e5);
        float fp = (float)(100.0 * urand(&rng));
        same &= terrain_material_noise(SEED, u, v, 1234.5f, 0.0f, 0.0f, fp) ==
                terrain_material_noise_plane(SEED, u, v, fp);
    }
    CHECK(same);
    printf("triplanar weights: sum within %.2e of 1 over slopes 1e-3..1e6; flat ground bitwise "
           "the planar noise: %s\n", worst, same ? "yes" : "NO");

    /* 2 */
    double r_tri, r_plane;
    double z_tri = stretch_z(0, &r_tri), z_plane = stretch_z(1, &r_plane);
    CHECK(fabs(z_tri) < 4.0);
    CHECK(z_plane < -4.0);
    return test_finish();
}
