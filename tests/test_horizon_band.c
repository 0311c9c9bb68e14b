/* test_horizon_band — no band at the horizon: scans of the view zenith across the horizon in
 * fine steps, every method.
 * labels: kernel slow
 *
 * Scans. View zenith across the true horizon (the ground's tangent, where the ground begins to
 * hide the air behind it: a real jump) in 400 steps: 0.01 deg over +-2 deg for cameras at
 * 1.7 m (the default camera), 1 km and 10 km (horizon depressed by 1.0 and 3.2 deg); from space
 * (the `space` preset's 2000 km and 1e8 m) across the limb, from half the limb's width of
 * black space through the atmosphere's outer edge (a real onset, L ~ sqrt(view angle past it))
 * and the ground's limb into half a width of ground (steps of 3e-3 and 1.6e-4 deg). Suns: 60 deg
 * toward and away from the view, 88 deg (sunset) toward, across and away (rays that cross the
 * planet's shadow). Edges fall mid-step; the steps across them are not judged.
 *
 * Criterion (single, march, lut at small table sizes, fast; common random numbers, so each scan
 * is as smooth as the method itself: 16 march offsets shared by all rays): every step
 * |L(i+1) - L(i)| must be at most K = 4 times the median of the 6 steps around it on the same
 * side of the edges, plus 1e-4 of L. Why this bound: the sky is smooth on the scale of the
 * steps, so neighbouring steps of a smooth profile differ by a small fraction, and at a kink
 * (the bilinear texels of a LUT, a slope change of a few times at most between texels) the
 * step lies between the slopes of the two sides, whose median it cannot exceed by 4; a band
 * (texels of the wrong half at the horizon, a ground/sky test that disagrees with a distance,
 * a LUT row mapping that folds) is a jump of many times the local step. The 1e-4 of L covers
 * float rounding (~1e-6 of L). The point sun's shadow edge crossing one of the 16 x 32 march
 * samples is a true step of a march with fixed offsets; with the sun at 88 deg away from the
 * view it stays within the bound. Steps where both values are below 1e-9 W m^-2 sr^-1
 * nm^-1 (darker than a moonless night sky: the shadowed limb, where the march's multiple
 * scattering at ~1e-19 does jump by 3x) are not judged. fast reads its sky-view LUT of each
 * camera inside the atmosphere (asserted: no randomness on those rays) and falls back to the
 * march from space.
 * The detector's reach is printed: near the horizon, where the profile is steepest, the jump it
 * catches is 2-11 % of L on the air's side and 7-41 % on the ground's; and the test checks itself
 * on a synthetic band of +0.5 % over the 0.1 deg above the horizon from the ground (caught at
 * 5x its bound).
 *
 * Reference (Monte Carlo): independent samples (1024 per ray) on every 5th ray of the scans from
 * 1.7 m, 10 km and 2000 km, sun 60 and 88 deg toward the view; the second differences of its
 * difference from the march (smooth, checked above) must be within 5.5 standard errors: it
 * catches a band of more than ~25 % of L (5.5 x sqrt(6) x its median standard error, 1.7 %).
 *
 * Measured (PoCL): worst step / bound 0.71 single, 0.79 march, 0.65 lut, 0.79 fast; reference
 * worst |z| 3.5. No method shows a band.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/atmosphere_ref.h"
#include "testlib.h"
#include "testprobe.h"

#define DEG (M_PI / 180.0)
#define STEPS 401 /* 400 steps: 0.01 deg over +-2 deg from the ground and the air */
#define N_CAMERAS 5
#define N_SUNS 5
#define NEIGHBOURS 3 /* steps on each side whose median sets the local variation */
#define K_STEP 4.0
#define FLOOR 1e-4
#define BLACK 1e-9 /* W m^-2 sr^-1 nm^-1: darker than a moonless night sky */

static const double sun_cfg[N_SUNS][2] = {{60, 0}, {60, 180}, {88, 0}, {88, 90}, {88, 180}};

typedef struct scan {
    double r, first_deg, step_deg;
    double horizon_deg; /* the ground's edge: hit or miss */
    double top_deg;     /* from space: the atmosphere's outer edge (else 0) */
} scan;

