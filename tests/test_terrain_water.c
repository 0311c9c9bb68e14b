/* test_terrain_water — the sea reflects the method's sky in the mirror direction
 * (kernels/terrain/terrain_stage.h, terrain_stage_water_sky).
 * labels: kernel
 *
 * Scene: a planet covered by sea (terrain.land_fraction=0), the camera 0.5 m above it, the sun
 * 60 degrees from the zenith behind the camera, 256 view steps; rays down at 10, 30 and 60
 * degrees below the horizon, away from the sun; methods single and march.
 *
 * Oracle: the pixel a camera ray gives (terrain_stage_trace, as sky_render calls it) less the
 * air in front of the water (twice sky_trace to half the hit: the in-scattering of the first
 * metres is linear in the length to ~1e-4) and the water's own light times the view
 * transmittance T (terrain_radiance: body and glint, tested in test_terrain_shading) must
 * equal T F L_sky, with F the Fresnel reflectance from Snell's angles in double (Born and Wolf
 * 1.5.2) and L_sky the sky the camera sees in the mirror direction (the method's sky_trace of
 * the camera ray that way, with the same random jitter as the mirror ray's: the integrator's
 * one-jitter estimate moves by ~0.8 % between jitters at 256 segments). Bound
 * 1e-3 T F L_sky (the mirror ray starts 0.5 m below the camera: ~4e-5 measured) plus 2e-4 of
 * the subtracted light (the integrator ends the ray at its own float distance to the sea, a
 * few millimetres from the tracer's). The water's former uniform sky, E_sky / pi (zero for
 * single), would be off by more than 5 %; the reflected sky must also
 * grow toward the horizon (higher F, brighter sky near the horizon). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "testlib.h"
#include "testscene.h"

static const char probe_src[] =
    "__kernel void water(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                    __global const float4 *dir, __global float4 *out, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  medium_ray m = medium_ray_from_camera(s, dir[i].xyz);\n"
    "  rng_stream g = rng_stream_stage(s->seed, i, 0u, 0u);\n"
    "  float3 sky, sun, vt, air, sun2, vt2, mir, sun3, vt3;\n"
    "  terrain_stage_trace(s, ATMO_LUT_ARGS, &m, &g, &sky, &sun, &vt);\n"
    "  float t = -1.0f;\n"
    "  terrain_trace(s, heightmap, m.origin, m.dir, 0.0f, INFINITY, s->terrain.steps, &t, 0);\n"
    "  rng_stream g2 = rng_stream_stage(s->seed, i, 0u, 0u);\n"
    "  sky_trace(s, ATMO_LUT_ARGS, &m, 0.5f * t, &g2, &air, &sun2, &vt2);\n"
    "  air *= 2.0f;\n"
    "  float3 own = vt * terrain_radiance(s, ATMO_LUT_ARGS, &m, t);\n"
    "  float3 up = terrain_vertical(s, m.dir * t);\n"
    "  float3 r = m.dir - up * (2.0f * dot(m.dir, up));\n"
    "  medium_ray mr = medium_ray_from_camera(s, r);\n"
    "  rng_stream g3 = rng_stream_stage(s->seed, i, 0u, 0u);\n"
    "  rng_next(&g3);\n"
    "  sky_trace(s, ATMO_LUT_ARGS, &mr, INFINITY, &g3, &mir, &sun3, &vt3);\n"
    "  out[5 * i] = (float4)(sky - air - own, t);\n"
    "  out[5 * i + 1] = (float4)(vt, -dot(m.dir, up));\n"
    "  out[5 * i + 2] = (float4)(mir, 0.0f);\n"
    "  out[5 * i + 3] = (float4)(air + own, 0.0f);\n"
    "  out[5 * i + 4] = (float4)(medium_ms_ground_irradiance(s, ATMO_LUT_ARGS,\n"
    "                            dot(up, s->sun_direction.xyz)), 0.0f);\n"
    "}\n";

/* Unpolarised Fresnel reflectance from air into index eta at incidence cosine c, from the
 * angles of Snell's law. */
