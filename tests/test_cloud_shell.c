/* test_cloud_shell — the cloud shell and observer (kernels/cloud_shell/cloud_shell.h, observer.h) in
 * the medium integrator (kernels/media/medium.h).
 * labels: kernel render
 * composes: atmosphere cloud visibility cloud_march medium
 *
 * Oracles:
 *  1. (host, the same header compiled as C, one octave = single scattering, atmosphere off)
 *     the closed form of single scattering by a homogeneous plane-parallel slab of optical
 *     thickness tau seen from above: L = omega p(theta) E mu_s / (mu_s + mu_v)
 *     (1 - e^{-tau (1/mu_s + 1/mu_v)}). The shell is a sphere of radius 6361 km; over the
 *     <= 3 km a ray crosses it, it departs from a plane by d^2 / (2R) <= 0.7 m of a 200 m slab,
 *     and the sun's slant path changes by as little, so the closed form holds to ~3e-3; the
 *     optical-depth steps integrate exactly for a slab, so the tolerance is 5e-3.
 *  2. (PoCL, preset glory; its cloud with stratus drops for the glory) the fog bow and the first
 *     glory ring in a radiance profile around the antisolar point at fixed view zenith lie where
 *     the uploaded Mie table (550 nm) has its maxima, within 0.5 degrees (the profile's 0.1-degree step plus the shift of a
 *     maximum by the smooth multiple-scattering octaves' slope);
 *  3. (PoCL, preset brocken) a ray toward where the observer's shadow axis meets the fog top
 *     is at most 0.3 of a ray 3 shadow radii away (geometry: the entry point's distance from
 *     the shadow axis), and a ray just outside the edge at least 0.6 of it;
 *  4. no NaN or Inf from camera heights below, inside, above the cloud and above the
 *     atmosphere for view cosines -1..1. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#define ATMO_CLOUD_OCTAVES 1
#include "kernels_composed.h"
#include "testlib.h"
#include "testscene.h"

/* the host build's buffer list (sky_method.h): the transmittance LUT, then the tables */
#define LUTS                                                                                       \
    lut, lut, lut, lut, lut, table, NULL, NULL, NULL, lut, NULL, NULL, NULL, NULL, NULL, NULL, NULL

