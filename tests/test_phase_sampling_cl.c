/* test_phase_sampling_cl.c — the samplers and pdfs of kernels/common/phase.h compiled by OpenCL (PoCL):
 * HG (g up to 0.995), Cornette-Shanks, Draine, two-term HG, Jendersie-d'Eon at 5, 10, 20 and
 * 50 um, and the tabulated Mie CDF of a cumulus at 550 nm (built on the host, uploaded as float
 * buffers).
 * labels: stat kernel
 *
 * Oracles:
 *   - Chi-square goodness of fit of 200000 device samples per sampler (counter-based uniforms of
 *     kernels/common/rng.h, fixed seed) against the exact distribution in double: the closed-form CDFs
 *     (HG: F(mu) = (1-g^2)/(2g) [1/t - 1/(1+g)], t = sqrt(1+g^2-2g mu); Draine: the A(mu) of
 *     phase.h's comment, whose derivative is 2 pi p_D; mixtures by weight), and for the table the
 *     piecewise-linear-in-mu CDF that the table sampler inverts. 100 bins of equal expected
 *     probability (edges by bisection on F), except that edges closer than 1e-5 in mu are merged
 *     so a bin spans >= 160 float steps of mu near 1 and the samples' float rounding (half a step)
 *     cannot move a measurable share across an edge. Fails above the p = 1e-4 critical value.
 *   - pdf == the normalised phase on the device: pdf and phase agree to float rounding (1e-6
 *     relative) at 201 cosines, and the device phase integrates to 1 over the sphere within 1e-4
 *     (table: 2e-4; see test_phase_sampling.c for both) by Simpson's rule in s, mu = 1 - 2 s^3,
 *     20001 nodes: dense enough for the g = 0.995 peak (width 1.3e-5 in 1 - mu, ~400 nodes).
 *   - Each single-lobe sampler inverts its exact CDF, and the device and host builds of the same
 *     header give the same samples, within float rounding: either within 4 ulp of 1 in mu
 *     (MU_TOL; where the CDF is steep, as in a g = 0.995 peak or the table's first degrees, one
 *     float step of mu near 1 holds up to 0.2 % of the probability, so only mu can be compared),
 *     or within 1e-5 in probability (PROB_TOL; Draine's float CDF is a difference of terms up to
 *     ~30 (1/t, c^2/t at the peak), rounded to ~30 x 1.2e-7 = 4e-6, and Newton stops on that).
 *     Phase values agree within 1e-5 relative (powers and divisions of a few ulp each, with
 *     FP_CONTRACT allowed on the device). */
#include <stdlib.h>
#include <string.h>
#include "atmo/mie.h"
#include "common/phase.h"
#include "common/rng.h"
#include "testcl.h"
#include "testlib.h"

#define NSAMPLES 200000
#define NBINS 100
#define NEVAL 20001
#define SEED 4242u
/* float rounding, in probability and in mu (see the header) */
#define PROB_TOL 1e-5
#define MU_TOL (4.0 / 16777216.0)

/* One dispatch over the samplers, compiled as host C here and, stringified, as OpenCL C in the
 * probe (# does not macro-expand its argument, so ATMO_FN and ATMO_GLOBAL reach each compiler
 * as written). kind: 0 HG(a), 1 Cornette-Shanks(a), 2 Draine(a, alpha b), 3 two-term HG(a, b,
 * weight c), 4 Jendersie-d'Eon(diameter a), 5 table. what: 0 phase, 1 pdf at nu; 2 sample. */
#define PROBE_CODE(...) __VA_ARGS__
#define PROBE_TEXT(...) #__VA_ARGS__
#define PROBE_DISPATCH(X)                                                                       \
    X(ATMO_FN float probe_phase(int kind, int what, float a, float b, float c, float nu,        \
                                float u1, float u2, const ATMO_GLOBAL float *mu,                \
                                const ATMO_GLOBAL float *P, const ATMO_GLOBAL float *cdf, int n) \
      {                                                                                         \
          phase_jd_params jd = phase_jendersie_deon_params(a);                                  \
          if (what == 2) {                                                                      \
              switch (kind) {                                                                   \
              case 0: return phase_henyey_greenstein_sample(a, u1);                             \
              case 1: return phase_cornette_shanks_sample(a, u1);                               \
              case 2: return phase_draine_sample(a, b, u1);                                     \
              case 3: return phase_two_term_hg_sample(a, b, c, u1, u2);                         \
              case 4: return phase_jendersie_deon_sample(jd, u1, u2);                           \
              default: return phase_table_sample(mu, cdf, n, u1);                               \
              }                                                                                 \
          }                                                                                     \
          switch (kind * 2 + what) {                                                            \
          case 0: return phase_henyey_greenstein(nu, a);                                        \
          case 1: return phase_henyey_greenstein_pdf(nu, a);                                    \
          case 2: return phase_cornette_shanks(nu, a);                                          \
          case 3: return phase_cornette_shanks_pdf(nu, a);                                      \
          case 4: return phase_draine(nu, a, b);                                                \
          case 5: return phase_draine_pdf(nu, a, b);                                            \
          case 6: return phase_two_term_hg(nu, a, b, c);                                        \
          case 7: return phase_two_term_hg_pdf(nu, a, b, c);                                    \
          case 8: return phase_jendersie_deon(nu, jd);                                          \
          case 9: return phase_jendersie_deon_pdf(nu, jd);                                      \
          case 10: return phase_table(nu, mu, P, n);                                            \
          default: return phase_table_pdf(nu, mu, cdf, n);                                      \
          }                                                                                     \
      })

