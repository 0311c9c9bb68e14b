/* precompute.c — the plan's named buffers, their precompute passes and their disk cache
 * (atmo/render.h).
 *
 * Every precompute kernel takes (scene, <the plan's buffers in plan order>, int arg)
 * (atmo/plan.h's ATMO_LUT_OUT_PARAMS), so one loop runs any feature's passes. 2-D passes use
 * 8 x 8 work-groups and 3-D passes 4 x 4 x 4; global sizes are padded to them and the kernels
 * bounds-check. Host tables (a buffer's host_data) are copied in before any pass.
 *
 * Launches: under a control (atmo_precompute_control) a pass runs in budgeted slices along its
 * last dimension through the global work offset (get_global_id includes it), the way a render
 * runs in budgeted batches, so a cancel token stops a precompute within about one launch
 * budget; a work item computes the same values in a slice as in one launch, so the buffers are
 * bitwise the same either way. A cancelled precompute returns ATMO_INTERRUPTED_EMPTY before the
 * feature it stopped in is cached.
 *
 * Cache: the unit is one feature's buffers (the products of its passes), stored as
 *   "<feature>-<key>.bin", a self-verifying cache file (atmo/cache_file.h: kind = the feature,
 *   key, lengths, checksum) whose payload is the buffer count, each buffer's size and the bytes,
 * under the key of exactly its inputs (atmo_product_key), so editing sky.cl, changing
 * render.view_steps, the camera or the sun keeps the `lut` tables, while another device or
 * driver, another atmosphere or another source of the passes computes them anew. A file is used
 * only when the header, the key, the sizes and the checksum all verify; a file that exists but
 * does not verify is reported on stderr in one line, deleted, recomputed and rewritten. Computed
 * buffers of float type are checked for NaN and Inf before they are stored or used: one is an
 * error naming the buffer. Features whose buffers follow the view (fast's sky-view LUT) are
 * never cached, unless their row names params, which then cover the camera and the sun their
 * passes read (the terrain's sun-height map): those are loaded and stored like the others when
 * a session opens, and on a view change (atmo_precompute_view) loaded where a file verifies
 * but not stored, so a moving viewer writes no file per frame. Stores fsync and rename a
 * temporary file, so a reader never sees half a file. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/clock.h"
#include "atmo/cache_file.h"
#include "atmo/embedded.h"
#include "atmo/features.h"
#include "atmo/fileio.h"
#include "atmo/render.h"

/* Loading a verified product of these sizes takes about 1 ms: what takes longer than this to
 * compute is worth storing (the transmittance and Psi_ms LUTs of a warm `fast` render). */
#define ATMO_LUT_CACHE_MIN_SECONDS 0.02
#define CACHE_MAGIC "atmo-product-3"
#define FNV_BASIS 1469598103934665603ull

static size_t pad_to(int n, size_t m) { return ((size_t)n + m - 1) / m * m; }

