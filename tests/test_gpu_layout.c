/* test_gpu_layout — the structs of include/atmo/gpu_types.h have the same size and field offsets
 * in the OpenCL C compiler as on the host.
 * labels: kernel
 *
 * Oracle: the host compiler's sizeof/offsetof (which host/plan.c also pins with _Static_assert);
 * a probe kernel reports the device compiler's, and every pair must be equal. */
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
    X(atmo_gpu_scene, lut_dims) X(atmo_gpu_scene, method_int) X(atmo_gpu_scene, method_float)  \
    X(atmo_gpu_scene, cloud_extinction) X(atmo_gpu_scene, observer)                               \
    X(atmo_gpu_scene, cloud_phase) X(atmo_gpu_scene, cloud_steps)

#define HOST_OFFSET(type, field) (uint)offsetof(type, field),
#define DEVICE_OFFSET(type, field) "out[n++] = (uint)__builtin_offsetof(" #type ", " #field ");\n"

static const char probe[] =
    "__kernel void probe(__global uint *out) {\n"
    "  int n = 0;\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_atmosphere);\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_camera);\n"
    "  out[n++] = (uint)sizeof(atmo_gpu_scene);\n" FIELDS(DEVICE_OFFSET) "}\n";

int main(void)
{
    uint want[] = {(uint)sizeof(atmo_gpu_atmosphere), (uint)sizeof(atmo_gpu_camera),
                   (uint)sizeof(atmo_gpu_scene), FIELDS(HOST_OFFSET)};
    enum { N = sizeof want / sizeof want[0] };
    atmo_cl cl;
    test_cl_open(&cl);
    const char *fragments[] = {"kernels/common/compat.h", "include/atmo/gpu_types.h"};
    cl_program prog = test_cl_build(&cl, fragments, 2, probe);
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