PROBE_DISPATCH(PROBE_CODE)

static const char probe_source[] = PROBE_DISPATCH(PROBE_TEXT) "\n"
    "__kernel void probe(__global float *out, __global const float *nu, __global const float *mu,\n"
    "                    __global const float *P, __global const float *cdf, int n, int kind,\n"
    "                    int what, float a, float b, float c, uint count) {\n"
    "  uint i = get_global_id(0); if (i >= count) return;\n"
    "  float u1 = rng_uniform(4242u, i, 0u, 0u), u2 = rng_uniform(4242u, i, 0u, 1u);\n"
    "  out[i] = probe_phase(kind, what, a, b, c, what == 2 ? 0.0f : nu[i], u1, u2, mu, P, cdf, n);\n"
    "}\n";

typedef struct sampler {
    const char *name;
    int kind;
    float a, b, c;
} sampler;

/* the float table as uploaded, in double for the exact CDF */
static float *tab_mu, *tab_P, *tab_cdf;
static int tab_n;

static double hg_cdf(double x, double g)
{
    if (fabs(g) < 1e-9)
        return 0.5 * (x + 1.0);
    double t = sqrt(1.0 + g * g - 2.0 * g * x);
    return (1.0 - g * g) / (2.0 * g) * (1.0 / t - 1.0 / (1.0 + g));
}

static double draine_cdf(double x, double g, double alpha)
{
    double N = 1.0 + alpha * (1.0 + 2.0 * g * g) / 3.0, c = 1.0 + g * g, k = alpha / (4.0 * g * g);
    double t = sqrt(c - 2.0 * g * x), t0 = 1.0 + g;
    double A = 1.0 / t + k * (c * c / t + 2.0 * c * t - t * t * t / 3.0);
    double A0 = 1.0 / t0 + k * (c * c / t0 + 2.0 * c * t0 - t0 * t0 * t0 / 3.0);
    return (1.0 - g * g) / (2.0 * N * g) * (A - A0);
}

/* P(cos theta < x) of sampler s, exact, in double */
static double exact_cdf(const sampler *s, double x)
{
    switch (s->kind) {
    case 0: return hg_cdf(x, s->a);
    case 1: return draine_cdf(x, s->a, 1.0);
    case 2: return draine_cdf(x, s->a, s->b);
    case 3: return s->c * hg_cdf(x, s->a) + (1.0 - s->c) * hg_cdf(x, s->b);
    case 4: {
        phase_jd_params p = phase_jendersie_deon_params(s->a); /* the fit's parameters, in float */
        return (1.0 - p.w_d) * hg_cdf(x, p.g_hg) + p.w_d * draine_cdf(x, p.g_d, p.alpha);
    }
    default: {
        if (x >= 1.0)
            return 1.0;
        int i = 0;
        while (i < tab_n - 2 && tab_mu[i + 1] >= x)
            i++;
        double t = ((double)tab_mu[i] - x) / ((double)tab_mu[i] - (double)tab_mu[i + 1]);
        return 1.0 - ((double)tab_cdf[i] + t * ((double)tab_cdf[i + 1] - (double)tab_cdf[i]));
    }
    }
}

static atmo_cl cl;
static cl_program prog;
static cl_mem b_mu, b_P, b_cdf, b_nu, b_out;