static unsigned long long fnv(unsigned long long h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

/* A string with its terminator, so "ab" + "c" differs from "a" + "bc". */
static unsigned long long fnv_str(unsigned long long h, const char *s)
{
    return fnv(h, s ? s : "", strlen(s ? s : "") + 1);
}

static int feature_index(const atmo_plan *plan, const char *name)
{
    for (int i = 0; i < plan->feature_count; i++)
        if (strcmp(plan->features[i]->name, name) == 0)
            return i;
    return -1;
}

unsigned long long atmo_product_key(const atmo_plan *plan, int feature,
                                    const atmo_device_identity *device,
                                    const struct atmo_embedded_file *sources)
{
    const atmo_feature *f = plan->features[feature];
    unsigned long long h = fnv_str(FNV_BASIS, CACHE_MAGIC);
    h = fnv_str(h, device->name);
    h = fnv_str(h, device->vendor);
    h = fnv_str(h, device->driver);
    h = fnv_str(h, f->name);
    h = fnv_str(h, f->defines);
    for (const char *const *src = f->sources; src && *src; src++) {
        const struct atmo_embedded_file *text = atmo_embedded_find(sources, *src);
        h = fnv_str(h, *src);
        if (text)
            h = fnv(h, text->text, text->size);
    }
    for (const atmo_gpu_field *p = f->params; p && p->size; p++)
        h = fnv(h, (const char *)&plan->gpu + p->offset, p->size);
    for (int i = 0; i < plan->buffer_count; i++) {
        const atmo_plan_buffer *b = &plan->buffers[i];
        if (b->feature != feature)
            continue;
        uint64_t bytes = b->bytes;
        h = fnv_str(h, b->name);
        h = fnv_str(h, b->type);
        h = fnv(h, &bytes, sizeof bytes);
        if (b->host_data)
            h = fnv(h, b->host_data, b->bytes);
    }
    for (int i = 0; i < plan->pass_count; i++) {
        const atmo_plan_pass *pass = &plan->passes[i];
        if (pass->feature != feature)
            continue;
        int dims[4] = {pass->width, pass->height, pass->depth, pass->arg};
        h = fnv_str(h, pass->kernel);
        h = fnv(h, dims, sizeof dims);
    }
    for (const char *const *need = f->needs; need && *need; need++) {
        int j = feature_index(plan, *need);
        unsigned long long k = j >= 0 ? atmo_product_key(plan, j, device, sources) : 0;
        h = fnv(h, &k, sizeof k);
    }
    return h;
}

/* The feature owns a buffer that holds one camera and sun (e.g. fast's sky-view LUT). */
static int follows_view(const atmo_plan *plan, int feature)
{
    for (int i = 0; i < plan->buffer_count; i++)
        if (plan->buffers[i].feature == feature && plan->buffers[i].follows_view)
            return 1;
    return 0;
}

/* A feature's buffers can be cached: it has passes, sources and data, and none of its buffers
 * follows the view unless its row names params (its key then covers the camera and the sun its
 * passes read: the terrain's sun-height map). */
static int cacheable(const atmo_plan *plan, int feature)
{
    int passes = 0, data = 0;
    for (int i = 0; i < plan->pass_count; i++)
        passes += plan->passes[i].feature == feature;
    for (int i = 0; i < plan->buffer_count; i++)
        if (plan->buffers[i].feature == feature)
            data += plan->buffers[i].bytes > 0;
    const atmo_feature *f = plan->features[feature];
    return passes > 0 && data > 0 && f->sources != NULL &&
           (!follows_view(plan, feature) || f->params != NULL);
}

/* The feature's buffers in plan order (indices into plan->buffers); returns their count. */
static int feature_buffers(const atmo_plan *plan, int feature, int out[ATMO_PLAN_MAX_BUFFERS])
{
    int n = 0;
    for (int i = 0; i < plan->buffer_count; i++)
        if (plan->buffers[i].feature == feature && plan->buffers[i].bytes > 0)
            out[n++] = i;
    return n;
}

/* Fill a feature's buffers from its cache file (atmo/cache_file.h; payload: uint32 count, uint64
 * size of each buffer, the buffers' bytes): 0 loaded, 1 no file, -1 damaged (warned and
 * deleted), -2 an OpenCL error. Nothing is written to a buffer unless all of it verifies. */
static int cache_load(atmo_cl *cl, const atmo_plan *plan, int feature, unsigned long long key,
                      const char *path, cl_mem buffers[])
{
    void *payload = NULL;
    size_t bytes = 0;
    uint64_t file_key = key;
    int rc = atmo_cache_file_read(path, plan->features[feature]->name, &file_key,
                                  sizeof file_key, &payload, &bytes);
    if (rc)
        return rc;
    int idx[ATMO_PLAN_MAX_BUFFERS], n = feature_buffers(plan, feature, idx);
    uint32_t count = 0;
    size_t want = sizeof count + sizeof(uint64_t) * (size_t)n;
    const unsigned char *p = payload;
    if (bytes >= sizeof count)
        memcpy(&count, p, sizeof count);
    int same = count == (uint32_t)n && bytes >= want;
    for (int i = 0; i < n && same; i++) {
        uint64_t size;
        memcpy(&size, p + sizeof count + sizeof size * (size_t)i, sizeof size);
        same = size == plan->buffers[idx[i]].bytes;
        want += plan->buffers[idx[i]].bytes;
    }
    if (!same || bytes != want) {
        atmo_cache_file_reject(path, "its buffers do not match the plan's");
        free(payload);
        return -1;
    }
    p += sizeof count + sizeof(uint64_t) * (size_t)n;
    for (int i = 0; i < n && rc == 0; i++) {
        size_t size = plan->buffers[idx[i]].bytes;
        if (clEnqueueWriteBuffer(cl->queue, buffers[idx[i]], CL_TRUE, 0, size, p, 0, NULL,
                                 NULL) != CL_SUCCESS)
            rc = -2;
        p += size;
    }
    free(payload);
    return rc;
}

/* Read a feature's buffers back into one cache payload (layout as cache_load's), checking that
 * every float in them is finite: a table with NaN or Inf is an error naming it, never stored. */
static int read_feature(atmo_cl *cl, const atmo_plan *plan, int feature, cl_mem buffers[],
                        unsigned char **payload, size_t *bytes, atmo_err *e)
{
    int idx[ATMO_PLAN_MAX_BUFFERS], n = feature_buffers(plan, feature, idx);
    uint32_t count = (uint32_t)n;
    size_t total = sizeof count + sizeof(uint64_t) * (size_t)n;
    for (int i = 0; i < n; i++)
        total += plan->buffers[idx[i]].bytes;
    unsigned char *data = malloc(total), *p = data;
    if (!data)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading back %s",
                         plan->features[feature]->name);
    memcpy(p, &count, sizeof count);
    p += sizeof count;
    for (int i = 0; i < n; i++, p += sizeof(uint64_t)) {
        uint64_t size = plan->buffers[idx[i]].bytes;
        memcpy(p, &size, sizeof size);
    }
    for (int i = 0; i < n; i++) {
        const atmo_plan_buffer *b = &plan->buffers[idx[i]];
        cl_int err = clEnqueueReadBuffer(cl->queue, buffers[idx[i]], CL_TRUE, 0, b->bytes, p, 0,
                                         NULL, NULL);
        if (err != CL_SUCCESS) {
            free(data);
            return atmo_cl_fail(e, "clEnqueueReadBuffer(precomputed)", err);
        }
        long at = strncmp(b->type, "float", 5) == 0
                      ? atmo_first_nonfinite_float((const float *)(const void *)p,
                                                   b->bytes / sizeof(float))
                      : -1;
        if (at >= 0) {
            free(data);
            return atmo_fail(e, ATMO_ERR_RUNTIME,
                             "precomputed %s (feature %s) has a non-finite value at float %ld of "
                             "%zu; it is not cached or used (a bug: please report the scene)",
                             b->name, plan->features[feature]->name, at,
                             b->bytes / sizeof(float));
        }
        p += b->bytes;
    }
    *payload = data;
    *bytes = total;
    return ATMO_OK;
}

