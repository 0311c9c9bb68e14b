/* test_precompute_slices — precompute passes launched in budgeted slices along their last
 * dimension give the same buffers as one launch per pass, and a cancel token stops them
 * without caching anything (host/render/precompute.c).
 * labels: kernel unit
 *
 * Oracles: the unsliced precompute (atmo_precompute: one launch per pass), bitwise; the
 * definition of a cancel (ATMO_INTERRUPTED_EMPTY, no cache file).
 *  1. Methods lut (2-D and 3-D passes, reduced tables) and fast (multiple-scattering and
 *     sky-view LUTs, 2-D): every buffer of the plan, precomputed in slices of one work-group
 *     slab per launch, of at most 3 slabs (an uneven last slice), and adaptively at a 2 ms
 *     budget, is bitwise equal to the unsliced precompute's. A work item computes the same
 *     values wherever its slice starts, so any difference is a bug in the offsets or sizes.
 *  2. A token requested before the precompute stops it with ATMO_INTERRUPTED_EMPTY, and the
 *     plan's cache (cache_luts = 2: store every feature it computes) holds no file afterwards.
 *     A token requested by another thread at 30% of the time that a 1-slab precompute of the
 *     plan takes (timed here, after part 1 ran the kernels once, so not PoCL's first-launch
 *     compilation) stops the same precompute with ATMO_INTERRUPTED_EMPTY, and no file of the
 *     lut feature (computed last) is cached; a feature finished
 *     before the cancel may be, since it is whole.
 * ctest gives the test its own cache directory. */
#include <dirent.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "atmo/clock.h"
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

/* Every buffer of the plan after a precompute under `control` (NULL: unsliced), concatenated. */
static unsigned char *precompute_all(atmo_cl *cl, cl_program prog, const atmo_plan *plan,
                                     const atmo_precompute_control *control, size_t *bytes)
{
    cl_mem scene = test_cl_buffer(cl, sizeof plan->gpu, &plan->gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    atmo_precompute_info info;
    atmo_err e;
    if (atmo_precompute_controlled(cl, prog, plan, scene, luts, control, &info, &e)) {
        fprintf(stderr, "precompute: %s\n", e.msg);
        exit(1);
    }
    *bytes = 0;
    for (int i = 0; i < plan->buffer_count; i++)
        *bytes += plan->buffers[i].bytes;
    unsigned char *all = malloc(*bytes ? *bytes : 1), *p = all;
    CHECK(all != NULL);
    for (int i = 0; i < plan->buffer_count; i++) {
        if (plan->buffers[i].bytes)
            test_cl_read(cl, luts[i], plan->buffers[i].bytes, p);
        p += plan->buffers[i].bytes;
    }
    atmo_release_buffers(luts);
    clReleaseMemObject(scene);
    return all;
}

/* Seconds that method lut's precompute takes in 1-slab slices (timed in part 2). */
static double lut_one_slab_seconds;

static void test_slices_equal(atmo_cl *cl, const char *method)
{
    atmo_plan plan;
    test_sky_plan(method, 1000.0, 50.0, &plan);
    plan.cache_luts = 0;
    int three_d = 0;
    for (int i = 0; i < plan.pass_count; i++)
        three_d |= plan.passes[i].depth > 1;
    if (strcmp(method, "lut") == 0)
        CHECK(three_d); /* the 3-D slicing is exercised */
    cl_program prog = test_plan_program(cl, &plan, NULL);
    size_t n, m;
    unsigned char *want = precompute_all(cl, prog, &plan, NULL, &n);
    const atmo_precompute_control controls[3] = {{1e-6, 0, NULL}, {1e5, 3, NULL},
                                                 {2.0, 0, NULL}};
    for (int c = 0; c < 3; c++) {
        unsigned char *got = precompute_all(cl, prog, &plan, &controls[c], &m);
        CHECK(m == n && n > 0);
        CHECK(memcmp(got, want, n) == 0);
        if (memcmp(got, want, n) != 0)
            fprintf(stderr, "%s: slices under control %d differ from one launch\n", method, c);
        free(got);
    }
    free(want);
    clReleaseProgram(prog);
    atmo_plan_free(&plan);
}

/* Product files in the test's cache directory whose names start with `prefix` ("" for all;
 * the kernel binaries that the test's builds cache are not counted). */
static int cache_files(const char *prefix)
{
    DIR *d = opendir(getenv("ATMO_CACHE_DIR"));
    int n = 0;
    for (struct dirent *f; d && (f = readdir(d));)
        n += f->d_name[0] != '.' && strncmp(f->d_name, "kernel-", 7) != 0 &&
             strncmp(f->d_name, prefix, strlen(prefix)) == 0;
    if (d)
        closedir(d);
    return n;
}

static void *cancel_later(void *token)
{
    double t = 0.3 * lut_one_slab_seconds;
    struct timespec wait = {(time_t)t, (long)(1e9 * (t - (double)(time_t)t))};
    nanosleep(&wait, NULL);
    atmo_cancel_request(token);
    return NULL;
}

static void test_cancel(atmo_cl *cl)
{
    atmo_plan plan;
    test_sky_plan("lut", 1000.0, 50.0, &plan); /* cache_luts = 2 */
    cl_program prog = test_plan_program(cl, &plan, NULL);
    cl_mem scene = test_cl_buffer(cl, sizeof plan.gpu, &plan.gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    atmo_precompute_info info;
    atmo_err e;
    atmo_cancel token;
    atmo_cancel_clear(&token);
    atmo_cancel_request(&token);
    atmo_precompute_control before = {100.0, 0, &token};
    CHECK(atmo_precompute_controlled(cl, prog, &plan, scene, luts, &before, &info, &e) ==
          ATMO_INTERRUPTED_EMPTY);
    atmo_release_buffers(luts);
    CHECK(cache_files("") == 0);

    atmo_cancel_clear(&token);
    atmo_precompute_control during = {1e-6, 0, &token};
    atmo_plan uncached = plan; /* a view of the same plan that stores nothing (not freed) */
    uncached.cache_luts = 0;
    size_t n;
    double t0 = atmo_now_seconds();
    free(precompute_all(cl, prog, &uncached, &during, &n));
    lut_one_slab_seconds = atmo_now_seconds() - t0;
    pthread_t thread;
    CHECK(pthread_create(&thread, NULL, cancel_later, &token) == 0);
    int rc = atmo_precompute_controlled(cl, prog, &plan, scene, luts, &during, &info, &e);
    pthread_join(thread, NULL);
    CHECK(rc == ATMO_INTERRUPTED_EMPTY);
    if (rc == ATMO_INTERRUPTED_EMPTY)
        printf("cancelled at %.2f s (1-slab precompute %.2f s): %s\n",
               0.3 * lut_one_slab_seconds, lut_one_slab_seconds, e.msg);
    atmo_release_buffers(luts);
    CHECK(cache_files("lut-") == 0);
    clReleaseMemObject(scene);
    clReleaseProgram(prog);
    atmo_plan_free(&plan);
}

int main(void)
{
    test_fresh_cache_dir();
    atmo_cl cl;
    test_cl_open(&cl);
    test_slices_equal(&cl, "lut");
    test_slices_equal(&cl, "fast");
    test_cancel(&cl);
    atmo_cl_close(&cl);
    return test_finish();
}
