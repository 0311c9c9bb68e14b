/* test_sky_single — the single-scattering sky kernel against the host double reference.
 * labels: kernel
 *
 * Oracle: atmo_ref_single_scattering (+ atmo_ref_ground_radiance for rays that hit the ground),
 * adaptive double-precision quadrature accurate to 1e-6. The kernel integrand (the medium
 * integrator, kernels/media/medium.h, as method single configures it) is
 * run on the device for each ray with 64 segments and 64 stratified values of the per-sample
 * offset, averaged, as a render with 64 samples per pixel would. Target: every
 * channel within 1 %. Rays: cameras at 1 m, 10 km and above the atmosphere; sun zenith 0..85 deg;
 * views from the zenith to just above the horizon toward, across and away from the sun, and
 * views down onto the ground. Rays within a degree of the planet's shadow boundary are left out
 * (the reference and the kernel both use a point sun, but a one-degree step is enough to move
 * a sample across the terminator). */
#include <math.h>
#include <stdio.h>
#include "atmo/atmosphere_ref.h"
#include "testlib.h"
#include "testscene.h"

#define JITTERS 64
#define MAX_RAYS 1024

static const char probe[] =
    "__kernel void probe(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                    __global const float4 *rays, __global float4 *out, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  float4 q = rays[i];\n"
    "  float3 sum = (float3)(0.0f);\n"
    "  for (int j = 0; j < 64; j++) {\n"
    "    medium_ray m = medium_ray_from_cosines(s, q.x, q.y, q.z, q.w);\n"
    "    medium_result res;\n"
    "    medium_integrate(s, ATMO_LUT_ARGS, &m, 0.0f, INFINITY, s->view_steps,\n"
    "                     ((float)j + 0.5f) / 64.0f, 0, &res);\n"
    "    sum += medium_radiance(s, ATMO_LUT_ARGS, &res, q.w);\n"
    "  }\n"
    "  out[i] = (float4)(sum / 64.0f, 0.0f);\n"
    "}\n";

int main(void)
{
    atmo_scene scene;
    atmo_plan plan;
    test_scene_preset(&scene, "sky-noon");
    test_scene_set(&scene, "render.view_steps=64");
    test_plan(&scene, &plan);
    const atmo_atmosphere *a = &plan.atmosphere;

    static float4 rays[MAX_RAYS];
    static double want[MAX_RAYS][3];
    int n = 0;
    static const double altitudes[] = {1.0, 10e3, 1000e3};
    static const double sun_zenith[] = {0, 30, 60, 80, 85};
    static const double view_zenith[] = {0, 30, 60, 80, 85, 89, 95, 120, 180};
    static const double view_azimuth[] = {0, 90, 180};
    for (int ia = 0; ia < 3; ia++)
        for (int is = 0; is < 5; is++)
            for (int iv = 0; iv < 9; iv++)
                for (int iz = 0; iz < 3; iz++) {
                    double r = a->bottom_radius_m + altitudes[ia];
                    double ts = sun_zenith[is] * M_PI / 180, tv = view_zenith[iv] * M_PI / 180;
                    double pv = view_azimuth[iz] * M_PI / 180;
                    double mu = cos(tv), mu_s = cos(ts);
                    double nu = sin(tv) * sin(ts) * cos(pv) + cos(tv) * cos(ts);
                    float4 q = {(float)r, (float)mu, (float)mu_s, (float)nu};
                    rays[n] = q;
                    double ss[3], g[3] = {0, 0, 0};
                    atmo_ref_single_scattering(a, q.x, q.y, q.z, q.w, ss);
                    if (atmo_ref_ray_hits_ground(q.x, q.y, a->bottom_radius_m))
                        atmo_ref_ground_radiance(a, q.x, q.y, q.z, q.w, g);
                    for (int c = 0; c < 3; c++)
                        want[n][c] = ss[c] + g[c];
                    n++;
                }

    atmo_cl cl;
    test_cl_open(&cl);
    cl_program prog = test_plan_program(&cl, &plan, probe);
    cl_mem b_scene = test_cl_buffer(&cl, sizeof plan.gpu, &plan.gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    test_precompute(&cl, prog, b_scene, &plan, luts);
    cl_mem b_rays = test_cl_buffer(&cl, sizeof rays, rays);
    cl_mem b_out = test_cl_buffer(&cl, sizeof(float) * 4 * MAX_RAYS, NULL);
    cl_int err;
    cl_kernel k = clCreateKernel(prog, "probe", &err);
    cl_uint count = (cl_uint)n;
    clSetKernelArg(k, 0, sizeof b_scene, &b_scene);
    int arg = test_bind_buffers(k, luts);
    clSetKernelArg(k, arg, sizeof b_rays, &b_rays);
    clSetKernelArg(k, arg + 1, sizeof b_out, &b_out);
    clSetKernelArg(k, arg + 2, sizeof count, &count);
    test_cl_run_1d(&cl, k, (size_t)n);
    static float out[MAX_RAYS][4];
    test_cl_read(&cl, b_out, sizeof out, out);

    double worst = 0.0;
    int compared = 0;
    for (int i = 0; i < n; i++) {
        if (want[i][0] <= 0.0 && want[i][1] <= 0.0 && want[i][2] <= 0.0) {
            CHECK_ABS(out[i][0] + out[i][1] + out[i][2], 0.0, 0.0); /* dark stays dark */
            continue;
        }
        compared++;
        for (int c = 0; c < 3; c++) {
            double rel = fabs(out[i][c] - want[i][c]) / want[i][c];
            if (rel > 0.01)
                fprintf(stderr, "ray r=%.0f mu=%.4f mu_s=%.4f nu=%.4f channel %d:\n", rays[i].x,
                        rays[i].y, rays[i].z, rays[i].w, c);
            CHECK_REL(out[i][c], want[i][c], 0.01);
            worst = fmax(worst, rel);
        }
    }
    printf("single scattering: worst relative error %.2e over %d rays\n", worst, compared);

    clReleaseKernel(k);
    clReleaseMemObject(b_out);
    clReleaseMemObject(b_rays);
    test_release_luts(luts);
    clReleaseMemObject(b_scene);
    clReleaseProgram(prog);
    atmo_cl_close(&cl);
    return test_finish();
}