/* Whether the control stops the work before the next launch (and says so in e). */
static int cancelled(const atmo_precompute_control *control, const char *kernel, atmo_err *e)
{
    if (!control || !atmo_cancel_requested(control->cancel))
        return ATMO_OK;
    return atmo_fail(e, ATMO_INTERRUPTED_EMPTY,
                     "interrupted during the precompute (%s); nothing was rendered or cached",
                     kernel);
}

/* One pass, in slices of whole work-group slabs along its last dimension (rows of a 2-D pass,
 * layers of a 3-D one) placed by the global work offset, so each work item computes exactly
 * what it does in a single launch. With a control, each slice is waited for and timed and the
 * next one holds as many slabs as fit launch_budget_ms at the measured rate (at most twice the
 * last, like the render batches), and the cancel token is checked before every slice. */
static int run_pass(atmo_cl *cl, cl_program program, const atmo_plan *plan, cl_mem scene,
                    cl_mem buffers[], const atmo_plan_pass *pass,
                    const atmo_precompute_control *control, atmo_err *e)
{
    cl_int err;
    int rc = cancelled(control, pass->kernel, e);
    if (rc)
        return rc;
    cl_kernel k = clCreateKernel(program, pass->kernel, &err);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clCreateKernel(precompute)", err);
    int next = 0;
    err = clSetKernelArg(k, 0, sizeof scene, &scene);
    if (err != CL_SUCCESS)
        rc = atmo_cl_fail(e, "clSetKernelArg(precompute)", err);
    else if ((next = atmo_bind_buffers(k, 1, plan, buffers, e)) < 0)
        rc = ATMO_ERR_RUNTIME;
    else if ((err = clSetKernelArg(k, (cl_uint)next, sizeof pass->arg, &pass->arg)) != CL_SUCCESS)
        rc = atmo_cl_fail(e, "clSetKernelArg(precompute)", err);
    int three_d = pass->depth > 1, last = three_d ? 2 : 1;
    size_t local[3] = {three_d ? 4 : 8, three_d ? 4 : 8, three_d ? 4 : 1};
    size_t global[3] = {pad_to(pass->width, local[0]), pad_to(pass->height, local[1]),
                        pad_to(pass->depth, local[2])};
    size_t slabs = global[last] / local[last], per = 1;
    int sliced = control && control->launch_budget_ms > 0.0;
    if (!sliced)
        per = slabs;
    for (size_t first = 0; !rc && first < slabs;) {
        size_t n = per < slabs - first ? per : slabs - first;
        size_t offset[3] = {0, 0, 0}, size[3] = {global[0], global[1], global[2]};
        offset[last] = first * local[last];
        size[last] = n * local[last];
        double t0 = atmo_now_seconds();
        err = clEnqueueNDRangeKernel(cl->queue, k, three_d ? 3 : 2, offset, size, local, 0, NULL,
                                     NULL);
        if (err != CL_SUCCESS) {
            rc = atmo_cl_fail(e, pass->kernel, err);
            break;
        }
        first += n;
        if (!sliced)
            continue;
        if ((err = clFinish(cl->queue)) != CL_SUCCESS) {
            rc = atmo_cl_fail(e, "clFinish(precompute)", err);
            break;
        }
        double ms = 1e3 * (atmo_now_seconds() - t0);
        double fit = (double)n * control->launch_budget_ms / (ms > 1e-3 ? ms : 1e-3);
        per = fit > 2.0 * (double)n ? 2 * n : fit < 1.0 ? 1 : (size_t)fit;
        if (control->max_slabs > 0 && per > (size_t)control->max_slabs)
            per = (size_t)control->max_slabs;
        if (first < slabs)
            rc = cancelled(control, pass->kernel, e);
    }
    clReleaseKernel(k);
    return rc;
}

