/* test_lut_method — atmosphere method "lut": the 4-D parametrisation on the host, then the
 * precomputed tables on the device, order by order.
 * labels: kernel slow
 *
 * Oracles and tolerances:
 * 1. Parametrisation (kernels/atmosphere/lut_scattering.h, on the host): the inverse maps are exact
 *    inverses. Texel centres: value_at(i) maps back to position i within 5e-3 texel (r rounds
 *    to 0.25 m at 6.4e6 m, and next to the ground, where dp/dr = (n - 1) r / (H rho) is
 *    steepest, that is 2e-3 texel of a 32-texel axis), and within 5e-2 texel for mu, whose
 *    float rounding (6e-8 relative) the slope dd/dmu ~ r^2 / sqrt(discriminant) amplifies next
 *    to the horizon at the lowest radii (as in test_lut_param). Random values round-trip
 *    (value -> position -> value) to 1e-6 relative in r (float epsilon 6e-8 amplified by the
 *    square root near the ground) and to 1e-3 texel in the mu and mu_s positions. The horizon
 *    is the last texel of each half; sun zenith 110 deg lies inside the mu_s axis.
 * 2. Order 1 against the host double reference (atmo_ref_single_scattering + the directly lit
 *    ground, accurate to 1e-9): within 1 % (the target for single scattering, as in
 *    test_sky_single) at texel centres and at points between texels, for sun zenith <= 80 deg.
 *    Rays whose sun visibility changes along them (the planet's shadow boundary, a step that a
 *    texel's midpoint rule cannot resolve) are left out here and covered by the NaN and horizon
 *    scans.
 * 3. Orders converge: the contribution of each order n >= 2 (the sky radiance after n orders
 *    minus after n - 1) is positive and smaller than the previous one, so the sum is monotone; the
 *    order whose contribution falls below 0.1 % in blue with the sun on the horizon is printed
 *    (it sets lut.orders' default).
 * 4. No band at the horizon: scans of 0.02-degree steps over +-1 degree around the horizon from
 *    the ground and from 10 km: on each side of the true edge (the ground hides the air behind
 *    it, a real jump) every step is at most 3 times the larger of its neighbours, or 1e-4 of the
 *    radiance (a band, from a mismatch of texels near the horizon, is a jump many times the
 *    smooth change around it; a smooth curve sampled this finely changes its steps by a few
 *    tens of percent, a texel kink by up to ~2x).
 * 5. No NaN or Inf (sky and sun) for altitudes 0 .. 1e8 m, sun zenith 0 .. 180 deg, any view.
 * 6. All orders (the default lut.orders, sphere grid and mu_s and nu sizes; r and mu halved)
 *    against the Monte Carlo table tests/data/reference_sky.csv (camera at the ground, 0.3 %
 *    standard error; skipped, and said so, where the file is missing): within 2 % + 3
 *    standard errors for sun zenith <= 80 deg, and 5 % + 3 standard errors at 90 deg (the
 *    method's accuracy targets, as in test_reference_accuracy). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "atmo/atmosphere_ref.h"
#include "atmo/render.h"
#include "atmosphere/lut_scattering.h"
#include "testlib.h"
#include "testscene.h"

#define DEG (M_PI / 180.0)
#define MAX_RAYS 20000
#define ORDERS 8
#define ORDERS_TEXT "8"

static const char probe_src[] =
    "__kernel void lut_probe(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                        __global const float4 *rays, __global float4 *sky_out,\n"
    "                        __global float4 *sun_out, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  float4 q = rays[i]; float3 sky, sun;\n"
    "  sky_radiance(s, ATMO_LUT_ARGS, q.x, q.y, q.z, q.w, i, 0u, &sky, &sun);\n"
    "  sky_out[i] = (float4)(sky, 0.0f); sun_out[i] = (float4)(sun, 0.0f);\n"
    "}\n";

/* ---------------------------------------------------------------- 1: parametrisation */

static double frand(unsigned *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (double)(*state >> 8) / 16777216.0;
}

