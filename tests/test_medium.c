/* test_medium — the medium integrator (kernels/media/medium.h) on camera-relative 3-D segments,
 * the planet's shadow as a visibility source (kernels/media/visibility.h), and a cloud shell
 * the ray never meets.
 * labels: kernel
 *
 * Oracles:
 *  1. Segments between 3-D points (inside the atmosphere, far from the camera, starting at
 *     t0 > 0, crossing the top, ending at the ground) against the double-precision host
 *     reference (atmo_ref_single_scattering_to / _parts / _ground_radiance and
 *     atmo_ref_optical_depth_to: adaptive quadrature to 1e-9), with the segment's (r, mu, mu_s,
 *     nu) at its origin computed in double from the 3-D points. The kernel runs method single's
 *     configuration with 64 segments and 64 stratified sample offsets, as test_sky_single does
 *     for whole rays, whose worst error (0.09 %, rays toward a sun 85 degrees from the zenith)
 *     bounds the quadrature's and the transmittance LUT's error on any part of such a ray:
 *     bound 0.1 %. The view transmittance is the mean of 64 exp(-sum sigma_t dt), sums of 64
 *     samples of an optical depth below 1 with (i/n)^2 segments, whose quadrature error
 *     (second order in the segment length, ~ tau (dt/H)^2 / 24 over the segments that start
 *     below a scale height H) stays below 1e-4 for these rays: bound 2e-4.
 *  2. The sun's visibility from the planet at 3-D points against its closed form: with the
 *     planet centre C, the unit vector s toward the sun and oc = P - C, a point above the
 *     ground is lit iff not (oc . s < 0 and |oc - (oc . s) s| < R). Points on both sides of the
 *     shadow's edge within 20 m .. 2 km of it (near the terminator), up to 2000 km from the
 *     camera, and random points around the camera. Points within 20 m of the edge are left
 *     out: the kernel's radius and sun cosine carry float rounding of about 1 m at 6400 km
 *     (ray.h), which moves the edge by as much.
 *  3. A cloud shell the ray never meets changes nothing: methods single and march with a shell
 *     and an observer below a camera looking up (the view rays and the sun's paths from every
 *     sample rise, so neither ever meets the shell or the observer) equal the same plans
 *     without them to float rounding: a sum of view_steps terms with a few roundings each,
 *     bound 1e-5 relative. Control: rays down through the shell differ by more than 1 %. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/atmosphere_ref.h"
#include "testlib.h"
#include "testprobe.h"
#include "testscene.h"

#define JITTERS 64

static const char probe_src[] =
    "__kernel void segment(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                      __global const float4 *origin, __global const float4 *dir,\n"
    "                      __global float4 *L, __global float4 *T, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  medium_ray m = medium_ray_make(s, origin[i].xyz, dir[i].xyz);\n"
    "  float3 sl = (float3)(0.0f), st = (float3)(0.0f);\n"
    "  for (int j = 0; j < 64; j++) {\n"
    "    medium_result res;\n"
    "    medium_integrate(s, ATMO_LUT_ARGS, &m, origin[i].w, dir[i].w, s->view_steps,\n"
    "                     ((float)j + 0.5f) / 64.0f, 0, &res);\n"
    "    sl += medium_radiance(s, ATMO_LUT_ARGS, &res, m.nu);\n"
    "    st += res.view_t;\n"
    "  }\n"
    "  L[i] = (float4)(sl / 64.0f, 0.0f); T[i] = (float4)(st / 64.0f, 0.0f);\n"
    "}\n"
    "__kernel void sun_visibility(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                             __global const float4 *p, __global float *v, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  medium_ray m = medium_ray_make(s, p[i].xyz, (float3)(0.0f, 1.0f, 0.0f));\n"
    "  medium_point q = medium_ray_at(&m, 0.0f, s->atmosphere.bottom_radius);\n"
    "  v[i] = visibility_sun(s, ATMO_LUT_ARGS, &q).x;\n"
    "}\n";

typedef struct segment {
    double origin[3], dir[3], t0, t1;
    const char *what;
} segment;

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void normalise(double *v)
{
    double l = sqrt(dot3(v, v));
    for (int i = 0; i < 3; i++)
        v[i] /= l;
}

static void segment_tests(atmo_cl *cl)
{
    atmo_scene scene;
    atmo_plan plan;
    test_scene_preset(&scene, "sky-noon");
    test_scene_set(&scene, "atmosphere.method=single");
    test_scene_set(&scene, "render.view_steps=64");
    test_scene_set(&scene, "camera.position_m=0,1000,0");
    test_scene_set(&scene, "sun.zenith_deg=50");
    test_plan(&scene, &plan);
    const atmo_atmosphere *a = &plan.atmosphere;
    cl_program prog = test_plan_program(cl, &plan, probe_src);
    cl_mem b_scene = test_cl_buffer(cl, sizeof plan.gpu, &plan.gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    test_precompute(cl, prog, b_scene, &plan, luts);

    segment segs[] = {
        {{2000, 500, -1000}, {1, 0.3, 0.2}, 0, 20e3, "inside"},
        {{-30e3, 4000, 10e3}, {0.6, -0.05, -0.8}, 0, 60e3, "inside, grazing down"},
        {{150e3, 12e3, -80e3}, {-1, 0.05, 0.3}, 0, 100e3, "far from the camera"},
        {{0, 0, 0}, {0.3, 0.15, 0.9}, 5e3, 30e3, "from t0 = 5 km"},
        {{0, 3000, 0}, {0.2, 1, 0.1}, 0, 400e3, "crossing the top"},
        {{5000, 2000, 3000}, {0.5, -0.4, 0.1}, 0, INFINITY, "ending at the ground"},
        {{0, 0, 0}, {-0.7, -0.02, 0.3}, 0, INFINITY, "to the ground, grazing"},
    };
    enum { N = sizeof segs / sizeof segs[0] };
    float4 o[N], d[N], L[N], T[N];
    double sun[3], r_c = plan.gpu.camera.local_up.w;
    atmo_sun_direction(scene.sun.zenith_deg, scene.sun.azimuth_deg, sun);
    for (int i = 0; i < N; i++) {
        normalise(segs[i].dir);
        float4 oi = {(float)segs[i].origin[0], (float)segs[i].origin[1], (float)segs[i].origin[2],
                     (float)segs[i].t0};
        float4 di = {(float)segs[i].dir[0], (float)segs[i].dir[1], (float)segs[i].dir[2],
                     (float)segs[i].t1};
        o[i] = oi, d[i] = di;
    }
    cl_mem b_o = test_cl_buffer(cl, sizeof o, o), b_d = test_cl_buffer(cl, sizeof d, d);
    cl_mem b_l = test_cl_buffer(cl, sizeof L, NULL), b_t = test_cl_buffer(cl, sizeof T, NULL);
    cl_int err;
    cl_kernel k = clCreateKernel(prog, "segment", &err);
    CHECK(err == CL_SUCCESS);
    cl_uint n = N;
    CHECK(clSetKernelArg(k, 0, sizeof b_scene, &b_scene) == CL_SUCCESS);
    cl_uint arg = (cl_uint)test_bind_buffers(k, luts);
    CHECK(clSetKernelArg(k, arg, sizeof b_o, &b_o) == CL_SUCCESS);
    CHECK(clSetKernelArg(k, arg + 1, sizeof b_d, &b_d) == CL_SUCCESS);
    CHECK(clSetKernelArg(k, arg + 2, sizeof b_l, &b_l) == CL_SUCCESS);
    CHECK(clSetKernelArg(k, arg + 3, sizeof b_t, &b_t) == CL_SUCCESS);
    CHECK(clSetKernelArg(k, arg + 4, sizeof n, &n) == CL_SUCCESS);
    test_cl_run_1d(cl, k, N);
    test_cl_read(cl, b_l, sizeof L, L);
    test_cl_read(cl, b_t, sizeof T, T);

    double worst_l = 0.0, worst_t = 0.0;
    for (int i = 0; i < N; i++) {
        /* the segment's start in double: q = r_c up + origin + t0 dir, up = +Y here */
        double q[3], dir[3] = {d[i].x, d[i].y, d[i].z};
        for (int j = 0; j < 3; j++)
            q[j] = (double)(&o[i].x)[j] + (double)o[i].w * dir[j];
        q[1] += r_c;
        double r = sqrt(dot3(q, q)), mu = dot3(q, dir) / r, mu_s = dot3(q, sun) / r;
        double nu = dot3(dir, sun), len = (double)d[i].w - (double)o[i].w;
        double want[3], ground[3] = {0, 0, 0}, tau[3];
        if (isinf(len)) {
            atmo_ref_single_scattering(a, r, mu, mu_s, nu, want);
            atmo_ref_ground_radiance(a, r, mu, mu_s, nu, ground);
            atmo_ref_optical_depth(a, r, mu, tau);
        } else {
            atmo_ref_single_scattering_to(a, r, mu, mu_s, nu, len, want);
            atmo_ref_optical_depth_to(a, r, mu, len, tau);
        }
        double got[3] = {L[i].x, L[i].y, L[i].z}, got_t[3] = {T[i].x, T[i].y, T[i].z};
        for (int c = 0; c < 3; c++) {
            double w = want[c] + ground[c], wt = exp(-tau[c]);
            CHECK_REL(got[c], w, 1e-3);
            CHECK_REL(got_t[c], wt, 2e-4);
            worst_l = fmax(worst_l, fabs(got[c] / w - 1.0));
            worst_t = fmax(worst_t, fabs(got_t[c] / wt - 1.0));
        }
        printf("  %-24s r - R %8.1f m  mu %+.4f  L %.4e (ref %.4e)  T %.4f (ref %.4f)\n",
               segs[i].what, r - a->bottom_radius_m, mu, got[1], want[1] + ground[1], got_t[1],
               exp(-tau[1]));
    }
    printf("segments vs the double reference: worst relative error L %.2e, T %.2e\n", worst_l,
           worst_t);
    clReleaseKernel(k);
    clReleaseMemObject(b_t);
    clReleaseMemObject(b_l);
    clReleaseMemObject(b_d);
    clReleaseMemObject(b_o);
    test_release_luts(luts);
    clReleaseMemObject(b_scene);
    clReleaseProgram(prog);
    atmo_plan_free(&plan);
}

