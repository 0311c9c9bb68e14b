/* test_reference — the Monte Carlo reference method (kernels/atmosphere/method_reference.h) checked as an
 * estimator.
 * labels: kernel stat
 *
 * Oracles:
 *   1. order 1 (reference.min_order = max_order = 1) against atmo_ref_single_scattering plus
 *      atmo_ref_ground_radiance (double-precision adaptive quadrature, relative error 1e-9): a
 *      z-test per ray and channel with the estimator's own sample variance over N independent
 *      samples, |z| < 4 (a false alarm about once in 16 000 checks; the float-precision bias of
 *      the kernel, ~1e-5 relative, is far below the standard errors of ~0.5 %). Rays: cameras
 *      at the ground, 10 km and in space; sun zenith 0 to 95 deg (sunset and twilight); views
 *      up, toward, across and away from the sun, near the horizon and down onto the ground.
 *   2. 1/sqrt(N) convergence: on one ray the RMS error of 64 independent estimates against the
 *      oracle of 1 is measured for N = 16 ... 1024 samples; the fitted log-log slope must be
 *      -1/2 within 0.15 (the RMS of 64 estimates has a relative spread of 1/sqrt(128) = 9 %,
 *      which over a factor 64 in N gives a slope spread of about 0.03; a bias would flatten it).
 *   3. Transmittance: the ratio-tracking estimator media_walk_sun_transmittance (media_walk.h) against
 *      atmo_ref_transmittance (z-test, |z| < 4) on vertical, slanted and grazing rays, and
 *      against the closed form exp(-beta H (1 - e^{-Z/H})) of a vertical ray through a pure
 *      exponential Rayleigh atmosphere of thickness Z; and the sun disc output, W E / Omega_sun.
 *   4. Orders: all orders = order 1 + orders 2..inf within 4 combined standard errors, all
 *      orders > order 1 by more than 4 standard errors (multiple scattering adds 8-34 %,
 *      atmosphere.md), and no non-finite sample for cameras from 0 to 1e8 m and suns 0..180 deg. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "atmo/atmosphere_ref.h"
#include "testlib.h"
#include "testscene.h"

#define DEG (M_PI / 180.0)

static const char probe_src[] =
    "__kernel void probe(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                    __global const float4 *rays, __global float4 *sky,\n"
    "                    __global float4 *sun, uint n, uint per_ray) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  float4 q = rays[i / per_ray];\n"
    "  float3 a, b;\n"
    "  sky_radiance(s, ATMO_LUT_ARGS, q.x, q.y, q.z, q.w, i, 0u, &a, &b);\n"
    "  sky[i] = (float4)(a, 0.0f); sun[i] = (float4)(b, 0.0f);\n"
    "}\n"
    "__kernel void probe_t(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                      __global const float4 *rays,\n"
    "                      __global float4 *out, uint n, uint per_ray) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  float4 q = rays[i / per_ray];\n"
    "  rng_stream g = sky_probe_stream(s, i, 0u);\n"
    "  medium_point x;\n" /* the ray's start at radius q.x, toward cosine q.y */
    "  x.p = v3(0.0f, 0.0f, 0.0f); x.r = q.x; x.h = q.x - s->atmosphere.bottom_radius;\n"
    "  x.mu = q.y; x.mu_s = q.y;\n"
    "  out[i] = (float4)(media_walk_sun_transmittance(s, ATMO_LUT_ARGS, &x, MEDIA_WALK_SHADOW, &g), 0.0f);\n"
    "}\n";

typedef struct ctx {
    atmo_cl cl;
    cl_program prog;
    cl_mem scene, luts[ATMO_PLAN_MAX_BUFFERS];
} ctx;