static void run_probe(const sampler *s, int what, int count, float *out)
{
    cl_int err;
    cl_kernel k = clCreateKernel(prog, "probe", &err);
    CHECK(err == CL_SUCCESS);
    cl_int n = tab_n, kind = s->kind, w = what;
    cl_uint cnt = (cl_uint)count;
    clSetKernelArg(k, 0, sizeof b_out, &b_out);
    clSetKernelArg(k, 1, sizeof b_nu, &b_nu);
    clSetKernelArg(k, 2, sizeof b_mu, &b_mu);
    clSetKernelArg(k, 3, sizeof b_P, &b_P);
    clSetKernelArg(k, 4, sizeof b_cdf, &b_cdf);
    clSetKernelArg(k, 5, sizeof n, &n);
    clSetKernelArg(k, 6, sizeof kind, &kind);
    clSetKernelArg(k, 7, sizeof w, &w);
    clSetKernelArg(k, 8, sizeof s->a, &s->a);
    clSetKernelArg(k, 9, sizeof s->b, &s->b);
    clSetKernelArg(k, 10, sizeof s->c, &s->c);
    clSetKernelArg(k, 11, sizeof cnt, &cnt);
    test_cl_run_1d(&cl, k, (size_t)count);
    test_cl_read(&cl, b_out, sizeof(float) * (size_t)count, out);
    clReleaseKernel(k);
}

static void check_sampler(const sampler *s)
{
    static float dev[NSAMPLES], nu[NEVAL], val[NEVAL], pdf[NEVAL];
    static double edges[NBINS + 1];
    static long counts[NBINS];
    run_probe(s, 2, NSAMPLES, dev);

    /* equal-probability edges, merged where closer than 1e-5 in mu */
    int nb = 0;
    edges[0] = -1.0;
    for (int j = 1; j < NBINS; j++) {
        double lo = -1.0, hi = 1.0, target = (double)j / NBINS;
        for (int it = 0; it < 100; it++) {
            double m = 0.5 * (lo + hi);
            if (exact_cdf(s, m) < target)
                lo = m;
            else
                hi = m;
        }
        if (lo - edges[nb] >= 1e-5 && 1.0 - lo >= 1e-5)
            edges[++nb] = lo;
    }
    edges[++nb] = 1.0;
    for (int j = 0; j < nb; j++)
        counts[j] = 0;
    double max_diff = 0.0, max_inv = 0.0;
    int bad = 0, disagree = 0, inexact = 0;
    for (int i = 0; i < NSAMPLES; i++) {
        float x = dev[i];
        bad += !(x >= -1.0f && x <= 1.0f);
        int lo = 0, hi = nb; /* edges[lo] <= x < edges[hi] */
        while (hi - lo > 1) {
            int m = (lo + hi) / 2;
            if ((double)x >= edges[m])
                lo = m;
            else
                hi = m;
        }
        counts[lo]++;
        float u1 = rng_uniform(SEED, (uint)i, 0u, 0u), u2 = rng_uniform(SEED, (uint)i, 0u, 1u);
        float host = probe_phase(s->kind, 2, s->a, s->b, s->c, 0.0f, u1, u2, tab_mu, tab_P, tab_cdf,
                                 tab_n);
        double dF = fabs(exact_cdf(s, host) - exact_cdf(s, x));
        max_diff = fmax(max_diff, dF);
        disagree += dF > PROB_TOL && fabs((double)host - (double)x) > MU_TOL;
        if (s->kind <= 2 || s->kind == 5) { /* one lobe: F(mu(u1)) = u1 (table: 1 - u1) */
            double u = s->kind == 5 ? 1.0 - (double)u1 : (double)u1, inv = fabs(exact_cdf(s, x) - u);
            max_inv = fmax(max_inv, inv);
            inexact += inv > PROB_TOL && !(exact_cdf(s, x - MU_TOL) <= u && u <= exact_cdf(s, x + MU_TOL));
        }
    }
    CHECK(bad == 0);
    double chi2 = 0.0;
    for (int j = 0; j < nb; j++) {
        double p = exact_cdf(s, edges[j + 1]) - exact_cdf(s, edges[j]);
        double expect = NSAMPLES * p;
        chi2 += (counts[j] - expect) * (counts[j] - expect) / expect;
    }
    double crit = test_chi2_critical_1e4(nb - 1);
    CHECK(chi2 < crit);
    CHECK(disagree == 0);
    CHECK(inexact == 0);

    /* phase and pdf on the device: equal, normalised, and equal to the host's */
    for (int i = 0; i < NEVAL; i++) {
        double sv = (double)i / (NEVAL - 1);
        nu[i] = (float)(1.0 - 2.0 * sv * sv * sv);
    }
    clEnqueueWriteBuffer(cl.queue, b_nu, CL_TRUE, 0, sizeof nu, nu, 0, NULL, NULL);
    run_probe(s, 0, NEVAL, val);
    run_probe(s, 1, NEVAL, pdf);
    double integral = 0.0, max_rel_host = 0.0;
    for (int i = 0; i < NEVAL; i++) {
        double sv = (double)i / (NEVAL - 1);
        double w = (i == 0 || i == NEVAL - 1) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        integral += w * (double)val[i] * 6.0 * sv * sv;
        float host = probe_phase(s->kind, 0, s->a, s->b, s->c, nu[i], 0.0f, 0.0f, tab_mu, tab_P,
                                 tab_cdf, tab_n);
        max_rel_host = fmax(max_rel_host, fabs((double)host - val[i]) / fmax((double)host, 1e-30));
        if (s->kind != 5 && i % 100 == 0)
            CHECK_REL(pdf[i], val[i], 1e-6);
    }
    integral *= 2.0 * 3.14159265358979323846 / (3.0 * (NEVAL - 1));
    CHECK_ABS(integral, 1.0, s->kind == 5 ? 2e-4 : 1e-4);
    CHECK(max_rel_host <= 1e-5);
    printf("%-26s chi2 %6.1f (%3d bins, crit %.1f)  integral %.7f  |F(u)-u| %.1e  "
           "dev-host: F %.1e phase %.1e\n", s->name, chi2, nb, crit, integral, max_inv, max_diff,
           max_rel_host);
}