/* A uniform number in [0, 1) from a fixed 64-bit LCG (Knuth's MMIX constants). */
static double lcg(unsigned long long *x)
{
    *x = *x * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*x >> 11) * (1.0 / 9007199254740992.0);
}

#define VIS_POINTS 4000

static void visibility_tests(atmo_cl *cl)
{
    atmo_scene scene;
    atmo_plan plan;
    test_scene_preset(&scene, "sky-noon");
    test_scene_set(&scene, "atmosphere.method=single");
    test_scene_set(&scene, "camera.position_m=0,1000,0");
    test_scene_set(&scene, "sun.zenith_deg=90.5"); /* just above the horizon seen from 1 km */
    test_scene_set(&scene, "sun.azimuth_deg=30");
    test_plan(&scene, &plan);
    double R = plan.atmosphere.bottom_radius_m, r_c = plan.gpu.camera.local_up.w, sun[3];
    atmo_sun_direction(scene.sun.zenith_deg, scene.sun.azimuth_deg, sun);
    /* a unit basis (e1, e2) of the plane perpendicular to the sun */
    double e1[3] = {sun[1], -sun[0], 0.0}, e2[3];
    normalise(e1);
    e2[0] = sun[1] * e1[2] - sun[2] * e1[1];
    e2[1] = sun[2] * e1[0] - sun[0] * e1[2];
    e2[2] = sun[0] * e1[1] - sun[1] * e1[0];
    static float4 pts[VIS_POINTS];
    static int want[VIS_POINTS];
    static double edge[VIS_POINTS];
    unsigned long long x = 12345;
    int n = 0, near = 0;
    while (n < VIS_POINTS) {
        double oc[3];
        if (n % 2 == 0) { /* near the shadow's edge: radius R +- (20 m .. 2 km) from its axis */
            double b = -2000e3 * lcg(&x), phi = 2.0 * M_PI * lcg(&x);
            double rho = R + (lcg(&x) < 0.5 ? -1.0 : 1.0) * (20.0 + 1980.0 * lcg(&x));
            for (int j = 0; j < 3; j++)
                oc[j] = b * sun[j] + rho * (cos(phi) * e1[j] + sin(phi) * e2[j]);
        } else { /* around the camera, up to 300 km across and 100 km up */
            double u = lcg(&x), v = lcg(&x), w = lcg(&x);
            oc[0] = 600e3 * (u - 0.5), oc[1] = r_c - 5e3 + 105e3 * v, oc[2] = 600e3 * (w - 0.5);
        }
        double p[3] = {oc[0], oc[1] - r_c, oc[2]};
        if (dot3(oc, oc) <= (R + 1.0) * (R + 1.0) || sqrt(dot3(p, p)) > 2500e3)
            continue; /* underground, or too far */
        double b = dot3(oc, sun), perp[3];
        for (int j = 0; j < 3; j++)
            perp[j] = oc[j] - b * sun[j];
        double rho = sqrt(dot3(perp, perp));
        if (b < 0.0 && fabs(rho - R) < 20.0)
            continue;
        float4 q = {(float)p[0], (float)p[1], (float)p[2], 0.0f};
        pts[n] = q;
        want[n] = !(b < 0.0 && rho < R);
        edge[n] = b < 0.0 ? fabs(rho - R) : 1e30;
        near += edge[n] < 2000.0;
        n++;
    }
    cl_program prog = test_plan_program(cl, &plan, probe_src);
    cl_mem b_scene = test_cl_buffer(cl, sizeof plan.gpu, &plan.gpu);
    cl_mem b_p = test_cl_buffer(cl, sizeof pts, pts);
    cl_mem b_v = test_cl_buffer(cl, sizeof(float) * VIS_POINTS, NULL);
    cl_int err;
    cl_kernel k = clCreateKernel(prog, "sun_visibility", &err);
    CHECK(err == CL_SUCCESS);
    cl_uint count = VIS_POINTS;
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    test_precompute(cl, prog, b_scene, &plan, luts);
    CHECK(clSetKernelArg(k, 0, sizeof b_scene, &b_scene) == CL_SUCCESS);
    cl_uint arg = (cl_uint)test_bind_buffers(k, luts);
    CHECK(clSetKernelArg(k, arg, sizeof b_p, &b_p) == CL_SUCCESS);
    CHECK(clSetKernelArg(k, arg + 1, sizeof b_v, &b_v) == CL_SUCCESS);
    CHECK(clSetKernelArg(k, arg + 2, sizeof count, &count) == CL_SUCCESS);
    test_cl_run_1d(cl, k, VIS_POINTS);
    static float v[VIS_POINTS];
    test_cl_read(cl, b_v, sizeof v, v);
    int wrong = 0, lit = 0, dark = 0;
    double closest_wrong = 1e30;
    for (int i = 0; i < n; i++) {
        lit += want[i], dark += !want[i];
        if ((v[i] > 0.5f) != want[i]) {
            wrong++;
            closest_wrong = fmin(closest_wrong, edge[i]);
        }
    }
    printf("planet shadow: %d points (%d lit, %d shadowed, %d within 2 km of the edge): %d wrong",
           n, lit, dark, near, wrong);
    if (wrong)
        printf(" (nearest the edge %.1f m)", closest_wrong);
    printf("\n");
    CHECK(wrong == 0);
    CHECK(lit > VIS_POINTS / 5 && dark > VIS_POINTS / 5 && near > VIS_POINTS / 3);
    clReleaseKernel(k);
    clReleaseMemObject(b_v);
    clReleaseMemObject(b_p);
    test_release_luts(luts);
    clReleaseMemObject(b_scene);
    clReleaseProgram(prog);
    atmo_plan_free(&plan);
}

