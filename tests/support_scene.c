/* Test helpers that need a whole scene: see testscene.h. */
#include <stdio.h>
#include <stdlib.h>
#include "testscene.h"

void test_scene_preset(atmo_scene *s, const char *preset)
{
    atmo_err e;
    atmo_scene_defaults(s);
    if (atmo_scene_apply_preset(s, preset, &e)) {
        fprintf(stderr, "preset %s: %s\n", preset, e.msg);
        exit(1);
    }
}

void test_scene_set(atmo_scene *s, const char *assignment)
{
    atmo_err e;
    if (atmo_scene_assign(s, assignment, "test", &e)) {
        fprintf(stderr, "%s: %s\n", assignment, e.msg);
        exit(1);
    }
}

void test_plan(const atmo_scene *s, atmo_plan *p)
{
    atmo_err e;
    if (atmo_plan_make(s, p, &e)) {
        fprintf(stderr, "plan: %s\n", e.msg);
        exit(1);
    }
}

cl_program test_plan_program(atmo_cl *cl, const atmo_plan *p, const char *extra)
{
    return test_cl_build(cl, p->fragments, p->fragment_count, extra);
}

cl_mem test_transmittance_lut(atmo_cl *cl, cl_program prog, cl_mem scene, const atmo_plan *p)
{
    cl_int err;
    int w = p->gpu.transmittance_width, h = p->gpu.transmittance_height;
    cl_mem lut = test_cl_buffer(cl, sizeof(float) * 4 * (size_t)w * (size_t)h, NULL);
    cl_kernel k = clCreateKernel(prog, "transmittance_lut", &err);
    clSetKernelArg(k, 0, sizeof scene, &scene);
    clSetKernelArg(k, 1, sizeof lut, &lut);
    size_t local[2] = {8, 8}, global[2] = {(size_t)(w + 7) / 8 * 8, (size_t)(h + 7) / 8 * 8};
    err = clEnqueueNDRangeKernel(cl->queue, k, 2, NULL, global, local, 0, NULL, NULL);
    if (err == CL_SUCCESS)
        err = clFinish(cl->queue);
    if (err != CL_SUCCESS) {
        fprintf(stderr, "transmittance_lut: %s\n", atmo_cl_error_string(err));
        exit(1);
    }
    clReleaseKernel(k);
    return lut;
}
