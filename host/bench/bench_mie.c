/* bench_mie.c — `atmo bench mie`: how well and how fast each kernel phase option stands in for
 * the tabulated Mie phase of cloud drops, and what a table costs to build.
 *
 * Reference: the 4pi-normalised table of the cumulus preset (gamma, r_eff 10 um, v_eff 0.1) at
 * 550 nm, water index from data/, default grid and radius step (host/mie_table.c; cached).
 * Options (kernels/common/phase.h, host build, float), each with parameters from the same table:
 *   hg          Henyey-Greenstein with the table's g
 *   two-term-hg (g1, g2) minimising the RMS of ln(P/P_mie) over 0-180 deg in 1 deg steps, the
 *               weight set so the mean cosine is the table's g (matching the first three
 *               Legendre moments has no real solution with |g| < 1 and 0 <= w <= 1 here)
 *   cornette-shanks  g chosen so its mean cosine 3g(4+g^2)/(5(2+g^2)) is the table's g
 *   draine      (g, alpha) minimising the RMS of ln(P/P_mie) over 0-180 deg in 1 deg steps
 *   jendersie-deon   the 2023 fit at diameter 2 r_eff = 20 um
 *   mie-table   the float table with the kernel's interpolation (phase_table); mie-table-1deg the
 *               same from a uniform 1 deg grid.
 * Error: for each angle range (forward peak 0-10 deg, 10-90, bow 130-150, glory 170-180, and all
 * of 0-180) the RMS over theta, sampled uniformly every 0.01 deg, of the relative error
 * P_option / P_mie - 1 (P_mie interpolated linearly in theta).
 * Cost: ns per call to evaluate (phase at a varying cosine) and to sample (a varying u1, u2),
 * measured on the HOST (one core, the float build of kernels/common/phase.h), 2e6 calls each; the
 * relative costs carry over to kernels, the absolute ones do not.
 * Table builds: cumulus at 550 nm on the default angle grid for the radius rules: fixed
 * size-parameter steps 0.5 (the former default), 0.1 and 0.03, the converged rule at its default
 * tolerance 1e-3 and at 3e-4, against the converged integral (fixed step 0.005, the last row).
 * Time: wall and CPU seconds of the build on the host (two threads); error = RMS over 0-180 deg
 * (0.01 deg steps) of P / P_ref - 1, and its largest value.
 * Outputs: DIR/mie.csv (method, settings, errors per range, eval_ns, sample_ns), DIR/mie_table.csv
 * (settings, n_angles, n_radii, dx, seconds, cpu_seconds, error, error_max) and DIR/mie.svg
 * (gnuplot: error in each range against eval cost, and table error against build CPU time).
 * --quick: two table settings on a coarse uniform grid, for tests. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "atmo/bench.h"
#include "atmo/fileio.h"
#include "atmo/mie.h"
#include "common/phase.h"

#define BENCH_MIE_NRANGES 5
#define BENCH_MIE_CALLS 2000000
static const double bench_mie_range[BENCH_MIE_NRANGES][2] = {
    {0.0, 10.0}, {10.0, 90.0}, {130.0, 150.0}, {170.0, 180.0}, {0.0, 180.0}};
static const char *const bench_mie_range_name[BENCH_MIE_NRANGES] = {
    "err_0_10", "err_10_90", "err_130_150", "err_170_180", "err_all"};

typedef struct bench_mie_option {
    char method[32], settings[96];
    int kind; /* 0 hg, 1 two-term, 2 cs, 3 draine, 4 jd, 5 table */
    float a, b, c;
    phase_jd_params jd;
    float *mu, *P, *cdf; /* table */
    int n;
    double err[BENCH_MIE_NRANGES], eval_ns, sample_ns;
} bench_mie_option;

