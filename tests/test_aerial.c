/* test_aerial — aerial perspective: every method's sky_segment (kernels/atmosphere/sky_method.h), the light
 * in-scattered toward the camera by the air before a black surface at distance d, and the
 * transmittance T(0, d), run through the sky_probe_segment kernel (atmo_probe_segments: 64
 * batches, whose spread gives each value's standard error SE).
 * labels: kernel slow
 *
 * Oracles and tolerances:
 * 1. Definition: a segment longer than its ray (d = 1e9 m) is the ray's sky radiance. The same
 *    random numbers reach both kernels, so reference, single, march and lut must agree to float
 *    rounding (1e-6 relative), and fast's segment (march's integrator with fast's Psi_ms LUT) with
 *    march's sky radiance. Cameras from the ground to 1e7 m, views up, grazing and down.
 * 2. Transmittance against exp(-atmo_ref_optical_depth_to) (double adaptive quadrature, 1e-11):
 *    the marching methods (single, march, fast, and lut where d ends in the air) multiply
 *    e^{-sigma(t_i) dt} at one random point per segment, an unbiased estimate of the optical
 *    depth whose mean over samples converges on T (Jensen's bias, Var(tau_hat) / 2, is of order
 *    1e-5 for 32 segments); allowed: 4 SE + float error. The float error: altitudes along a ray are
 *    rounded to about 0.5 m at 6.4e6 m, so the aerosol density e^{-h/1200 m} is off by up to
 *    4e-4 relative, and tau (hence T relatively) by 4e-4 tau; plus 32 rounded products, 1e-5:
 *    |dT| <= 4 SE + (4e-4 tau + 1e-5) T. Reference (ratio tracking, unbiased): |dT| <= 4 SE +
 *    1e-5 T. lut where d reaches the ray's end (its transmittance LUT, target 1e-3 relative
 *    where T > 1e-2): 1e-3 T.
 * 3. Single scattering over [0, d] (method single) against atmo_ref_single_scattering_to (plus
 *    atmo_ref_ground_radiance where d reaches the ground; double quadrature, 1e-9): within 1 %
 *    (the target for the single-scattering sky, test_sky_single's, which a segment meets with the
 *    same or shorter steps) + 4 SE. Sun zenith <= 80 deg, as in test_sky_single (a point sun's
 *    shadow boundary is a step the march places to one segment).
 * 4. The reference's black surface: orders 1 only (reference.max_order = 1) against the same
 *    double integral, a z-test |z| < 4 per ray and channel with its own SE (float bias ~1e-5,
 *    far below the SE). Cameras at the ground, 10 km and 100 km (above the atmosphere: d counts
 *    from the camera, the ray enters at the top).
 * 5. All orders against the stored Monte Carlo table tests/data/reference_segments.csv
 *    (tools/make_segment_table.py: the reference method, cameras at the ground and 10 km, sun
 *    zenith 0-90 deg, d = 1, 10, 100 km, standard error 0.3 % where 4 rounds got there, 0.74 % at
 *    worst; skipped, and said so, where the file is missing), each method's error within the
 *    methods' accuracy target plus 3 standard errors (the table's and the method's combined): lut
 *    2 % for sun zenith <= 80 deg and 5 % at 90 deg; march and fast 3 % and 5 % from 10 km. From
 *    the ground march and fast meet the daytime target (measured 2.7 %) but not the one with the
 *    sun on the horizon: their Psi_ms source (ms_lut.h: orders >= 2 with an approximate angular
 *    shape) is off by a few % in the air next to the ground at twilight, which a whole ray
 *    averages away (they meet the targets for the sky) but a 1-10 km segment does not: measured
 *    5.3 % at 90 deg (how it got there: docs/notes/ms_lut.md); asserted here as a measured bound,
 *    5.5 % + 3 SE, so that it cannot silently get worse -- not as a target met. (From 10 km:
 *    0.85 % and 0.92 %.)
 * 6. The horizon: lut segments for views scanned across the horizon in 0.005 deg steps (+-0.3
 *    deg) from 1 km and 10 km with d = 10 and 50 km (segments that end in the air on both sides,
 *    so the radiance is continuous there), all with the same random offsets (pixel 0): every
 *    step is at most 3 times the larger of its neighbours or 1e-4 of the radiance, as
 *    test_lut_method's horizon scan asks of the sky. The known failures of Bruneton's
 *    two-lookup difference S(x, v) - T(x, y) S(y, v) (method_lut.h) are probed on the same
 *    tables: it must show a band in the same scans and miss the 2 % target by more than 10 %
 *    on some 1 km ray of the table, or the reason given for the march is gone.
 * 7. No NaN, Inf, negative radiance or T outside [0, 1] for any method: cameras 0 .. 1e7 m, sun
 *    zenith 0 .. 180 deg, views 0 .. 180 deg and the horizon, d from 1 m to 1e9 m.
 * lut runs at reduced sizes (r 16, mu 64, mu_s 24, 5 orders, 32 steps per texel ray: precomputed
 * in about 10 s), which
 * measured within 2.3 % of the table (sun zenith <= 80 deg; 2.1 % at the default sizes). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "atmo/atmosphere_ref.h"
#include "atmo/probe.h"
#include "testlib.h"
#include "testscene.h"

#define DEG (M_PI / 180.0)
#define MAX_RAYS 4096
#define TABLE_ROWS 256

typedef struct seg_ray {
    double alt, view_zenith, sun_zenith, azimuth, d;
} seg_ray;

typedef struct method {
    const char *name;
    atmo_plan plan;
    atmo_probe probe;
} method;

typedef struct result {
    double L[MAX_RAYS][3], L_se[MAX_RAYS][3], T[MAX_RAYS][3], T_se[MAX_RAYS][3];
} result;

static const char scan_src[] =
    /* sky_segment with the random offsets of pixel 0 for every ray (common random numbers) */
    "__kernel void scan_segment(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                           __global const float4 *rays, __global const float *dist,\n"
    "                           __global float4 *out, uint n, uint samples) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  float4 q = rays[i]; float3 sum = (float3)(0.0f);\n"
    "  for (uint k = 0; k < samples; k++) {\n"
    "    float3 l, t;\n"
    "    sky_segment(s, ATMO_LUT_ARGS, q.x, q.y, q.z, q.w, dist[i], 0u, k, &l, &t);\n"
    "    sum += l;\n"
    "  }\n"
    "  out[i] = (float4)(sum / (float)samples, 0.0f);\n"
    "}\n"
    /* Bruneton's two-lookup difference on the lut tables, both lookups on the camera ray's
     * side of the horizon (cameras inside the atmosphere only) */
    "__kernel void naive_segment(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                            __global const float4 *rays, __global const float *dist,\n"
    "                            __global float4 *out, uint n, uint samples) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  __global const atmo_gpu_atmosphere *a = &s->atmosphere;\n"
    "  float r = rays[i].x, mu = rays[i].y, mu_s = rays[i].z, nu = rays[i].w, d = dist[i];\n"
    "  int ground = geometry_ray_hits_ground(r, mu, a->bottom_radius);\n"
    "  float d_end = ground ? geometry_distance_to_bottom(r, mu, a->bottom_radius)\n"
    "                       : geometry_distance_to_top(r, mu, a->top_radius);\n"
    "  float3 L, T;\n"
    "  if (d >= d_end) {\n"
    "    L = lut_sky(s, ATMO_LUT_ARGS, r, mu, mu_s, nu, ground, &T);\n"
    "  } else {\n"
    "    float r_d = geometry_radius_at(r, mu, d);\n"
    "    float mu_d = atmo_clamp_cos((r * mu + d) / r_d);\n"
    "    float mu_s_d = atmo_clamp_cos((r * mu_s + d * nu) / r_d);\n"
    "    T = lut_transmittance_between(s, transmittance_lut, r, mu, r_d, mu_d, ground);\n"
    "    L = max(lut_scattered(s, scattering_rayleigh, scattering_mie, r, mu, mu_s, nu, ground) -\n"
    "            T * lut_scattered(s, scattering_rayleigh, scattering_mie, r_d, mu_d, mu_s_d, nu, "
    "ground), 0.0f);\n"
    "  }\n"
    "  out[i] = (float4)(L, 0.0f);\n"
    "}\n";

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void open_method(method *m, const char *name, const char *const *sets)
{
    atmo_scene s;
    atmo_err e;
    char buf[64];
    test_scene_preset(&s, "sky-noon");
    snprintf(buf, sizeof buf, "atmosphere.method=%s", name);
    test_scene_set(&s, buf);
    for (int i = 0; sets && sets[i]; i++)
        test_scene_set(&s, sets[i]);
    test_plan(&s, &m->plan);
    m->name = name;
    memset(&m->probe, 0, sizeof m->probe);
    double t0 = now();
    if (atmo_probe_open(&m->probe, &m->plan, NULL, &e)) {
        fprintf(stderr, "%s: %s\n", name, e.msg);
        exit(1);
    }
    printf("%s: built and precomputed in %.1f s\n", name, now() - t0);
}