static void test_parametrisation(const atmo_gpu_atmosphere *a, const int dims[4])
{
    int n_nu = dims[0], n_mu_s = dims[1], n_mu = dims[2], n_r = dims[3];
    double worst_centre = 0.0, worst_mu = 0.0, worst_trip = 0.0;
    for (int i = 0; i < n_r; i++) {
        float r = lut_r_at(a, (float)i, n_r);
        worst_centre = fmax(worst_centre, fabs(lut_r_position(a, r, n_r) - i));
        for (int j = 0; j < n_mu; j++) {
            int ground;
            float mu = lut_mu_at(a, r, (float)j, n_mu, &ground);
            CHECK(ground == (j < n_mu / 2));
            if (i > 0) /* at the ground every downward ray has length 0: one texel, not a map */
                worst_mu = fmax(worst_mu, fabs(lut_mu_position(a, r, mu, ground, n_mu) - j));
        }
    }
    for (int k = 0; k < n_mu_s; k++)
        worst_centre = fmax(
            worst_centre, fabs(lut_mu_s_position(a, lut_mu_s_at(a, (float)k, n_mu_s), n_mu_s) - k));
    for (int l = 0; l < n_nu; l++)
        worst_centre = fmax(
            worst_centre, fabs(lut_nu_position(lut_nu_at((float)l, n_nu, 0.0f, 0.0f), n_nu) - l));
    CHECK(worst_centre < 5e-3);
    CHECK(worst_mu < 5e-2);

    unsigned seed = 12345u;
    for (int t = 0; t < 20000; t++) {
        float r = (float)(a->bottom_radius + 1.0 +
                          frand(&seed) * (a->top_radius - a->bottom_radius - 2.0));
        float mu = (float)(2.0 * frand(&seed) - 1.0), mu_s = (float)(-0.4 + 1.4 * frand(&seed));
        int ground = geometry_ray_hits_ground(r, mu, a->bottom_radius), g2;
        float p_r = lut_r_position(a, r, n_r);
        CHECK_REL(lut_r_at(a, p_r, n_r), r, 1e-6);
        float p_mu = lut_mu_position(a, r, mu, ground, n_mu);
        CHECK(ground ? p_mu <= n_mu / 2 - 1 : p_mu >= n_mu / 2);
        float mu2 = lut_mu_at(a, r, p_mu, n_mu, &g2);
        CHECK(g2 == ground);
        worst_trip = fmax(worst_trip, fabs(lut_mu_position(a, r, mu2, ground, n_mu) - p_mu));
        float p_mu_s = lut_mu_s_position(a, mu_s, n_mu_s);
        float mu_s2 = lut_mu_s_at(a, p_mu_s, n_mu_s);
        worst_trip = fmax(worst_trip, fabs(lut_mu_s_position(a, mu_s2, n_mu_s) - p_mu_s));
    }
    CHECK(worst_trip < 1e-3);
    /* the horizon is the outer texel of each half, from the ground and from 30 km */
    for (int i = 0; i < 2; i++) { /* within 0.05 texel: mu_h is rounded, as above */
        float r = a->bottom_radius + (i ? 30e3f : 1.0f);
        float mu_h = -sqrtf((r - a->bottom_radius) * (r + a->bottom_radius)) / r;
        CHECK_ABS(lut_mu_position(a, r, mu_h, 0, n_mu), n_mu - 1, 0.05);
        CHECK_ABS(lut_mu_position(a, r, mu_h, 1, n_mu), 0.0, 0.05);
    }
    /* twilight: sun zenith 110 deg is inside the axis, 120 deg at its end */
    CHECK(lut_mu_s_position(a, (float)cos(110 * DEG), n_mu_s) > 0.5);
    CHECK(lut_mu_s_position(a, (float)cos(121 * DEG), n_mu_s) == 0.0f);
    printf("parametrisation: texel centres within %.1e texel (mu: %.1e), round trips within %.1e "
           "texel\n", worst_centre, worst_mu, worst_trip);
}

/* ---------------------------------------------------------------- device helpers */

typedef struct ctx {
    atmo_cl cl;
    cl_program prog;
    cl_mem scene, luts[ATMO_PLAN_MAX_BUFFERS];
    const atmo_plan *plan;
} ctx;

