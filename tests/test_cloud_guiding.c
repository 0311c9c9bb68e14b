/* test_cloud_guiding — the clouds' sun-guided continuation (kernels/media/phase_table.h:
 * cloud_guiding_pdf, cloud_phase_direction; host build of the shared header, float) for
 * Henyey-Greenstein (g = 0.8, 0.85, 0.9 per channel), Jendersie-d'Eon (20 um) and the cumulus
 * Mie table as the plan gives it to the kernels, with eps = 0.3 and the sun 40 degrees from
 * the path's direction d, for a path of throughput 1 and (HG, the table) one whose largest
 * channel is 4: the header's rule scales the sun lobe's share to eps_b = eps / 4, which the
 * oracles below take from that rule (a sampler that ignored the throughput would draw the sun's
 * lobe four times too often and fail the chi-square by far).
 * labels: unit stat
 *
 * Oracles:
 *   - Quadrature over the sphere in double of the float density: the sphere is split by the
 *     partition of unity h_d + h_s = 1, h_d = q_p(d . w) / (q_p(d . w) + q_p(s . w)), and
 *     q h_d is integrated in polar coordinates about d, q h_s about s (midpoint rule,
 *     QUAD_THETA x QUAD_PHI cells, finer toward each pole where the lobes peak), so each
 *     lobe's peak sits at its grid's pole. The mixture's density must integrate to 1 within
 *     QUAD_TOL. Measured: 2e-6 (HG), 2e-5 (the table), 6.7e-4 (Jendersie-d'Eon, whose HG lobe
 *     of g = 0.9946 peaks at 5400 / sr: its float cosines from float directions near the pole
 *     are off by ~1e-7, a few per cent of 1 - cos there); doubling either grid changes them by
 *     less than 3e-4. The phase itself integrates to 1 within 1e-4 in one dimension (the
 *     Simpson rule below), which is the normalisation the second check relies on.
 *   - Chi-square of the sampler against q: N_SAMPLES directions (fixed seed) in BINS_C x
 *     BINS_PHI bins of (d . w, azimuth about d); each bin's probability is the same
 *     quadrature of q restricted to the bin. Bins expecting fewer than 5 are pooled; the
 *     statistic must stay below the chi-square critical value at p = 1e-4
 *     (test_chi2_critical_1e4). The quadrature's error per bin (< 1e-4 of the total) is far
 *     below a bin's sampling spread (~ 1 / sqrt(count) > 1e-2 of its count).
 *   - Unbiasedness of the weights: for each channel c and each bin of d . w,
 *     mean(f_c 1[bin]) estimates int_bin p_c dw, which is 2 pi int p_c(x) dx over the bin's
 *     cosines (adaptive Simpson in theta, double); |z| < 4.5 with the sample's standard error
 *     (BINS_C x 3 comparisons per phase; a false alarm about 4e-4 for all). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "common/compat.h"
#include "common/frame.h"
#include "common/phase.h"
#include "common/rng.h"
#include "media/phase_table.h"
#include "atmo/plan.h"
#include "testlib.h"
#include "testscene.h"

#define EPS 0.3f
#define N_SAMPLES 400000
#define BINS_C 20
#define BINS_PHI 16
#define BINS (BINS_C * BINS_PHI)
#define QUAD_THETA 4096
#define QUAD_PHI 1024
#define QUAD_TOL 1e-3
#define Z_MAX 4.5

typedef struct guided_phase {
    const char *name;
    int phase;
    vec3 g_hg;
    const float4 *rows;
    const float *cdf;
    int n;
} guided_phase;

static const float diameter_um = 20.0f;

/* The throughput of the path the sampler is given, and the share of the sun's lobe it implies by
 * the header's rule eps_b = eps / max(1, beta_max). */
static vec3 beta_now;
static float eps_now;

static float pdf_at(const guided_phase *p, float c)
{
    return cloud_phase_pdf(p->phase, p->g_hg, diameter_um, p->rows, p->cdf, p->n, c);
}

/* The bin of the unit w in the frame (t, b, d): cosine to d and azimuth about it. */
static int bin_of(vec3 d, vec3 t, vec3 b, vec3 w)
{
    float c = atmo_clamp_cos(v3_dot(d, w));
    double phi = atan2(v3_dot(w, b), v3_dot(w, t)) + M_PI;
    int i = (int)((c + 1.0) * 0.5 * BINS_C), j = (int)(phi / (2.0 * M_PI) * BINS_PHI);
    i = i < 0 ? 0 : i >= BINS_C ? BINS_C - 1 : i;
    j = j < 0 ? 0 : j >= BINS_PHI ? BINS_PHI - 1 : j;
    return i * BINS_PHI + j;
}

