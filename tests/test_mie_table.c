/* test_mie_table.c — phase tables and where the photometeors appear.
 * labels: unit
 *
 * Oracles:
 *   - P is 4pi-normalised by construction (divided by the exact C_sca), so (1/2) integral
 *     P sin d theta on the grid measures the grid's quadrature error: bound 1 +- 1e-4.
 *     g of the table against the cross-section-weighted g of the same radius sum: also 1e-4
 *     (same quadrature). A uniform 1 deg grid must miss by > 5 % (mie.md: 12 % at r_eff 10 um).
 *   - CDF: monotone, 0 and 1 at the ends.
 *   - Fog bow (mie.md, Laven): maximum between 138 and 148 deg, moving outward as drops shrink.
 *   - Corona: first bright ring of a narrow distribution (5 % spread) at x sin(theta) = 5.136
 *     (Airy maximum); we allow 5 % for the spread and the Mie-vs-Airy difference; theta * r
 *     constant (rings ~ 1/r) to the same 5 %.
 *   - Glory: ring spacing ~ 180 deg / x; the spacing of successive maxima within 170-180 deg of
 *     a narrow (2 %) distribution, within 25 % (the "about" of mie.md: the rings are not exactly
 *     periodic). */
#include <stdlib.h>
#include "atmo/mie.h"
#include "testlib.h"

#define PI 3.14159265358979323846

static void test_normalisation(void)
{
    mie_dsd d;
    mie_table t, u;
    atmo_err e;
    mie_dsd_preset("cumulus", &d);
    CHECK(mie_table_build(&d, 550.0, 1.3359, 2.5e-9, NULL, &t, &e) == ATMO_OK);
    double g = mie_table_asymmetry(&t);
    printf("cumulus 550 nm: %d angles, norm - 1 = %.2g, g table %.6f bulk %.6f\n", t.n,
           t.norm - 1.0, g, t.bulk.g);
    CHECK_ABS(t.norm, 1.0, 1e-4);
    CHECK_ABS(g, t.bulk.g, 1e-4);
    CHECK(t.cdf[0] == 0.0 && t.cdf[t.n - 1] == 1.0);
    int mono = 1;
    for (int i = 1; i < t.n; i++)
        mono &= t.cdf[i] >= t.cdf[i - 1] && t.theta_deg[i] > t.theta_deg[i - 1];
    CHECK(mono);
    /* fine near the ends, 0.1 deg elsewhere */
    CHECK(t.theta_deg[1] <= fmin(0.1, 10.0 / t.bulk.x_max) + 1e-12);
    mie_table_options coarse = {.uniform = 1, .coarse_step_deg = 1.0};
    CHECK(mie_table_build(&d, 550.0, 1.3359, 2.5e-9, &coarse, &u, &e) == ATMO_OK);
    printf("uniform 1 deg grid: norm - 1 = %.3f, g %.4f\n", u.norm - 1.0, mie_table_asymmetry(&u));
    CHECK(fabs(u.norm - 1.0) > 0.05);
    /* the sun's disc keeps the normalisation (it only redistributes) */
    mie_table_options sun = {.sun_radius_deg = 0.2665};
    mie_table s;
    CHECK(mie_table_build(&d, 550.0, 1.3359, 2.5e-9, &sun, &s, &e) == ATMO_OK);
    printf("with sun disc: norm - 1 = %.2g, P(0) %.1f -> %.1f\n", s.norm - 1.0, t.P[0], s.P[0]);
    CHECK_ABS(s.norm, 1.0, 1e-3);
    CHECK(s.P[0] < t.P[0]);
    mie_table_free(&t);
    mie_table_free(&u);
    mie_table_free(&s);
}

/* angle of the largest P in [a, b] degrees, sampled every `step` */
static double argmax_deg(const mie_dsd *d, double a, double b, double step)
{
    int n = (int)((b - a) / step) + 1;
    double *mu = malloc(sizeof *mu * n), *P = malloc(sizeof *P * n);
    for (int i = 0; i < n; i++)
        mu[i] = cos((a + i * step) * PI / 180.0);
    mie_bulk bulk;
    atmo_err e;
    CHECK(mie_dsd_integrate(d, 550.0, 1.3359, 2.5e-9, 0.0, 0.0, n, mu, P, &bulk, &e) == ATMO_OK);
    int best = 0;
    for (int i = 1; i < n; i++)
        if (P[i] > P[best])
            best = i;
    free(mu);
    free(P);
    return a + best * step;
}

static void test_fog_bow(void)
{
    double prev = 0.0;
    static const double reff[] = {20.0, 10.0, 5.0};
    for (int i = 0; i < 3; i++) {
        mie_dsd d = {.kind = MIE_DSD_GAMMA, .r_eff_um = reff[i], .v_eff = 0.05};
        double th = argmax_deg(&d, 125.0, 165.0, 0.1);
        printf("fog bow r_eff %g um: %.1f deg\n", reff[i], th);
        CHECK(th >= 138.0 && th <= 148.0);
        CHECK(th > prev);
        prev = th;
    }
}

static void test_corona(void)
{
    static const double r[] = {5.0, 10.0, 20.0};
    double tr0 = 0.0;
    for (int i = 0; i < 3; i++) {
        mie_dsd d = {.kind = MIE_DSD_LOGNORMAL, .r_g_um = r[i], .sigma_g = 1.05};
        double x = 2.0 * PI * r[i] / 0.55;
        double airy = asin(5.136 / x) * 180.0 / PI;
        /* the first ring lies between the first and second Airy zeros */
        double lo = asin(3.832 / x) * 180.0 / PI, hi = asin(7.016 / x) * 180.0 / PI;
        double th = argmax_deg(&d, lo, hi, (hi - lo) / 400.0);
        printf("corona r %g um: first ring %.3f deg (Airy %.3f)\n", r[i], th, airy);
        CHECK_REL(th, airy, 0.05);
        if (i == 0)
            tr0 = th * r[i];
        else
            CHECK_REL(th * r[i], tr0, 0.05);
    }
}

static void test_glory(void)
{
    mie_dsd d = {.kind = MIE_DSD_LOGNORMAL, .r_g_um = 10.0, .sigma_g = 1.02};
    double x = 2.0 * PI * 10.0 / 0.55;
    enum { N = 1001 };
    static double mu[N], P[N];
    for (int i = 0; i < N; i++)
        mu[i] = cos((170.0 + 10.0 * i / (N - 1)) * PI / 180.0);
    mie_bulk b;
    atmo_err e;
    CHECK(mie_dsd_integrate(&d, 550.0, 1.3359, 2.5e-9, 0.0, 0.0, N, mu, P, &b, &e) == ATMO_OK);
    double maxima[32];
    int m = 0;
    for (int i = 1; i < N - 1 && m < 32; i++)
        if (P[i] > P[i - 1] && P[i] >= P[i + 1])
            maxima[m++] = 170.0 + 10.0 * i / (N - 1);
    CHECK(m >= 3);
    if (m >= 3) {
        double spacing = (maxima[m - 1] - maxima[0]) / (m - 1);
        printf("glory r 10 um: %d rings in 170-180 deg, spacing %.3f deg, 180/x = %.3f deg\n", m,
               spacing, 180.0 / x);
        CHECK_REL(spacing, 180.0 / x, 0.25);
    }
}

int main(void)
{
    test_normalisation();
    test_fog_bow();
    test_corona();
    test_glory();
    return test_finish();
}