/* per_ray samples of each ray (one work item each, pixel = item index): sky and sun. */
static void run_probe(ctx *c, const atmo_plan *p, const float4 *rays, int n_rays, int per_ray,
                      float4 *sky, float4 *sun)
{
    cl_int err;
    size_t n = (size_t)n_rays * (size_t)per_ray;
    clEnqueueWriteBuffer(c->cl.queue, c->scene, CL_TRUE, 0, sizeof p->gpu, &p->gpu, 0, NULL, NULL);
    cl_mem b_rays = test_cl_buffer(&c->cl, sizeof(float4) * (size_t)n_rays, rays);
    cl_mem b_sky = test_cl_buffer(&c->cl, sizeof(float4) * n, NULL);
    cl_mem b_sun = test_cl_buffer(&c->cl, sizeof(float4) * n, NULL);
    cl_kernel k = clCreateKernel(c->prog, "probe", &err);
    cl_uint count = (cl_uint)n, per = (cl_uint)per_ray;
    clSetKernelArg(k, 0, sizeof c->scene, &c->scene);
    int a = test_bind_buffers(k, c->luts);
    clSetKernelArg(k, a, sizeof b_rays, &b_rays);
    clSetKernelArg(k, a + 1, sizeof b_sky, &b_sky);
    clSetKernelArg(k, a + 2, sizeof b_sun, &b_sun);
    clSetKernelArg(k, a + 3, sizeof count, &count);
    clSetKernelArg(k, a + 4, sizeof per, &per);
    test_cl_run_1d(&c->cl, k, n);
    test_cl_read(&c->cl, b_sky, sizeof(float4) * n, sky);
    test_cl_read(&c->cl, b_sun, sizeof(float4) * n, sun);
    clReleaseKernel(k);
    clReleaseMemObject(b_sun);
    clReleaseMemObject(b_sky);
    clReleaseMemObject(b_rays);
}

static void run_transmittance(ctx *c, const atmo_plan *p, const float4 *rays, int n_rays,
                              int per_ray, float4 *out)
{
    cl_int err;
    size_t n = (size_t)n_rays * (size_t)per_ray;
    clEnqueueWriteBuffer(c->cl.queue, c->scene, CL_TRUE, 0, sizeof p->gpu, &p->gpu, 0, NULL, NULL);
    cl_mem b_rays = test_cl_buffer(&c->cl, sizeof(float4) * (size_t)n_rays, rays);
    cl_mem b_out = test_cl_buffer(&c->cl, sizeof(float4) * n, NULL);
    cl_kernel k = clCreateKernel(c->prog, "probe_t", &err);
    cl_uint count = (cl_uint)n, per = (cl_uint)per_ray;
    clSetKernelArg(k, 0, sizeof c->scene, &c->scene);
    int a = test_bind_buffers(k, c->luts);
    clSetKernelArg(k, a, sizeof b_rays, &b_rays);
    clSetKernelArg(k, a + 1, sizeof b_out, &b_out);
    clSetKernelArg(k, a + 2, sizeof count, &count);
    clSetKernelArg(k, a + 3, sizeof per, &per);
    test_cl_run_1d(&c->cl, k, n);
    test_cl_read(&c->cl, b_out, sizeof(float4) * n, out);
    clReleaseKernel(k);
    clReleaseMemObject(b_out);
    clReleaseMemObject(b_rays);
}

static float chan(const float4 *v, int c) { return c == 0 ? v->x : c == 1 ? v->y : v->z; }

/* Mean and standard error of the mean of channel c over samples [0, n) of one ray. */
static void mean_se(const float4 *v, int n, int c, double *mean, double *se)
{
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; i++)
        s += chan(&v[i], c);
    double m = s / n;
    for (int i = 0; i < n; i++)
        s2 += (chan(&v[i], c) - m) * (chan(&v[i], c) - m);
    *mean = m;
    *se = sqrt(s2 / (n - 1) / n);
}

