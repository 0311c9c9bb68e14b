/* test_cache_files — every kind of cache file verifies itself (host/base/cache_file.c), and a
 * damaged one is warned about once, deleted, recomputed and rewritten.
 * labels: kernel unit
 *
 * Oracles: recomputation without the cache (the products are deterministic, so a recovered
 * product must equal it bit for bit) and the file format's definition (a rewritten file must
 * verify with atmo_cache_file_check).
 *  1. For each kind of cache (a kernel binary, method lut's tables at reduced sizes, a small Mie
 *     phase table) and each damage (the last byte cut off, one byte in the middle flipped, the
 *     whole file zeroed, 64 bytes appended): the next use prints exactly one warning line naming
 *     the file, recomputes, gives a product bitwise equal to the fresh one, and leaves a file
 *     that verifies, which the use after that loads (a cache hit).
 *  2. A kernel binary that verifies but that the OpenCL driver refuses (a valid file holding
 *     bytes that are no binary) is rejected in one warning line, rebuilt and rewritten.
 *  3. Non-finite precomputed data: a precompute pass that writes one NaN into a LUT makes the
 *     precompute fail with an error naming the buffer, and no cache file is written; the scan
 *     finds NaN, +Inf and -Inf at the first, a middle and the last index, and passes FLT_MAX,
 *     -0, subnormals and DBL_MAX.
 *  4. Stale temporary files: the next atomic write of a name removes NAME.tmp.PID of a PID that
 *     is no running process (a child that has exited and been reaped) and keeps that of a live
 *     process (PID 1).
 * The test starts from an empty cache directory of its own (removed at the end), since it
 * asserts what a first use stores. */
#include <fcntl.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "atmo/cache_file.h"
#include "atmo/embedded.h"
#include "atmo/features.h"
#include "atmo/fileio.h"
#include "atmo/mie.h"
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

enum { CUT_LAST_BYTE, FLIP_MIDDLE_BYTE, ZERO_ALL, EXTEND_64, DAMAGE_KINDS };
static const char *const damage_names[] = {"last byte cut", "middle byte flipped", "zeroed",
                                           "64 bytes appended"};

static const char capture_path[] = "test_cache_files.stderr";
static int saved_stderr = -1;

