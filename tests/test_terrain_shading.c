/* test_terrain_shading — the terrain's surface light, materials, water and shadows
 * (kernels/terrain/terrain_shade.h, terrain_material.h, water.h, terrain.h).
 * labels: kernel
 *
 * Oracles:
 *  1. Fresnel reflectance of water (water_fresnel, float) against the closed form written with
 *     the angles of Snell's law in double, R = (sin^2(i - t) / sin^2(i + t) + tan^2(i - t) /
 *     tan^2(i + t)) / 2 (Born and Wolf 1.5.2), at incidences 0..89.9 degrees: bound 1e-6
 *     (float rounding of a quotient of sums, R <= 1), and its value at normal incidence
 *     ((eta - 1) / (eta + 1))^2.
 *  2. Material bands (terrain_material_weights) at chosen altitudes, slopes and detail against
 *     the values the formulas of terrain_material.h give by hand (grass only low and flat; rock
 *     only steep; dirt and rock half and half above the grass line with no detail; snow full
 *     above 3100 m on gentle slopes, half at 2800 m, none on steep faces), bound 1e-6, and the
 *     weights summing to 1 at 10^4 random inputs, bound 1e-6.
 *  3. The disc fraction: the visible fraction of the sun disc behind a straight edge, F(x),
 *     against a midpoint-rule area integral of the disc's chords in double (1e5 strips, error
 *     ~ 1e-7), bound 1e-6; and the exact shadow's Vogel points on the disc, N of them, counted
 *     on the visible side of the edge, against F(x): equal-area cells of size ~ 2/sqrt(N) disc
 *     radii, of which the edge crosses at most sqrt(N) + 1, so the count is off by at most
 *     (sqrt(N) + 1) / N.
 *  4. A flat patch (max height 1 mm, all land: grass, normal = vertical) under a sun 60
 *     degrees from the zenith: the device's terrain radiance against albedo / pi (E T_sun mu_s
 *     + E_sky), T_sun from the double-precision host reference (atmo_ref_sun_transmittance),
 *     E_sky the method's own sky irradiance (zero for single; march's Psi_ms irradiance from a
 *     probe of medium_ms_ground_irradiance): bound 2e-3 relative, the transmittance LUT's
 *     interpolation error at the ground (test_transmittance).
 *  5. Shadows: points 0.5 m above the thesis site's surface, the sun 6 degrees high; the
 *     device's exact shadow (16 rays to Vogel points of the sun disc) against the same 16
 *     directions marched in double (0.25 m steps over the first 10 m, where the ray leaves the
 *     point's own surface, then terrain_ref_hit within terrain.shadow_far_m): the fraction
 *     that escapes must be equal where every direction is clear-cut (a miss by more than 1 m
 *     beyond the first 10 m and 0.1 m within them, or a hit 0.5 m deep 50 m on); points in full
 *     shadow (0) and full light (1) must both occur. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/atmosphere_ref.h"
#include "atmo/terrain_ref.h"
#include "terrain/terrain.h"
#include "terrain/terrain_material.h"
#include "terrain/water.h"
#include "testlib.h"
#include "testscene.h"

static const char probe_src[] =
    "__kernel void flat(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                   __global const float4 *dir, __global float4 *out, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  medium_ray m = medium_ray_from_camera(s, dir[i].xyz);\n"
    "  float t = -1.0f;\n"
    "  if (!terrain_trace(s, heightmap, m.origin, m.dir, 0.0f, INFINITY, s->terrain.steps, &t, 0))\n"
    "    { out[2 * i] = (float4)(-1.0f); return; }\n"
    "  float3 L = terrain_radiance(s, ATMO_LUT_ARGS, &m, t);\n"
    "  float3 p = m.dir * t;\n"
    "  float mu_s = dot(terrain_vertical(s, p), s->sun_direction.xyz);\n"
    "  out[2 * i] = (float4)(L, t);\n"
    "  out[2 * i + 1] = (float4)(medium_ms_ground_irradiance(s, ATMO_LUT_ARGS, mu_s), mu_s);\n"
    "}\n"
    "__kernel void shadow(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                     __global const float4 *p, __global float *out, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  out[i] = terrain_sun_visible(s, heightmap, p[i].xyz, 0.0f);\n"
    "}\n";

#define SHADOW_RAYS 16
#define N_POINTS 150

static double urand(unsigned *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (*state >> 8) / 16777216.0;
}

static double fresnel_angles(double c, double eta)
{
    double i = acos(c), t = asin(sin(i) / eta);
    if (i < 1e-9)
        return pow((eta - 1) / (eta + 1), 2);
    double rs = pow(sin(i - t) / sin(i + t), 2), rp = pow(tan(i - t) / tan(i + t), 2);
    return 0.5 * (rs + rp);
}

static void host_checks(void)
{
    double worst = 0;
    for (int k = 0; k <= 899; k++) {
        double c = cos(k * 0.1 * M_PI / 180.0);
        double err = fabs(water_fresnel((float)c, WATER_INDEX) - fresnel_angles(c, 1.333));
        worst = fmax(worst, err);
        CHECK(err <= 1e-6);
    }
    CHECK_ABS(water_fresnel(1.0f, WATER_INDEX), pow(0.333 / 2.333, 2), 1e-7);
    printf("Fresnel: worst %.2g against the closed form, %.6f at normal incidence\n", worst,
           (double)water_fresnel(1.0f, WATER_INDEX));

    float w[TERRAIN_MATERIALS];
    terrain_material_weights(500.0f, 1.0f, 0.0f, w);
    CHECK_ABS(w[TERRAIN_GRASS], 1.0, 1e-6);
    terrain_material_weights(1500.0f, 0.5f, 0.3f, w);
    CHECK_ABS(w[TERRAIN_ROCK], 1.0, 1e-6);
    terrain_material_weights(1500.0f, 1.0f, 0.0f, w);
    CHECK_ABS(w[TERRAIN_DIRT], 0.5, 1e-6);
    CHECK_ABS(w[TERRAIN_ROCK], 0.5, 1e-6);
    terrain_material_weights(3500.0f, 1.0f, 0.0f, w);
    CHECK_ABS(w[TERRAIN_SNOW], 1.0, 1e-6);
    terrain_material_weights(2800.0f, 1.0f, 0.0f, w);
    CHECK_ABS(w[TERRAIN_SNOW], 0.5, 1e-6);
    terrain_material_weights(3500.0f, 0.5f, 0.0f, w);
    CHECK_ABS(w[TERRAIN_SNOW], 0.0, 1e-6);
    CHECK_ABS(w[TERRAIN_ROCK], 1.0, 1e-6);
    unsigned rng = 99u;
    double worst_sum = 0;
    for (int k = 0; k < 10000; k++) {
        terrain_material_weights((float)(4000 * urand(&rng)), (float)urand(&rng),
                                 (float)(2 * urand(&rng) - 1), w);
        double sum = 0;
        for (int m = 0; m < TERRAIN_MATERIALS; m++)
            sum += w[m];
        worst_sum = fmax(worst_sum, fabs(sum - 1));
    }
    CHECK(worst_sum <= 1e-6);

    double worst_f = 0;
    for (int k = -10; k <= 10; k++) {
        double x = k / 10.0, area = 0;
        int strips = 100000;
        for (int j = 0; j < strips; j++) { /* chords at a in [-x, 1]: the visible part */
            double a = -x + (1 + x) * (j + 0.5) / strips;
            area += 2 * sqrt(fmax(0, 1 - a * a)) * (1 + x) / strips;
        }
        worst_f = fmax(worst_f, fabs(terrain_disc_fraction((float)x) - area / M_PI));
    }
    CHECK(worst_f <= 1e-6);
    printf("disc fraction F(x): worst %.2g against the chord integral\n", worst_f);
    for (int n = 4; n <= 1024; n *= 4) {
        double worst_n = 0;
        for (int k = -20; k <= 20; k++) {
            double x = k / 20.0;
            int seen = 0;
            for (int j = 0; j < n; j++) {
                float a, b;
                terrain_disc_point(j, n, &a, &b);
                seen += a > -x;
            }
            worst_n = fmax(worst_n, fabs((double)seen / n - terrain_disc_fraction((float)x)));
        }
        double bound = (sqrt((double)n) + 1) / n;
        CHECK(worst_n <= bound);
        printf("  %4d Vogel points: straight-edge fraction off by at most %.4f (bound %.4f)\n", n,
               worst_n, bound);
    }
}