static void run_pass(ctx *c, const atmo_plan_pass *pass)
{
    cl_int err;
    cl_kernel k = clCreateKernel(c->prog, pass->kernel, &err);
    CHECK(err == CL_SUCCESS);
    clSetKernelArg(k, 0, sizeof c->scene, &c->scene);
    int a = test_bind_buffers(k, c->luts);
    clSetKernelArg(k, a, sizeof pass->arg, &pass->arg);
    int three_d = pass->depth > 1;
    size_t local[3] = {three_d ? 4 : 8, three_d ? 4 : 8, three_d ? 4 : 1};
    size_t global[3];
    int n[3] = {pass->width, pass->height, pass->depth};
    for (int i = 0; i < 3; i++)
        global[i] = ((size_t)n[i] + local[i] - 1) / local[i] * local[i];
    err = clEnqueueNDRangeKernel(c->cl.queue, k, three_d ? 3 : 2, NULL, global, local, 0, NULL,
                                 NULL);
    CHECK(err == CL_SUCCESS);
    clFinish(c->cl.queue);
    clReleaseKernel(k);
}

/* sky and sun radiance for n rays (r, mu, mu_s, nu) */
static void probe(ctx *c, const float4 *rays, int n, float (*sky)[4], float (*sun)[4])
{
    cl_int err;
    cl_mem b_rays = test_cl_buffer(&c->cl, sizeof(float4) * (size_t)n, rays);
    cl_mem b_sky = test_cl_buffer(&c->cl, sizeof(float4) * (size_t)n, NULL);
    cl_mem b_sun = test_cl_buffer(&c->cl, sizeof(float4) * (size_t)n, NULL);
    cl_kernel k = clCreateKernel(c->prog, "lut_probe", &err);
    cl_uint count = (cl_uint)n;
    clSetKernelArg(k, 0, sizeof c->scene, &c->scene);
    int a = test_bind_buffers(k, c->luts);
    clSetKernelArg(k, a, sizeof b_rays, &b_rays);
    clSetKernelArg(k, a + 1, sizeof b_sky, &b_sky);
    clSetKernelArg(k, a + 2, sizeof b_sun, &b_sun);
    clSetKernelArg(k, a + 3, sizeof count, &count);
    test_cl_run_1d(&c->cl, k, (size_t)n);
    test_cl_read(&c->cl, b_sky, sizeof(float4) * (size_t)n, sky);
    if (sun)
        test_cl_read(&c->cl, b_sun, sizeof(float4) * (size_t)n, sun);
    clReleaseKernel(k);
    clReleaseMemObject(b_sun);
    clReleaseMemObject(b_sky);
    clReleaseMemObject(b_rays);
}

static float4 make_ray(double r, double view_zenith_deg, double sun_zenith_deg,
                       double azimuth_deg)
{
    double tv = view_zenith_deg * DEG, ts = sun_zenith_deg * DEG, p = azimuth_deg * DEG;
    float4 q = {(float)r, (float)cos(tv), (float)cos(ts),
                (float)(sin(tv) * sin(ts) * cos(p) + cos(tv) * cos(ts))};
    return q;
}

/* 1 if the sun's visibility (the point sun, as in the reference) changes along the ray */
static int crosses_shadow(const atmo_atmosphere *a, float4 q)
{
    double r = q.x, mu = q.y, mu_s = q.z, nu = q.w;
    double d = atmo_ref_ray_hits_ground(r, mu, a->bottom_radius_m)
                   ? atmo_ref_distance_to_bottom(r, mu, a->bottom_radius_m)
                   : atmo_ref_distance_to_top(r, mu, a->top_radius_m);
    int first = -1;
    for (int i = 0; i <= 400; i++) {
        double t = d * i / 400.0, r_t = atmo_ref_radius_at(r, mu, t);
        double m = atmo_ref_mu_s_at(r, mu, mu_s, nu, t);
        int lit = !atmo_ref_ray_hits_ground(r_t, m, a->bottom_radius_m);
        if (first < 0)
            first = lit;
        else if (lit != first)
            return 1;
    }
    return 0;
}

/* ---------------------------------------------------------------- 2: order 1 vs reference */