static scan make_scan(const atmo_atmosphere *a, double r)
{
    scan s;
    s.r = r;
    s.horizon_deg = 180.0 - asin(a->bottom_radius_m / r) / DEG;
    if (r > a->top_radius_m) { /* across the limb: half its width of space and of ground */
        s.top_deg = 180.0 - asin(a->top_radius_m / r) / DEG;
        s.step_deg = 2.0 * (s.horizon_deg - s.top_deg) / (STEPS - 1);
        s.first_deg = s.horizon_deg - 299.5 * s.step_deg; /* both edges between samples */
    } else {
        s.top_deg = 0.0;
        s.step_deg = 4.0 / (STEPS - 1);
        s.first_deg = s.horizon_deg - 199.5 * s.step_deg;
    }
    return s;
}

static void scan_rays(const scan *s, double sun_zenith, double azimuth, float4 *rays)
{
    double ts = sun_zenith * DEG, pa = azimuth * DEG;
    for (int i = 0; i < STEPS; i++) {
        double tv = (s->first_deg + i * s->step_deg) * DEG;
        float4 q = {(float)s->r, (float)cos(tv), (float)cos(ts),
                    (float)(sin(tv) * sin(ts) * cos(pa) + cos(tv) * cos(ts))};
        rays[i] = q;
    }
}

/* the edge index e: a true edge lies between samples e and e + 1 */
static int edge_after(const scan *s, double edge_deg)
{
    return (int)floor((edge_deg - s->first_deg) / s->step_deg);
}

static int compare_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

