/* test_gpu_layout — the structs of include/atmo/gpu_types.h and of each feature's header
 * (gpu_atmosphere.h, gpu_ms_lut.h, gpu_sky_view.h, gpu_lut.h, gpu_reference.h, gpu_cloud.h,
 * gpu_clouds.h, gpu_path.h, gpu_terrain.h) have
 * the same size and field offsets in the OpenCL C compiler as on the host.
 * labels: kernel
 *
 * Oracle: the host compiler's sizeof/offsetof (which host/plan/plan.c also pins with
 * _Static_assert); a probe kernel reports the device compiler's, and every pair must be equal. */
#include <stddef.h>
#include "atmo/gpu_types.h"
#include "testcl.h"
#include "testlib.h"

#define FIELDS(X)                                                                                  \
    X(atmo_gpu_atmosphere, ground_albedo) X(atmo_gpu_atmosphere, bottom_radius)                    \
    X(atmo_gpu_atmosphere, mie_phase) X(atmo_gpu_atmosphere, sun_angular_radius)                   \
    X(atmo_gpu_camera, local_up) X(atmo_gpu_camera, kind) X(atmo_gpu_camera, tan_half_fov)         \
    X(atmo_gpu_scene, camera) X(atmo_gpu_scene, sun_direction) X(atmo_gpu_scene, sun_factor)       \
    X(atmo_gpu_scene, view_steps) X(atmo_gpu_scene, seed)                        \
    X(atmo_gpu_scene, ms) X(atmo_gpu_scene, sky_view) X(atmo_gpu_scene, lut)                      \
    X(atmo_gpu_scene, reference) X(atmo_gpu_scene, cloud)                                         \
    X(atmo_gpu_ms_lut, steps) X(atmo_gpu_ms_lut, higher_anisotropy) X(atmo_gpu_ms_lut, g2)        \
    X(atmo_gpu_sky_view, steps) X(atmo_gpu_lut, steps) X(atmo_gpu_lut, orders)                    \
    X(atmo_gpu_reference, max_order) X(atmo_gpu_cloud, observer) X(atmo_gpu_cloud, base_m)        \
    X(atmo_gpu_cloud, phase) X(atmo_gpu_cloud, steps) X(atmo_gpu_scene, clouds)                  \
    X(atmo_gpu_clouds, origin) X(atmo_gpu_clouds, bottom_m) X(atmo_gpu_clouds, majorant)          \
    X(atmo_gpu_clouds, phase) X(atmo_gpu_clouds, seed) X(atmo_gpu_scene, path)                    \
    X(atmo_gpu_path, object_count) X(atmo_gpu_path, sampler) X(atmo_gpu_path, filter_radius)      \
    X(atmo_gpu_path, focus_m) X(atmo_gpu_object, emission) X(atmo_gpu_object, kind) \
    X(atmo_gpu_scene, terrain)                 \
    X(atmo_gpu_terrain_field, seed) X(atmo_gpu_terrain_field, heightmap_extent_m)                \
    X(atmo_gpu_terrain_field, base_rect) X(atmo_gpu_terrain_field, base_detail)                  \
    X(atmo_gpu_terrain_field, detail_octave0) X(atmo_gpu_terrain_field, detail_octaves)          \
    X(atmo_gpu_terrain_field, detail_amplitude_m) X(atmo_gpu_terrain_field, warp)                \
    X(atmo_gpu_terrain, camera) X(atmo_gpu_terrain, steps) X(atmo_gpu_terrain, shafts)          \
    X(atmo_gpu_terrain, pixel_angle) X(atmo_gpu_terrain, sun_map_size)                          \
    X(atmo_gpu_terrain, sun_map_extent_m) X(atmo_gpu_terrain, sun_map_soft_m)                    \
    X(atmo_gpu_terrain, sun_map_axis) X(atmo_gpu_terrain, stretch_slope)                       \
    X(atmo_gpu_terrain, slope_growth_per_m)

#define HOST_OFFSET(type, field) (uint)offsetof(type, field),
#define DEVICE_OFFSET(type, field) "out[n++] = (uint)__builtin_offsetof(" #type ", " #field ");\n"

static const char probe[] =
    "__kernel void probe(__global uint *out) {\n"
    "  int n = 0;\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_atmosphere);\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_camera);\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_scene);\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_ms_lut);\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_sky_view);\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_lut);\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_reference);\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_cloud);\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_clouds);\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_path);\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_object);\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_terrain_field);\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_terrain);\n" FIELDS(DEVICE_OFFSET) "}\n";

int main(void)
{
    uint want[] = {(uint)sizeof(atmo_gpu_atmosphere), (uint)sizeof(atmo_gpu_camera),
                   (uint)sizeof(atmo_gpu_scene), (uint)sizeof(atmo_gpu_ms_lut),
                   (uint)sizeof(atmo_gpu_sky_view), (uint)sizeof(atmo_gpu_lut),
                   (uint)sizeof(atmo_gpu_reference), (uint)sizeof(atmo_gpu_cloud),
                   (uint)sizeof(atmo_gpu_clouds), (uint)sizeof(atmo_gpu_path),
                   (uint)sizeof(atmo_gpu_object),
                   (uint)sizeof(atmo_gpu_terrain_field), (uint)sizeof(atmo_gpu_terrain),
                   FIELDS(HOST_OFFSET)};
    enum { N = sizeof want / sizeof want[0] };
    atmo_cl cl;
    test_cl_open(&cl);
    const char *fragments[] = {"kernels/common/compat.h",       "include/atmo/gpu_enums.h",
                               "include/atmo/gpu_atmosphere.h", "include/atmo/gpu_ms_lut.h",
                               "include/atmo/gpu_sky_view.h",   "include/atmo/gpu_lut.h",
                               "include/atmo/gpu_reference.h",  "include/atmo/gpu_cloud.h",
                               "include/atmo/gpu_clouds.h",     "include/atmo/gpu_path.h",
                               "include/atmo/gpu_terrain.h",    "include/atmo/gpu_types.h"};
    cl_program prog = test_cl_build(&cl, fragments, 12, probe);
    cl_int err;
    cl_kernel k = clCreateKernel(prog, "probe", &err);
    cl_mem out = test_cl_buffer(&cl, sizeof want, NULL);
    clSetKernelArg(k, 0, sizeof out, &out);
    size_t one = 1;
    clEnqueueNDRangeKernel(cl.queue, k, 1, NULL, &one, &one, 0, NULL, NULL);
    uint got[N];
    test_cl_read(&cl, out, sizeof got, got);
    for (int i = 0; i < N; i++)
        CHECK_ABS(got[i], want[i], 0);
    clReleaseMemObject(out);
    clReleaseKernel(k);
    clReleaseProgram(prog);
    atmo_cl_close(&cl);
    return test_finish();
}
