/* test_cl_runtime — device choice, program builds, the binary cache and build failures.
 * labels: kernel unit
 *
 * Oracle: the contract of include/atmo/cl_runtime.h. Selecting by index and by a
 * case-insensitive name part finds the same device as the default on a one-device machine; an
 * out-of-range index or an unknown name is a usage error; a second build of the same source is a
 * cache hit and yields a working program; a source with an error fails with the call named and
 * the --dump-kernels hint, and writes the source when asked; error strings name the constant.
 * The kernels' requirements (atmo_cl_caps_usable): the device under test meets them, and caps
 * that each break one requirement (unavailable, no compiler, OpenCL C 1.1, float without Inf/NaN
 * or round-to-nearest, work groups of 32 items or 4 x 4 x 4) are refused with a reason that names
 * it, while OpenCL C 2.0 and 3.0 are accepted. */
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>
#include "testcl.h"
#include "testlib.h"

static const char good[] =
    "__kernel void twice(__global float *x) { x[get_global_id(0)] *= 2.0f; }\n";
static const char bad[] = "__kernel void broken(__global float *x) { x[0] = undefined_name; }\n";

static void test_requirements(const atmo_cl *cl)
{
    char why[256];
    atmo_cl_caps real, c;
    atmo_cl_query_caps(cl->device, &real);
    CHECK(atmo_cl_caps_usable(&real, why, sizeof why) == 1 && why[0] == '\0');
    c = real;
    c.available = 0;
    CHECK(!atmo_cl_caps_usable(&c, why, sizeof why) && strstr(why, "not available"));
    c = real;
    c.compiler = 0;
    CHECK(!atmo_cl_caps_usable(&c, why, sizeof why) && strstr(why, "compiler"));
    c = real;
    snprintf(c.c_version, sizeof c.c_version, "OpenCL C 1.1 vendor");
    CHECK(!atmo_cl_caps_usable(&c, why, sizeof why) && strstr(why, "OpenCL C 1.2"));
    snprintf(c.c_version, sizeof c.c_version, "OpenCL C 2.0 ");
    CHECK(atmo_cl_caps_usable(&c, why, sizeof why));
    snprintf(c.c_version, sizeof c.c_version, "OpenCL C 3.0");
    CHECK(atmo_cl_caps_usable(&c, why, sizeof why));
    c = real;
    c.single_fp &= ~(cl_device_fp_config)CL_FP_INF_NAN;
    CHECK(!atmo_cl_caps_usable(&c, why, sizeof why) && strstr(why, "NaN"));
    c = real;
    c.single_fp &= ~(cl_device_fp_config)CL_FP_ROUND_TO_NEAREST;
    CHECK(!atmo_cl_caps_usable(&c, why, sizeof why) && strstr(why, "round-to-nearest"));
    c = real;
    c.max_work_group = 32;
    CHECK(!atmo_cl_caps_usable(&c, why, sizeof why) && strstr(why, "work groups of 32"));
    c = real;
    c.max_work_item[0] = c.max_work_item[1] = c.max_work_item[2] = 4;
    CHECK(!atmo_cl_caps_usable(&c, why, sizeof why) && strstr(why, "4 x 4 x 4"));
}

