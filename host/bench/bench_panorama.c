/* bench_panorama.c — `atmo bench panorama`: the whole process of rendering a sky panorama to
 * EXR, stage by stage, for each cache state and size.
 *
 * Each run is this atmo binary started anew (/proc/self/exe) as
 *   atmo render --preset sky-noon --camera panorama --width W --height H --samples 1
 *        --output DIR/panorama.exr --report R --quiet
 * (method fast, the default), timed from the spawn to the exit, with the stages from its run
 * report: device init, kernel build, precompute, render, read-back, write (the rest, process
 * start, OpenCL platform loading and exit, is wall minus their sum). Cases:
 *   warm            the kernel and LUT caches full (a run before fills them)
 *   warm-exr-none   the same, EXR without compression (--exr-compression none)
 *   new-atmosphere  the kernels cached, the LUTs computed (--no-lut-cache: a new atmosphere)
 *   cold            empty atmo and PoCL caches: a user's first run
 * at 512x256, 1024x512, 2048x1024 and 4096x2048 (--quick: the first two). The caches live in a
 * fresh directory under DIR (removed after), so the user's caches are neither used nor
 * changed. Every case but cold (once: its build alone takes seconds) runs 3 times (--quick:
 * once), interleaved (size by size, case by case, in turn), and the run of the median wall time
 * is reported, since a shared machine's load moves single runs.
 * Outputs: DIR/panorama.csv (case, size, wall and stage seconds, launches, device) and
 * DIR/panorama.svg, wall seconds against megapixels per case, log-log, beside the peer the
 * issue measured: Blender's sky texture bake as a whole process on a 2-core machine of this
 * kind (0.15 s at 512x256, 2.07 s at 2048x1024, 8.2 s at 4096x2048). */
#include <cjson/cJSON.h>
#include <errno.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include "atmo/bench.h"
#include "atmo/clock.h"
#include "atmo/fileio.h"

extern char **environ;

enum { STAGES = 6, CASES = 4, SIZES = 4, MAX_REPEATS = 5 };

static const char *const stage_keys[STAGES] = {"device_init", "kernel_build", "precompute",
                                               "render",      "read_back",    "write"};
static const char *const case_names[CASES] = {"warm", "warm-exr-none", "new-atmosphere",
                                              "cold"};
static const int sizes[SIZES][2] = {{512, 256}, {1024, 512}, {2048, 1024}, {4096, 2048}};

typedef struct run {
    double wall, stage[STAGES];
    int launches;
    char device[128];
} run;

/* The environment with ATMO_CACHE_DIR and POCL_CACHE_DIR replaced by the bench's own. */
static char **child_environment(const char *atmo_cache, const char *pocl_cache, char *buf_a,
                                char *buf_p, size_t size)
{
    int n = 0;
    while (environ[n])
        n++;
    char **env = calloc((size_t)n + 3, sizeof *env);
    if (!env)
        return NULL;
    int k = 0;
    for (int i = 0; i < n; i++)
        if (strncmp(environ[i], "ATMO_CACHE_DIR=", 15) != 0 &&
            strncmp(environ[i], "POCL_CACHE_DIR=", 15) != 0)
            env[k++] = environ[i];
    snprintf(buf_a, size, "ATMO_CACHE_DIR=%s", atmo_cache);
    snprintf(buf_p, size, "POCL_CACHE_DIR=%s", pocl_cache);
    env[k++] = buf_a;
    env[k++] = buf_p;
    return env;
}

/* The run report's seconds and launches. */
static int read_report(const char *path, run *r, atmo_err *e)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "bench panorama: no run report '%s': %s", path,
                         strerror(errno));
    char text[1 << 16];
    size_t len = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[len] = 0;
    cJSON *root = cJSON_Parse(text);
    cJSON *seconds = cJSON_GetObjectItem(root, "seconds");
    cJSON *render = cJSON_GetObjectItem(root, "render");
    int ok = seconds && render;
    for (int s = 0; ok && s < STAGES; s++) {
        cJSON *v = cJSON_GetObjectItem(seconds, stage_keys[s]);
        ok = cJSON_IsNumber(v);
        r->stage[s] = ok ? v->valuedouble : 0.0;
    }
    cJSON *launches = cJSON_GetObjectItem(render, "launches");
    ok = ok && cJSON_IsNumber(launches);
    r->launches = ok ? launches->valueint : 0;
    const char *name = cJSON_GetStringValue(cJSON_GetObjectItem(cJSON_GetObjectItem(root, "device"),
                                                                "name"));
    snprintf(r->device, sizeof r->device, "%s", name ? name : "?");
    cJSON_Delete(root);
    return ok ? ATMO_OK
              : atmo_fail(e, ATMO_ERR_RUNTIME, "bench panorama: run report '%s' lacks the "
                                               "stage timings", path);
}