static float4 make_ray(double R, const seg_ray *q)
{
    double tv = q->view_zenith * DEG, ts = q->sun_zenith * DEG, pv = q->azimuth * DEG;
    float4 v = {(float)(R + q->alt), (float)cos(tv), (float)cos(ts),
                (float)(sin(tv) * sin(ts) * cos(pv) + cos(tv) * cos(ts))};
    return v;
}

static void segments(method *m, const seg_ray *q, int n, int samples, result *out)
{
    static float4 rays[MAX_RAYS];
    static float dist[MAX_RAYS];
    atmo_err e;
    double R = m->plan.atmosphere.bottom_radius_m;
    for (int i = 0; i < n; i++)
        rays[i] = make_ray(R, &q[i]), dist[i] = (float)q[i].d;
    if (atmo_probe_segments(&m->probe, rays, dist, n, samples, out->L, out->L_se, out->T,
                            out->T_se, &e)) {
        fprintf(stderr, "%s: %s\n", m->name, e.msg);
        exit(1);
    }
}

/* The double-precision quantities of a ray, at the float values the kernel sees. */
static void reference_values(const atmo_atmosphere *a, const seg_ray *q, double tau[3],
                             double single[3])
{
    float4 v = make_ray(a->bottom_radius_m, q);
    double r = v.x, mu = v.y, mu_s = v.z, nu = v.w, d = (double)(float)q->d;
    double ground[3] = {0.0, 0.0, 0.0};
    atmo_ref_optical_depth_to(a, r, mu, d, tau);
    atmo_ref_single_scattering_to(a, r, mu, mu_s, nu, d, single);
    if (atmo_ref_ray_hits_ground(r, mu, a->bottom_radius_m) &&
        d >= atmo_ref_distance_to_bottom(r, mu, a->bottom_radius_m)) /* the lit ground shows */
        atmo_ref_ground_radiance(a, r, mu, mu_s, nu, ground);
    for (int c = 0; c < 3; c++)
        single[c] += ground[c];
}