static void slab_tests(void)
{
    atmo_gpu_scene s;
    memset(&s, 0, sizeof s);
    float4 lut[16], table[2];
    memset(lut, 0, sizeof lut); /* optical depth 0: the atmosphere is off */
    memset(table, 0, sizeof table);
    s.atmosphere.bottom_radius = 6360e3f;
    s.atmosphere.top_radius = 6420e3f;
    s.atmosphere.rayleigh_scale_height = 8000.0f;
    s.atmosphere.mie_scale_height = 1200.0f;
    s.atmosphere.solar_irradiance.x = s.atmosphere.solar_irradiance.y = 1.0f;
    s.atmosphere.solar_irradiance.z = 1.0f;
    s.transmittance_width = s.transmittance_height = 4;
    s.sun_direction.w = cosf(0.0047f);
    s.camera.local_up.y = 1.0f;
    s.cloud.steps = 32;
    s.cloud.phase = ATMO_CLOUD_PHASE_HG; /* so the oracle's phase is exact */
    s.cloud.g.x = 0.5f, s.cloud.g.y = 0.8f, s.cloud.g.z = -0.3f;
    s.cloud.albedo.x = s.cloud.albedo.y = s.cloud.albedo.z = 0.99f;
    s.cloud.base_m = 1000.0f, s.cloud.top_m = 1200.0f;
    const double taus[] = {0.05, 1.0, 30.0}, mu_ss[] = {0.9, 0.4}, mu_vs[] = {1.0, 0.6};
    double worst = 0.0;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 2; b++)
            for (int c = 0; c < 2; c++) {
                double tau = taus[a], mu_s = mu_ss[b], mu_v = mu_vs[c];
                float sigma = (float)(tau / 200.0);
                s.cloud.extinction.x = s.cloud.extinction.y = s.cloud.extinction.z = sigma;
                double phi = 2.0; /* azimuth between view and sun, radians */
                double nu = -mu_v * mu_s + sqrt(1 - mu_v * mu_v) * sqrt(1 - mu_s * mu_s) * cos(phi);
                float r = 6360e3f + 1300.0f;
                s.camera.local_up.w = r;
                s.sun_direction.x = (float)sqrt(1 - mu_s * mu_s), s.sun_direction.y = (float)mu_s;
                medium_ray m =
                    medium_ray_from_cosines(&s, r, (float)-mu_v, (float)mu_s, (float)nu);
                medium_result res;
                medium_integrate(&s, LUTS, &m, 0.0f, INFINITY, 8, 0.5f, 0, &res);
                vec3 sky = medium_radiance(&s, LUTS, &res, (float)nu);
                double want[3], got[3] = {sky.x, sky.y, sky.z}, g[3] = {0.5, 0.8, -0.3};
                for (int k = 0; k < 3; k++) {
                    double p = (1 - g[k] * g[k]) /
                               (4 * M_PI * pow(1 + g[k] * g[k] - 2 * g[k] * nu, 1.5));
                    want[k] = 0.99 * p * mu_s / (mu_s + mu_v) *
                              (1 - exp(-tau * (1 / mu_s + 1 / mu_v)));
                    CHECK_REL(got[k], want[k], 5e-3);
                    worst = fmax(worst, fabs(got[k] / want[k] - 1));
                }
            }
    printf("slab single scattering vs closed form: worst relative error %.2e\n", worst);
}

/* The plan's program with its -D flags (test_plan_program builds without them, and the cloud
 * code exists only under -DATMO_CLOUD). */
static cl_program build_plan(atmo_cl *cl, const atmo_plan *plan)
{
    const char *texts[ATMO_PLAN_MAX_FRAGMENTS];
    atmo_plan_fragment_texts(plan, texts);
    atmo_cl_build_options bo = {plan->fragments, plan->fragment_count, plan->defines, NULL, 1, NULL,
                                plan->prelude, texts};
    atmo_cl_build_info bi;
    atmo_err e;
    cl_program prog = NULL;
    if (atmo_cl_build(cl, &bo, &prog, &bi, &e)) {
        fprintf(stderr, "build: %s\n", e.msg);
        exit(1);
    }
    return prog;
}