/* Send stderr to a file until capture_end, which returns how many lines name `path`. */
static void capture_begin(void)
{
    fflush(stderr);
    saved_stderr = dup(2);
    int fd = open(capture_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    CHECK(saved_stderr >= 0 && fd >= 0);
    dup2(fd, 2);
    close(fd);
}

static int capture_end(const char *path)
{
    fflush(stderr);
    dup2(saved_stderr, 2);
    close(saved_stderr);
    FILE *f = fopen(capture_path, "r");
    char line[8192];
    int lines = 0;
    while (f && fgets(line, sizeof line, f)) {
        fputs(line, stderr); /* keep it in the test's log */
        lines += strstr(line, path) != NULL && strstr(line, "cache file") != NULL;
    }
    if (f)
        fclose(f);
    remove(capture_path);
    return lines;
}

static unsigned char *read_all(const char *path, long *n)
{
    FILE *f = fopen(path, "rb");
    CHECK(f != NULL);
    if (!f)
        exit(1);
    fseek(f, 0, SEEK_END);
    *n = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *data = malloc((size_t)*n + 64);
    CHECK(data && fread(data, 1, (size_t)*n, f) == (size_t)*n);
    fclose(f);
    return data;
}

static void damage(const char *path, int kind)
{
    long n;
    unsigned char *data = read_all(path, &n);
    long keep = n;
    if (kind == CUT_LAST_BYTE)
        keep = n - 1;
    else if (kind == FLIP_MIDDLE_BYTE)
        data[n / 2] ^= 0x01;
    else if (kind == ZERO_ALL)
        memset(data, 0, (size_t)n);
    else
        memset(data + n, 0xab, 64), keep = n + 64;
    FILE *f = fopen(path, "wb");
    CHECK(f && fwrite(data, 1, (size_t)keep, f) == (size_t)keep);
    fclose(f);
    free(data);
}

static int file_valid(const char *path, const char *kind)
{
    char got[ATMO_CACHE_KIND_MAX];
    const char *why;
    return atmo_cache_file_check(path, got, &why) == 0 && strcmp(got, kind) == 0;
}

/* ---- 1, 2: kernel binaries ------------------------------------------------------------------ */

static const char probe_source[] =
    "__kernel void probe(__global float *out)\n"
    "{\n"
    "    int i = get_global_id(0);\n"
    "    if (i < 64)\n"
    "        out[i] = sqrt((float)i) * 0.37f + sin(0.3f * (float)i);\n"
    "}\n";

/* Build the probe program (through the cache or not) and run it; info as atmo_cl_build's. */
static void probe_run(atmo_cl *cl, int use_cache, float out[64], atmo_cl_build_info *info)
{
    atmo_cl_build_options o = {NULL, 0, NULL, NULL, use_cache, probe_source, NULL, NULL};
    cl_program prog;
    atmo_err e;
    if (atmo_cl_build(cl, &o, &prog, info, &e)) {
        fprintf(stderr, "build: %s\n", e.msg);
        exit(1);
    }
    cl_int err;
    cl_kernel k = clCreateKernel(prog, "probe", &err);
    CHECK(err == CL_SUCCESS);
    cl_mem b = test_cl_buffer(cl, 64 * sizeof(float), NULL);
    CHECK(clSetKernelArg(k, 0, sizeof b, &b) == CL_SUCCESS);
    test_cl_run_1d(cl, k, 64);
    test_cl_read(cl, b, 64 * sizeof(float), out);
    clReleaseMemObject(b);
    clReleaseKernel(k);
    clReleaseProgram(prog);
}

static void test_kernel_cache(atmo_cl *cl, const char *dir)
{
    float fresh[64], got[64];
    atmo_cl_build_info info;
    probe_run(cl, 0, fresh, &info);
    probe_run(cl, 1, got, &info);
    CHECK(!info.cache_hit && memcmp(got, fresh, sizeof fresh) == 0);
    char path[1200];
    snprintf(path, sizeof path, "%s/kernel-%016llx.bin", dir, info.key);
    CHECK(file_valid(path, "kernel"));
    for (int d = 0; d < DAMAGE_KINDS; d++) {
        damage(path, d);
        capture_begin();
        probe_run(cl, 1, got, &info);
        CHECK(capture_end(path) == 1);
        CHECK(!info.cache_hit && memcmp(got, fresh, sizeof fresh) == 0);
        CHECK(file_valid(path, "kernel"));
        probe_run(cl, 1, got, &info);
        CHECK(info.cache_hit && memcmp(got, fresh, sizeof fresh) == 0);
        printf("kernel binary, %s: one warning, rebuilt bitwise equal, rewritten valid\n",
               damage_names[d]);
    }

    /* a file that verifies but holds no binary: the driver refuses it */
    static const char junk[] = "these bytes verify as a cache file but are no OpenCL binary";
    unsigned long long key = info.key;
    CHECK(atmo_cache_file_write(path, "kernel", &key, sizeof key, junk, sizeof junk) == ATMO_OK);
    CHECK(file_valid(path, "kernel"));
    capture_begin();
    probe_run(cl, 1, got, &info);
    CHECK(capture_end(path) == 1);
    CHECK(!info.cache_hit && memcmp(got, fresh, sizeof fresh) == 0);
    long n;
    free(read_all(path, &n));
    CHECK(file_valid(path, "kernel") && n > (long)sizeof junk + 64);
    probe_run(cl, 1, got, &info);
    CHECK(info.cache_hit);
    printf("kernel binary the driver refuses: one warning, rebuilt and rewritten\n");
}

/* ---- 1, 3: LUTs ------------------------------------------------------------------------------ */

static int feature_of(const atmo_plan *p, const char *name)
{
    for (int i = 0; i < p->feature_count; i++)
        if (strcmp(p->features[i]->name, name) == 0)
            return i;
    return -1;
}

/* Precompute the plan and return all its buffers' bytes concatenated (plan order). */
static unsigned char *precompute_all(atmo_cl *cl, cl_program prog, const atmo_plan *plan,
                                     atmo_precompute_info *info, size_t *total)
{
    cl_mem scene = test_cl_buffer(cl, sizeof plan->gpu, &plan->gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    atmo_err e;
    if (atmo_precompute(cl, prog, plan, scene, luts, info, &e)) {
        fprintf(stderr, "precompute: %s\n", e.msg);
        exit(1);
    }
    *total = 0;
    for (int i = 0; i < plan->buffer_count; i++)
        *total += plan->buffers[i].bytes;
    unsigned char *all = malloc(*total), *p = all;
    for (int i = 0; i < plan->buffer_count; p += plan->buffers[i].bytes, i++)
        if (plan->buffers[i].bytes)
            test_cl_read(cl, luts[i], plan->buffers[i].bytes, p);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    return all;
}

static const char poison_source[] =
    "__kernel void poison_lut(__global const atmo_gpu_scene *s, ATMO_LUT_OUT_PARAMS, int arg)\n"
    "{\n"
    "    if (get_global_id(0) == 0 && get_global_id(1) == 0)\n"
    "        scattering_rayleigh[arg] = (float4)(0.0f, NAN, 0.0f, 0.0f);\n"
    "}\n";

static void test_lut_cache(atmo_cl *cl, const char *dir)
{
    atmo_plan plan, fresh_plan;
    test_sky_plan("lut", 0.0, 30.0, &plan);
    fresh_plan = plan;
    fresh_plan.cache_luts = 0;
    cl_program prog = test_plan_program(cl, &plan, poison_source);
    atmo_precompute_info info;
    size_t bytes, n;
    unsigned char *fresh = precompute_all(cl, prog, &fresh_plan, &info, &bytes);
    free(precompute_all(cl, prog, &plan, &info, &n)); /* stores the files */
    atmo_device_identity dev = {cl->device_name, cl->device_vendor, cl->driver_version};
    int lut = feature_of(&plan, "lut");
    CHECK(lut >= 0);
    char path[1200];
    snprintf(path, sizeof path, "%s/lut-%016llx.bin", dir,
             atmo_product_key(&plan, lut, &dev, atmo_kernel_sources));
    CHECK(file_valid(path, "lut"));
    for (int d = 0; d < DAMAGE_KINDS; d++) {
        damage(path, d);
        capture_begin();
        unsigned char *got = precompute_all(cl, prog, &plan, &info, &n);
        CHECK(capture_end(path) == 1);
        CHECK(info.damaged == 1 && info.computed == 1 && !info.cache_hit);
        CHECK(n == bytes && memcmp(got, fresh, bytes) == 0);
        CHECK(file_valid(path, "lut"));
        free(got);
        got = precompute_all(cl, prog, &plan, &info, &n);
        CHECK(info.damaged == 0 && info.cache_hit && memcmp(got, fresh, bytes) == 0);
        free(got);
        printf("lut tables, %s: one warning, recomputed bitwise equal, rewritten valid\n",
               damage_names[d]);
    }

    /* one NaN written by an extra pass of the lut feature */
    atmo_plan poisoned = plan;
    CHECK(poisoned.pass_count < ATMO_PLAN_MAX_PASSES);
    poisoned.passes[poisoned.pass_count++] = (atmo_plan_pass){"poison_lut", 1, 1, 1, 5, lut};
    char poisoned_path[1200];
    snprintf(poisoned_path, sizeof poisoned_path, "%s/lut-%016llx.bin", dir,
             atmo_product_key(&poisoned, lut, &dev, atmo_kernel_sources));
    cl_mem scene = test_cl_buffer(cl, sizeof poisoned.gpu, &poisoned.gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    atmo_err e;
    CHECK(atmo_precompute(cl, prog, &poisoned, scene, luts, &info, &e) == ATMO_ERR_RUNTIME);
    CHECK(strstr(e.msg, "scattering_rayleigh") && strstr(e.msg, "non-finite"));
    CHECK(access(poisoned_path, F_OK) != 0);
    printf("a NaN in lut's tables: refused (%s), nothing cached\n", e.msg);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    free(fresh);
    clReleaseProgram(prog);
}

/* ---- 1: Mie tables --------------------------------------------------------------------------- */

static int same_table(const mie_table *a, const mie_table *b)
{
    size_t n = (size_t)a->n * sizeof(double);
    return a->n == b->n && memcmp(a->theta_deg, b->theta_deg, n) == 0 &&
           memcmp(a->mu, b->mu, n) == 0 && memcmp(a->P, b->P, n) == 0 &&
           memcmp(a->cdf, b->cdf, n) == 0 && a->norm == b->norm &&
           memcmp(&a->bulk, &b->bulk, sizeof a->bulk) == 0;
}

static void test_mie_cache(void)
{
    mie_dsd d;
    mie_dsd_preset("stratus", &d);
    mie_table_options opt = {.coarse_step_deg = 1.0, .fine_step_deg = 0.5, .max_dx = 0.5};
    mie_table fresh, t;
    atmo_err e;
    int hit;
    CHECK(mie_table_build(&d, 550.0, 1.333, 1e-9, &opt, &fresh, &e) == ATMO_OK);
    CHECK(mie_table_get(&d, 550.0, 1.333, 1e-9, &opt, 1, &t, &hit, &e) == ATMO_OK && !hit);
    mie_table_free(&t);
    char path[4096];
    CHECK(mie_table_cache_path(&d, 550.0, 1.333, 1e-9, &opt, path, sizeof path) == 0);
    CHECK(file_valid(path, "mie-table"));
    for (int k = 0; k < DAMAGE_KINDS; k++) {
        damage(path, k);
        capture_begin();
        CHECK(mie_table_get(&d, 550.0, 1.333, 1e-9, &opt, 1, &t, &hit, &e) == ATMO_OK);
        CHECK(capture_end(path) == 1);
        CHECK(!hit && same_table(&t, &fresh));
        CHECK(file_valid(path, "mie-table"));
        mie_table_free(&t);
        CHECK(mie_table_get(&d, 550.0, 1.333, 1e-9, &opt, 1, &t, &hit, &e) == ATMO_OK);
        CHECK(hit && same_table(&t, &fresh));
        mie_table_free(&t);
        printf("mie table (%d angles), %s: one warning, rebuilt bitwise equal, rewritten valid\n",
               fresh.n, damage_names[k]);
    }
    mie_table_free(&fresh);
}

/* ---- 3: the non-finite scan ------------------------------------------------------------------ */

static void test_nonfinite_scan(void)
{
    float f[7] = {FLT_MAX, -FLT_MAX, -0.0f, FLT_MIN / 4.0f, 1.0f, 0.0f, FLT_MIN};
    double g[5] = {DBL_MAX, -DBL_MAX, -0.0, DBL_MIN / 8.0, 3.0};
    CHECK(atmo_first_nonfinite_float(f, 7) == -1 && atmo_first_nonfinite_double(g, 5) == -1);
    const float bad_f[3] = {NAN, INFINITY, -INFINITY};
    const double bad_g[3] = {NAN, INFINITY, -INFINITY};
    const size_t where[3] = {0, 3, 6};
    for (int b = 0; b < 3; b++)
        for (int w = 0; w < 3; w++) {
            float fc[7];
            memcpy(fc, f, sizeof f);
            fc[where[w]] = bad_f[b];
            CHECK(atmo_first_nonfinite_float(fc, 7) == (long)where[w]);
            double gc[7] = {1, 2, 3, 4, 5, 6, 7};
            gc[where[w]] = bad_g[b];
            CHECK(atmo_first_nonfinite_double(gc, 7) == (long)where[w]);
        }
    printf("non-finite scan: NaN, +Inf, -Inf found at 0, 3, 6; extremes and -0 pass\n");
}

/* ---- 4: stale temporary files ---------------------------------------------------------------- */

static void test_stale_tmp(const char *dir)
{
    pid_t child = fork();
    if (child == 0)
        _exit(0);
    CHECK(child > 0 && waitpid(child, NULL, 0) == child); /* reaped: its PID is no process */
    char path[1200], dead[1300], live[1300];
    snprintf(path, sizeof path, "%s/stale-test.txt", dir);
    snprintf(dead, sizeof dead, "%s.tmp.%ld", path, (long)child);
    snprintf(live, sizeof live, "%s.tmp.1", path);
    atmo_err e;
    CHECK(atmo_write_text_file(dead, "left by a killed writer\n", &e) == ATMO_OK);
    CHECK(atmo_write_text_file(live, "a live writer's\n", &e) == ATMO_OK);
    CHECK(atmo_write_text_file(path, "complete\n", &e) == ATMO_OK);
    CHECK(access(dead, F_OK) != 0 && access(live, F_OK) == 0 && access(path, F_OK) == 0);
    remove(live);
    remove(path);
    printf("stale %s removed by the next write; PID 1's kept\n", strrchr(dead, '/') + 1);
}

int main(void)
{
    test_require_opencl();
    char dir[] = "/tmp/atmo-test-cache-files-XXXXXX";
    if (!mkdtemp(dir))
        return 1;
    setenv("ATMO_CACHE_DIR", dir, 1);
    test_nonfinite_scan();
    test_stale_tmp(dir);
    test_mie_cache();
    atmo_cl cl;
    test_cl_open(&cl);
    test_kernel_cache(&cl, dir);
    test_lut_cache(&cl, dir);
    atmo_cl_close(&cl);
    char cmd[256];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0);
    return test_finish();
}