static double bench_clock(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double bench_now(void) { return bench_clock(CLOCK_MONOTONIC); }

static float bench_mie_eval(const bench_mie_option *o, float nu)
{
    switch (o->kind) {
    case 0: return phase_henyey_greenstein(nu, o->a);
    case 1: return phase_two_term_hg(nu, o->a, o->b, o->c);
    case 2: return phase_cornette_shanks(nu, o->a);
    case 3: return phase_draine(nu, o->a, o->b);
    case 4: return phase_jendersie_deon(nu, o->jd);
    default: return phase_table(nu, o->mu, o->P, o->n);
    }
}

static float bench_mie_sample(const bench_mie_option *o, float u1, float u2)
{
    switch (o->kind) {
    case 0: return phase_henyey_greenstein_sample(o->a, u1);
    case 1: return phase_two_term_hg_sample(o->a, o->b, o->c, u1, u2);
    case 2: return phase_cornette_shanks_sample(o->a, u1);
    case 3: return phase_draine_sample(o->a, o->b, u1);
    case 4: return phase_jendersie_deon_sample(o->jd, u1, u2);
    default: return phase_table_sample(o->mu, o->cdf, o->n, u1);
    }
}

/* RMS (and largest, into *mx unless NULL) of f(theta) / P_ref(theta) - 1 over [lo, hi] every
 * 0.01 deg; f = option or table */
static double bench_mie_error(const mie_table *ref, const bench_mie_option *o,
                                const mie_table *other, double lo, double hi, double *mx)
{
    int n = (int)lround((hi - lo) / 0.01);
    double sum = 0.0;
    if (mx)
        *mx = 0.0;
    for (int i = 0; i <= n; i++) {
        double th = lo + (hi - lo) * i / n, pr = mie_table_eval(ref, th);
        double p = other ? mie_table_eval(other, th)
                         : 4.0 * 3.14159265358979323846 *
                               (double)bench_mie_eval(o, (float)cos(th * 3.14159265358979323846 / 180.0));
        sum += (p / pr - 1.0) * (p / pr - 1.0);
        if (mx)
            *mx = fmax(*mx, fabs(p / pr - 1.0));
    }
    return sqrt(sum / (n + 1));
}

/* ns per call; the sum keeps the calls from being optimised away */
static void bench_mie_cost(bench_mie_option *o, int calls)
{
    volatile float sink = 0.0f;
    float acc = 0.0f;
    double t0 = bench_now();
    /* a scrambled order of the cosines and numbers, as scattering events see them */
    for (int i = 0; i < calls; i++)
        acc += bench_mie_eval(o, 1.0f - 2.0f * ((float)((long long)i * 7919 % calls) + 0.5f) / (float)calls);
    double t1 = bench_now();
    for (int i = 0; i < calls; i++) {
        float u1 = ((float)((long long)i * 7919 % calls) + 0.5f) / (float)calls;
        acc += bench_mie_sample(o, u1, 1.0f - u1);
    }
    double t2 = bench_now();
    sink = acc;
    (void)sink;
    o->eval_ns = 1e9 * (t1 - t0) / calls;
    o->sample_ns = 1e9 * (t2 - t1) / calls;
}

static double bench_mie_log_rms(const mie_table *ref, const bench_mie_option *o)
{
    double s = 0.0;
    for (int d = 0; d <= 180; d++) {
        double p = 4.0 * 3.14159265358979323846 *
                   (double)bench_mie_eval(o, (float)cos(d * 3.14159265358979323846 / 180.0));
        double r = log(p / mie_table_eval(ref, d));
        s += r * r;
    }
    return s;
}

static int bench_mie_to_float(const mie_table *t, bench_mie_option *o, atmo_err *e)
{
    o->n = t->n;
    o->mu = malloc(sizeof *o->mu * (size_t)t->n);
    o->P = malloc(sizeof *o->P * (size_t)t->n);
    o->cdf = malloc(sizeof *o->cdf * (size_t)t->n);
    if (!o->mu || !o->P || !o->cdf)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for a %d-angle table", t->n);
    for (int i = 0; i < t->n; i++)
        o->mu[i] = (float)t->mu[i], o->P[i] = (float)t->P[i], o->cdf[i] = (float)t->cdf[i];
    return ATMO_OK;
}

static const char bench_mie_plot[] =
    "set datafile separator ','\nset logscale xy\nset grid\nset key off\n"
    "set multiplot layout 2,3 title \"%s\" noenhanced\n"
    "%s"
    "set title 'table build (cumulus 550 nm)'\nset xlabel 'CPU seconds (host, 2 threads)'\n"
    "set ylabel 'RMS rel. error vs step 0.005'\n"
    "plot '%s' using 6:7 every ::1 with points pt 7, '' using 6:7:1 every ::1 with labels "
    "offset 0,0.8 font ',7' noenhanced\n"
    "unset multiplot\n";

/* two-term HG: w g1 + (1 - w) g2 = g fixes w; (g1, g2) minimise the log RMS */
static void bench_mie_fit_two_term(const mie_table *ref, double g, bench_mie_option *o)
{
    o->kind = 1;
    double best = HUGE_VAL, b1 = 0.0, b2 = 0.0;
    for (int i = 0; i < 100; i++)
        for (int j = 0; j < 40; j++) {
            double g1 = fmax(g + 0.001, 0.5 + 0.005 * i), g2 = -0.8 + 0.04 * j;
            o->a = (float)g1, o->b = (float)g2, o->c = (float)((g - g2) / (g1 - g2));
            double s = bench_mie_log_rms(ref, o);
            if (s < best)
                best = s, b1 = g1, b2 = g2;
        }
    o->a = (float)b1, o->b = (float)b2, o->c = (float)((g - b2) / (b1 - b2));
    snprintf(o->method, sizeof o->method, "two-term-hg");
    snprintf(o->settings, sizeof o->settings, "g1=%.3f g2=%.2f w=%.3f", b1, b2, (double)o->c);
}

/* Cornette-Shanks: the g whose mean cosine 3g(4+g^2)/(5(2+g^2)) is the table's, by bisection */
static void bench_mie_fit_cornette_shanks(double g, bench_mie_option *o)
{
    double lo = 0.0, hi = 0.9999;
    for (int i = 0; i < 60; i++) {
        double c = 0.5 * (lo + hi);
        if (3.0 * c * (4.0 + c * c) / (5.0 * (2.0 + c * c)) < g)
            lo = c;
        else
            hi = c;
    }
    snprintf(o->method, sizeof o->method, "cornette-shanks");
    snprintf(o->settings, sizeof o->settings, "g=%.4f", lo);
    o->kind = 2, o->a = (float)lo;
}

/* Draine: (g, alpha) minimising the log RMS on a grid */
static void bench_mie_fit_draine(const mie_table *ref, bench_mie_option *o)
{
    o->kind = 3;
    double bg = 0.0, ba = 0.0, best = HUGE_VAL;
    for (int i = 0; i <= 99; i++)
        for (int j = 0; j <= 40; j++) {
            o->a = 0.5f + 0.005f * (float)i, o->b = 0.5f * (float)j;
            double s = bench_mie_log_rms(ref, o);
            if (s < best)
                best = s, bg = o->a, ba = o->b;
        }
    o->a = (float)bg, o->b = (float)ba;
    snprintf(o->method, sizeof o->method, "draine");
    snprintf(o->settings, sizeof o->settings, "g=%.3f alpha=%.1f", bg, ba);
}

/* The options, each fitted to (or taken from) the reference table; *coarse gets the 1-degree
 * table. Returns the count in *nopt. */
static int bench_mie_options(const mie_dsd *d, double n, double k, const mie_table *ref,
                             mie_table *coarse, bench_mie_option *opt, int *nopt, atmo_err *e)
{
    int rc;
    double g = mie_table_asymmetry(ref);
    bench_mie_option *o = &opt[(*nopt)++];
    snprintf(o->method, sizeof o->method, "hg");
    snprintf(o->settings, sizeof o->settings, "g=%.4f", g);
    o->kind = 0, o->a = (float)g;
    bench_mie_fit_two_term(ref, g, &opt[(*nopt)++]);
    bench_mie_fit_cornette_shanks(g, &opt[(*nopt)++]);
    bench_mie_fit_draine(ref, &opt[(*nopt)++]);
    o = &opt[(*nopt)++];
    o->kind = 4, o->jd = phase_jendersie_deon_params((float)(2.0 * d->r_eff_um));
    snprintf(o->method, sizeof o->method, "jendersie-deon");
    snprintf(o->settings, sizeof o->settings, "d=%.0fum", 2.0 * d->r_eff_um);
    o = &opt[(*nopt)++];
    o->kind = 5;
    snprintf(o->method, sizeof o->method, "mie-table");
    snprintf(o->settings, sizeof o->settings, "%d angles", ref->n);
    if ((rc = bench_mie_to_float(ref, o, e)))
        return rc;
    mie_table_options uni = {.uniform = 1, .coarse_step_deg = 1.0};
    if ((rc = mie_table_get(d, 550.0, n, k, &uni, 1, coarse, NULL, e)))
        return rc;
    o = &opt[(*nopt)++];
    o->kind = 5;
    snprintf(o->method, sizeof o->method, "mie-table-1deg");
    snprintf(o->settings, sizeof o->settings, "%d angles", coarse->n);
    return bench_mie_to_float(coarse, o, e);
}

/* Each option's error per range and its cost. */
static void bench_mie_measure(const mie_table *ref, bench_mie_option *opt, int nopt, int quick)
{
    for (int i = 0; i < nopt; i++) {
        for (int r = 0; r < BENCH_MIE_NRANGES; r++)
            opt[i].err[r] = bench_mie_error(ref, &opt[i], NULL, bench_mie_range[r][0],
                                              bench_mie_range[r][1], NULL);
        bench_mie_cost(&opt[i], quick ? BENCH_MIE_CALLS / 20 : BENCH_MIE_CALLS);
        fprintf(stderr, "bench mie: %-16s %-30s errors %.2e %.2e %.2e %.2e all %.2e  eval %.1f ns  "
                "sample %.1f ns\n", opt[i].method, opt[i].settings, opt[i].err[0], opt[i].err[1],
                opt[i].err[2], opt[i].err[3], opt[i].err[4], opt[i].eval_ns, opt[i].sample_ns);
    }
}

/* The table builds, timed; the last setting is the reference for the others. */
typedef struct bench_mie_builds {
    const mie_table_options *set;
    int nset;
    mie_table t[6];
    double secs[6], cpus[6], errs[6], maxs[6];
} bench_mie_builds;

static int bench_mie_build_tables(const mie_dsd *d, double n, double k, int quick,
                                  bench_mie_builds *b, atmo_err *e)
{
    static const mie_table_options full[] = {
        {.max_dx = 0.5}, {.max_dx = 0.1}, {.max_dx = 0.03}, {.tolerance = 0.0},
        {.tolerance = 3e-4}, {.max_dx = 0.005}};
    static const mie_table_options fast[] = {
        {.uniform = 1, .coarse_step_deg = 2.0, .max_dx = 0.5},
        {.uniform = 1, .coarse_step_deg = 2.0, .max_dx = 0.05}};
    int rc;
    b->set = quick ? fast : full;
    b->nset = quick ? 2 : 6;
    for (int i = 0; i < b->nset; i++) {
        const mie_table_options *s = &b->set[i];
        double t0 = bench_now(), c0 = bench_clock(CLOCK_PROCESS_CPUTIME_ID);
        if ((rc = mie_table_build(d, 550.0, n, k, s, &b->t[i], e)))
            return rc;
        b->secs[i] = bench_now() - t0;
        b->cpus[i] = bench_clock(CLOCK_PROCESS_CPUTIME_ID) - c0;
        fprintf(stderr, "bench mie: table %s %g: %d angles, %d radii (dx %.4f), %.3f s, %.3f s CPU\n",
                s->max_dx > 0.0 ? "fixed step" : "tolerance",
                s->max_dx > 0.0 ? s->max_dx : (s->tolerance > 0.0 ? s->tolerance : MIE_DSD_TOLERANCE),
                b->t[i].n, b->t[i].bulk.n_radii, b->t[i].bulk.dx, b->secs[i], b->cpus[i]);
    }
    for (int i = 0; i < b->nset; i++)
        b->errs[i] = bench_mie_error(&b->t[b->nset - 1], NULL, &b->t[i], 0.0, 180.0, &b->maxs[i]);
    return ATMO_OK;
}

/* DIR/mie.csv: method, settings, errors per range, costs */
static int bench_mie_write_options(const char *csv, const bench_mie_option *opt, int nopt,
                                   atmo_err *e)
{
    char tmp[ATMO_TMP_PATH_MAX];
    FILE *f = atmo_atomic_open(csv, tmp, e);
    if (!f)
        return ATMO_ERR_RUNTIME;
    fprintf(f, "method,settings");
    for (int r = 0; r < BENCH_MIE_NRANGES; r++)
        fprintf(f, ",%s", bench_mie_range_name[r]);
    fprintf(f, ",eval_ns,sample_ns,timed_on\n");
    for (int i = 0; i < nopt; i++) {
        fprintf(f, "%s,%s", opt[i].method, opt[i].settings);
        for (int r = 0; r < BENCH_MIE_NRANGES; r++)
            fprintf(f, ",%.4e", opt[i].err[r]);
        fprintf(f, ",%.2f,%.2f,host\n", opt[i].eval_ns, opt[i].sample_ns);
    }
    return atmo_atomic_commit(f, tmp, csv, e);
}

/* DIR/mie_table.csv: the builds' settings, sizes, times and errors */
static int bench_mie_write_builds(const char *csv2, const bench_mie_builds *b, atmo_err *e)
{
    char tmp[ATMO_TMP_PATH_MAX];
    FILE *f = atmo_atomic_open(csv2, tmp, e);
    if (!f)
        return ATMO_ERR_RUNTIME;
    fprintf(f, "settings,n_angles,n_radii,dx,seconds,cpu_seconds,error,error_max\n");
    for (int i = 0; i < b->nset; i++) {
        const mie_table_options *s = &b->set[i];
        int last = i == b->nset - 1;
        char label[64];
        if (s->max_dx > 0.0)
            snprintf(label, sizeof label, "%sdx=%g", last ? "reference " : "", s->max_dx);
        else
            snprintf(label, sizeof label, "tol=%g", s->tolerance > 0.0 ? s->tolerance
                                                                       : MIE_DSD_TOLERANCE);
        fprintf(f, "%s%s,%d,%d,%.5f,%.4f,%.4f,%.4e,%.4e\n", label, s->uniform ? " uniform-grid" : "",
                b->t[i].n, b->t[i].bulk.n_radii, b->t[i].bulk.dx, b->secs[i], b->cpus[i],
                last ? 0.0 : b->errs[i], last ? 0.0 : b->maxs[i]);
    }
    return atmo_atomic_commit(f, tmp, csv2, e);
}

/* DIR/mie.svg: error in each range against eval cost, and table error against build time */
static int bench_mie_chart(const char *svg, const char *csv, const char *csv2, atmo_err *e)
{
    char panels[4096];
    size_t len = 0;
    for (int r = 0; r < 4; r++)
        len += (size_t)snprintf(panels + len, sizeof panels - len,
            "set title 'error %g-%g deg'\nset xlabel 'ns per evaluation (host)'\n"
            "set ylabel 'RMS of P/P_{mie} - 1'\n"
            "plot '%s' using 8:%d every ::1 with points pt 7, '' using 8:%d:1 every ::1 "
            "with labels offset 0,0.8 font ',7' noenhanced\n",
            bench_mie_range[r][0], bench_mie_range[r][1], csv, r + 3, r + 3);
    len += (size_t)snprintf(panels + len, sizeof panels - len,
        "set title 'error 0-180 deg vs sampling cost'\nset xlabel 'ns per sample (host)'\n"
        "plot '%s' using 9:7 every ::1 with points pt 7, '' using 9:7:1 every ::1 with labels "
        "offset 0,0.8 font ',7' noenhanced\n", csv);
    char *script = malloc(sizeof panels + 8192);
    if (!script)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the chart script");
    snprintf(script, sizeof panels + 8192, bench_mie_plot,
             "phase options vs tabulated Mie (cumulus, 550 nm)", panels, csv2);
    int rc = bench_plot(svg, 1500, 900, script, e);
    free(script);
    return rc;
}

int bench_mie(const char *dir, int quick, atmo_err *e)
{
    mie_dsd d;
    mie_table ref = {0}, coarse = {0};
    bench_mie_builds builds = {0};
    bench_mie_option opt[8];
    int nopt = 0, rc;
    double n, k;
    char csv[4200], csv2[4200], svg[4200];
    memset(opt, 0, sizeof opt);
    mie_dsd_preset("cumulus", &d);
    if ((rc = mie_water_index(550.0, &n, &k, e)))
        return rc;
    fprintf(stderr, "bench mie: reference table (cumulus, 550 nm; cached after the first run)\n");
    if ((rc = mie_table_get(&d, 550.0, n, k, NULL, 1, &ref, NULL, e)) ||
        (rc = bench_mie_options(&d, n, k, &ref, &coarse, opt, &nopt, e)))
        goto done;
    bench_mie_measure(&ref, opt, nopt, quick);
    if ((rc = bench_mie_build_tables(&d, n, k, quick, &builds, e)))
        goto done;
    snprintf(csv, sizeof csv, "%s/mie.csv", dir);
    snprintf(csv2, sizeof csv2, "%s/mie_table.csv", dir);
    snprintf(svg, sizeof svg, "%s/mie.svg", dir);
    if ((rc = bench_mie_write_options(csv, opt, nopt, e)) ||
        (rc = bench_mie_write_builds(csv2, &builds, e)) ||
        (rc = bench_mie_chart(svg, csv, csv2, e)))
        goto done;
    printf("wrote %s, %s and %s\n", csv, csv2, svg);
done:
    for (int i = 0; i < nopt; i++) {
        free(opt[i].mu);
        free(opt[i].P);
        free(opt[i].cdf);
    }
    for (int i = 0; i < 6; i++)
        mie_table_free(&builds.t[i]);
    mie_table_free(&coarse);
    mie_table_free(&ref);
    return rc;
}