/* One whole-process render of one case. */
static int run_case(const char *exe, const char *dir, const char *cache, int which, int w, int h,
                    const char *device, run *r, atmo_err *e)
{
    char atmo_cache[1200], pocl_cache[1300], out[1200], report[1200], width[16], height[16];
    char env_a[1400], env_p[1400];
    snprintf(atmo_cache, sizeof atmo_cache, "%s/%s", cache,
             strcmp(case_names[which], "cold") == 0 ? "cold" : "warm");
    snprintf(pocl_cache, sizeof pocl_cache, "%s/pocl", atmo_cache);
    if (strcmp(case_names[which], "cold") == 0) {
        char cmd[1400];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", atmo_cache);
        if (system(cmd) != 0)
            return atmo_fail(e, ATMO_ERR_RUNTIME, "bench panorama: cannot empty '%s'",
                             atmo_cache);
    }
    snprintf(out, sizeof out, "%s/panorama.exr", dir);
    snprintf(report, sizeof report, "%s/panorama-report.json", cache);
    snprintf(width, sizeof width, "%d", w);
    snprintf(height, sizeof height, "%d", h);
    const char *argv[24] = {exe,        "render",  "--preset",   "sky-noon", "--camera",
                            "panorama", "--width", width,        "--height", height,
                            "--samples", "1",      "--output",   out,        "--report",
                            report,     "--quiet"};
    int argc = 17;
    if (strcmp(case_names[which], "warm-exr-none") == 0) {
        argv[argc++] = "--exr-compression";
        argv[argc++] = "none";
    }
    if (strcmp(case_names[which], "new-atmosphere") == 0)
        argv[argc++] = "--no-lut-cache";
    if (device) {
        argv[argc++] = "--device";
        argv[argc++] = device;
    }
    argv[argc] = NULL;
    char **env = child_environment(atmo_cache, pocl_cache, env_a, env_p, sizeof env_a);
    if (!env)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory");
    pid_t pid;
    int status = 0;
    double t0 = atmo_now_seconds();
    int err = posix_spawn(&pid, exe, NULL, NULL, (char *const *)argv, env);
    if (err == 0 && waitpid(pid, &status, 0) < 0)
        err = errno;
    r->wall = atmo_now_seconds() - t0;
    free(env);
    if (err != 0)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "bench panorama: cannot run '%s': %s", exe,
                         strerror(err));
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "bench panorama: '%s render' (%s, %dx%d) failed "
                                              "with status %d", exe, case_names[which], w, h,
                         WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    return read_report(report, r, e);
}

static int by_wall(const void *a, const void *b)
{
    double x = ((const run *)a)->wall, y = ((const run *)b)->wall;
    return (x > y) - (x < y);
}

static int write_csv(const char *path, run results[SIZES][CASES], int n_sizes,
                     const char *device_name, atmo_err *e)
{
    char tmp[ATMO_TMP_PATH_MAX];
    FILE *f = atmo_atomic_open(path, tmp, e);
    if (!f)
        return ATMO_ERR_RUNTIME;
    fprintf(f, "case,width,height,megapixels,wall,device_init,kernel_build,precompute,render,"
               "read_back,write,other,launches,device\n");
    for (int c = 0; c < CASES; c++) /* a case's rows together: the chart joins them */
        for (int s = 0; s < n_sizes; s++) {
            const run *r = &results[s][c];
            double sum = 0.0;
            fprintf(f, "%s,%d,%d,%.6f,%.4f", case_names[c], sizes[s][0], sizes[s][1],
                    sizes[s][0] * (double)sizes[s][1] / 1e6, r->wall);
            for (int k = 0; k < STAGES; k++) {
                fprintf(f, ",%.4f", r->stage[k]);
                sum += r->stage[k];
            }
            fprintf(f, ",%.4f,%d,\"%s\"\n", r->wall - sum, r->launches, device_name);
        }
    return atmo_atomic_commit(f, tmp, path, e);
}

