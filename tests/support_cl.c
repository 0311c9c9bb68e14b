/* Implementation of tests/testcl.h. */
#include <stdio.h>
#include <stdlib.h>
#include "testcl.h"
#include "testlib.h"

void test_cl_open(atmo_cl *cl)
{
    atmo_err e;
    test_require_opencl();
    if (atmo_cl_open(cl, NULL, &e)) {
        fprintf(stderr, "cannot open OpenCL device: %s\n", e.msg);
        exit(1);
    }
}

cl_program test_cl_build(atmo_cl *cl, const char *const *fragments, int count, const char *extra)
{
    return test_cl_build_defines(cl, fragments, count, "", extra);
}

cl_program test_cl_build_defines(atmo_cl *cl, const char *const *fragments, int count,
                                 const char *defines, const char *extra)
{
    atmo_err e;
    cl_program p;
    atmo_cl_build_options o = {fragments, count, defines, NULL, 1, extra, NULL, NULL};
    atmo_cl_build_info info;
    if (atmo_cl_build(cl, &o, &p, &info, &e)) {
        fprintf(stderr, "kernel build failed: %s\n", e.msg);
        exit(1);
    }
    return p;
}

cl_mem test_cl_buffer(atmo_cl *cl, size_t bytes, const void *init)
{
    cl_int err;
    cl_mem b = clCreateBuffer(cl->context, CL_MEM_READ_WRITE | (init ? CL_MEM_COPY_HOST_PTR : 0),
                              bytes, (void *)init, &err);
    if (err != CL_SUCCESS) {
        fprintf(stderr, "clCreateBuffer failed: %s\n", atmo_cl_error_string(err));
        exit(1);
    }
    return b;
}

void test_cl_run_1d(atmo_cl *cl, cl_kernel k, size_t n)
{
    size_t local = 64, global = (n + local - 1) / local * local;
    cl_int err = clEnqueueNDRangeKernel(cl->queue, k, 1, NULL, &global, &local, 0, NULL, NULL);
    if (err == CL_SUCCESS)
        err = clFinish(cl->queue);
    if (err != CL_SUCCESS) {
        fprintf(stderr, "kernel launch failed: %s\n", atmo_cl_error_string(err));
        exit(1);
    }
}

void test_cl_read(atmo_cl *cl, cl_mem b, size_t bytes, void *out)
{
    cl_int err = clEnqueueReadBuffer(cl->queue, b, CL_TRUE, 0, bytes, out, 0, NULL, NULL);
    if (err != CL_SUCCESS) {
        fprintf(stderr, "clEnqueueReadBuffer failed: %s\n", atmo_cl_error_string(err));
        exit(1);
    }
}