/* ------------------------------------------------------------------ 1: definition */

static void check_definition(method *ms[], int count, method *march)
{
    static seg_ray q[MAX_RAYS];
    static float4 rays[MAX_RAYS];
    static double sky[MAX_RAYS][3];
    static result seg;
    static const double alts[] = {0.0, 1e3, 1e4, 1e5, 1e7};
    static const double views[] = {0, 60, 89, 90.5, 95, 120, 180};
    int n = 0;
    for (int ia = 0; ia < 5; ia++)
        for (int iv = 0; iv < 7; iv++)
            for (int is = 0; is < 3; is++) {
                seg_ray r = {alts[ia], views[iv], 45.0 * is, 60.0, 1e9};
                q[n++] = r;
            }
    for (int k = 0; k < count; k++) {
        method *m = ms[k], *sky_of = strcmp(m->name, "fast") == 0 ? march : m;
        atmo_err e;
        for (int i = 0; i < n; i++)
            rays[i] = make_ray(m->plan.atmosphere.bottom_radius_m, &q[i]);
        int samples = strcmp(m->name, "reference") == 0 ? 256 : 64;
        if (atmo_probe_rays(&sky_of->probe, rays, n, samples, sky, NULL, &e)) {
            fprintf(stderr, "%s: %s\n", sky_of->name, e.msg);
            exit(1);
        }
        segments(m, q, n, samples, &seg);
        double worst = 0.0;
        for (int i = 0; i < n; i++)
            for (int c = 0; c < 3; c++) {
                double diff = fabs(seg.L[i][c] - sky[i][c]);
                CHECK(diff <= 1e-6 * sky[i][c] + 1e-30);
                if (sky[i][c] > 0.0)
                    worst = fmax(worst, diff / sky[i][c]);
            }
        printf("1. %-9s segment beyond the ray's end = %s's sky radiance: worst %.1e relative "
               "(%d rays)\n", m->name, sky_of->name, worst, n);
    }
}

