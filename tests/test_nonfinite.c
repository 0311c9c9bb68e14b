/* test_nonfinite — no NaN, no Inf and no negative radiance from any method, for cameras from
 * the ground to 1e8 m and every sun zenith from 0 to 180 deg.
 * labels: kernel slow
 *
 * Oracle: the closed set of valid values. Every sample of sky and sun radiance (not only the
 * means, which could hide a negative sample) must be finite and >= 0, counted in the probe
 * kernel (testprobe.h).
 *
 * Rays: altitudes 0, 1, 10, ..., 1e8 m and the top of the atmosphere -1 m, exactly, +1 m;
 * sun zenith 0 to 180 deg every 10 deg; view zenith 0 to 180 deg every 10 deg plus the rays
 * 1e-3 deg either side of the ground's horizon and, from above the atmosphere, of its outer
 * limb (where distances come from nearly vanishing discriminants); view azimuth from the sun
 * 0, 45, 90, 135, 180 deg. Methods single, march, lut (small tables), reference (4 samples per
 * ray) take the camera from each ray; fast reads its sky-view LUT only for the camera and sun
 * of its plan, so it gets one plan per camera inside the atmosphere (the ground, 10 km and the
 * top -1 m; the other altitudes and every ray from above take the march fallback, covered by
 * the scan of all rays) and sun zenith, and its LUT rays are asserted to be deterministic (the
 * LUT path, not the fallback). The counter is checked on a NaN ray (method single: 4 bad of 4).
 * Measured (PoCL): 0 bad samples of 28405 rays x 4 samples for each method and 6555 rays of
 * fast's LUT path. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "testlib.h"
#include "testprobe.h"

#define DEG (M_PI / 180.0)
#define N_ALT 13
#define N_SUN 19
#define N_VIEW 23
#define N_AZ 5
#define MAX_RAYS (N_ALT * N_SUN * N_VIEW * N_AZ)

/* View zeniths for a camera at radius r: every 10 deg, and 1e-3 deg either side of the
 * ground's horizon and (from above the atmosphere) of its outer limb; N_VIEW values. */
static void view_zeniths(const atmo_atmosphere *a, double r, double *out)
{
    int n = 0;
    for (int i = 0; i <= 18; i++)
        out[n++] = 10.0 * i;
    double horizon = 180.0 - asin(fmin(a->bottom_radius_m / r, 1.0)) / DEG;
    out[n++] = horizon - 1e-3, out[n++] = horizon + 1e-3;
    double limb = r > a->top_radius_m ? 180.0 - asin(a->top_radius_m / r) / DEG : 90.0;
    out[n++] = limb - 1e-3, out[n++] = limb + 1e-3;
}

/* The rays of one camera radius and sun zenith (sun cosine mu_s as given) */
static int camera_rays(const atmo_atmosphere *a, float r, float mu_s, float4 *rays)
{
    double views[N_VIEW], sin_s = sqrt(fmax(1.0 - (double)mu_s * mu_s, 0.0));
    view_zeniths(a, r, views);
    int n = 0;
    for (int iv = 0; iv < N_VIEW; iv++)
        for (int ia = 0; ia < N_AZ; ia++) {
            double tv = views[iv] * DEG, pa = 45.0 * ia * DEG;
            float4 q = {r, (float)cos(tv), mu_s,
                        (float)(sin(tv) * sin_s * cos(pa) + cos(tv) * mu_s)};
            rays[n++] = q;
        }
    return n;
}

static int report(const char *method, const float4 *rays, const int *bad, int n)
{
    int total = 0;
    for (int i = 0; i < n; i++) {
        if (bad[i] && total < 5)
            fprintf(stderr, "%s: %d bad samples at r = %.9g m, mu = %.9g, mu_s = %.9g, "
                    "nu = %.9g\n", method, bad[i], rays[i].x, rays[i].y, rays[i].z, rays[i].w);
        total += bad[i];
    }
    return total;
}

int main(void)
{
    atmo_cl cl;
    test_cl_open(&cl);
    static float4 rays[MAX_RAYS];
    static double L[MAX_RAYS][3], se[MAX_RAYS][3];
    static int bad[MAX_RAYS];
    static const char *const methods[] = {"single", "march", "lut", "reference", "fast"};
    atmo_plan p;
    test_sky_plan("single", 0.0, 0.0, &p);
    const atmo_atmosphere *a = &p.atmosphere;
    double R = a->bottom_radius_m, top = a->top_radius_m, alt[N_ALT];
    for (int i = 0; i <= 8; i++)
        alt[i] = i ? pow(10.0, i - 1) : 0.0;
    alt[9] = top - R - 1.0, alt[10] = top - R, alt[11] = top - R + 1.0, alt[12] = 1e8;

    int n = 0;
    for (int ia = 0; ia < N_ALT; ia++)
        for (int is = 0; is < N_SUN; is++)
            n += camera_rays(a, (float)(R + alt[ia]), (float)cos(10.0 * is * DEG), rays + n);

    for (int m = 0; m < 5; m++) {
        const char *method = methods[m];
        test_sky_plan(method, 0.0, 0.0, &p);
        test_probe t;
        test_probe_open(&t, &cl, &p);
        test_probe_rays(&t, rays, n, 4, 1, TEST_PROBE_INDEPENDENT, L, NULL, NULL,
                        bad);
        if (m == 0) { /* the counter itself: single turns a NaN ray into NaN radiance */
            float4 nan_ray = {NAN, NAN, NAN, NAN};
            double L1[1][3];
            int bad1;
            test_probe_rays(&t, &nan_ray, 1, 4, 1, TEST_PROBE_INDEPENDENT, L1, NULL, NULL,
                            &bad1);
            CHECK(bad1 == 4);
        }
        test_probe_close(&t);
        int total = report(method, rays, bad, n);
        CHECK(total == 0);
        printf("%-9s %d rays x 4 samples: %d non-finite or negative\n", method, n, total);
    }

    /* fast's LUT path: a plan per camera inside the atmosphere and sun zenith */
    static const double fast_alt[3] = {0.0, 1e4, 59999.0};
    int total = 0, count = 0;
    for (int ia = 0; ia < 3; ia++)
        for (int is = 0; is < N_SUN; is++) {
            test_sky_plan("fast", fast_alt[ia], 10.0 * is, &p);
            int k = camera_rays(a, p.gpu.camera.local_up.w, p.gpu.sun_direction.y, rays);
            test_probe t;
            test_probe_open(&t, &cl, &p);
            test_probe_rays(&t, rays, k, 4, 1, TEST_PROBE_INDEPENDENT, L, se, NULL, bad);
            test_probe_close(&t);
            total += report("fast (LUT)", rays, bad, k);
            count += k;
            for (int i = 0; i < k; i++)
                for (int c = 0; c < 3; c++)
                    CHECK(se[i][c] == 0.0); /* the LUT path: no randomness */
        }
    CHECK(total == 0);
    printf("fast LUT  %d rays x 4 samples (cameras at 0, 10 km, top - 1 m): %d non-finite or "
           "negative\n", count, total);
    atmo_cl_close(&cl);
    return test_finish();
}
