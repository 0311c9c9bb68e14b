/* mie_table_errors.c — the errors of droplet phase tables against a converged radius integral,
 * for docs/mie_radius.md.
 *
 *   build/mie_table_errors NAME|SPEC WAVELENGTH_NM [...more pairs]
 *
 * For each distribution and wavelength (water index from data/): the default table
 * (mie_table_build, converged rule) and the fixed size-parameter step 0.5, each against the
 * trapezoid rule at step 0.005 on every 2nd angle of the table grid. Errors are relative,
 * e = P / P_ref - 1: RMS over theta (trapezoid weights in theta) and the largest |e|, over
 * 0-180 deg and in 90-130 (the side minimum), 138-145 (fog bow) and 175-180 deg (glory). The
 * bow maximum is the angle of the largest P in 130-150 deg on a 0.01 deg grid, for each of the
 * three rules. Also the co-albedo, g and sigma_ext/LWC of each, and the CPU seconds of each build
 * (CLOCK_PROCESS_CPUTIME_ID, both threads). One line per pair on stdout. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "atmo/mie.h"

#define PI 3.14159265358979323846
#define REF_DX 0.005
#define OLD_DX 0.5
#define BOW_N 2001

static double cpu_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* RMS (theta-weighted) and largest |P / R - 1| over the angles in [lo, hi] */
static void errors(const double *th, const double *P, const double *R, int n, double lo,
                   double hi, double *rms, double *mx)
{
    double s = 0.0, sw = 0.0;
    *mx = 0.0;
    for (int i = 0; i < n; i++) {
        if (th[i] < lo || th[i] > hi)
            continue;
        double w = (i > 0 ? th[i] - th[i - 1] : 0.0) + (i + 1 < n ? th[i + 1] - th[i] : 0.0);
        double r = P[i] / R[i] - 1.0;
        s += w * r * r, sw += w;
        *mx = fmax(*mx, fabs(r));
    }
    *rms = sw > 0.0 ? sqrt(s / sw) : 0.0;
}

static double bow_max(const mie_dsd *d, double lambda, double n, double k, double dx, atmo_err *e,
                      int *rc)
{
    static double mu[BOW_N], P[BOW_N];
    for (int i = 0; i < BOW_N; i++)
        mu[i] = cos((130.0 + 0.01 * i) * PI / 180.0);
    mie_bulk b;
    if ((*rc = mie_dsd_integrate(d, lambda, n, k, dx, 0.0, BOW_N, mu, P, &b, e)))
        return 0.0;
    int best = 0;
    for (int i = 1; i < BOW_N; i++)
        if (P[i] > P[best])
            best = i;
    return 130.0 + 0.01 * best;
}

static int one(const char *spec, double lambda)
{
    mie_dsd d;
    atmo_err e;
    double n, k;
    mie_table t = {0}, o = {0};
    double *th = NULL, *mu = NULL, *R = NULL, *P = NULL, *Po = NULL;
    int rc = mie_dsd_parse(spec, &d, &e);
    if (!rc)
        rc = mie_water_index(lambda, &n, &k, &e);
    if (rc)
        goto done;
    mie_table_options old = {.max_dx = OLD_DX};
    double c0 = cpu_s();
    if ((rc = mie_table_build(&d, lambda, n, k, NULL, &t, &e)))
        goto done;
    double c_new = cpu_s() - c0;
    c0 = cpu_s();
    if ((rc = mie_table_build(&d, lambda, n, k, &old, &o, &e)))
        goto done;
    double c_old = cpu_s() - c0;
    int m = (t.n + 1) / 2;
    th = malloc(sizeof *th * m), mu = malloc(sizeof *mu * m), R = malloc(sizeof *R * m);
    P = malloc(sizeof *P * m), Po = malloc(sizeof *Po * m);
    if (!th || !mu || !R || !P || !Po) {
        fprintf(stderr, "out of memory\n");
        rc = ATMO_ERR_RUNTIME;
        goto done;
    }
    for (int i = 0; i < m; i++)
        th[i] = t.theta_deg[2 * i], mu[i] = t.mu[2 * i], P[i] = t.P[2 * i], Po[i] = o.P[2 * i];
    mie_bulk b;
    c0 = cpu_s();
    if ((rc = mie_dsd_integrate(&d, lambda, n, k, REF_DX, 0.0, m, mu, R, &b, &e)))
        goto done;
    double c_ref = cpu_s() - c0;
    double bow_ref = bow_max(&d, lambda, n, k, REF_DX, &e, &rc);
    double bow_new = rc ? 0.0 : bow_max(&d, lambda, n, k, 0.0, &e, &rc);
    double bow_old = rc ? 0.0 : bow_max(&d, lambda, n, k, OLD_DX, &e, &rc);
    if (rc)
        goto done;
    static const double zone[4][2] = {{0.0, 180.0}, {90.0, 130.0}, {138.0, 145.0}, {175.0, 180.0}};
    const double *rows[2] = {P, Po};
    const mie_table *tabs[2] = {&t, &o};
    const char *names[2] = {"default", "fixed 0.5"};
    double secs[2] = {c_new, c_old}, bows[2] = {bow_new, bow_old};
    printf("%s %g nm: reference (step %g) %.1f s CPU, bow max %.2f deg, co-albedo %.4e, g %.6f, "
           "sigma_ext/LWC %.6f\n", spec, lambda, REF_DX, c_ref, bow_ref, 1.0 - b.albedo, b.g,
           b.sigma_ext_per_lwc);
    for (int r = 0; r < 2; r++) {
        double rms[4], mx[4];
        for (int z = 0; z < 4; z++)
            errors(th, rows[r], R, m, zone[z][0], zone[z][1], &rms[z], &mx[z]);
        printf("  %-9s %6d radii (step %.4f) %6.2f s CPU: RMS %.1e max %.1e | 90-130 %.1e  bow "
               "%.1e  glory %.1e (max) | bow max %.2f | co-albedo %+.1f %% g %+.1e sigma %+.1e\n",
               names[r], tabs[r]->bulk.n_radii, tabs[r]->bulk.dx, secs[r], rms[0], mx[0], mx[1],
               mx[2], mx[3], bows[r], 100.0 * ((1.0 - tabs[r]->bulk.albedo) / (1.0 - b.albedo) - 1.0),
               tabs[r]->bulk.g - b.g, tabs[r]->bulk.sigma_ext_per_lwc / b.sigma_ext_per_lwc - 1.0);
    }
done:
    if (rc)
        fprintf(stderr, "mie_table_errors: %s %g nm: %s\n", spec, lambda, e.msg);
    free(th), free(mu), free(R), free(P), free(Po);
    mie_table_free(&t);
    mie_table_free(&o);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc < 3 || argc % 2 == 0) {
        fprintf(stderr, "usage: mie_table_errors NAME|SPEC WAVELENGTH_NM [...]\n");
        return 2;
    }
    int rc = 0;
    for (int i = 1; i + 1 < argc; i += 2)
        rc |= one(argv[i], atof(argv[i + 1]));
    return rc ? 1 : 0;
}