int main(void)
{
    test_fresh_cache_dir(); /* hits and misses below assume an empty cache */
    test_require_opencl();
    atmo_cl cl, by_name, by_index;
    atmo_err e;
    test_cl_open(&cl);
    test_requirements(&cl);

    CHECK(atmo_cl_open(&by_index, "0", &e) == ATMO_OK);
    atmo_cl_close(&by_index);
    char part[8];
    snprintf(part, sizeof part, "%.4s", cl.device_name); /* a prefix, upper-cased */
    for (char *c = part; *c; c++)
        *c = (char)(*c >= 'a' && *c <= 'z' ? *c - 32 : *c);
    CHECK(atmo_cl_open(&by_name, part, &e) == ATMO_OK);
    CHECK(strncasecmp(by_name.device_name, part, strlen(part)) == 0);
    atmo_cl_close(&by_name);
    CHECK(atmo_cl_open(&by_index, "99", &e) == ATMO_ERR_USAGE && strstr(e.msg, "99"));
    CHECK(atmo_cl_open(&by_index, "no-such-device-xyz", &e) == ATMO_ERR_USAGE &&
          strstr(e.msg, "no-such-device-xyz"));

    CHECK(strcmp(atmo_cl_error_string(CL_INVALID_KERNEL_NAME), "CL_INVALID_KERNEL_NAME") == 0);
    CHECK(atmo_cl_fail(&e, "clFoo", CL_OUT_OF_RESOURCES) == ATMO_ERR_RUNTIME &&
          strstr(e.msg, "clFoo") && strstr(e.msg, "CL_OUT_OF_RESOURCES"));

    /* build twice: the second is served by the cache (ctest gives this test its own cache dir) */
    const char *fragments[] = {"kernels/common/compat.h"};
    atmo_cl_build_options o = {fragments, 1, "", NULL, 1, good, NULL, NULL};
    atmo_cl_build_info first, second;
    cl_program p1, p2;
    CHECK(atmo_cl_build(&cl, &o, &p1, &first, &e) == ATMO_OK);
    CHECK(atmo_cl_build(&cl, &o, &p2, &second, &e) == ATMO_OK);
    CHECK(second.cache_hit == 1 && second.key == first.key);
    float x[4] = {1.0f, 2.0f, 3.0f, 4.0f};
    cl_mem b = test_cl_buffer(&cl, sizeof x, x);
    cl_int err;
    cl_kernel k = clCreateKernel(p2, "twice", &err);
    CHECK(err == CL_SUCCESS);
    clSetKernelArg(k, 0, sizeof b, &b);
    size_t n = 4;
    clEnqueueNDRangeKernel(cl.queue, k, 1, NULL, &n, NULL, 0, NULL, NULL);
    test_cl_read(&cl, b, sizeof x, x);
    CHECK(x[0] == 2.0f && x[3] == 8.0f); /* the cached binary runs */
    clReleaseKernel(k);
    clReleaseMemObject(b);
    clReleaseProgram(p1);
    clReleaseProgram(p2);

    /* a different option set is a different key */
    atmo_cl_build_options o2 = {fragments, 1, "-DATMO_SOMETHING=1", NULL, 1, good, NULL, NULL};
    atmo_cl_build_info third;
    cl_program p3;
    CHECK(atmo_cl_build(&cl, &o2, &p3, &third, &e) == ATMO_OK && third.key != first.key &&
          !third.cache_hit);
    clReleaseProgram(p3);

    /* a failing build names the call and where the source would be dumped, and dumps it */
    char dir[] = "test-cl-runtime-dump";
    atmo_cl_build_options ob = {fragments, 1, "", dir, 0, bad, NULL, NULL};
    atmo_cl_build_info bi;
    cl_program pb = NULL;
    fprintf(stderr, "(a build log of a deliberately broken kernel follows)\n");
    CHECK(atmo_cl_build(&cl, &ob, &pb, &bi, &e) == ATMO_ERR_RUNTIME);
    CHECK(strstr(e.msg, "clBuildProgram") && strstr(e.msg, "--dump-kernels"));
    char path[256];
    snprintf(path, sizeof path, "%s/atmo-%016llx.cl", dir, bi.key);
    struct stat st;
    CHECK(stat(path, &st) == 0 && st.st_size > (off_t)strlen(bad));
    remove(path);
    rmdir(dir);

    /* #line directives name every fragment */
    char *src = atmo_cl_assemble(NULL, fragments, NULL, 1, good, &e);
    CHECK(src && strstr(src, "#line 1 \"kernels/common/compat.h\"") &&
          strstr(src, "#line 1 \"extra\""));
    free(src);
    atmo_cl_close(&cl);
    return test_finish();
}