static void open_plan(atmo_plan *p, const char *method, const char *const *extra)
{
    atmo_scene s;
    char buf[64];
    test_scene_preset(&s, "sky-noon");
    snprintf(buf, sizeof buf, "atmosphere.method=%s", method);
    test_scene_set(&s, buf);
    test_scene_set(&s, "terrain.enabled=true");
    for (; *extra; extra++)
        test_scene_set(&s, *extra);
    test_plan(&s, p);
}

static void flat_patch(atmo_cl *cl, const char *method)
{
    static const char *const extra[] = {"terrain.max_height_m=0.001", "terrain.land_fraction=1",
                                        "camera.position_m=0,100,0", "sun.zenith_deg=60",
                                        "sun.azimuth_deg=30", NULL};
    atmo_plan p;
    open_plan(&p, method, extra);
    p.cache_luts = 2;
    cl_program prog = test_plan_program(cl, &p, probe_src);
    cl_int err;
    cl_mem scene = clCreateBuffer(cl->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                  sizeof p.gpu, &p.gpu, &err);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    test_precompute(cl, prog, scene, &p, luts);
    enum { N = 16 };
    float4 dir[N], out[2 * N];
    for (int i = 0; i < N; i++) {
        double mu = -0.3 - 0.6 * i / (N - 1.0), phi = 0.4 * i, s = sqrt(1 - mu * mu);
        dir[i].x = (float)(s * cos(phi)), dir[i].y = (float)mu, dir[i].z = (float)(s * sin(phi));
        dir[i].w = 0.0f;
    }
    cl_mem bd = test_cl_buffer(cl, sizeof dir, dir), bo = test_cl_buffer(cl, sizeof out, NULL);
    cl_kernel k = clCreateKernel(prog, "flat", &err);
    clSetKernelArg(k, 0, sizeof scene, &scene);
    int a = test_bind_buffers(k, luts);
    cl_uint n = N;
    clSetKernelArg(k, a++, sizeof bd, &bd);
    clSetKernelArg(k, a++, sizeof bo, &bo);
    clSetKernelArg(k, a++, sizeof n, &n);
    test_cl_run_1d(cl, k, N);
    test_cl_read(cl, bo, sizeof out, out);
    vec3 albedo = terrain_material_albedo(TERRAIN_GRASS);
    double alb[3] = {albedo.x, albedo.y, albedo.z}, worst = 0;
    for (int i = 0; i < N; i++) {
        CHECK(out[2 * i].w > 0.0f);
        double mu_s = out[2 * i + 1].w, T[3];
        /* the hit lies ~100 m / |mu| away: its sun cosine differs from the camera's by d / R */
        atmo_ref_sun_transmittance(&p.atmosphere, p.atmosphere.bottom_radius_m, mu_s, T);
        for (int c = 0; c < 3; c++) {
            double E = p.atmosphere.solar_irradiance[c], sky = (&out[2 * i + 1].x)[c];
            double want = alb[c] / M_PI * (E * T[c] * mu_s + sky);
            double got = (&out[2 * i].x)[c];
            worst = fmax(worst, fabs(got / want - 1));
            CHECK_REL(got, want, 2e-3);
        }
        if (strcmp(method, "single") == 0)
            CHECK(out[2 * i + 1].x == 0.0f);
        else
            CHECK(out[2 * i + 1].x > 0.0f);
    }
    printf("flat patch, method %-6s: radiance within %.2g of albedo/pi (E T_sun mu_s + E_sky)\n",
           method, worst);
    clReleaseKernel(k);
    clReleaseMemObject(bo);
    clReleaseMemObject(bd);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    clReleaseProgram(prog);
    atmo_plan_free(&p);
}

