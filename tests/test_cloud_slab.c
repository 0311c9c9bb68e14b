/* test_cloud_slab — the Monte Carlo reference (kernels/atmosphere/method_reference.h) through
 * the homogeneous cloud shell (kernels/cloud_shell/cloud_shell.h), all orders of scattering, against
 * an independent solution of the same plane-parallel problem.
 * labels: kernel stat slow
 *
 * Oracle: adding-doubling in double precision on the host (tests/support_slab.c, testslab.h:
 * delta-M truncation to M Legendre moments, N Gauss cosines per hemisphere, doubling from a
 * single-scattering layer, the single scattering of the exact phase function restored by the
 * TMS correction of Nakajima & Tanaka 1988). The solver is checked first: its moments of HG are
 * g^l (1e-9), a slab of tau = 1e-6 gives the closed form of single scattering
 * omega p mu0 / (mu + mu0) (1 - e^{-tau (1/mu + 1/mu0)}) (double scattering is below 1e-5 of
 * it), and the fluxes of albedo 1 add up, R + T_diffuse + T_direct = 1 to 1e-6 (HG and Mie,
 * tau 1 and 10). Each radiance it gives the test is its answer at N = 2 x 32 streams and
 * M = 32 moments, and both its quadrature (N = 32 -> 64) and its truncation (M = 32 -> 48)
 * change it by less than a tenth of the Monte Carlo standard error it is compared with.
 *
 * Scene: the atmosphere switched off (no Rayleigh, aerosol or ozone), a black ground, the shell
 * from 1000 to 1200 m on a planet of 6360 km, a point sun at mu0 = 0.6; cloud.lwc_g_m3 chosen
 * from the plan's sigma_ext per LWC so that tau = sigma_ext(550 nm) x 200 m = 1 and 10; phase
 * HG with cloud.hg_g = 0.85, and the cumulus Mie table (its 550 nm channel, the rows the kernels
 * read, interpolated as phase_table.h interpolates them). The sphere departs from its tangent
 * plane by x^2 / (2R) at a horizontal distance x: 0.08 m (4e-4 of the slab) at x = 1 km (5 slab
 * thicknesses, beyond which a few per cent of the light at tau = 10 spreads, e^-5-like tails),
 * and the local vertical turns by x / R = 1.6e-4 rad there; so the curvature changes the radiances
 * by ~1e-3 or less, below the tolerance. Radiance at 550 nm reflected 50 m above the slab and
 * transmitted 50 m below it (diffuse: the views are 35 degrees or more from the sun, and the sun
 * disc of the probe is checked to be zero) at four view cosines and azimuths, each compared with
 * the solver: z = (L_mc - L_ad) / se, se the standard error from independent batches of 4096
 * paths (64 batches; 256 for Mie at tau = 10), and |z| < 4 for each of the 32 comparisons (a
 * false alarm about 2e-3 for all of them together; the random numbers are fixed, so a run
 * repeats on the same device). The Mie table's forward peak (p(0) ~ 560 / sr) makes the
 * next-event estimates heavy-tailed; the reference's sun guiding (cloud.sun_guiding, default
 * 0.1, its share scaled down on paths of throughput above 1: kernels/media/phase_table.h) and
 * its roulette, whose survival probability min(1, w x gain) leaves the weight of a path with
 * w x gain >= 1 unchanged (method_reference.h), tame them: the Mie standard errors are
 * 0.5-1.7 % at tau = 1 (64 batches) and 0.7-1.7 % at tau = 10 (256 batches), so |z| < 4
 * catches a Mie error of 2-7 % at either. The Mie z values still lean negative (12 of 16
 * below 0: the forward peak's rare large estimates, a tail the batch standard error
 * underestimates; docs/notes/clouds.md). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include "testlib.h"
#include "testprobe.h"
#include "testscene.h"
#include "testslab.h"

#define DEG (M_PI / 180.0)
#define BASE_M 1000.0
#define THICK_M 200.0
#define MU0 0.6
#define VIEWS 4
#define PATHS 4096 /* per batch */
#define STREAMS 32
#define MOMENTS 32

typedef struct slab_view {
    double mu, phi_deg; /* the photon's cosine to the normal it leaves by, azimuth from the sun */
} slab_view;

static const slab_view views[VIEWS] = {{0.95, 0.0}, {0.7, 60.0}, {0.4, 180.0}, {0.25, 120.0}};

static double hg(double c, const void *ctx)
{
    double g = *(const double *)ctx;
    return (1.0 - g * g) / (4.0 * M_PI * pow(1.0 + g * g - 2.0 * g * c, 1.5));
}

typedef struct table_phase {
    const float4 *rows;
    int n;
} table_phase;