/* ------------------------------------------------------------------ the rays of 2, 3 and 5 */

static int table_rays(seg_ray *q)
{
    static const double alts[] = {0.0, 1e4}, suns[] = {0, 45, 80, 90}, ds[] = {1e3, 1e4, 1e5};
    static const double views[][2] = {{0, 0}, {60, 0}, {85, 0}, {85, 180}, {100, 90}};
    int n = 0;
    for (int ia = 0; ia < 2; ia++)
        for (int is = 0; is < 4; is++)
            for (int id = 0; id < 3; id++)
                for (int iv = 0; iv < 5; iv++) {
                    if (ia == 0 && views[iv][0] > 90.0)
                        continue;
                    seg_ray r = {alts[ia], views[iv][0], suns[is], views[iv][1], ds[id]};
                    q[n++] = r;
                }
    return n;
}

/* ------------------------------------------------------------------ 2 and 3 */

static void check_transmittance(const atmo_atmosphere *a, const char *name, const seg_ray *q,
                                int n, const result *res, int lut)
{
    double worst = 0.0, worst_z = 0.0;
    for (int i = 0; i < n; i++) {
        double tau[3], single[3];
        reference_values(a, &q[i], tau, single);
        float4 v = make_ray(a->bottom_radius_m, &q[i]);
        int ground = atmo_ref_ray_hits_ground(v.x, v.y, a->bottom_radius_m);
        double end = ground ? atmo_ref_distance_to_bottom(v.x, v.y, a->bottom_radius_m)
                            : atmo_ref_distance_to_top(v.x, v.y, a->top_radius_m);
        int whole = q[i].d >= end;
        for (int c = 0; c < 3; c++) {
            double T = exp(-tau[c]), got = res->T[i][c], se = res->T_se[i][c], tol;
            if (strcmp(name, "reference") == 0)
                tol = 4.0 * se + 1e-5 * T;
            else if (lut && whole)
                tol = 1e-3 * T;
            else
                tol = 4.0 * se + (4e-4 * tau[c] + 1e-5) * T;
            if (fabs(got - T) > tol)
                fprintf(stderr, "%s T alt %g view %g,%g d %g ch %d: %.6f, want %.6f +- %.1e\n",
                        name, q[i].alt, q[i].view_zenith, q[i].azimuth, q[i].d, c, got, T, tol);
            CHECK(fabs(got - T) <= tol);
            worst = fmax(worst, fabs(got / T - 1.0));
            if (se > 0.0)
                worst_z = fmax(worst_z, fabs(got - T) / se);
        }
    }
    printf("2. %-9s T(0, d) vs double: worst %.1e relative, %.1f SE\n", name, worst, worst_z);
}