/* int q over the sphere and over each bin (prob[]), by the partition of unity of the header.
 * The polar grid about each axis is uniform in sqrt(theta / pi), so cells shrink toward the
 * pole (2.4e-5 rad at 1 mrad from it, 1.5e-3 rad at the antipode). */
static double quadrature(const guided_phase *p, vec3 d, vec3 sun, double *prob)
{
    vec3 t, b;
    frame_basis(d, &t, &b);
    for (int k = 0; k < BINS; k++)
        prob[k] = 0.0;
    double total = 0.0;
    for (int lobe = 0; lobe < 2; lobe++) {
        vec3 axis = lobe ? sun : d;
        for (int i = 0; i < QUAD_THETA; i++) {
            double x0 = (double)i / QUAD_THETA, x1 = (double)(i + 1) / QUAD_THETA;
            double xm = 0.5 * (x0 + x1);
            double th0 = M_PI * x0 * x0, th1 = M_PI * x1 * x1, th = M_PI * xm * xm;
            double ring = (cos(th0) - cos(th1)) * 2.0 * M_PI / QUAD_PHI; /* cell solid angle */
            for (int j = 0; j < QUAD_PHI; j++) {
                vec3 w = frame_direction(axis, (float)cos(th), (float)(2.0 * M_PI * (j + 0.5) / QUAD_PHI));
                float pd = pdf_at(p, v3_dot(d, w)), ps = pdf_at(p, v3_dot(sun, w));
                if (pd + ps <= 0.0f)
                    continue;
                double share = (lobe ? ps : pd) / ((double)pd + ps);
                double q = cloud_guiding_pdf(p->phase, p->g_hg, diameter_um, p->rows, p->cdf, p->n,
                                             d, sun, eps_now, w);
                double m = q * share * ring;
                total += m;
                prob[bin_of(d, t, b, w)] += m;
            }
        }
    }
    return total;
}

/* 2 pi int_{c0}^{c1} p_ch(x) dx as 2 pi int p sin(theta) dtheta, adaptive Simpson in theta */
static double phase_theta(const guided_phase *p, int ch, double th)
{
    vec3 v = cloud_phase_eval(p->phase, p->g_hg, diameter_um, p->rows, p->n, (float)cos(th));
    return 2.0 * M_PI * (ch == 0 ? v.x : ch == 1 ? v.y : v.z) * sin(th);
}

static double simpson(const guided_phase *p, int ch, double a, double b, double fa, double fm,
                      double fb, double whole, int depth)
{
    double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    double flm = phase_theta(p, ch, lm), frm = phase_theta(p, ch, rm);
    double left = (b - a) / 12.0 * (fa + 4.0 * flm + fm), right = (b - a) / 12.0 * (fm + 4.0 * frm + fb);
    if (depth <= 0 || fabs(left + right - whole) < 1e-10)
        return left + right;
    return simpson(p, ch, a, m, fa, flm, fm, left, depth - 1) +
           simpson(p, ch, m, b, fm, frm, fb, right, depth - 1);
}

static double phase_mass(const guided_phase *p, int ch, double c0, double c1)
{
    double a = acos(c1), b = acos(c0); /* theta ascending */
    int pieces = 64; /* the forward peak: start from a fine split */
    double sum = 0.0;
    for (int k = 0; k < pieces; k++) {
        double lo = a + (b - a) * k / pieces, hi = a + (b - a) * (k + 1) / pieces;
        double fa = phase_theta(p, ch, lo), fb = phase_theta(p, ch, hi);
        double fm = phase_theta(p, ch, 0.5 * (lo + hi));
        sum += simpson(p, ch, lo, hi, fa, fm, fb, (hi - lo) / 6.0 * (fa + 4.0 * fm + fb), 18);
    }
    return sum;
}