/* phase_table.h's phase_rows_eval in double: channel 1 (550 nm), linear in theta, / 4 pi */
static double table(double c, const void *ctx)
{
    const table_phase *t = ctx;
    double th = acos(fmax(-1.0, fmin(1.0, c)));
    int lo = 0, hi = t->n - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (t->rows[mid].w <= th)
            lo = mid;
        else
            hi = mid;
    }
    double a = t->rows[lo].w, b = t->rows[hi].w;
    double f = b > a ? fmax(0.0, fmin(1.0, (th - a) / (b - a))) : 0.0;
    return ((1.0 - f) * t->rows[lo].y + f * t->rows[hi].y) / (4.0 * M_PI);
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void solver_checks(const table_phase *mie)
{
    double g = 0.85, chi[40];
    slab_moments(hg, &g, 40, chi);
    double worst = 0.0;
    for (int l = 0; l < 40; l++)
        worst = fmax(worst, fabs(chi[l] - pow(g, l)));
    CHECK(worst < 1e-9);
    printf("solver: HG moments vs g^l, worst %.1e\n", worst);

    double mu[VIEWS], phi[VIEWS], r[VIEWS], t[VIEWS];
    for (int v = 0; v < VIEWS; v++)
        mu[v] = views[v].mu, phi[v] = views[v].phi_deg * DEG;
    slab_problem thin = {1e-6, 0.9, MU0, hg, &g, 16, 0};
    CHECK(slab_solve(&thin, VIEWS, mu, phi, r, t, NULL) == 0);
    worst = 0.0;
    for (int v = 0; v < VIEWS; v++) {
        double c = -mu[v] * MU0 + sqrt(1 - mu[v] * mu[v]) * sqrt(1 - MU0 * MU0) * cos(phi[v]);
        double want = 0.9 * hg(c, &g) * MU0 / (mu[v] + MU0) * -expm1(-1e-6 * (1 / mu[v] + 1 / MU0));
        worst = fmax(worst, fabs(r[v] / want - 1.0));
    }
    CHECK(worst < 1e-4);
    printf("solver: tau 1e-6 vs single scattering, worst relative %.1e\n", worst);

    for (int k = 0; k < 2; k++)
        for (int a = 0; a < 2; a++) {
            slab_problem p = {a ? 10.0 : 1.0, 1.0, MU0, k ? table : hg, k ? (const void *)mie : &g,
                              STREAMS, MOMENTS};
            slab_fluxes f;
            CHECK(slab_solve(&p, VIEWS, mu, phi, r, t, &f) == 0);
            double sum = f.reflected + f.diffuse + f.direct;
            CHECK(fabs(sum - 1.0) < 1e-6);
            printf("solver: %s tau %g albedo 1: R %.6f + T %.6f + direct %.6f - 1 = %.1e "
                   "(delta-M f = %.3f)\n",
                   k ? "mie" : "hg", p.tau, f.reflected, f.diffuse, f.direct, sum - 1.0,
                   f.truncated);
        }
}

/* The scene of one case: phase "hg" or "mie", optical thickness tau at 550 nm. */
static void slab_plan(const char *phase, double tau, atmo_plan *p)
{
    atmo_scene s;
    char set[128];
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "atmosphere.method=reference");
    test_scene_set(&s, "atmosphere.rayleigh_coefficient=0");
    test_scene_set(&s, "atmosphere.mie_extinction_per_m=0");
    test_scene_set(&s, "atmosphere.ozone_column_du=0");
    test_scene_set(&s, "atmosphere.ground_albedo=0");
    test_scene_set(&s, "cloud.enabled=true");
    test_scene_set(&s, "cloud.dsd=cumulus");
    snprintf(set, sizeof set, "cloud.bottom_m=%g", BASE_M);
    test_scene_set(&s, set);
    snprintf(set, sizeof set, "cloud.top_m=%g", BASE_M + THICK_M);
    test_scene_set(&s, set);
    snprintf(set, sizeof set, "cloud.phase=%s", phase);
    test_scene_set(&s, set);
    test_scene_set(&s, "cloud.hg_g=0.85");
    snprintf(set, sizeof set, "sun.zenith_deg=%.9f", acos(MU0) / DEG);
    test_scene_set(&s, set);
    test_scene_set(&s, "cloud.lwc_g_m3=1");
    atmo_plan unit;
    test_plan(&s, &unit);
    double lwc = tau / (THICK_M * unit.gpu.cloud.extinction.y);
    atmo_plan_free(&unit);
    snprintf(set, sizeof set, "cloud.lwc_g_m3=%.9g", lwc);
    test_scene_set(&s, set);
    test_plan(&s, p);
}