#define CLOUD_RAYS 16

static void cloud_plan(const char *method, int cloud, atmo_plan *p)
{
    atmo_scene s;
    char buf[64];
    test_scene_preset(&s, "sky-noon");
    snprintf(buf, sizeof buf, "atmosphere.method=%s", method);
    test_scene_set(&s, buf);
    test_scene_set(&s, "camera.position_m=0,2000,0");
    test_scene_set(&s, "sun.zenith_deg=30");
    if (cloud) {
        test_scene_set(&s, "cloud.enabled=true");
        test_scene_set(&s, "cloud.bottom_m=500");
        test_scene_set(&s, "cloud.top_m=1000");
        test_scene_set(&s, "observer.enabled=true");
        test_scene_set(&s, "observer.distance_m=100");
        test_scene_set(&s, "observer.height_m=-1500");
        test_scene_set(&s, "observer.radius_m=1");
    }
    test_plan(&s, p);
}

static void cloud_tests(atmo_cl *cl)
{
    const char *methods[] = {"single", "march"};
    for (int m = 0; m < 2; m++) {
        atmo_plan clear, cloudy;
        cloud_plan(methods[m], 0, &clear);
        cloud_plan(methods[m], 1, &cloudy);
        float4 rays[CLOUD_RAYS + 2];
        double mu_s = cos(30.0 * M_PI / 180.0), r = clear.gpu.camera.local_up.w;
        int n = 0;
        const double mus[] = {0.05, 0.2, 0.5, 0.8, 1.0}, cphi[] = {1.0, 0.0, -1.0};
        for (int i = 0; i < 5; i++)
            for (int j = 0; j < 3 && n < CLOUD_RAYS; j++) {
                double mu = mus[i];
                double nu = mu * mu_s + sqrt(1 - mu * mu) * sqrt(1 - mu_s * mu_s) * cphi[j];
                float4 q = {(float)r, (float)mu, (float)mu_s, (float)nu};
                rays[n++] = q;
            }
        int up = n;
        float4 down1 = {(float)r, -0.5f, (float)mu_s, (float)(-0.5 * mu_s)};
        float4 down2 = {(float)r, -0.9f, (float)mu_s, (float)(-0.9 * mu_s)};
        rays[n++] = down1, rays[n++] = down2;
        static double a_mean[CLOUD_RAYS + 2][3], b_mean[CLOUD_RAYS + 2][3];
        test_probe t;
        test_probe_open(&t, cl, &clear);
        test_probe_rays(&t, rays, n, 1, 4, TEST_PROBE_COMMON, a_mean, NULL, NULL, NULL);
        test_probe_close(&t);
        test_probe_open(&t, cl, &cloudy);
        test_probe_rays(&t, rays, n, 1, 4, TEST_PROBE_COMMON, b_mean, NULL, NULL, NULL);
        test_probe_close(&t);
        double worst = 0.0, control = 1e30;
        for (int i = 0; i < n; i++)
            for (int c = 0; c < 3; c++) {
                double rel = fabs(b_mean[i][c] / a_mean[i][c] - 1.0);
                if (i < up) {
                    CHECK_REL(b_mean[i][c], a_mean[i][c], 1e-5);
                    worst = fmax(worst, rel);
                } else {
                    control = fmin(control, rel);
                }
            }
        printf("%s: a shell and an observer the rays never meet change the sky by at most %.2e "
               "(relative); rays through the shell by at least %.2f\n",
               methods[m], worst, control);
        CHECK(control > 0.01);
        atmo_plan_free(&cloudy);
        atmo_plan_free(&clear);
    }
}

int main(void)
{
    atmo_cl cl;
    test_cl_open(&cl);
    segment_tests(&cl);
    visibility_tests(&cl);
    cloud_tests(&cl);
    atmo_cl_close(&cl);
    return test_finish();
}