int main(void)
{
    mie_dsd d;
    mie_table t;
    atmo_err e;
    double n, k;
    mie_dsd_preset("cumulus", &d);
    if (mie_water_index(550.0, &n, &k, &e) || mie_table_build(&d, 550.0, n, k, NULL, &t, &e)) {
        fprintf(stderr, "%s\n", e.msg);
        return 1;
    }
    tab_n = t.n;
    tab_mu = malloc(sizeof *tab_mu * (size_t)t.n);
    tab_P = malloc(sizeof *tab_P * (size_t)t.n);
    tab_cdf = malloc(sizeof *tab_cdf * (size_t)t.n);
    for (int i = 0; i < t.n; i++)
        tab_mu[i] = (float)t.mu[i], tab_P[i] = (float)t.P[i], tab_cdf[i] = (float)t.cdf[i];

    test_cl_open(&cl);
    const char *fragments[] = {"kernels/common/compat.h", "kernels/common/rng.h", "kernels/common/phase.h"};
    prog = test_cl_build(&cl, fragments, 3, probe_source);
    b_mu = test_cl_buffer(&cl, sizeof(float) * (size_t)tab_n, tab_mu);
    b_P = test_cl_buffer(&cl, sizeof(float) * (size_t)tab_n, tab_P);
    b_cdf = test_cl_buffer(&cl, sizeof(float) * (size_t)tab_n, tab_cdf);
    b_nu = test_cl_buffer(&cl, sizeof(float) * NEVAL, NULL);
    b_out = test_cl_buffer(&cl, sizeof(float) * NSAMPLES, NULL);

    const sampler list[] = {
        {"HG g=0.76", 0, 0.76f, 0, 0},
        {"HG g=-0.3", 0, -0.3f, 0, 0},
        {"HG g=0.995", 0, 0.995f, 0, 0},
        {"Cornette-Shanks g=0.76", 1, 0.76f, 0, 0},
        {"Draine g=0.6 a=10", 2, 0.6f, 10.0f, 0},
        {"two-term HG .85/-.4 w=.8", 3, 0.85f, -0.4f, 0.8f},
        {"Jendersie-d'Eon d=5 um", 4, 5.0f, 0, 0},
        {"Jendersie-d'Eon d=10 um", 4, 10.0f, 0, 0},
        {"Jendersie-d'Eon d=20 um", 4, 20.0f, 0, 0},
        {"Jendersie-d'Eon d=50 um", 4, 50.0f, 0, 0},
        {"Mie table cumulus 550 nm", 5, 0, 0, 0},
    };
    for (size_t i = 0; i < sizeof list / sizeof list[0]; i++) {
        CHECK_ABS(exact_cdf(&list[i], 1.0), 1.0, 1e-12); /* the closed forms reach 1 */
        check_sampler(&list[i]);
    }

    clReleaseMemObject(b_out);
    clReleaseMemObject(b_nu);
    clReleaseMemObject(b_cdf);
    clReleaseMemObject(b_P);
    clReleaseMemObject(b_mu);
    clReleaseProgram(prog);
    atmo_cl_close(&cl);
    free(tab_mu);
    free(tab_P);
    free(tab_cdf);
    mie_table_free(&t);
    return test_finish();
}