static void slab_case(atmo_cl *cl, const char *phase, double tau, int batches)
{
    atmo_plan p;
    slab_plan(phase, tau, &p);
    const atmo_gpu_cloud *c = &p.gpu.cloud;
    double tau_k = (double)c->extinction.y * THICK_M, omega = c->albedo.y, g = c->g.y;
    const atmo_plan_buffer *rows = atmo_plan_buffer_find(&p, "cloud_phase_table");
    table_phase mie = {rows->host_data, c->table_size};
    int is_mie = strcmp(phase, "mie") == 0;

    /* [N, M]: (STREAMS, MOMENTS), (2 STREAMS, MOMENTS), (2 STREAMS, 3/2 MOMENTS) */
    double mu[VIEWS], phi[VIEWS], ad[3][2][VIEWS], E = p.gpu.atmosphere.solar_irradiance.y;
    for (int v = 0; v < VIEWS; v++)
        mu[v] = views[v].mu, phi[v] = views[v].phi_deg * DEG;
    double t0 = now();
    for (int k = 0; k < 3; k++) {
        slab_problem sp = {tau_k, omega, MU0, is_mie ? table : hg, is_mie ? (const void *)&mie : &g,
                           k ? 2 * STREAMS : STREAMS, k == 2 ? 3 * MOMENTS / 2 : MOMENTS};
        CHECK(slab_solve(&sp, VIEWS, mu, phi, ad[k][0], ad[k][1], NULL) == 0);
    }
    double t_solver = now() - t0;

    /* the probe's rays (r, mu, mu_s, nu): 50 m above the slab looking down, 50 m below looking up */
    float4 rays[2 * VIEWS];
    double R = p.gpu.atmosphere.bottom_radius, s0 = sqrt(1.0 - MU0 * MU0);
    for (int side = 0; side < 2; side++)
        for (int v = 0; v < VIEWS; v++) {
            double m = views[v].mu, sv = sqrt(1.0 - m * m), cp = cos(views[v].phi_deg * DEG);
            double r = R + (side ? BASE_M - 50.0 : BASE_M + THICK_M + 50.0);
            double mu_view = side ? m : -m;
            float4 q = {(float)r, (float)mu_view, (float)MU0, (float)(mu_view * MU0 + sv * s0 * cp)};
            rays[side * VIEWS + v] = q;
        }
    test_probe t;
    test_probe_open(&t, cl, &p);
    double mean[2 * VIEWS][3], se[2 * VIEWS][3], sun[2 * VIEWS][3];
    int bad[2 * VIEWS];
    t0 = now();
    test_probe_rays(&t, rays, 2 * VIEWS, batches, PATHS, TEST_PROBE_INDEPENDENT, mean, se, sun,
                    bad);
    double t_mc = now() - t0;
    test_probe_close(&t);

    printf("%s tau %.4f omega %.6f%s: adding-doubling %.1f s, reference %d x %d samples per view "
           "%.1f s\n",
           phase, tau_k, omega, is_mie ? "" : " g 0.85", t_solver, batches, PATHS, t_mc);
    for (int side = 0; side < 2; side++)
        for (int v = 0; v < VIEWS; v++) {
            int i = side * VIEWS + v;
            double want = E * ad[1][side][v], got = mean[i][1], err = se[i][1];
            double streams = E * fabs(ad[1][side][v] - ad[0][side][v]);
            double moments = E * fabs(ad[2][side][v] - ad[1][side][v]);
            double z = (got - want) / err;
            printf("  %s mu %.2f phi %3.0f: reference %.5e +- %.1e, adding-doubling %.5e "
                   "(changes: 2N %.0e, 3M/2 %.0e), rel %+.4f, z %+.2f\n",
                   side ? "transmitted" : "reflected  ", views[v].mu, views[v].phi_deg, got, err,
                   want, streams / want, moments / want, got / want - 1.0, z);
            CHECK(fabs(z) < 4.0);
            CHECK(streams < 0.1 * err && moments < 0.1 * err);
            CHECK(bad[i] == 0 && sun[i][1] == 0.0);
        }
    atmo_plan_free(&p);
}

int main(void)
{
    atmo_cl cl;
    test_cl_open(&cl);
    atmo_plan mie_plan;
    slab_plan("mie", 1.0, &mie_plan);
    const atmo_plan_buffer *rows = atmo_plan_buffer_find(&mie_plan, "cloud_phase_table");
    table_phase mie = {rows->host_data, mie_plan.gpu.cloud.table_size};
    solver_checks(&mie);
    atmo_plan_free(&mie_plan);

    slab_case(&cl, "hg", 1.0, 64);
    slab_case(&cl, "hg", 10.0, 64);
    slab_case(&cl, "mie", 1.0, 64);
    slab_case(&cl, "mie", 10.0, 256);
    atmo_cl_close(&cl);
    return test_finish();
}