static float4 make_ray(double r, double view_zenith_deg, double sun_zenith_deg, double azimuth_deg)
{
    double tv = view_zenith_deg * DEG, ts = sun_zenith_deg * DEG, pv = azimuth_deg * DEG;
    float4 q = {(float)r, (float)cos(tv), (float)cos(ts),
                (float)(sin(tv) * sin(ts) * cos(pv) + cos(tv) * cos(ts))};
    return q;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* 1. Order 1 against the double-precision single-scattering integral. */
static void test_order_one(ctx *c, const atmo_scene *base)
{
    enum { N = 4096 };
    static const double ray_def[][4] = {
        /* altitude m, view zenith, sun zenith, azimuth */
        {0, 0, 0, 0},       {0, 60, 30, 0},     {0, 85, 60, 180},   {0, 85, 80, 0},
        {0, 45, 88, 90},    {0, 80, 95, 0},     {1, 120, 40, 0},    {10e3, 90, 70, 0},
        {10e3, 100, 30, 90}, {1000e3, 176, 50, 0}, {0, 30, 45, 90},
    };
    int n = (int)(sizeof ray_def / sizeof ray_def[0]);
    atmo_scene s = *base;
    test_scene_set(&s, "reference.min_order=1");
    test_scene_set(&s, "reference.max_order=1");
    atmo_plan p;
    test_plan(&s, &p);
    float4 rays[16];
    for (int i = 0; i < n; i++)
        rays[i] = make_ray(p.atmosphere.bottom_radius_m + ray_def[i][0], ray_def[i][1],
                           ray_def[i][2], ray_def[i][3]);
    float4 *sky = malloc(sizeof(float4) * N * (size_t)n), *sun = malloc(sizeof(float4) * N * (size_t)n);
    run_probe(c, &p, rays, n, N, sky, sun);
    double worst_z = 0.0, worst_se = 0.0;
    for (int i = 0; i < n; i++) {
        double ss[3], g[3] = {0, 0, 0};
        atmo_ref_single_scattering(&p.atmosphere, rays[i].x, rays[i].y, rays[i].z, rays[i].w, ss);
        if (atmo_ref_ray_hits_ground(rays[i].x, rays[i].y, p.atmosphere.bottom_radius_m))
            atmo_ref_ground_radiance(&p.atmosphere, rays[i].x, rays[i].y, rays[i].z, rays[i].w, g);
        for (int ch = 0; ch < 3; ch++) {
            double want = ss[ch] + g[ch], mean, se;
            mean_se(sky + (size_t)i * N, N, ch, &mean, &se);
            double z = se > 0.0 ? (mean - want) / se : (mean == want ? 0.0 : 1e9);
            if (fabs(z) >= 4.0)
                fprintf(stderr, "order 1, ray %d (h=%.0f vz=%.0f sz=%.0f az=%.0f) ch %d: %.6e vs "
                                "%.6e (se %.2e, z %.2f)\n",
                        i, ray_def[i][0], ray_def[i][1], ray_def[i][2], ray_def[i][3], ch, mean,
                        want, se, z);
            CHECK(fabs(z) < 4.0);
            worst_z = fmax(worst_z, fabs(z));
            if (want > 0.0)
                worst_se = fmax(worst_se, se / want);
        }
    }
    printf("order 1 vs double single scattering: %d rays x 3 channels, N = %d, worst |z| = %.2f, "
           "worst relative standard error %.2e\n",
           n, N, worst_z, worst_se);
    free(sky);
    free(sun);
}

/* 2. The RMS error of independent estimates falls as N^-1/2. */
static void test_convergence(ctx *c, const atmo_scene *base)
{
    enum { GROUPS = 64, NMAX = 1024 };
    atmo_scene s = *base;
    test_scene_set(&s, "reference.min_order=1");
    test_scene_set(&s, "reference.max_order=1");
    atmo_plan p;
    test_plan(&s, &p);
    float4 ray = make_ray(p.atmosphere.bottom_radius_m, 70, 60, 180);
    double want[3];
    atmo_ref_single_scattering(&p.atmosphere, ray.x, ray.y, ray.z, ray.w, want);
    float4 *sky = malloc(sizeof(float4) * GROUPS * NMAX), *sun = malloc(sizeof(float4) * GROUPS * NMAX);
    run_probe(c, &p, &ray, 1, GROUPS * NMAX, sky, sun);
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int points = 0;
    printf("convergence (order 1, blue): N, RMS relative error:");
    for (int N = 16; N <= NMAX; N *= 4) {
        double mse = 0.0;
        for (int gi = 0; gi < GROUPS; gi++) {
            double m = 0.0;
            for (int k = 0; k < N; k++)
                m += sky[(size_t)gi * NMAX + (size_t)k].z;
            m /= N;
            mse += (m - want[2]) * (m - want[2]);
        }
        double rms = sqrt(mse / GROUPS) / want[2];
        printf(" %d %.3e", N, rms);
        double x = log((double)N), y = log(rms);
        sx += x, sy += y, sxx += x * x, sxy += x * y, points++;
    }
    double slope = (points * sxy - sx * sy) / (points * sxx - sx * sx);
    printf("; slope %.3f (want -0.5)\n", slope);
    CHECK_ABS(slope, -0.5, 0.15);
    free(sky);
    free(sun);
}

/* 3. Ratio-tracking transmittance and the sun disc. */
static void test_transmittance(ctx *c, const atmo_scene *base)
{
    enum { N = 4096 };
    atmo_plan p;
    test_plan(base, &p);
    double R = p.atmosphere.bottom_radius_m;
    float4 rays[4] = {make_ray(R, 0, 0, 0), make_ray(R, 75, 0, 0), make_ray(R + 5e3, 89.5, 0, 0),
                      make_ray(R + 20e3, 93, 0, 0)};
    float4 *t = malloc(sizeof(float4) * N * 4);
    run_transmittance(c, &p, rays, 4, N, t);
    double worst_z = 0.0;
    for (int i = 0; i < 4; i++) {
        double want[3];
        atmo_ref_transmittance(&p.atmosphere, rays[i].x, rays[i].y, want);
        for (int ch = 0; ch < 3; ch++) {
            double mean, se;
            mean_se(t + (size_t)i * N, N, ch, &mean, &se);
            double z = (mean - want[ch]) / fmax(se, 1e-30);
            if (fabs(z) >= 4.0)
                fprintf(stderr, "transmittance ray %d ch %d: %.6e vs %.6e (se %.2e)\n", i, ch,
                        mean, want[ch], se);
            CHECK(fabs(z) < 4.0);
            worst_z = fmax(worst_z, fabs(z));
        }
    }
    printf("ratio-tracking transmittance vs double reference: 4 rays, worst |z| = %.2f\n", worst_z);

    /* closed form: vertical ray through Rayleigh only */
    atmo_scene s = *base;
    test_scene_set(&s, "atmosphere.mie_extinction_per_m=0");
    test_scene_set(&s, "atmosphere.ozone_column_du=0");
    atmo_plan q;
    test_plan(&s, &q);
    run_transmittance(c, &q, rays, 1, N, t);
    double H = q.atmosphere.rayleigh_scale_height_m, Z = q.atmosphere.top_radius_m - R;
    for (int ch = 0; ch < 3; ch++) {
        double want = exp(-q.atmosphere.rayleigh_scattering_per_m[ch] * H * (1.0 - exp(-Z / H)));
        double mean, se;
        mean_se(t, N, ch, &mean, &se);
        printf("closed form vertical Rayleigh T[%d]: %.6f vs %.6f (se %.1e)\n", ch, mean, want, se);
        CHECK(fabs(mean - want) < 4.0 * se + 1e-6);
    }

    /* the sun disc: a ray at the sun sees E T / Omega_sun */
    atmo_scene d = *base;
    test_scene_set(&d, "sun.zenith_deg=60");
    atmo_plan pd;
    test_plan(&d, &pd);
    float4 at_sun = make_ray(R, 60, 60, 0);
    float4 *sky = malloc(sizeof(float4) * N), *sun = malloc(sizeof(float4) * N);
    run_probe(c, &pd, &at_sun, 1, N, sky, sun);
    double T[3];
    atmo_ref_transmittance(&pd.atmosphere, at_sun.x, at_sun.y, T);
    double omega = 2.0 * M_PI * (1.0 - cos(pd.atmosphere.sun_angular_radius_rad));
    for (int ch = 0; ch < 3; ch++) {
        double mean, se, want = pd.atmosphere.solar_irradiance[ch] * T[ch] / omega;
        mean_se(sun, N, ch, &mean, &se);
        CHECK(fabs(mean - want) < 4.0 * se + 1e-6 * want);
    }
    free(sky);
    free(sun);
    free(t);
}

/* 4. Order windows add up; multiple scattering adds light; nothing non-finite anywhere. */
static void test_orders(ctx *c, const atmo_scene *base)
{
    enum { N = 8192, RAYS = 3 };
    atmo_plan p1, p2, pa;
    atmo_scene s = *base;
    test_scene_set(&s, "reference.min_order=1");
    test_scene_set(&s, "reference.max_order=1");
    test_plan(&s, &p1);
    /* other seeds: the three estimates must be independent for the z-test of their sum */
    test_scene_set(&s, "reference.min_order=2");
    test_scene_set(&s, "reference.max_order=0");
    test_scene_set(&s, "image.seed=1");
    test_plan(&s, &p2);
    test_scene_set(&s, "reference.min_order=1");
    test_scene_set(&s, "image.seed=2");
    test_plan(&s, &pa);
    double R = pa.atmosphere.bottom_radius_m;
    float4 rays[RAYS] = {make_ray(R, 0, 30, 0), make_ray(R, 80, 70, 180), make_ray(R, 60, 89, 90)};
    static float4 o1[N * RAYS], o2[N * RAYS], oa[N * RAYS], sun[N * RAYS];
    run_probe(c, &p1, rays, RAYS, N, o1, sun);
    run_probe(c, &p2, rays, RAYS, N, o2, sun);
    double t0 = now();
    run_probe(c, &pa, rays, RAYS, N, oa, sun);
    double seconds = now() - t0;
    for (int i = 0; i < RAYS; i++)
        for (int ch = 0; ch < 3; ch++) {
            double m1, e1, m2, e2, ma, ea;
            mean_se(o1 + i * N, N, ch, &m1, &e1);
            mean_se(o2 + i * N, N, ch, &m2, &e2);
            mean_se(oa + i * N, N, ch, &ma, &ea);
            double z = (ma - m1 - m2) / sqrt(e1 * e1 + e2 * e2 + ea * ea);
            if (fabs(z) >= 4.0)
                fprintf(stderr, "orders ray %d ch %d: all %.5e, 1 %.5e, 2+ %.5e\n", i, ch, ma, m1,
                        m2);
            CHECK(fabs(z) < 4.0);
            CHECK(ma - m1 > 4.0 * sqrt(e1 * e1 + ea * ea));
            if (ch == 2 || ma - m1 <= 4.0 * sqrt(e1 * e1 + ea * ea))
                printf("ray %d channel %d: order 1 %.4e, orders 2+ %.4e (%.1f %% of all), all %.4e (se %.1e)\n", i,
                       ch, m1, m2, 100.0 * m2 / ma, ma, ea);
        }
    printf("all orders: %.1f us per sample (3 rays x %d samples, %.3f s, shared cores)\n",
           1e6 * seconds / (RAYS * N), N, seconds);

    /* stability: cameras from the ground to 1e8 m, suns up to 180 deg, views all around */
    enum { M = 16 };
    static float4 wide[7 * 5 * 5], out_sky[7 * 5 * 5 * M], out_sun[7 * 5 * 5 * M];
    static const double alt[] = {0, 1, 1e3, 59.9e3, 60.1e3, 1e6, 1e8};
    static const double sz[] = {0, 60, 90, 120, 180}, vz[] = {0, 89.9, 90.1, 135, 180};
    int n = 0;
    for (int a = 0; a < 7; a++)
        for (int b = 0; b < 5; b++)
            for (int v = 0; v < 5; v++)
                wide[n++] = make_ray(R + alt[a], vz[v], sz[b], 45);
    run_probe(c, &pa, wide, n, M, out_sky, out_sun);
    int bad = 0;
    for (int i = 0; i < n * M; i++)
        for (int ch = 0; ch < 3; ch++)
            bad += !isfinite(chan(&out_sky[i], ch)) || !isfinite(chan(&out_sun[i], ch)) ||
                   chan(&out_sky[i], ch) < 0.0f;
    CHECK(bad == 0);
}

int main(void)
{
    atmo_scene base;
    atmo_plan plan;
    test_scene_preset(&base, "sky-noon");
    test_scene_set(&base, "atmosphere.method=reference");
    test_plan(&base, &plan);
    ctx c;
    test_cl_open(&c.cl);
    c.prog = test_plan_program(&c.cl, &plan, probe_src);
    c.scene = test_cl_buffer(&c.cl, sizeof plan.gpu, &plan.gpu);
    test_precompute(&c.cl, c.prog, c.scene, &plan, c.luts);

    test_order_one(&c, &base);
    test_convergence(&c, &base);
    test_transmittance(&c, &base);
    test_orders(&c, &base);

    test_release_luts(c.luts);
    clReleaseMemObject(c.scene);
    clReleaseProgram(c.prog);
    atmo_cl_close(&c.cl);
    return test_finish();
}