static void test_order1(ctx *c, const atmo_atmosphere *a, const atmo_gpu_atmosphere *ga,
                        const int dims[4])
{
    static float4 rays[MAX_RAYS];
    static float sky[MAX_RAYS][4];
    static double want[MAX_RAYS][3];
    static int centre[MAX_RAYS];
    int n = 0, n_nu = dims[0], n_mu_s = dims[1], n_mu = dims[2], n_r = dims[3];
    /* texel centres: a few radii, every other mu, sun zenith <= 80 deg, four nu */
    int radii[3] = {1, n_r / 3, n_r - 1};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < n_mu; j += 2)
            for (int k = 0; k < n_mu_s; k += 2)
                for (int l = 0; l < n_nu; l += 2) {
                    float r = lut_r_at(ga, (float)radii[i], n_r);
                    int ground;
                    float mu = lut_mu_at(ga, r, (float)j, n_mu, &ground);
                    float mu_s = lut_mu_s_at(ga, (float)k, n_mu_s);
                    float nu = lut_nu_at((float)l, n_nu, mu, mu_s);
                    float4 q = {r, mu, mu_s, nu};
                    /* j = 0 is the horizon, where hit or miss is decided by rounding: the scan
                     * across the horizon covers it */
                    if (j == 0 || mu_s < cosf(80.0f * (float)DEG) || crosses_shadow(a, q))
                        continue;
                    centre[n] = 1;
                    rays[n++] = q;
                }
    int n_centre = n;
    /* points between texels: random rays from the ground, 1 km, 10 km and 30 km */
    unsigned seed = 777u;
    static const double alt[] = {1.7, 1e3, 10e3, 30e3};
    while (n < n_centre + 600) {
        float4 q = make_ray(a->bottom_radius_m + alt[n % 4], 180.0 * frand(&seed),
                            80.0 * frand(&seed), 180.0 * frand(&seed));
        if (crosses_shadow(a, q))
            continue;
        centre[n] = 0;
        rays[n++] = q;
    }
    for (int i = 0; i < n; i++) {
        double ss[3], g[3] = {0, 0, 0};
        atmo_ref_single_scattering(a, rays[i].x, rays[i].y, rays[i].z, rays[i].w, ss);
        if (atmo_ref_ray_hits_ground(rays[i].x, rays[i].y, a->bottom_radius_m))
            atmo_ref_ground_radiance(a, rays[i].x, rays[i].y, rays[i].z, rays[i].w, g);
        for (int ch = 0; ch < 3; ch++)
            want[i][ch] = ss[ch] + g[ch];
    }
    probe(c, rays, n, sky, NULL);
    double worst[2] = {0, 0};
    for (int i = 0; i < n; i++)
        for (int ch = 0; ch < 3; ch++) {
            if (want[i][ch] <= 0.0) {
                CHECK_ABS(sky[i][ch], 0.0, 0.0);
                continue;
            }
            double rel = fabs(sky[i][ch] - want[i][ch]) / want[i][ch];
            if (rel > 0.01)
                fprintf(stderr, "%s r=%.0f mu=%.5f mu_s=%.4f nu=%.4f ch %d: %.4g vs %.4g\n",
                        centre[i] ? "texel" : "between", rays[i].x, rays[i].y, rays[i].z,
                        rays[i].w, ch, sky[i][ch], want[i][ch]);
            CHECK(rel <= 0.01);
            worst[centre[i] ? 0 : 1] = fmax(worst[centre[i] ? 0 : 1], rel);
        }
    printf("order 1 vs double reference: worst %.2f %% at %d texel centres, %.2f %% at %d points "
           "between texels\n", 100 * worst[0], n_centre, 100 * worst[1], n - n_centre);

    /* near the top, upward views see almost no air (1e-4 of the ground's sky) and change by
     * orders of magnitude between the top texels: judged against the brightest radiance of the
     * same views (the image's scale), not each ray's own */
    n = 0;
    while (n < 300) {
        float4 q = make_ray(a->bottom_radius_m + 59e3, 180.0 * frand(&seed), 80.0 * frand(&seed),
                            180.0 * frand(&seed));
        if (!crosses_shadow(a, q))
            rays[n++] = q;
    }
    double scale[3] = {0, 0, 0}, worst_top = 0.0;
    for (int i = 0; i < n; i++) {
        double ss[3], g[3] = {0, 0, 0};
        atmo_ref_single_scattering(a, rays[i].x, rays[i].y, rays[i].z, rays[i].w, ss);
        if (atmo_ref_ray_hits_ground(rays[i].x, rays[i].y, a->bottom_radius_m))
            atmo_ref_ground_radiance(a, rays[i].x, rays[i].y, rays[i].z, rays[i].w, g);
        for (int ch = 0; ch < 3; ch++) {
            want[i][ch] = ss[ch] + g[ch];
            scale[ch] = fmax(scale[ch], want[i][ch]);
        }
    }
    probe(c, rays, n, sky, NULL);
    for (int i = 0; i < n; i++)
        for (int ch = 0; ch < 3; ch++)
            worst_top = fmax(worst_top, fabs(sky[i][ch] - want[i][ch]) / scale[ch]);
    CHECK(worst_top <= 0.01);
    printf("order 1 at 59 km: worst error %.2f %% of the brightest view\n", 100 * worst_top);
}