static void check_single(const atmo_atmosphere *a, const seg_ray *q, int n, const result *res)
{
    double worst = 0.0;
    for (int i = 0; i < n; i++) {
        if (q[i].sun_zenith > 80.0)
            continue;
        double tau[3], want[3];
        reference_values(a, &q[i], tau, want);
        for (int c = 0; c < 3; c++) {
            double got = res->L[i][c], tol = 0.01 * want[c] + 4.0 * res->L_se[i][c];
            if (fabs(got - want[c]) > tol)
                fprintf(stderr, "single alt %g sun %g view %g,%g d %g ch %d: %.5g, want %.5g\n",
                        q[i].alt, q[i].sun_zenith, q[i].view_zenith, q[i].azimuth, q[i].d, c,
                        got, want[c]);
            CHECK(fabs(got - want[c]) <= tol);
            worst = fmax(worst, fabs(got / want[c] - 1.0));
        }
    }
    printf("3. single    in-scattering over [0, d] vs double: worst %.2f %%\n", 100.0 * worst);
}

/* ------------------------------------------------------------------ 4 */

static void check_reference_order1(void)
{
    static const char *const sets[] = {"reference.max_order=1", NULL};
    static method m;
    static seg_ray q[MAX_RAYS];
    static result res;
    static const double alts[] = {0.0, 1e4, 1e5}, ds[] = {1e3, 3e4, 1e5};
    static const double views[][2] = {{0, 0}, {60, 0}, {85, 180}, {100, 90}, {120, 0}};
    int n = 0;
    for (int ia = 0; ia < 3; ia++)
        for (int iv = 0; iv < 5; iv++)
            for (int id = 0; id < 3; id++) {
                if (ia == 0 && views[iv][0] > 90.0)
                    continue;
                double d = ia == 2 ? ds[id] + 4e4 : ds[id]; /* from 100 km: 40 km to the top */
                seg_ray r = {alts[ia], views[iv][0], 30.0, views[iv][1], d};
                q[n++] = r;
            }
    open_method(&m, "reference", sets);
    const atmo_atmosphere *a = &m.plan.atmosphere;
    segments(&m, q, n, 16384, &res);
    double worst_z = 0.0;
    for (int i = 0; i < n; i++) {
        double tau[3], want[3];
        reference_values(a, &q[i], tau, want);
        for (int c = 0; c < 3; c++) {
            double se = res.L_se[i][c], z = se > 0.0 ? (res.L[i][c] - want[c]) / se
                                                     : (res.L[i][c] == want[c] ? 0.0 : 1e9);
            if (fabs(z) >= 4.0)
                fprintf(stderr, "reference order 1 alt %g view %g,%g d %g ch %d: %.5g +- %.2g, "
                        "want %.5g\n", q[i].alt, q[i].view_zenith, q[i].azimuth, q[i].d, c,
                        res.L[i][c], se, want[c]);
            CHECK(fabs(z) < 4.0);
            worst_z = fmax(worst_z, fabs(z));
        }
    }
    printf("4. reference order 1 over [0, d] vs double: worst |z| %.2f (%d rays)\n", worst_z, n);
    atmo_probe_close(&m.probe);
}

/* ------------------------------------------------------------------ 5 */

typedef struct table_row {
    seg_ray q;
    double L[3], se[3];
} table_row;

static int read_table(table_row *rows)
{
    const char *root = getenv("ATMO_SOURCE_DIR");
    char path[1024], line[1024];
    snprintf(path, sizeof path, "%s/tests/data/reference_segments.csv", root ? root : "..");
    FILE *f = fopen(path, "r");
    if (!f) {
        printf("5. all orders vs Monte Carlo: %s not found, skipped\n", path);
        return 0;
    }
    int n = 0;
    while (fgets(line, sizeof line, f) && n < TABLE_ROWS) {
        table_row *t = &rows[n];
        double samples;
        if (line[0] == '#' ||
            sscanf(line, "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &t->q.alt,
                   &t->q.sun_zenith, &t->q.view_zenith, &t->q.azimuth, &t->q.d, &samples,
                   &t->L[0], &t->L[1], &t->L[2], &t->se[0], &t->se[1], &t->se[2]) != 12)
            continue; /* comments and the header */
        n++;
    }
    fclose(f);
    return n;
}