static void check_phase(const guided_phase *p, vec3 beta)
{
    beta_now = beta;
    eps_now = EPS / fmaxf(1.0f, fmaxf(beta.x, fmaxf(beta.y, beta.z)));
    const vec3 d = v3_normalize(v3(0.2f, -0.3f, 0.93f));
    vec3 t, b;
    frame_basis(d, &t, &b);
    const vec3 sun = frame_direction(d, cosf(40.0f * (float)M_PI / 180.0f), 1.0f);
    static double prob[BINS];
    double total = quadrature(p, d, sun, prob);
    double norm = phase_mass(p, 1, -1.0, 1.0);
    printf("%s, throughput max %g (eps_b %g): int q dw = %.6f (int p dw, 1-D: %.6f)\n", p->name,
           (double)fmaxf(beta.x, fmaxf(beta.y, beta.z)), (double)eps_now, total, norm);
    CHECK_ABS(total, 1.0, QUAD_TOL);
    CHECK_ABS(norm, 1.0, 1e-4);

    static double count[BINS];
    double sum[3][BINS_C] = {{0}}, sum2[3][BINS_C] = {{0}};
    for (int k = 0; k < BINS; k++)
        count[k] = 0.0;
    for (int i = 0; i < N_SAMPLES; i++) {
        rng_stream g = rng_stream_stage(41u, (uint)i, 0u, 0u);
        float u1 = rng_next(&g), u2 = rng_next(&g);
        vec3 weight;
        vec3 w = cloud_phase_direction(p->phase, p->g_hg, diameter_um, p->rows, p->cdf, p->n, d, sun,
                                       EPS, beta_now, u1, u2, &g, &weight);
        int k = bin_of(d, t, b, w);
        count[k] += 1.0;
        float f[3] = {weight.x, weight.y, weight.z};
        for (int ch = 0; ch < 3; ch++)
            sum[ch][k / BINS_PHI] += f[ch], sum2[ch][k / BINS_PHI] += (double)f[ch] * f[ch];
    }

    double chi2 = 0.0, pool_n = 0.0, pool_e = 0.0;
    int dof = -1;
    for (int k = 0; k < BINS; k++) {
        double e = prob[k] / total * N_SAMPLES;
        if (e < 5.0) {
            pool_n += count[k], pool_e += e;
            continue;
        }
        chi2 += (count[k] - e) * (count[k] - e) / e;
        dof++;
    }
    if (pool_e > 0.0)
        chi2 += (pool_n - pool_e) * (pool_n - pool_e) / pool_e, dof++;
    double crit = test_chi2_critical_1e4(dof);
    printf("%s: chi-square %.1f over %d degrees of freedom (critical %.1f)\n", p->name, chi2, dof,
           crit);
    CHECK(chi2 < crit);

    double worst = 0.0;
    for (int ch = 0; ch < 3; ch++)
        for (int i = 0; i < BINS_C; i++) {
            double c0 = -1.0 + 2.0 * i / BINS_C, c1 = -1.0 + 2.0 * (i + 1) / BINS_C;
            double want = phase_mass(p, ch, c0, c1);
            double mean = sum[ch][i] / N_SAMPLES;
            double se = sqrt(fmax(sum2[ch][i] / N_SAMPLES - mean * mean, 0.0) / N_SAMPLES);
            double z = se > 0.0 ? (mean - want) / se : 0.0;
            worst = fmax(worst, fabs(z));
            CHECK_ABS(mean, want, Z_MAX * se + 1e-7);
        }
    printf("%s: weighted bins of d . w vs int p_c, worst |z| %.2f\n", p->name, worst);
}

int main(void)
{
    guided_phase hg = {"Henyey-Greenstein", ATMO_CLOUD_PHASE_HG, v3(0.8f, 0.85f, 0.9f), NULL, NULL, 0};
    check_phase(&hg, v3(1.0f, 1.0f, 1.0f));
    check_phase(&hg, v3(0.5f, 4.0f, 2.0f));
    guided_phase jd = {"Jendersie-d'Eon 20 um", ATMO_CLOUD_PHASE_JENDERSIE_DEON, v3(0, 0, 0), NULL,
                       NULL, 0};
    check_phase(&jd, v3(1.0f, 1.0f, 1.0f));

    atmo_plan p;
    const void *rows, *cdf;
    int n = test_cumulus_phase_table(&p, &rows, &cdf);
    guided_phase mie = {"cumulus Mie table", ATMO_CLOUD_PHASE_MIE, v3(0, 0, 0), rows, cdf, n};
    check_phase(&mie, v3(1.0f, 1.0f, 1.0f));
    check_phase(&mie, v3(4.0f, 0.5f, 0.5f));
    atmo_plan_free(&p);
    return test_finish();
}