/* Wall seconds against megapixels, one series per case, and Blender's three points. */
static int write_chart(const char *csv, const char *svg, const char *device_name, atmo_err *e)
{
    char *script = NULL;
    size_t size = 0;
    FILE *f = open_memstream(&script, &size);
    if (!f)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the chart script of %s", svg);
    fprintf(f, "set datafile separator ','\nset logscale xy\n"
               "set xlabel 'megapixels (512x256 to 4096x2048 panoramas)'\n"
               "set ylabel 'whole process, seconds'\nset grid\nset key left top\n"
               "set title \"atmo render, fast, 1 sample, EXR\\n%s\"\n"
               "$blender << EOD\n0.131072,0.15\n2.097152,2.07\n8.388608,8.2\nEOD\nplot ",
            device_name);
    for (int c = 0; c < CASES; c++)
        fprintf(f, "'%s' using (strcol(1) eq '%s' ? $4 : 1/0):5 with linespoints title '%s', ",
                csv, case_names[c], case_names[c]);
    fprintf(f, "$blender using 1:2 with linespoints dashtype 2 title 'Blender sky bake (issue)'\n");
    int rc = bench_plot_close(f, &script, svg, 800, 500, e);
    return rc;
}

int bench_panorama(const char *dir, const char *device, int quick, atmo_err *e)
{
    char exe[1024], cache[1200];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len <= 0)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "bench panorama: cannot find the atmo binary "
                                              "(/proc/self/exe): %s", strerror(errno));
    exe[len] = 0;
    snprintf(cache, sizeof cache, "%s/panorama-cache-%d", dir, (int)getpid());
    if (mkdir(cache, 0755) != 0 && errno != EEXIST)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "bench panorama: cannot create '%s': %s", cache,
                         strerror(errno));
    int n_sizes = quick ? 2 : SIZES, repeats = quick ? 1 : 3, rc = ATMO_OK;
    static run results[SIZES][CASES];
    run first;
    fprintf(stderr, "bench panorama: filling the warm caches\n");
    rc = run_case(exe, dir, cache, 0, sizes[0][0], sizes[0][1], device, &first, e);
    for (int s = 0; s < n_sizes && !rc; s++) {
        run runs[CASES][MAX_REPEATS];
        int count[CASES] = {repeats, repeats, repeats, 1}; /* a cold build is long: once */
        for (int k = 0; k < repeats && !rc; k++)
            for (int c = 0; c < CASES && !rc; c++)
                if (k < count[c])
                    rc = run_case(exe, dir, cache, c, sizes[s][0], sizes[s][1], device,
                                  &runs[c][k], e);
        for (int c = 0; c < CASES && !rc; c++) {
            qsort(runs[c], (size_t)count[c], sizeof runs[c][0], by_wall);
            results[s][c] = runs[c][count[c] / 2];
            const run *r = &results[s][c];
            fprintf(stderr, "bench panorama: %4dx%-4d %-14s %6.3fs (device %.3f, build %.3f, "
                            "precompute %.3f, render %.3f in %d launches, read-back %.3f, write "
                            "%.3f)\n",
                    sizes[s][0], sizes[s][1], case_names[c], r->wall, r->stage[0], r->stage[1],
                    r->stage[2], r->stage[3], r->launches, r->stage[4], r->stage[5]);
        }
    }
    char cmd[1400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s' '%s/panorama.exr'", cache, dir);
    if (system(cmd) != 0 && !rc)
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "bench panorama: cannot remove '%s'", cache);
    if (rc)
        return rc;
    char csv[4096], svg[4096], device_name[200];
    snprintf(csv, sizeof csv, "%s/panorama.csv", dir);
    snprintf(svg, sizeof svg, "%s/panorama.svg", dir);
    snprintf(device_name, sizeof device_name, "%s, %ld host cores", first.device,
             sysconf(_SC_NPROCESSORS_ONLN));
    if ((rc = write_csv(csv, results, n_sizes, device_name, e)) ||
        (rc = write_chart(csv, svg, device_name, e)))
        return rc;
    printf("wrote %s and %s\n", csv, svg);
    return ATMO_OK;
}