/* One feature's buffers: loaded from its cache file under dir (NULL: no cache) where one
 * verifies, else computed by its passes, checked for non-finite values and, with store, written
 * to the cache when they took long enough (or the file was damaged, or cache_luts is 2). */
static int precompute_feature(atmo_cl *cl, cl_program program, const atmo_plan *plan,
                              cl_mem scene, cl_mem buffers[], int f,
                              const atmo_precompute_control *control, const char *dir, int store,
                              atmo_precompute_info *info, atmo_err *e)
{
    atmo_device_identity device = {cl->device_name, cl->device_vendor, cl->driver_version};
    int cached = dir && cacheable(plan, f), damaged = 0, rc;
    unsigned long long key = 0;
    char path[1200];
    cl_int err;
    if (cached) {
        key = atmo_product_key(plan, f, &device, atmo_kernel_sources);
        snprintf(path, sizeof path, "%s/%s-%016llx.bin", dir, plan->features[f]->name, key);
        int loaded = cache_load(cl, plan, f, key, path, buffers);
        if (loaded == -2)
            return atmo_fail(e, ATMO_ERR_RUNTIME, "clEnqueueWriteBuffer(cached %s) failed",
                             plan->features[f]->name);
        if (loaded == 0) {
            info->loaded++;
            return ATMO_OK;
        }
        if (loaded == -1) {
            info->damaged++;
            damaged = 1;
        }
    }
    double tf = atmo_now_seconds();
    for (int p = 0; p < plan->pass_count; p++)
        if (plan->passes[p].feature == f &&
            (rc = run_pass(cl, program, plan, scene, buffers, &plan->passes[p], control, e)))
            return rc;
    if ((err = clFinish(cl->queue)) != CL_SUCCESS)
        return atmo_cl_fail(e, "clFinish(precompute)", err);
    if (!cacheable(plan, f))
        return ATMO_OK;
    info->computed++;
    store = store && cached &&
            (damaged || plan->cache_luts == 2 ||
             atmo_now_seconds() - tf > ATMO_LUT_CACHE_MIN_SECONDS);
    unsigned char *payload = NULL;
    size_t bytes = 0;
    if ((rc = read_feature(cl, plan, f, buffers, &payload, &bytes, e)))
        return rc;
    uint64_t file_key = key;
    if (store)
        atmo_cache_file_write(path, plan->features[f]->name, &file_key, sizeof file_key, payload,
                              bytes);
    free(payload);
    return ATMO_OK;
}

int atmo_bind_buffers(cl_kernel k, int first_arg, const atmo_plan *plan,
                      cl_mem buffers[ATMO_PLAN_MAX_BUFFERS], atmo_err *e)
{
    for (int i = 0; i < plan->buffer_count; i++) {
        cl_int err = clSetKernelArg(k, (cl_uint)(first_arg + i), sizeof buffers[i], &buffers[i]);
        if (err != CL_SUCCESS) {
            atmo_cl_fail(e, "clSetKernelArg(buffer)", err);
            return -1;
        }
    }
    return first_arg + plan->buffer_count;
}