static double fresnel_angles(double c, double eta)
{
    double i = acos(c), t = asin(sin(i) / eta);
    if (i < 1e-9)
        return pow((eta - 1) / (eta + 1), 2);
    double a = sin(i - t) / sin(i + t), b = tan(i - t) / tan(i + t);
    return 0.5 * (a * a + b * b);
}

static void check_method(atmo_cl *cl, const char *method)
{
    atmo_scene s;
    atmo_plan p;
    char buf[64];
    test_scene_preset(&s, "sky-noon");
    snprintf(buf, sizeof buf, "atmosphere.method=%s", method);
    test_scene_set(&s, buf);
    test_scene_set(&s, "terrain.enabled=true");
    test_scene_set(&s, "terrain.land_fraction=0");
    test_scene_set(&s, "camera.position_m=0,0.5,0");
    test_scene_set(&s, "sun.zenith_deg=60");
    test_scene_set(&s, "render.view_steps=256");
    test_plan(&s, &p);
    cl_program prog = test_plan_program(cl, &p, probe_src);
    cl_int err;
    cl_mem scene = clCreateBuffer(cl->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                  sizeof p.gpu, &p.gpu, &err);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    test_precompute(cl, prog, scene, &p, luts);
    enum { N = 3 };
    static const double below_deg[N] = {10, 30, 60};
    double hx = -p.gpu.sun_direction.x, hz = -p.gpu.sun_direction.z, hl = hypot(hx, hz);
    float4 dir[N], out[5 * N];
    for (int i = 0; i < N; i++) {
        double e = below_deg[i] * M_PI / 180.0;
        dir[i].x = (float)(cos(e) * hx / hl), dir[i].y = (float)-sin(e);
        dir[i].z = (float)(cos(e) * hz / hl), dir[i].w = 0.0f;
    }
    cl_mem bd = test_cl_buffer(cl, sizeof dir, dir), bo = test_cl_buffer(cl, sizeof out, NULL);
    cl_kernel k = clCreateKernel(prog, "water", &err);
    clSetKernelArg(k, 0, sizeof scene, &scene);
    int a = test_bind_buffers(k, luts);
    cl_uint n = N;
    clSetKernelArg(k, a++, sizeof bd, &bd);
    clSetKernelArg(k, a++, sizeof bo, &bo);
    clSetKernelArg(k, a++, sizeof n, &n);
    test_cl_run_1d(cl, k, N);
    test_cl_read(cl, bo, sizeof out, out);
    double worst = 0, last = INFINITY;
    for (int i = 0; i < N; i++) {
        CHECK(out[5 * i].w > 0.0f);
        double c = out[5 * i + 1].w, F = fresnel_angles(c, 1.333), uniform_off = 0;
        for (int ch = 0; ch < 3; ch++) {
            double got = (&out[5 * i].x)[ch], T = (&out[5 * i + 1].x)[ch];
            double want = T * F * (&out[5 * i + 2].x)[ch], rest = (&out[5 * i + 3].x)[ch];
            double uniform = T * F * (&out[5 * i + 4].x)[ch] / M_PI;
            worst = fmax(worst, fabs(got - want) / (1e-3 * want + 2e-4 * rest));
            uniform_off = fmax(uniform_off, fabs(uniform / want - 1));
            CHECK_ABS(got, want, 1e-3 * want + 2e-4 * rest);
        }
        CHECK(uniform_off > 0.05);
        double green = (&out[5 * i].x)[1];
        CHECK(green < last); /* steeper: less reflected */
        last = green;
        printf("method %-6s, %2.0f degrees down: F = %.4f, reflected sky %.4g (green) within "
               "%.2g of its bound; a uniform sky E_sky / pi would be off by %.0f %%\n",
               method, below_deg[i], F, green, worst, 100 * uniform_off);
    }
    clReleaseKernel(k);
    clReleaseMemObject(bo);
    clReleaseMemObject(bd);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    clReleaseProgram(prog);
    atmo_plan_free(&p);
}

int main(void)
{
    test_require_opencl();
    atmo_cl cl;
    test_cl_open(&cl);
    check_method(&cl, "single");
    check_method(&cl, "march");
    atmo_cl_close(&cl);
    return test_finish();
}
