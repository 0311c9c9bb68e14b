/* test_phase_sampling.c — samplers and pdfs of kernels/common/phase.h (host build of the shared header,
 * float), for HG, Cornette-Shanks, Draine, two-term HG, Jendersie-d'Eon and the Mie table.
 * labels: stat
 *
 * Oracles:
 *   - Chi-square goodness of fit: 200000 samples (fixed seed) in 100 bins uniform in cos theta;
 *     expected bin probabilities integrate each pdf in double (adaptive Simpson). The
 *     test fails when the statistic exceeds the chi-square quantile with p-value 1e-3
 *     (Wilson-Hilferty approximation, 99 degrees of freedom: 148.2).
 *   - Each phase function integrates to 1 over the sphere (adaptive Simpson of a float function),
 *     within 1e-4: float rounding of the evaluations is ~1e-6. The table's linear interpolant in
 *     cos theta integrates to its trapezoid sum in cos theta, which differs from the trapezoid in
 *     theta that normalised it (1 +- 1e-4, test_mie_table) by O(h^2): 2e-4 there.
 *     Jendersie-d'Eon at d = 50 um has an HG lobe with g = 0.995, whose peak 1 + g^2 - 2 g nu
 *     = (1 - g)^2 = 2.5e-5 the textbook float formula formed by cancellation (7.7e-4 off in the
 *     integral); kernels/common/phase.h forms it without, and it must meet the same 1e-4 (measured
 *     2.4e-5, the rounding of nu to float in this integrator).
 *   - pdf == phase where the sampling is exact (every analytic one): pdf(nu) and phase(nu) agree
 *     to float rounding (1e-6 relative). The table's pdf is its own piecewise-constant density;
 *     it must agree with the table's P within the linear-interpolation error (checked in
 *     aggregate through the bins of the chi-square). */
#include <stdint.h>
#include <stdlib.h>
#include "atmo/mie.h"
#include "common/phase.h"
#include "testlib.h"

#define NBINS 100
#define NSAMPLES 200000

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static float uniform(void)
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return (float)((rng_state * 0x2545F4914F6CDD1Dull) >> 40) * (1.0f / 16777216.0f);
}

typedef struct sampler {
    const char *name;
    int kind;
    float a, b, c;
} sampler;

static phase_jd_params jd;
static float *table_mu, *table_P, *table_cdf;
static int table_n;

static float s_pdf(const sampler *s, float nu)
{
    switch (s->kind) {
    case 0: return phase_henyey_greenstein_pdf(nu, s->a);
    case 1: return phase_cornette_shanks_pdf(nu, s->a);
    case 2: return phase_draine_pdf(nu, s->a, s->b);
    case 3: return phase_two_term_hg_pdf(nu, s->a, s->b, s->c);
    case 4: return phase_jendersie_deon_pdf(nu, jd);
    default: return phase_table_pdf(nu, table_mu, table_cdf, table_n);
    }
}

static float s_phase(const sampler *s, float nu)
{
    switch (s->kind) {
    case 0: return phase_henyey_greenstein(nu, s->a);
    case 1: return phase_cornette_shanks(nu, s->a);
    case 2: return phase_draine(nu, s->a, s->b);
    case 3: return phase_two_term_hg(nu, s->a, s->b, s->c);
    case 4: return phase_jendersie_deon(nu, jd);
    default: return phase_table(nu, table_mu, table_P, table_n);
    }
}

static float s_sample(const sampler *s, float u1, float u2)
{
    switch (s->kind) {
    case 0: return phase_henyey_greenstein_sample(s->a, u1);
    case 1: return phase_cornette_shanks_sample(s->a, u1);
    case 2: return phase_draine_sample(s->a, s->b, u1);
    case 3: return phase_two_term_hg_sample(s->a, s->b, s->c, u1, u2);
    case 4: return phase_jendersie_deon_sample(jd, u1, u2);
    default: return phase_table_sample(table_mu, table_cdf, table_n, u1);
    }
}

static double eval(const sampler *s, int pdf, double nu)
{
    return pdf ? s_pdf(s, (float)nu) : s_phase(s, (float)nu);
}

/* adaptive Simpson: the forward peaks (HG g = 0.995 for 20 um drops) are narrower than 1e-4 */
static double simpson(const sampler *s, int pdf, double a, double b, double fa, double fm,
                      double fb, double whole, double eps, int depth)
{
    double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    double flm = eval(s, pdf, lm), frm = eval(s, pdf, rm);
    double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm), right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    if (depth <= 0 || fabs(left + right - whole) <= 15.0 * eps)
        return left + right + (left + right - whole) / 15.0;
    return simpson(s, pdf, a, m, fa, flm, fm, left, 0.5 * eps, depth - 1) +
           simpson(s, pdf, m, b, fm, frm, fb, right, 0.5 * eps, depth - 1);
}