/* ---------------------------------------------------------------- 3: orders converge */

#define CONV_RAYS 160

static void conv_rays(const atmo_atmosphere *a, float4 *rays)
{
    static const double sun[] = {0, 45, 80, 90};
    int n = 0;
    for (int is = 0; is < 4; is++)
        for (int iv = 0; iv < 20; iv++)
            for (int iz = 0; iz < 2; iz++)
                rays[n++] = make_ray(a->bottom_radius_m + 1.7, 4.25 * iv, sun[is], 180.0 * iz);
}

/* radiance[k - 1] after k orders; checks and prints what each order adds */
static int check_convergence(const float4 *rays, float (*radiance)[CONV_RAYS][4], int orders)
{
    double sunset_blue[ORDERS + 1] = {0};
    for (int k = 2; k <= orders; k++)
        for (int i = 0; i < CONV_RAYS; i++)
            for (int ch = 0; ch < 3; ch++) {
                double total = radiance[k - 1][i][ch];
                double add = total - radiance[k - 2][i][ch];
                /* below 1e-6 of the total the difference of two float sums is rounding */
                CHECK(add > -1e-6 * total);
                if (k >= 3) {
                    double prev = radiance[k - 2][i][ch] - radiance[k - 3][i][ch];
                    if (prev > 1e-6 * total)
                        CHECK(add < prev);
                }
                if (ch == 2 && rays[i].z < 1e-6f)
                    sunset_blue[k] = fmax(sunset_blue[k], add / total);
            }
    int enough = orders;
    printf("largest share of order k in blue, sun on the horizon:");
    for (int k = 2; k <= orders; k++) {
        printf(" %d: %.2g", k, sunset_blue[k]);
        if (sunset_blue[k] < 1e-3 && enough == orders)
            enough = k - 1;
    }
    printf("\n%d orders leave < 0.1 %% to the next\n", enough);
    return enough;
}

/* ---------------------------------------------------------------- 4: horizon scan */

static void check_horizon(ctx *c, const atmo_atmosphere *a)
{
    enum { STEPS = 101 };
    static const double alt[] = {1.7, 10e3};
    static const double sun[] = {60, 85};
    double worst_ratio = 0.0;
    for (int ia = 0; ia < 2; ia++)
        for (int is = 0; is < 2; is++)
            for (int iz = 0; iz < 2; iz++) {
                double r = a->bottom_radius_m + alt[ia];
                double horizon = 90.0 + acos(a->bottom_radius_m / r) / DEG;
                float4 rays[STEPS];
                float sky[STEPS][4];
                for (int i = 0; i < STEPS; i++) /* 0.02-degree steps, horizon mid-step */
                    rays[i] = make_ray(r, horizon - 1.01 + 0.02 * i, sun[is], 180.0 * iz);
                probe(c, rays, STEPS, sky, NULL);
                int cross = STEPS / 2; /* the step from view cross - 1 to view cross */
                for (int ch = 0; ch < 3; ch++) {
                    double d[STEPS - 1];
                    for (int i = 0; i + 1 < STEPS; i++)
                        d[i] = fabs(sky[i + 1][ch] - sky[i][ch]);
                    /* every step but the true edge at most 3x its larger neighbour */
                    for (int i = 1; i + 2 < STEPS; i++) {
                        if (i == cross - 1 || i == cross - 2 || i == cross)
                            continue;
                        double nb = fmax(d[i - 1], d[i + 1]);
                        /* steps below 1e-4 of the radiance are invisible (8-bit output
                         * resolves 4e-3) and are where texel kinks dominate a flat sky */
                        double ratio = d[i] / fmax(nb, 1e-4 * sky[i][ch]);
                        if (ratio > 3.0)
                            fprintf(stderr, "horizon alt %.0f sun %.0f az %d ch %d view %.3f: "
                                    "step %.3g, neighbours %.3g %.3g\n", alt[ia], sun[is],
                                    180 * iz, ch, horizon - 1.01 + 0.02 * i, d[i], d[i - 1],
                                    d[i + 1]);
                        CHECK(ratio <= 3.0);
                        worst_ratio = fmax(worst_ratio, ratio);
                    }
                }
            }
    printf("horizon scans: largest step / larger neighbouring step %.2f\n", worst_ratio);
}