static double median(double *v, int n)
{
    for (int i = 1; i < n; i++) /* insertion sort, n <= 6 */
        for (int j = i; j > 0 && v[j] < v[j - 1]; j--) {
            double t = v[j];
            v[j] = v[j - 1], v[j - 1] = t;
        }
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Steps of one channel: each within K_STEP x the median of its neighbours on the same side of
 * the true edges, or FLOOR of the radiance; returns the worst ratio |step| / (bound) */
static double check_steps(const char *what, const scan *s, const double (*L)[3], int c,
                          int *fails, double detect[2])
{
    int e1 = edge_after(s, s->horizon_deg), e0 = s->top_deg > 0.0 ? edge_after(s, s->top_deg) : -1;
    double steps[STEPS], worst = 0.0;
    for (int i = 0; i + 1 < STEPS; i++)
        steps[i] = fabs(L[i + 1][c] - L[i][c]);
    for (int i = 0; i + 1 < STEPS; i++) {
        if (i == e1 || i == e0 || fmax(L[i][c], L[i + 1][c]) < BLACK)
            continue;
        int lo = i < e1 ? (i < e0 ? 0 : e0 + 1) : e1 + 1; /* the run of steps i is in */
        int hi = i < e1 ? (i < e0 ? e0 - 1 : e1 - 1) : STEPS - 2;
        double v[2 * NEIGHBOURS];
        int n = 0;
        for (int j = i - NEIGHBOURS; j <= i + NEIGHBOURS; j++)
            if (j != i && j >= lo && j <= hi)
                v[n++] = steps[j];
        if (n < 2)
            continue;
        double bound = K_STEP * median(v, n) + FLOOR * fmax(L[i][c], L[i + 1][c]);
        double ratio = bound > 0.0 ? steps[i] / bound : (steps[i] > 0.0 ? INFINITY : 0.0);
        if (abs(i - e1) <= 2 && L[i][c] > 0.0) /* the smallest jump caught next to the horizon */
            detect[i > e1] = fmax(detect[i > e1], bound / L[i][c]);
        if (ratio > 1.0) {
            if (*fails < 8)
                fprintf(stderr, "%s: step %d (view zenith %.3f deg, horizon %.3f) channel %d: "
                        "%.4g -> %.4g, %.1f x its bound\n", what, i, s->first_deg +
                        (i + 0.5) * s->step_deg, s->horizon_deg, c, L[i][c], L[i + 1][c],
                        ratio);
            (*fails)++;
        }
        worst = fmax(worst, ratio);
    }
    return worst;
}

/* The deterministic methods (common random numbers: every ray of a scan gets the same march
 * offsets, so a scan is as smooth as the method). */
static void check_method(atmo_cl *cl, const char *method, const double cam_r[N_CAMERAS],
                         double (*keep)[3], scan *keep_scan)
{
    static float4 rays[STEPS];
    static double L[STEPS][3], se[STEPS][3];
    int fails = 0, is_fast = !strcmp(method, "fast");
    double worst = 0.0, detect[N_CAMERAS][2] = {{0}};
    atmo_plan p;
    test_sky_plan(method, 0.0, 0.0, &p);
    const atmo_atmosphere *a = &p.atmosphere;
    test_probe t;
    int open = 0;
    for (int ic = 0; ic < N_CAMERAS; ic++)
        for (int is = 0; is < N_SUNS; is++) {
            /* fast: the sky-view LUT of this camera and sun zenith (for a camera in space every
             * ray falls back to the march, whatever the plan's camera) */
            int fast_lut = is_fast && cam_r[ic] <= a->top_radius_m;
            int new_view = fast_lut && (is == 0 || sun_cfg[is][0] != sun_cfg[is - 1][0]);
            if (open && new_view)
                test_probe_close(&t), open = 0;
            if (new_view)
                test_sky_plan(method, cam_r[ic] - a->bottom_radius_m, sun_cfg[is][0], &p);
            if (!open)
                test_probe_open(&t, cl, &p), open = 1;
            scan s = make_scan(a, fast_lut ? p.gpu.camera.local_up.w : cam_r[ic]);
            scan_rays(&s, sun_cfg[is][0], sun_cfg[is][1], rays);
            if (fast_lut)
                for (int i = 0; i < STEPS; i++)
                    rays[i].z = p.gpu.sun_direction.y; /* the LUT's sun cosine exactly */
            test_probe_rays(&t, rays, STEPS, 16, 1, TEST_PROBE_COMMON, L, se, NULL, NULL);
            char what[128];
            snprintf(what, sizeof what, "%s, camera at %.0f m, sun %g deg azimuth %g", method,
                     cam_r[ic] - a->bottom_radius_m, sun_cfg[is][0], sun_cfg[is][1]);
            for (int c = 0; c < 3; c++) {
                worst = fmax(worst, check_steps(what, &s, L, c, &fails, detect[ic]));
                for (int i = 0; fast_lut && i < STEPS; i++)
                    CHECK(se[i][c] == 0.0); /* the LUT path: no randomness */
            }
            if (keep && ic == 0 && is == 0) { /* a scan for the detector's own test */
                memcpy(keep, L, sizeof L);
                *keep_scan = s;
            }
        }
    if (open)
        test_probe_close(&t);
    CHECK(fails == 0);
    printf("%-9s worst step %.2f of its bound; caught next to the horizon: jumps above (%% of L, "
           "sky/ground side, per camera)", method, worst);
    for (int ic = 0; ic < N_CAMERAS; ic++)
        printf(" %.2g/%.2g", 100 * detect[ic][0], 100 * detect[ic][1]);
    printf("\n");
}

/* The detector itself: a band of +0.5 % over the 0.1 deg of sky above the horizon, added to a
 * real scan, must fail. */
static void check_detector(double (*L)[3], const scan *s)
{
    int e1 = edge_after(s, s->horizon_deg), fails = 0;
    double detect[2] = {0.0, 0.0};
    for (int i = e1 - 9; i <= e1; i++)
        for (int c = 0; c < 3; c++)
            L[i][c] *= 1.005;
    fprintf(stderr, "(a synthetic band, expected to be caught:)\n");
    check_steps("synthetic band", s, (const double(*)[3])L, 1, &fails, detect);
    CHECK(fails > 0);
    printf("a synthetic 0.5 %% band above the horizon: %s\n", fails ? "caught" : "MISSED");
}

/* The reference (Monte Carlo): independent samples per ray, every 5th ray of a scan; its
 * difference from the march (smooth, and checked above) must have second differences within
 * 5.5 of their standard errors. */
static void check_reference(atmo_cl *cl, const double cam_r[N_CAMERAS])
{
    enum { SUB = 5, N = (STEPS - 1) / SUB + 1, SAMPLES = 64 * 16 };
    static const int cameras[3] = {0, 2, 3}, suns[2] = {0, 2};
    static float4 all[STEPS], rays[N];
    static double Lr[N][3], se[N][3], Lm[N][3], rel[3 * N * 6];
    atmo_plan pr, pm;
    test_sky_plan("reference", 0.0, 0.0, &pr);
    test_sky_plan("march", 0.0, 0.0, &pm);
    const atmo_atmosphere *a = &pr.atmosphere;
    test_probe tr, tm;
    test_probe_open(&tr, cl, &pr);
    test_probe_open(&tm, cl, &pm);
    double worst_z = 0.0;
    int nrel = 0;
    for (int k = 0; k < 3; k++)
        for (int l = 0; l < 2; l++) {
            int ic = cameras[k], is = suns[l];
            scan s = make_scan(a, cam_r[ic]);
            scan_rays(&s, sun_cfg[is][0], sun_cfg[is][1], all);
            for (int i = 0; i < N; i++)
                rays[i] = all[i * SUB];
            test_probe_rays(&tr, rays, N, 64, SAMPLES / 64, TEST_PROBE_INDEPENDENT, Lr, se, NULL,
                            NULL);
            test_probe_rays(&tm, rays, N, 16, 1, TEST_PROBE_COMMON, Lm, NULL, NULL, NULL);
            int e1 = edge_after(&s, s.horizon_deg) / SUB;
            int e0 = s.top_deg > 0.0 ? edge_after(&s, s.top_deg) / SUB : -1;
            for (int i = 1; i + 1 < N; i++) {
                if (i == e1 || i == e1 + 1 || i == e0 || i == e0 + 1)
                    continue; /* the triple straddles a true edge */
                for (int c = 0; c < 3; c++) {
                    double d2 = (Lr[i - 1][c] - Lm[i - 1][c]) - 2.0 * (Lr[i][c] - Lm[i][c]) +
                                (Lr[i + 1][c] - Lm[i + 1][c]);
                    double sd = sqrt(se[i - 1][c] * se[i - 1][c] + 4.0 * se[i][c] * se[i][c] +
                                     se[i + 1][c] * se[i + 1][c]);
                    if (sd == 0.0) {
                        CHECK(d2 == 0.0);
                        continue;
                    }
                    double z = d2 / sd;
                    if (!(fabs(z) <= 5.5))
                        fprintf(stderr, "reference, camera at %.0f m, sun %g deg azimuth %g, "
                                "view zenith %.3f deg, channel %d: second difference z = %.2f\n",
                                cam_r[ic] - a->bottom_radius_m, sun_cfg[is][0], sun_cfg[is][1],
                                s.first_deg + i * SUB * s.step_deg, c, z);
                    CHECK(fabs(z) <= 5.5);
                    worst_z = fmax(worst_z, fabs(z));
                    if (Lr[i][c] > 0.0)
                        rel[nrel++] = se[i][c] / Lr[i][c];
                }
            }
        }
    test_probe_close(&tm);
    test_probe_close(&tr);
    qsort(rel, (size_t)nrel, sizeof *rel, compare_double);
    printf("reference worst |z| of second differences %.2f (%d samples per ray, median relative "
           "standard error %.1f %%)\n", worst_z, SAMPLES, nrel ? 100 * rel[nrel / 2] : 0.0);
}

int main(void)
{
    atmo_cl cl;
    test_cl_open(&cl);
    atmo_scene sp;
    atmo_plan p;
    test_scene_preset(&sp, "space");
    test_plan(&sp, &p);
    double R = p.atmosphere.bottom_radius_m;
    const double *x = sp.camera.position_m;
    double cam_r[N_CAMERAS] = {R + 1.7, R + 1e3, R + 1e4,
                               sqrt(x[0] * x[0] + (x[1] + R) * (x[1] + R) + x[2] * x[2]),
                               R + 1e8};
    static double keep[STEPS][3];
    scan keep_scan;
    check_method(&cl, "single", cam_r, NULL, NULL);
    check_method(&cl, "march", cam_r, keep, &keep_scan);
    check_method(&cl, "lut", cam_r, NULL, NULL);
    check_method(&cl, "fast", cam_r, NULL, NULL);
    check_reference(&cl, cam_r);
    check_detector(keep, &keep_scan);
    atmo_cl_close(&cl);
    return test_finish();
}