void atmo_release_buffers(cl_mem buffers[ATMO_PLAN_MAX_BUFFERS])
{
    for (int i = ATMO_PLAN_MAX_BUFFERS - 1; i >= 0; i--)
        if (buffers[i]) {
            clReleaseMemObject(buffers[i]);
            buffers[i] = NULL;
        }
}

int atmo_precompute(atmo_cl *cl, cl_program program, const atmo_plan *plan, cl_mem scene,
                    cl_mem buffers[ATMO_PLAN_MAX_BUFFERS], atmo_precompute_info *info,
                    atmo_err *e)
{
    return atmo_precompute_controlled(cl, program, plan, scene, buffers, NULL, info, e);
}

int atmo_precompute_controlled(atmo_cl *cl, cl_program program, const atmo_plan *plan,
                               cl_mem scene, cl_mem buffers[ATMO_PLAN_MAX_BUFFERS],
                               const atmo_precompute_control *control,
                               atmo_precompute_info *info, atmo_err *e)
{
    double t0 = atmo_now_seconds();
    cl_int err;
    int rc, cacheables = 0;
    char dir[1024];
    int use_cache = plan->cache_luts && atmo_cache_dir(dir, sizeof dir) == 0;
    memset(info, 0, sizeof *info);
    for (int i = 0; i < ATMO_PLAN_MAX_BUFFERS; i++)
        buffers[i] = NULL;
    for (int i = 0; i < plan->buffer_count; i++) {
        const atmo_plan_buffer *b = &plan->buffers[i];
        buffers[i] = clCreateBuffer(cl->context, CL_MEM_READ_WRITE, b->bytes ? b->bytes : 16, NULL,
                                    &err);
        if (err != CL_SUCCESS)
            return atmo_cl_fail(e, "clCreateBuffer(buffer)", err);
        if (b->host_data && (err = clEnqueueWriteBuffer(cl->queue, buffers[i], CL_FALSE, 0,
                                                        b->bytes, b->host_data, 0, NULL,
                                                        NULL)) != CL_SUCCESS)
            return atmo_cl_fail(e, "clEnqueueWriteBuffer(table)", err);
        /* every other buffer starts as zeros: parts a scene's passes never write (lut's scratch
         * with one order) are then defined, so a cached product is the same on every run */
        static const unsigned char zero = 0;
        if (!b->host_data && (err = clEnqueueFillBuffer(cl->queue, buffers[i], &zero, 1, 0,
                                                        b->bytes ? b->bytes : 16, 0, NULL,
                                                        NULL)) != CL_SUCCESS)
            return atmo_cl_fail(e, "clEnqueueFillBuffer(buffer)", err);
    }
    for (int f = 0; f < plan->feature_count; f++)
        if ((rc = precompute_feature(cl, program, plan, scene, buffers, f, control,
                                     use_cache ? dir : NULL, 1, info, e)))
            return rc;
    err = clFinish(cl->queue);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clFinish(precompute)", err);
    for (int f = 0; f < plan->feature_count; f++)
        cacheables += cacheable(plan, f);
    info->cache_hit = cacheables > 0 && info->loaded == cacheables;
    info->seconds = atmo_now_seconds() - t0;
    return ATMO_OK;
}

int atmo_precompute_view(atmo_cl *cl, cl_program program, const atmo_plan *plan, cl_mem scene,
                         cl_mem buffers[ATMO_PLAN_MAX_BUFFERS],
                         const atmo_precompute_control *control, double *seconds, atmo_err *e)
{
    double t0 = atmo_now_seconds();
    char dir[1024];
    int use_cache = plan->cache_luts && atmo_cache_dir(dir, sizeof dir) == 0;
    atmo_precompute_info info;
    memset(&info, 0, sizeof info);
    for (int f = 0; f < plan->feature_count; f++) {
        int rc = follows_view(plan, f)
                     ? precompute_feature(cl, program, plan, scene, buffers, f, control,
                                          use_cache ? dir : NULL, 0, &info, e)
                     : ATMO_OK;
        if (rc)
            return rc;
    }
    cl_int err = clFinish(cl->queue);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clFinish(precompute)", err);
    *seconds = atmo_now_seconds() - t0;
    return ATMO_OK;
}