/* Over the rows with a camera at altitude `alt` (all rows where alt < 0): asserts |error| <=
 * tol(sun) + 3 SE (tol80 for sun zenith <= 80 deg, tol90 at 90), SE the table's and the
 * method's combined, and prints the worst relative errors. */
static void table_check(const char *name, const table_row *rows, int n, const result *res,
                        double alt, double tol80, double tol90)
{
    double margin[2] = {-1.0, -1.0}, worst[2] = {0.0, 0.0};
    int count = 0;
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            if (alt >= 0.0 && rows[i].q.alt != alt)
                continue;
            count += c == 0;
            int low = rows[i].q.sun_zenith > 80.0;
            double L = rows[i].L[c], rel = fabs(res->L[i][c] / L - 1.0);
            double se = hypot(rows[i].se[c], res->L_se[i][c]) / L;
            margin[low] = fmax(margin[low], rel - (low ? tol90 : tol80) - 3.0 * se);
            if (rel - (low ? tol90 : tol80) - 3.0 * se > 0.0)
                fprintf(stderr, "%s alt %g sun %g view %g,%g d %g ch %d: %+.2f %% (3 SE %.2f %%)\n",
                        name, rows[i].q.alt, rows[i].q.sun_zenith, rows[i].q.view_zenith,
                        rows[i].q.azimuth, rows[i].q.d, c, 100.0 * (res->L[i][c] / L - 1.0),
                        300.0 * se);
            worst[low] = fmax(worst[low], rel);
        }
    CHECK(margin[0] <= 0.0);
    CHECK(margin[1] <= 0.0);
    printf("5. %-9s all orders vs Monte Carlo, %d segments from %s: worst %.2f %% for sun zenith "
           "<= 80 deg, %.2f %% at 90 deg (allowed %.1f %% and %.1f %% + 3 SE)\n", name, count,
           alt < 0.0 ? "both cameras" : alt == 0.0 ? "the ground" : "10 km", 100.0 * worst[0],
           100.0 * worst[1], 100.0 * tol80, 100.0 * tol90);
}

/* ------------------------------------------------------------------ 6 */

static void run_scan_kernel(method *lut, cl_program prog, const char *name, const float4 *rays,
                            const float *dist, int n, float (*out)[4])
{
    atmo_cl *cl = atmo_session_cl(lut->probe.session);
    atmo_err e;
    cl_int err;
    cl_mem b_rays = test_cl_buffer(cl, sizeof(float4) * (size_t)n, rays);
    cl_mem b_dist = test_cl_buffer(cl, sizeof(float) * (size_t)n, dist);
    cl_mem b_out = test_cl_buffer(cl, sizeof(float4) * (size_t)n, NULL);
    cl_kernel k = clCreateKernel(prog, name, &err);
    cl_uint count = (cl_uint)n, samples = 64;
    CHECK(err == CL_SUCCESS);
    cl_uint arg = 0;
    CHECK(atmo_session_bind(lut->probe.session, k, &arg, &e) == ATMO_OK &&
          arg == 1 + (cl_uint)atmo_session_plan(lut->probe.session)->buffer_count);
    clSetKernelArg(k, arg, sizeof b_rays, &b_rays);
    clSetKernelArg(k, arg + 1, sizeof b_dist, &b_dist);
    clSetKernelArg(k, arg + 2, sizeof b_out, &b_out);
    clSetKernelArg(k, arg + 3, sizeof count, &count);
    clSetKernelArg(k, arg + 4, sizeof samples, &samples);
    test_cl_run_1d(cl, k, (size_t)n);
    test_cl_read(cl, b_out, sizeof(float4) * (size_t)n, out);
    clReleaseKernel(k);
    clReleaseMemObject(b_out);
    clReleaseMemObject(b_dist);
    clReleaseMemObject(b_rays);
}

