/* testcl.h — OpenCL helpers for kernel tests: open the default device (exit 77 without one) and
 * build embedded fragments plus a probe kernel written in the test. */
#ifndef ATMO_TESTCL_H
#define ATMO_TESTCL_H
#include "atmo/cl_runtime.h"

/* Open the device (ATMO_DEVICE or the default); exits 77 if OpenCL has no platform. */
void test_cl_open(atmo_cl *cl);
/* Build fragments + extra; exits 1 with the error on failure. */
cl_program test_cl_build(atmo_cl *cl, const char *const *fragments, int count, const char *extra);
/* The same with build options (-D flags). */
cl_program test_cl_build_defines(atmo_cl *cl, const char *const *fragments, int count,
                                 const char *defines, const char *extra);
/* A read-write buffer initialised from host memory (may be NULL for uninitialised). */
cl_mem test_cl_buffer(atmo_cl *cl, size_t bytes, const void *init);
/* Run a 1-D kernel over n items (global size padded to 64; the kernel bounds-checks) and wait. */
void test_cl_run_1d(atmo_cl *cl, cl_kernel k, size_t n);
void test_cl_read(atmo_cl *cl, cl_mem b, size_t bytes, void *out);

#endif