static cl_mem probe_rays(atmo_cl *cl, cl_program prog, const atmo_plan *plan, const float4 *rays,
                         int n, int samples, float4 *out)
{
    cl_mem b_scene = test_cl_buffer(cl, sizeof plan->gpu, &plan->gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    test_precompute(cl, prog, b_scene, plan, luts);
    cl_mem b_rays = test_cl_buffer(cl, sizeof(float4) * (size_t)n, rays);
    cl_mem b_out = test_cl_buffer(cl, sizeof(float4) * (size_t)n, NULL);
    cl_int err;
    cl_kernel k = clCreateKernel(prog, "sky_probe", &err);
    uint count = (uint)n, ns = (uint)samples;
    clSetKernelArg(k, 0, sizeof b_scene, &b_scene);
    int a = test_bind_buffers(k, luts);
    clSetKernelArg(k, a, sizeof b_rays, &b_rays);
    clSetKernelArg(k, a + 1, sizeof b_out, &b_out);
    clSetKernelArg(k, a + 2, sizeof count, &count);
    clSetKernelArg(k, a + 3, sizeof ns, &ns);
    test_cl_run_1d(cl, k, (size_t)n);
    test_cl_read(cl, b_out, sizeof(float4) * (size_t)n, out);
    clReleaseKernel(k);
    clReleaseMemObject(b_out);
    clReleaseMemObject(b_rays);
    test_release_luts(luts);
    clReleaseMemObject(b_scene);
    return NULL;
}

/* argmax of f over theta in [lo, hi] (degrees) on the grid theta_i = i * step */
static double argmax(const double *f, double step, double lo, double hi)
{
    int best = -1;
    for (int i = (int)ceil(lo / step); i * step <= hi; i++)
        if (best < 0 || f[i] > f[best])
            best = i;
    return best * step;
}

#define STEP 0.1
#define NTH 1800

/* The radiance profile L (550 nm) around the antisolar point at its view zenith, 125..180 deg
 * from the sun, and the plan's Mie table P (550 nm) at the same angles, interpolated as the
 * kernel does. */
static void antisolar_profile(atmo_cl *cl, const atmo_scene *scene, double *L, double *P)
{
    atmo_plan plan;
    test_plan(scene, &plan);
    cl_program prog = build_plan(cl, &plan);
    const float4 *rows = atmo_plan_buffer_find(&plan, "cloud_phase_table")->host_data;
    int nrows = plan.gpu.cloud.table_size;
    double mu_s = cos(scene->sun.zenith_deg * M_PI / 180), mu = -mu_s;
    static float4 rays[NTH], out[NTH];
    int first = (int)(125.0 / STEP);
    for (int i = 0; i < NTH; i++) {
        double th = fmin(i * STEP, 179.95);
        float4 q = {plan.gpu.camera.local_up.w, (float)mu, (float)mu_s, (float)cos(th * M_PI / 180)};
        rays[i] = q;
        double t = th * M_PI / 180;
        int j = 0;
        while (j < nrows - 2 && rows[j + 1].w <= t)
            j++;
        double f = (t - rows[j].w) / (rows[j + 1].w - rows[j].w);
        P[i] = rows[j].y + f * (rows[j + 1].y - rows[j].y);
    }
    probe_rays(cl, prog, &plan, rays + first, NTH - first, 2, out + first);
    for (int i = 0; i < NTH; i++)
        L[i] = i >= first ? out[i].y : 0.0;
    clReleaseProgram(prog);
    atmo_plan_free(&plan);
}

static void glory_tests(atmo_cl *cl)
{
    atmo_scene scene;
    atmo_plan plan;
    static double L[NTH], P[NTH];
    /* the fog bow: preset glory (thesis-disperse drops) */
    test_scene_preset(&scene, "glory");
    antisolar_profile(cl, &scene, L, P);
    double bow_p = argmax(P, STEP, 130, 160), bow_l = argmax(L, STEP, 130, 160);
    /* the glory ring: that distribution's table rises steadily toward 180 deg once the sun's
     * disc smooths it (its one ring lies within 1 deg of the antisolar point), so the ring is
     * taken from stratus drops, whose first ring peaks near 177.5 deg at 550 nm; the maximum
     * must lie inside the window, not at its edge */
    test_scene_set(&scene, "cloud.dsd=stratus");
    antisolar_profile(cl, &scene, L, P);
    double gl_p = argmax(P, STEP, 172, 179), gl_l = argmax(L, STEP, 172, 179);
    printf("fog bow (glory preset): table %.1f deg, render %.1f deg; first glory ring (stratus): "
           "table %.1f, render %.1f\n",
           bow_p, bow_l, gl_p, gl_l);
    CHECK_ABS(bow_l, bow_p, 0.5);
    CHECK(gl_p > 172.0 + STEP && gl_p < 179.0 - STEP);
    CHECK_ABS(gl_l, gl_p, 0.5);

    test_scene_preset(&scene, "glory");
    test_plan(&scene, &plan);
    cl_program prog = build_plan(cl, &plan);
    /* no NaN or Inf: camera below, inside, above the cloud, above the atmosphere */
    const float heights[] = {1.7f, 999.0f, 1500.0f, 2000.5f, 3000.0f, 7e4f, 1e7f};
    static float4 sweep[7 * 41 * 3];
    int n = 0;
    for (int h = 0; h < 7; h++)
        for (int m = 0; m <= 40; m++)
            for (int c = 0; c < 3; c++) {
                float mv = -1.0f + 0.05f * (float)m, ms = (float)(c - 1) * 0.7f;
                float nu = mv * ms + sqrtf(fmaxf(1 - mv * mv, 0.0f)) *
                                         sqrtf(1 - ms * ms) * (float)(c - 1);
                float4 q = {6360e3f + heights[h], mv, ms, nu};
                sweep[n++] = q;
            }
    static float4 res[7 * 41 * 3];
    probe_rays(cl, prog, &plan, sweep, n, 1, res);
    int bad = 0;
    for (int i = 0; i < n; i++)
        if (!(isfinite(res[i].x) && isfinite(res[i].y) && isfinite(res[i].z) && res[i].x >= 0) &&
            bad++ < 5)
            fprintf(stderr, "  non-finite: r %.1f mu %g mu_s %g nu %g -> %g %g %g\n",
                    sweep[i].x, sweep[i].y, sweep[i].z, sweep[i].w, res[i].x, res[i].y, res[i].z);
    CHECK(bad == 0);
    clReleaseProgram(prog);
    atmo_plan_free(&plan);
}

static void brocken_tests(atmo_cl *cl)
{
    atmo_scene scene;
    atmo_plan plan;
    test_scene_preset(&scene, "brocken");
    test_plan(&scene, &plan);
    cl_program prog = build_plan(cl, &plan);
    double mu_s = cos(scene.sun.zenith_deg * M_PI / 180), sin_s = sqrt(1 - mu_s * mu_s);
    double c[2] = {-scene.observer.distance_m, scene.observer.height_m}, R = scene.observer.radius_m;
    double drop = scene.camera.position_m[1] - scene.cloud.top_m;
    /* in the sun plane (x toward the sun, y up): the ray at elevation e below the horizon,
     * away from the sun, meets the fog top at p; distance of p from the shadow axis */
    double e_axis = 0, best = 1e9;
    for (double e = 1; e < 60; e += 0.001) {
        double v[2] = {-cos(e * M_PI / 180), -sin(e * M_PI / 180)}, t = drop / -v[1];
        double p[2] = {v[0] * t - c[0], v[1] * t - c[1]};
        double along = -(p[0] * sin_s + p[1] * mu_s);
        double d = hypot(p[0] + along * sin_s, p[1] + along * mu_s);
        if (d < best)
            best = d, e_axis = e;
    }
    double t_axis = drop / sin(e_axis * M_PI / 180), edge = R / t_axis * 180 / M_PI;
    const double offs[] = {0.0, 1.5 * edge, 3.0 * edge};
    float4 rays[3], out[3];
    for (int i = 0; i < 3; i++) {
        double e = (e_axis + offs[i]) * M_PI / 180;
        double v[2] = {-cos(e), -sin(e)};
        float4 q = {plan.gpu.camera.local_up.w, (float)v[1], (float)mu_s,
                    (float)(v[0] * sin_s + v[1] * mu_s)};
        rays[i] = q;
    }
    probe_rays(cl, prog, &plan, rays, 3, 8, out);
    printf("observer shadow: axis at %.2f deg below the horizon, radius %.2f deg; radiance "
           "centre %.4g, 1.5 radii %.4g, 3 radii %.4g\n",
           e_axis, edge, out[0].y, out[1].y, out[2].y);
    CHECK(out[0].y < 0.3f * out[2].y);
    CHECK(out[1].y > 0.6f * out[2].y);
    clReleaseProgram(prog);
    atmo_plan_free(&plan);
}

int main(void)
{
    slab_tests();
    atmo_cl cl;
    test_cl_open(&cl);
    glory_tests(&cl);
    brocken_tests(&cl);
    atmo_cl_close(&cl);
    return test_finish();
}