#define SCAN 121
#define SCANS 16

/* Largest step / max(larger neighbouring step, 1e-4 L) over the scans. */
static double scan_ratio(float (*L)[4], int report, const char *name)
{
    double worst = 0.0;
    for (int s = 0; s < SCANS; s++)
        for (int c = 0; c < 3; c++) {
            float (*v)[4] = L + s * SCAN;
            for (int i = 1; i + 2 < SCAN; i++) {
                double step = fabs(v[i + 1][c] - v[i][c]);
                double nb = fmax(fabs(v[i][c] - v[i - 1][c]), fabs(v[i + 2][c] - v[i + 1][c]));
                double ratio = step / fmax(nb, 1e-4 * v[i][c]);
                if (report && ratio > 3.0)
                    fprintf(stderr, "%s: scan %d ch %d step %d: %.3g, neighbours %.3g\n", name, s,
                            c, i, step, nb);
                worst = fmax(worst, ratio);
            }
        }
    return worst;
}

static void check_horizon(method *lut, cl_program prog)
{
    static float4 rays[SCANS * SCAN];
    static float dist[SCANS * SCAN], L[SCANS * SCAN][4], naive[SCANS * SCAN][4];
    const atmo_atmosphere *a = &lut->plan.atmosphere;
    static const double alts[] = {1e3, 1e4}, ds[] = {1e4, 5e4}, suns[] = {30, 80};
    int n = 0;
    for (int ia = 0; ia < 2; ia++)
        for (int id = 0; id < 2; id++)
            for (int is = 0; is < 2; is++)
                for (int iz = 0; iz < 2; iz++) {
                    double R = a->bottom_radius_m, r = R + alts[ia];
                    double horizon = 90.0 + acos(R / r) / DEG;
                    for (int i = 0; i < SCAN; i++) {
                        seg_ray q = {alts[ia], horizon - 0.3 + 0.005 * i, suns[is], 180.0 * iz,
                                     ds[id]};
                        rays[n] = make_ray(R, &q), dist[n++] = (float)ds[id];
                    }
                }
    run_scan_kernel(lut, prog, "scan_segment", rays, dist, n, L);
    run_scan_kernel(lut, prog, "naive_segment", rays, dist, n, naive);
    double worst = scan_ratio(L, 1, "lut segment"), worst_naive = scan_ratio(naive, 0, "");
    CHECK(worst <= 3.0);
    CHECK(worst_naive > 3.0);
    printf("6. lut across the horizon: largest step / larger neighbouring step %.2f (the "
           "two-lookup difference: %.1f)\n", worst, worst_naive);
}

/* The two-lookup difference against the Monte Carlo table at 1 km. */
static void check_naive_short(method *lut, cl_program prog, const table_row *rows, int n)
{
    static float4 rays[TABLE_ROWS];
    static float dist[TABLE_ROWS], naive[TABLE_ROWS][4];
    for (int i = 0; i < n; i++)
        rays[i] = make_ray(lut->plan.atmosphere.bottom_radius_m, &rows[i].q),
        dist[i] = (float)rows[i].q.d;
    run_scan_kernel(lut, prog, "naive_segment", rays, dist, n, naive);
    double worst = 0.0;
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            if (rows[i].q.d == 1e3 && rows[i].q.sun_zenith <= 80.0)
                worst = fmax(worst, fabs(naive[i][c] / rows[i].L[c] - 1.0));
    CHECK(worst > 0.10);
    printf("6. the two-lookup difference at 1 km (sun zenith <= 80): worst %.0f %% off the "
           "Monte Carlo table\n", 100.0 * worst);
}

