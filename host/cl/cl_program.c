/* cl_program.c — assemble embedded kernel fragments, build them, and cache the binaries
 * (atmo/cl_runtime.h).
 *
 * Cache: <cache dir>/kernel-<key>.bin, a self-verifying file (atmo/cache_file.h) whose key is
 * FNV-1a 64 of the platform, device, driver, build options, assembled source and cache-file
 * format. Only a file that verifies is handed to clCreateProgramWithBinary (a truncated binary
 * can abort a driver); a binary the driver refuses is deleted, rebuilt from source and
 * rewritten. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "atmo/clock.h"
#include "atmo/cache_file.h"
#include "atmo/cl_runtime.h"
#include "atmo/embedded.h"
#include "atmo/fileio.h"

#define ATMO_CL_STD "-cl-std=CL1.2"

/* Fragment i's text and size: generated, or the embedded file. */
static const char *fragment_text(const char *const *fragments, const char *const *texts, int i,
                                 size_t *size)
{
    if (texts && texts[i]) {
        *size = strlen(texts[i]);
        return texts[i];
    }
    const struct atmo_embedded_file *f = atmo_embedded_find(atmo_kernel_sources, fragments[i]);
    *size = f ? f->size : 0;
    return f ? f->text : NULL;
}

char *atmo_cl_assemble(const char *prelude, const char *const *fragments,
                       const char *const *texts, int count, const char *extra, atmo_err *e)
{
    size_t total = 1 + (extra ? strlen(extra) + 32 : 0) + (prelude ? strlen(prelude) + 32 : 0);
    for (int i = 0; i < count; i++) {
        size_t size;
        if (!fragment_text(fragments, texts, i, &size)) {
            atmo_fail(e, ATMO_ERR_RUNTIME, "kernel fragment '%s' is not embedded (a build bug)",
                      fragments[i]);
            return NULL;
        }
        total += size + strlen(fragments[i]) + 32;
    }
    char *src = malloc(total), *p = src;
    if (!src) {
        atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory assembling kernels");
        return NULL;
    }
    if (prelude)
        p += sprintf(p, "#line 1 \"plan\"\n%s", prelude);
    for (int i = 0; i < count; i++) {
        size_t size;
        const char *text = fragment_text(fragments, texts, i, &size);
        p += sprintf(p, "#line 1 \"%s\"\n", fragments[i]);
        memcpy(p, text, size);
        p += size;
        if (size && text[size - 1] != '\n')
            *p++ = '\n';
    }
    if (extra)
        p += sprintf(p, "#line 1 \"extra\"\n%s\n", extra);
    *p = 0;
    return src;
}

/* FNV-1a, 64 bit: enough to key a cache, not a security hash. */
static unsigned long long fnv1a(unsigned long long h, const char *s)
{
    for (; *s; s++) {
        h ^= (unsigned char)*s;
        h *= 1099511628211ull;
    }
    return h ^ 0xffu; /* separator, so "ab"+"c" differs from "a"+"bc" */
}

static int mkdir_p(const char *dir)
{
    char tmp[1024];
    snprintf(tmp, sizeof tmp, "%s", dir);
    for (char *p = tmp + 1; *p; p++)
        if (*p == '/') {
            *p = 0;
            if (mkdir(tmp, 0755) != 0 && errno != EEXIST)
                return -1;
            *p = '/';
        }
    return mkdir(tmp, 0755) != 0 && errno != EEXIST ? -1 : 0;
}

int atmo_cache_dir_find(char *dir, size_t size, char *why, size_t why_size)
{
    const char *env = getenv("ATMO_CACHE_DIR");
    const char *xdg = getenv("XDG_CACHE_HOME");
    const char *home = getenv("HOME");
    if (env && *env)
        snprintf(dir, size, "%s", env);
    else if (xdg && *xdg)
        snprintf(dir, size, "%s/atmo", xdg);
    else if (home && *home)
        snprintf(dir, size, "%s/.cache/atmo", home);
    else {
        snprintf(dir, size, "(none)");
        snprintf(why, why_size, "none of ATMO_CACHE_DIR, XDG_CACHE_HOME and HOME is set");
        return -1;
    }
    if (mkdir_p(dir) != 0) {
        snprintf(why, why_size, "cannot create it: %s", strerror(errno));
        return -1;
    }
    return atmo_cache_dir_usable(dir, why, why_size) ? 0 : -1;
}

int atmo_cache_dir(char *dir, size_t size)
{
    static int warned;
    char why[256];
    if (atmo_cache_dir_find(dir, size, why, sizeof why) == 0)
        return 0;
    if (!warned++)
        fprintf(stderr, "atmo: warning: cache directory '%s' is unusable (%s); running without "
                        "the disk cache (set ATMO_CACHE_DIR to a writable directory, or pass "
                        "--no-kernel-cache and --no-lut-cache)\n", dir, why);
    return -1;
}