static void shadows(atmo_cl *cl)
{
    static const char *const extra[] = {"terrain.seed=46", "camera.position_m=23796,3000,16636",
                                        "sun.zenith_deg=84", "sun.azimuth_deg=-151",
                                        "terrain.shadow=exact", "terrain.shadow_rays=16",
                                        "terrain.shadow_far_m=20000", NULL};
    atmo_plan p;
    open_plan(&p, "single", extra);
    const atmo_gpu_terrain *tr = &p.gpu.terrain;
    double R = p.atmosphere.bottom_radius_m, cam[3] = {23796, 3000, 16636};
    float4 pts[N_POINTS];
    double world[N_POINTS][3];
    unsigned rng = 4242u;
    for (int i = 0; i < N_POINTS; i++) {
        double x = 23796 + (urand(&rng) - 0.5) * 6000, z = 16636 + (urand(&rng) - 0.5) * 6000;
        double h = terrain_ref_height(&tr->field, x, z, NULL, NULL) + 0.5;
        double n[3] = {x / R, sqrt(1 - (x * x + z * z) / (R * R)), z / R};
        for (int k = 0; k < 3; k++) {
            double w = n[k] * (R + h) - (k == 1 ? R : 0);
            float rel = (float)(w - cam[k]);
            (&pts[i].x)[k] = rel;
            world[i][k] = cam[k] + (double)rel;
        }
        pts[i].w = 0.0f;
    }
    cl_program prog = test_plan_program(cl, &p, probe_src);
    cl_int err;
    cl_mem scene = clCreateBuffer(cl->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                  sizeof p.gpu, &p.gpu, &err);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    test_precompute(cl, prog, scene, &p, luts);
    float vis[N_POINTS];
    cl_mem bp = test_cl_buffer(cl, sizeof pts, pts), bv = test_cl_buffer(cl, sizeof vis, NULL);
    cl_kernel k = clCreateKernel(prog, "shadow", &err);
    clSetKernelArg(k, 0, sizeof scene, &scene);
    int a = test_bind_buffers(k, luts);
    cl_uint n = N_POINTS;
    clSetKernelArg(k, a++, sizeof bp, &bp);
    clSetKernelArg(k, a++, sizeof bv, &bv);
    clSetKernelArg(k, a++, sizeof n, &n);
    test_cl_run_1d(cl, k, N_POINTS);
    test_cl_read(cl, bv, sizeof vis, vis);

    /* the kernel's 16 directions, in double from the float sun */
    double sun[3] = {p.gpu.sun_direction.x, p.gpu.sun_direction.y, p.gpu.sun_direction.z};
    double up[3] = {0, fabs(sun[1]) < 0.9 ? 1 : 0, fabs(sun[1]) < 0.9 ? 0 : 1}, e1[3], e2[3];
    if (up[1] == 0)
        up[0] = 1, up[2] = 0;
    e1[0] = sun[1] * up[2] - sun[2] * up[1];
    e1[1] = sun[2] * up[0] - sun[0] * up[2];
    e1[2] = sun[0] * up[1] - sun[1] * up[0];
    double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int c = 0; c < 3; c++)
        e1[c] /= l1;
    e2[0] = sun[1] * e1[2] - sun[2] * e1[1];
    e2[1] = sun[2] * e1[0] - sun[0] * e1[2];
    e2[2] = sun[0] * e1[1] - sun[1] * e1[0];
    double alpha = p.gpu.atmosphere.sun_angular_radius;
    int compared = 0, dark = 0, lit = 0, partial = 0, wrong = 0;
    for (int i = 0; i < N_POINTS; i++) {
        int escapes = 0, clear_cut = 1;
        for (int j = 0; j < SHADOW_RAYS && clear_cut; j++) {
            float fa, fb;
            terrain_disc_point(j, SHADOW_RAYS, &fa, &fb);
            double d[3], len = 0, t, mc = INFINITY;
            for (int c = 0; c < 3; c++)
                d[c] = sun[c] + alpha * (fa * e1[c] + fb * e2[c]), len += d[c] * d[c];
            for (int c = 0; c < 3; c++)
                d[c] /= sqrt(len);
            /* the first 10 m in 0.25 m steps (the ray leaves the point's own surface), then the
             * reference march from there */
            double o[3], near = INFINITY;
            for (int s = 1; s <= 40; s++) {
                double q[3];
                for (int c = 0; c < 3; c++)
                    q[c] = world[i][c] + 0.25 * s * d[c];
                near = fmin(near, terrain_ref_clearance(&tr->field, R, 0.0, q));
            }
            for (int c = 0; c < 3; c++)
                o[c] = world[i][c] + 10.0 * d[c];
            int hit = near <= 0.0 ||
                      terrain_ref_hit(&tr->field, R, 0.0, o, d, tr->shadow_far_m - 10.0, 5.0, &t,
                                      &mc);
            if (near <= 0.0) {
                clear_cut = near < -0.5;
            } else if (hit) {
                t += 10.0;
                double q[3];
                for (int c = 0; c < 3; c++)
                    q[c] = world[i][c] + (t + 50.0) * d[c];
                clear_cut = terrain_ref_clearance(&tr->field, R, 0.0, q) < -0.5;
            } else {
                clear_cut = mc > 1.0 && near > 0.1;
                escapes++;
            }
        }
        if (!clear_cut)
            continue;
        compared++;
        double want = (double)escapes / SHADOW_RAYS;
        dark += want == 0.0, lit += want == 1.0, partial += want > 0.0 && want < 1.0;
        if (vis[i] != (float)want) {
            wrong++;
            fprintf(stderr, "  point %d: visible %.4f, reference %.4f\n", i, vis[i], want);
        }
    }
    CHECK(wrong == 0);
    CHECK(dark > 0 && lit > 0);
    printf("shadows: %d of %d points clear-cut, %d dark, %d lit, %d partial; %d differ\n",
           compared, N_POINTS, dark, lit, partial, wrong);
    clReleaseKernel(k);
    clReleaseMemObject(bv);
    clReleaseMemObject(bp);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    clReleaseProgram(prog);
    atmo_plan_free(&p);
}

int main(void)
{
    host_checks();
    test_require_opencl();
    test_fresh_cache_dir();
    atmo_cl cl;
    test_cl_open(&cl);
    flat_patch(&cl, "single");
    flat_patch(&cl, "march");
    shadows(&cl);
    atmo_cl_close(&cl);
    return test_finish();
}