/* ------------------------------------------------------------------ 7 */

static void check_finite(method *ms[], int count)
{
    static seg_ray q[MAX_RAYS];
    static result res;
    static const double alts[] = {0, 1, 1e3, 1e4, 6e4, 1e5, 1e7}, ds[] = {1, 1e3, 1e5, 1e9};
    int n = 0;
    for (int ia = 0; ia < 7; ia++)
        for (int is = 0; is <= 6; is++)
            for (int iv = 0; iv <= 13; iv++)
                for (int id = 0; id < 4; id++) {
                    double r = 6360e3 + alts[ia];
                    double view = iv == 13 ? 90.0 + acos(6360e3 / r) / DEG : 15.0 * iv;
                    seg_ray s = {alts[ia], view, 30.0 * is, 90.0 * (id % 3), ds[id]};
                    q[n++] = s;
                }
    for (int k = 0; k < count; k++) {
        segments(ms[k], q, n, 64, &res);
        int bad = 0;
        for (int i = 0; i < n; i++)
            for (int c = 0; c < 3; c++)
                bad += !isfinite(res.L[i][c]) || res.L[i][c] < 0.0 || !isfinite(res.T[i][c]) ||
                       res.T[i][c] < 0.0 || res.T[i][c] > 1.0 + 1e-6;
        CHECK(bad == 0);
        printf("7. %-9s no NaN, Inf, negative radiance or T outside [0, 1]: %d bad of %d rays\n",
               ms[k]->name, bad, n);
    }
}

/* ------------------------------------------------------------------ main */

int main(void)
{
    test_require_opencl();
    static const char *const lut_sets[] = {"lut.r_size=16", "lut.mu_size=64", "lut.mu_s_size=24",
                                           "lut.orders=5", "lut.steps=32", NULL};
    static method ref, lut, march, single, fast;
    open_method(&ref, "reference", NULL);
    open_method(&single, "single", NULL);
    open_method(&march, "march", NULL);
    open_method(&fast, "fast", NULL);
    open_method(&lut, "lut", lut_sets);
    const atmo_atmosphere *a = &ref.plan.atmosphere;
    method *all[5] = {&ref, &single, &march, &fast, &lut};

    check_definition(all, 5, &march);

    static seg_ray q[MAX_RAYS];
    static result res;
    int n = table_rays(q);
    for (int k = 0; k < 5; k++) {
        int samples = k == 0 ? 4096 : k == 1 ? 1024 : 64;
        segments(all[k], q, n, samples, &res);
        check_transmittance(a, all[k]->name, q, n, &res, all[k] == &lut);
        if (all[k] == &single)
            check_single(a, q, n, &res);
    }

    check_reference_order1();

    static table_row rows[TABLE_ROWS];
    int n_rows = read_table(rows);
    if (n_rows > 0) {
        static seg_ray tq[TABLE_ROWS];
        for (int i = 0; i < n_rows; i++)
            tq[i] = rows[i].q;
        for (int k = 2; k < 5; k++) {
            segments(all[k], tq, n_rows, all[k] == &lut ? 256 : 1024, &res);
            if (all[k] == &lut) {
                table_check("lut", rows, n_rows, &res, -1.0, 0.02, 0.05);
            } else { /* the targets from 10 km; from the ground, the measured bound at 90 deg */
                table_check(all[k]->name, rows, n_rows, &res, 1e4, 0.03, 0.05);
                table_check(all[k]->name, rows, n_rows, &res, 0.0, 0.03, 0.055);
            }
        }
    }

    cl_program prog = test_plan_program(atmo_session_cl(lut.probe.session), &lut.plan, scan_src);
    check_horizon(&lut, prog);
    if (n_rows > 0)
        check_naive_short(&lut, prog, rows, n_rows);
    clReleaseProgram(prog);

    check_finite(all, 5);

    for (int k = 4; k >= 0; k--)
        atmo_probe_close(&all[k]->probe);
    return test_finish();
}