/* ---------------------------------------------------------------- 5: no NaN or Inf */

static void check_finite(ctx *c, const atmo_atmosphere *a)
{
    static const double alt[] = {0, 1, 100, 1e3, 1e4, 3e4, 6e4, 60000.5, 1e5, 1e6, 1e7, 1e8};
    static float4 rays[MAX_RAYS];
    static float sky[MAX_RAYS][4], sun[MAX_RAYS][4];
    int n = 0;
    for (int ia = 0; ia < 12; ia++)
        for (int is = 0; is <= 18; is++)
            for (int iv = 0; iv <= 19; iv++)
                for (int iz = 0; iz < 3; iz++) {
                    double r = a->bottom_radius_m + alt[ia];
                    double horizon = 90.0 + acos(a->bottom_radius_m / r) / DEG;
                    double view = iv == 19 ? horizon : 10.0 * iv; /* and the horizon itself */
                    rays[n++] = make_ray(r, view, 10.0 * is, 90.0 * iz);
                }
    probe(c, rays, n, sky, sun);
    int bad = 0;
    for (int i = 0; i < n; i++)
        for (int ch = 0; ch < 3; ch++)
            if (!isfinite(sky[i][ch]) || !isfinite(sun[i][ch]) || sky[i][ch] < 0.0f ||
                sun[i][ch] < 0.0f)
                bad++;
    CHECK(bad == 0);
    printf("no NaN, Inf or negative value: %d bad of %d rays (altitude 0..1e8 m, sun 0..180 deg)\n",
           bad, n);
}

/* ---------------------------------------------------------------- main */

/* ---------------------------------------------------------------- 6: Monte Carlo table */

static void check_reference(ctx *c, const atmo_atmosphere *a)
{
    const char *root = getenv("ATMO_SOURCE_DIR");
    char path[1024];
    snprintf(path, sizeof path, "%s/tests/data/reference_sky.csv", root ? root : "..");
    FILE *f = fopen(path, "r");
    if (!f) {
        printf("all orders vs Monte Carlo: %s not found, skipped\n", path);
        return;
    }
    static float4 rays[256];
    static double L[256][3], se[256][3], sun_zenith[256];
    static float sky[256][4];
    char line[1024];
    int n = 0;
    while (fgets(line, sizeof line, f) && n < 256) {
        double sz, vz, va, samples;
        if (line[0] == '#' ||
            sscanf(line, "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &sz, &vz, &va, &samples,
                   &L[n][0], &L[n][1], &L[n][2], &se[n][0], &se[n][1], &se[n][2]) != 10)
            continue; /* comments and the header */
        sun_zenith[n] = sz;
        rays[n++] = make_ray(a->bottom_radius_m, vz, sz, va); /* the sun at azimuth 0 */
    }
    fclose(f);
    CHECK(n > 0);
    probe(c, rays, n, sky, NULL);
    double worst_80 = 0.0, worst_90 = 0.0;
    for (int i = 0; i < n; i++)
        for (int ch = 0; ch < 3; ch++) {
            double rel = fabs(sky[i][ch] - L[i][ch]) / L[i][ch];
            if (sun_zenith[i] <= 80.0) {
                if (fabs(sky[i][ch] - L[i][ch]) > 0.02 * L[i][ch] + 3.0 * se[i][ch])
                    fprintf(stderr, "sun %.0f view mu %.4f nu %.4f ch %d: lut %.5g, MC %.5g +- "
                            "%.2g\n", sun_zenith[i], rays[i].y, rays[i].w, ch, sky[i][ch],
                            L[i][ch], se[i][ch]);
                CHECK(fabs(sky[i][ch] - L[i][ch]) <= 0.02 * L[i][ch] + 3.0 * se[i][ch]);
                worst_80 = fmax(worst_80, rel);
            } else {
                CHECK(fabs(sky[i][ch] - L[i][ch]) <= 0.05 * L[i][ch] + 3.0 * se[i][ch]);
                worst_90 = fmax(worst_90, rel);
            }
        }
    printf("all orders vs Monte Carlo (%d views at the ground): worst %.2f %% for sun zenith <= 80 "
           "deg, %.2f %% at 90 deg\n", n, 100 * worst_80, 100 * worst_90);
}

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void load_plan(ctx *c, const atmo_plan *plan)
{
    c->plan = plan;
    c->scene = test_cl_buffer(&c->cl, sizeof plan->gpu, &plan->gpu);
    for (int i = 0; i < ATMO_PLAN_MAX_BUFFERS; i++)
        c->luts[i] =
            i < plan->buffer_count
                ? test_cl_buffer(&c->cl, plan->buffers[i].bytes ? plan->buffers[i].bytes : 16, NULL)
                : NULL;
}

