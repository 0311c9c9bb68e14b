/* testlib.h — the few helpers every atmo test uses.
 *
 * A test is a main() that calls CHECK* for each assertion and returns test_finish(). Each
 * failed check prints file:line and the values; the process exits 1 if any failed. Tests that
 * need OpenCL call test_require_opencl(), which exits 77 (ctest "not run") when there is no
 * platform. Every test file names its oracle in its header comment and carries a
 * "labels: ..." line read by CMakeLists.txt. */
#ifndef ATMO_TESTLIB_H
#define ATMO_TESTLIB_H
#include <math.h>
#include <stdio.h>

extern int test_failures;
extern int test_checks;

#define CHECK(cond)                                                                     \
    do {                                                                                \
        test_checks++;                                                                  \
        if (!(cond)) {                                                                  \
            test_failures++;                                                            \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);   \
        }                                                                               \
    } while (0)

/* |got - want| <= tol */
#define CHECK_ABS(got, want, tol) test_check_abs(__FILE__, __LINE__, #got, (got), (want), (tol))
/* |got - want| <= rel * |want| */
#define CHECK_REL(got, want, rel) test_check_rel(__FILE__, __LINE__, #got, (got), (want), (rel))

int test_check_abs(const char *file, int line, const char *what, double got, double want,
                   double tol);
int test_check_rel(const char *file, int line, const char *what, double got, double want,
                   double rel);

/* Upper critical value of the chi-square distribution with `dof` degrees of freedom for a
 * one-sided test at p = 1e-4 (standard normal quantile 3.719), by the Wilson-Hilferty cube
 * approximation (relative error < 1e-3 for dof >= 10, far below the margin it decides). */
double test_chi2_critical_1e4(int dof);

/* Exit 77 unless an OpenCL platform with a device exists. */
void test_require_opencl(void);

/* Point ATMO_CACHE_DIR at a new empty directory inside the test's cache directory, so a test
 * that counts cache hits does not depend on earlier runs. */
void test_fresh_cache_dir(void);

/* Print a summary line ("N passed, M failed") and return the exit code. */
int test_finish(void);

#endif
