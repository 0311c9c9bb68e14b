/* Implementation of tests/testlib.h. */
#include <stdlib.h>
#include <CL/cl.h>
#include "testlib.h"

int test_failures;
int test_checks;

int test_check_abs(const char *file, int line, const char *what, double got, double want,
                   double tol)
{
    test_checks++;
    if (fabs(got - want) <= tol)
        return 1;
    test_failures++;
    fprintf(stderr, "%s:%d: %s = %.9g, want %.9g within %.3g (off by %.3g)\n", file, line, what,
            got, want, tol, fabs(got - want));
    return 0;
}

int test_check_rel(const char *file, int line, const char *what, double got, double want,
                   double rel)
{
    test_checks++;
    double err = fabs(got - want) / fabs(want);
    if (err <= rel && isfinite(got))
        return 1;
    test_failures++;
    fprintf(stderr, "%s:%d: %s = %.9g, want %.9g within %.3g relative (off by %.3g)\n", file,
            line, what, got, want, rel, err);
    return 0;
}

double test_chi2_critical_1e4(int dof)
{
    double k = dof, z = 3.719;
    double c = 1.0 - 2.0 / (9.0 * k) + z * sqrt(2.0 / (9.0 * k));
    return k * c * c * c;
}

void test_require_opencl(void)
{
    cl_uint platforms = 0;
    if (clGetPlatformIDs(0, NULL, &platforms) != CL_SUCCESS || platforms == 0) {
        fprintf(stderr, "no OpenCL platform: test not run\n");
        exit(77);
    }
}

void test_fresh_cache_dir(void)
{
    /* a new run-XXXXXX inside the test's own cache directory (set by ctest), else here */
    const char *base = getenv("ATMO_CACHE_DIR");
    static char path[4096];
    snprintf(path, sizeof path, "%s/run-XXXXXX", base && *base ? base : ".");
    char parent[4096];
    snprintf(parent, sizeof parent, "mkdir -p '%s'", base && *base ? base : ".");
    if (system(parent) != 0 || !mkdtemp(path)) {
        perror("test_fresh_cache_dir");
        exit(1);
    }
    setenv("ATMO_CACHE_DIR", path, 1);
}

int test_finish(void)
{
    printf("%d passed, %d failed\n", test_checks - test_failures, test_failures);
    return test_failures ? 1 : 0;
}