static void unload_plan(ctx *c)
{
    test_release_luts(c->luts);
    clReleaseMemObject(c->scene);
}

int main(int argc, char **argv)
{
    atmo_scene scene;
    static atmo_plan plan1, plan;
    test_scene_preset(&scene, "sky-noon");
    int default_orders = scene.atmosphere.lut_orders; /* the Monte Carlo check uses these */
    test_scene_set(&scene, "atmosphere.method=lut");
    test_scene_set(&scene, "lut.orders=1");
    for (int i = 1; i < argc; i++) /* other sizes, for exploring: key=value arguments */
        test_scene_set(&scene, argv[i]);
    test_plan(&scene, &plan1); /* order 1 at the default sizes */
    /* all orders with r and mu halved (precompute in seconds on 2 CPU cores) */
    test_scene_set(&scene, "lut.r_size=16");
    test_scene_set(&scene, "lut.mu_size=64");
    test_scene_set(&scene, "lut.orders=" ORDERS_TEXT);
    for (int i = 1; i < argc; i++)
        test_scene_set(&scene, argv[i]);
    test_plan(&scene, &plan);
    const atmo_atmosphere *a = &plan.atmosphere;

    test_parametrisation(&plan1.gpu.atmosphere, plan1.gpu.lut.dims);
    test_parametrisation(&plan.gpu.atmosphere, plan.gpu.lut.dims);

    ctx c;
    test_cl_open(&c.cl);
    c.prog = test_plan_program(&c.cl, &plan1, probe_src); /* the same program for both plans */

    load_plan(&c, &plan1);
    double t0 = seconds();
    run_pass(&c, &plan1.passes[0]); /* transmittance */
    run_pass(&c, &plan1.passes[1]); /* order 1 */
    printf("order 1 at %d x %d x %d x %d: precomputed in %.1f s\n", plan1.gpu.lut.dims[0],
           plan1.gpu.lut.dims[1], plan1.gpu.lut.dims[2], plan1.gpu.lut.dims[3],
           seconds() - t0);
    test_order1(&c, a, &plan1.gpu.atmosphere, plan1.gpu.lut.dims);
    unload_plan(&c);

    load_plan(&c, &plan);
    static float4 crays[CONV_RAYS];
    static float conv[ORDERS][CONV_RAYS][4];
    conv_rays(a, crays);
    t0 = seconds();
    run_pass(&c, &plan.passes[0]);
    run_pass(&c, &plan.passes[1]);
    probe(&c, crays, CONV_RAYS, conv[0], NULL);
    for (int k = 2; k <= ORDERS; k++) {
        for (int p = 0; p < 4; p++)
            run_pass(&c, &plan.passes[2 + 4 * (k - 2) + p]);
        probe(&c, crays, CONV_RAYS, conv[k - 1], NULL);
        if (k == default_orders)
            check_reference(&c, a);
    }
    printf("%d orders at %d x %d x %d x %d: precomputed in %.1f s\n", ORDERS,
           plan.gpu.lut.dims[0], plan.gpu.lut.dims[1], plan.gpu.lut.dims[2],
           plan.gpu.lut.dims[3], seconds() - t0);
    check_convergence(crays, conv, ORDERS);
    check_horizon(&c, a);
    check_finite(&c, a);
    unload_plan(&c);

    clReleaseProgram(c.prog);
    atmo_cl_close(&c.cl);
    return test_finish();
}