/* 2 pi integral of the pdf (pdf = 1) or phase over [a, b] in cos theta, to ~1e-8 absolute */
static double integrate(const sampler *s, int pdf, double a, double b)
{
    double sum = 0.0;
    for (int i = 0; i < 16; i++) { /* start from 16 panels so no lobe is missed */
        double x0 = a + (b - a) * i / 16.0, x1 = a + (b - a) * (i + 1) / 16.0;
        double f0 = eval(s, pdf, x0), fm = eval(s, pdf, 0.5 * (x0 + x1)), f1 = eval(s, pdf, x1);
        sum += simpson(s, pdf, x0, x1, f0, fm, f1, (x1 - x0) / 6.0 * (f0 + 4.0 * fm + f1), 1e-9, 30);
    }
    return 2.0 * 3.14159265358979323846 * sum;
}

static double chi2_quantile(int dof, double z)
{
    double k = dof, t = 1.0 - 2.0 / (9.0 * k) + z * sqrt(2.0 / (9.0 * k));
    return k * t * t * t;
}

static void check_sampler(const sampler *s)
{
    static long counts[NBINS];
    for (int i = 0; i < NBINS; i++)
        counts[i] = 0;
    for (int i = 0; i < NSAMPLES; i++) {
        float u1 = uniform(), u2 = uniform();
        float mu = s_sample(s, u1, u2);
        CHECK(mu >= -1.0f && mu <= 1.0f);
        int b = (int)((mu + 1.0f) * 0.5f * NBINS);
        counts[b < 0 ? 0 : (b >= NBINS ? NBINS - 1 : b)]++;
    }
    double chi2 = 0.0;
    for (int i = 0; i < NBINS; i++) {
        double lo = -1.0 + 2.0 * i / NBINS, hi = -1.0 + 2.0 * (i + 1) / NBINS;
        double expect = NSAMPLES * integrate(s, 1, lo, hi);
        chi2 += (counts[i] - expect) * (counts[i] - expect) / expect;
    }
    double crit = chi2_quantile(NBINS - 1, 3.090); /* p = 1e-3 */
    double norm = integrate(s, 0, -1.0, 1.0);
    printf("%-28s chi2 %.1f (critical %.1f)  integral %.7f\n", s->name, chi2, crit, norm);
    CHECK(chi2 < crit);
    CHECK_ABS(norm, 1.0, s->kind == 5 ? 2e-4 : 1e-4);
    if (s->kind != 5)
        for (int i = 0; i <= 20; i++) {
            float nu = -1.0f + 0.1f * (float)i;
            CHECK_REL(s_pdf(s, nu), s_phase(s, nu), 1e-6);
        }
}

int main(void)
{
    /* a fog table at 550 nm in float, as the kernels will get it */
    mie_dsd d;
    mie_table t;
    atmo_err e;
    mie_dsd_preset("stratus", &d);
    if (mie_table_build(&d, 550.0, 1.3359, 2.5e-9, NULL, &t, &e) != ATMO_OK) {
        fprintf(stderr, "%s\n", e.msg);
        return 1;
    }
    table_n = t.n;
    table_mu = malloc(sizeof *table_mu * t.n);
    table_P = malloc(sizeof *table_P * t.n);
    table_cdf = malloc(sizeof *table_cdf * t.n);
    for (int i = 0; i < t.n; i++)
        table_mu[i] = (float)t.mu[i], table_P[i] = (float)t.P[i], table_cdf[i] = (float)t.cdf[i];

    const sampler list[] = {
        {"HG g=0.76", 0, 0.76f, 0, 0},       {"HG g=-0.3", 0, -0.3f, 0, 0},
        {"HG g=0.9", 0, 0.9f, 0, 0},         {"Cornette-Shanks g=0.76", 1, 0.76f, 0, 0},
        {"Cornette-Shanks g=0.2", 1, 0.2f, 0, 0}, {"Draine g=0.6 a=10", 2, 0.6f, 10.0f, 0},
        {"Draine g=0.3 a=1", 2, 0.3f, 1.0f, 0},   {"two-term HG", 3, 0.85f, -0.4f, 0.8f},
    };
    for (size_t i = 0; i < sizeof list / sizeof list[0]; i++)
        check_sampler(&list[i]);
    static const float diam[] = {5.0f, 10.0f, 20.0f, 50.0f};
    for (int i = 0; i < 4; i++) {
        jd = phase_jendersie_deon_params(diam[i]);
        char name[64];
        snprintf(name, sizeof name, "Jendersie-d'Eon d=%g um", (double)diam[i]);
        sampler s = {name, 4, 0, 0, 0};
        check_sampler(&s);
    }
    sampler tab = {"Mie table (stratus 550 nm)", 5, 0, 0, 0};
    check_sampler(&tab);
    free(table_mu);
    free(table_P);
    free(table_cdf);
    mie_table_free(&t);
    return test_finish();
}