static int dump_source(const char *dir, unsigned long long key, const char *src, atmo_err *e)
{
    char path[1024];
    if (mkdir_p(dir) != 0)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "cannot create --dump-kernels directory '%s': %s",
                         dir, strerror(errno));
    snprintf(path, sizeof path, "%s/atmo-%016llx.cl", dir, key);
    return atmo_write_text_file(path, src, e);
}

/* Load a cached binary (atmo/cache_file.h); returns a built program or NULL. A file that fails
 * verification never reaches the driver; one the driver refuses is rejected like a damaged one,
 * and the caller rebuilds from source and rewrites it. */
static cl_program cache_load(atmo_cl *cl, const char *path, unsigned long long key,
                             const char *options)
{
    void *bin = NULL;
    size_t len = 0;
    if (atmo_cache_file_read(path, "kernel", &key, sizeof key, &bin, &len) != 0)
        return NULL;
    const unsigned char *bins[1] = {bin};
    cl_int status = CL_SUCCESS, err;
    cl_program prog = clCreateProgramWithBinary(cl->context, 1, &cl->device, &len, bins, &status,
                                                &err);
    if (err == CL_SUCCESS && status == CL_SUCCESS)
        err = clBuildProgram(prog, 1, &cl->device, options, NULL, NULL);
    else if (err == CL_SUCCESS)
        err = status;
    if (err != CL_SUCCESS) {
        char why[128];
        snprintf(why, sizeof why, "the OpenCL driver refused the binary: %s",
                 atmo_cl_error_string(err));
        atmo_cache_file_reject(path, why);
        if (prog)
            clReleaseProgram(prog);
        prog = NULL;
    }
    free(bin);
    return prog;
}

/* Store a built program's binary; failures only cost the next run a compile. */
static void cache_store(cl_program prog, const char *path, unsigned long long key)
{
    size_t size = 0;
    if (clGetProgramInfo(prog, CL_PROGRAM_BINARY_SIZES, sizeof size, &size, NULL) != CL_SUCCESS ||
        size == 0)
        return;
    unsigned char *bin = malloc(size);
    unsigned char *bins[1] = {bin};
    if (bin && clGetProgramInfo(prog, CL_PROGRAM_BINARIES, sizeof bins, bins, NULL) == CL_SUCCESS)
        atmo_cache_file_write(path, "kernel", &key, sizeof key, bin, size);
    free(bin);
}

int atmo_cl_build(atmo_cl *cl, const atmo_cl_build_options *o, cl_program *program,
                  atmo_cl_build_info *info, atmo_err *e)
{
    double t0 = atmo_now_seconds();
    int rc = ATMO_OK;
    char options[2048];
    snprintf(options, sizeof options, "%s %s", ATMO_CL_STD, o->defines ? o->defines : "");
    char *src = atmo_cl_assemble(o->prelude, o->fragments, o->texts, o->fragment_count,
                                 o->extra_source, e);
    if (!src)
        return ATMO_ERR_RUNTIME;

    unsigned long long key = 1469598103934665603ull;
    key = fnv1a(key, cl->platform_name);
    key = fnv1a(key, cl->device_name);
    key = fnv1a(key, cl->driver_version);
    key = fnv1a(key, options);
    key = fnv1a(key, src);
    key = fnv1a(key, ATMO_CACHE_FORMAT);
    info->key = key;
    info->cache_hit = 0;
    if (o->dump_dir && (rc = dump_source(o->dump_dir, key, src, e)))
        goto out;

    char dir[1024], path[1200];
    int cached = o->use_cache && atmo_cache_dir(dir, sizeof dir) == 0;
    if (cached) {
        snprintf(path, sizeof path, "%s/kernel-%016llx.bin", dir, key);
        *program = cache_load(cl, path, key, options);
        if (*program) {
            info->cache_hit = 1;
            goto out;
        }
    }

    cl_int err;
    const char *srcs[1] = {src};
    *program = clCreateProgramWithSource(cl->context, 1, srcs, NULL, &err);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "clCreateProgramWithSource", err);
        goto out;
    }
    err = clBuildProgram(*program, 1, &cl->device, options, NULL, NULL);
    if (err != CL_SUCCESS) {
        size_t log_size = 0;
        clGetProgramBuildInfo(*program, cl->device, CL_PROGRAM_BUILD_LOG, 0, NULL, &log_size);
        char *log = malloc(log_size + 1);
        if (log && clGetProgramBuildInfo(*program, cl->device, CL_PROGRAM_BUILD_LOG, log_size,
                                         log, NULL) == CL_SUCCESS) {
            log[log_size] = 0;
            fprintf(stderr, "OpenCL build log:\n%s\n", log);
        }
        free(log);
        rc = atmo_fail(e, ATMO_ERR_RUNTIME,
                       "clBuildProgram failed: %s (build log above; --dump-kernels DIR writes the "
                       "assembled source as DIR/atmo-%016llx.cl)",
                       atmo_cl_error_string(err), key);
        clReleaseProgram(*program);
        *program = NULL;
        goto out;
    }
    if (cached)
        cache_store(*program, path, key);
out:
    free(src);
    info->seconds = atmo_now_seconds() - t0;
    return rc;
}
