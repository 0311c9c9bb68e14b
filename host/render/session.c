/* session.c — render sessions (atmo/session.h): device, program and precomputed data opened
 * once, an image accumulated in budgeted steps, view updates that rerun only the passes that
 * follow the view.
 *
 * Launches: the scheduler (atmo/tiles.h) picks a rectangle of tiles and a batch; it is launched
 * with one fixed 8 x 8 local size, its global size padded to it (the kernel bounds-checks); the
 * step waits for it (clFinish) before timing it, calling the tile callback and checking the
 * cancel token, so a cancel takes effect after the launch in flight. The precompute passes run the same
 * way, in slices of about one launch budget with the token checked between them (precompute.c);
 * a precompute that the token stops leaves the session without its data: it returns
 * ATMO_INTERRUPTED_EMPTY, and steps and reads are refused until set_view or set_scene completes.
 *
 * Device memory: right after the device is opened, before the build and the precompute, the
 * accumulation buffers (two of width x height float4) and the plan's buffers are checked
 * against CL_DEVICE_MAX_MEM_ALLOC_SIZE (each) and CL_DEVICE_GLOBAL_MEM_SIZE (all together),
 * so an image the device cannot hold is refused (ATMO_ERR_USAGE, the limit named) before any
 * work. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/clock.h"
#include "atmo/render.h"
#include "atmo/session.h"

#define SESSION_LOCAL_SIZE 8

struct atmo_session {
    atmo_cl cl;
    int cl_open;
    cl_program program;
    cl_kernel render;
    cl_mem scene, buffers[ATMO_PLAN_MAX_BUFFERS]; /* the plan's named buffers, in plan order */
    cl_mem accum, accum_sq, nonfinite; /* created at the first step or read */
    cl_mem passes; /* the render passes' sums (plan.pass_planes planes), or none */
    double noise;  /* the noise target, 0 for none */
    atmo_plan plan;
    atmo_render_settings settings;
    atmo_tiles tiles;
    atmo_session_info info;
    double progress_start, progress_last;
    int data_incomplete; /* an interrupted precompute: 1 the view's passes, 2 all passes */
    double rate_start, rate_start_done; /* after the first launch: the rate's origin, or -1 */
};

void atmo_render_settings_default(atmo_render_settings *s)
{
    memset(s, 0, sizeof *s);
    s->tile_size = 64;
    s->launch_budget_ms = 100.0;
    s->use_kernel_cache = 1;
}

void atmo_cancel_request(atmo_cancel *c) { c->requested = 1; }
void atmo_cancel_clear(atmo_cancel *c) { c->requested = 0; }
int atmo_cancel_requested(const atmo_cancel *c) { return c && c->requested; }

static size_t round_up(int n, int m) { return (size_t)((n + m - 1) / m * m); }

/* Progress on stderr: a bar redrawn in place on a terminal, a line every few seconds otherwise. */
static void report_progress(atmo_session *s, int target, int finished)
{
    double t = atmo_now_seconds();
    int mode = s->settings.progress;
    if (!mode)
        return;
    double done = 0.0, total = 0.0;
    for (int i = 0; i < s->tiles.count; i++) {
        atmo_tile tile;
        atmo_tiles_get(&s->tiles, i, &tile);
        int n = s->tiles.converged[i] ? target : tile.samples; /* converged: met the noise target */
        done += (double)(n < target ? n : target) * tile.w * tile.h;
        total += (double)target * tile.w * tile.h;
    }
    /* The first launch carries one-time costs (the driver finishing the kernel's compilation,
     * the first batch size): the ETA is the rate measured from its end, none before that. */
    if (s->rate_start < 0.0) {
        s->rate_start = t;
        s->rate_start_done = done;
    }
    if (!finished && t - s->progress_last < (mode == 2 ? 0.2 : 5.0))
        return;
    s->progress_last = t;
    double f = total > 0 ? done / total : 1.0;
    double elapsed = t - s->progress_start, measured = done - s->rate_start_done;
    char eta[32] = "ETA --";
    if (finished)
        snprintf(eta, sizeof eta, "ETA 0.0s");
    else if (measured > 0.0 && t > s->rate_start)
        snprintf(eta, sizeof eta, "ETA %.1fs", (total - done) * (t - s->rate_start) / measured);
    if (mode == 2) {
        char bar[41];
        int n = (int)(f * 40.0);
        for (int i = 0; i < 40; i++)
            bar[i] = i < n ? '#' : '.';
        bar[40] = 0;
        fprintf(stderr, "\rrender [%s] %5.1f%%  %.1fs elapsed  %s ", bar, 100.0 * f, elapsed,
                eta);
        if (finished)
            fputc('\n', stderr);
    } else {
        fprintf(stderr, "render: %.1f%% done, %.1fs elapsed, %s\n", 100.0 * f, elapsed, eta);
    }
}

int atmo_session_bind(const atmo_session *s, cl_kernel k, cl_uint *arg, atmo_err *e)
{
    cl_int err = clSetKernelArg(k, *arg, sizeof s->scene, &s->scene);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clSetKernelArg(scene)", err);
    int next = atmo_bind_buffers(k, (int)*arg + 1, &s->plan, (cl_mem *)s->buffers, e);
    if (next < 0)
        return ATMO_ERR_RUNTIME;
    *arg = (cl_uint)next;
    return ATMO_OK;
}

static atmo_precompute_control precompute_control(const atmo_session *s)
{
    atmo_precompute_control c = {s->settings.launch_budget_ms, 0, s->settings.cancel};
    return c;
}

/* Upload the plan's scene struct, then every precompute pass (LUTs from the cache if keyed). */
static int precompute_all(atmo_session *s, atmo_err *e)
{
    cl_int err = clEnqueueWriteBuffer(s->cl.queue, s->scene, CL_TRUE, 0, sizeof s->plan.gpu,
                                      &s->plan.gpu, 0, NULL, NULL);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clEnqueueWriteBuffer(scene)", err);
    atmo_release_buffers(s->buffers);
    atmo_precompute_info pi;
    atmo_precompute_control control = precompute_control(s);
    int rc = atmo_precompute_controlled(&s->cl, s->program, &s->plan, s->scene, s->buffers,
                                        &control, &pi, e);
    s->data_incomplete = rc != ATMO_OK ? 2 : 0;
    if (rc)
        return rc;
    s->info.seconds_precompute += pi.seconds;
    s->info.lut_cache_hit = pi.cache_hit;
    return ATMO_OK;
}

/* The render passes' buffer (created once) cleared: plan.pass_planes planes of `plane` bytes. */
static cl_int restart_passes(atmo_session *s, size_t plane)
{
    cl_int err = CL_SUCCESS;
    size_t bytes = plane * (size_t)s->plan.pass_planes;
    if (!s->passes)
        s->passes = clCreateBuffer(s->cl.context, CL_MEM_READ_WRITE, bytes, NULL, &err);
    float zero4[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    if (err == CL_SUCCESS)
        err = clEnqueueFillBuffer(s->cl.queue, s->passes, zero4, sizeof zero4, 0, bytes, 0, NULL,
                                  NULL);
    return err;
}

/* The render kernel's buffers: accumulators created (once) and cleared, counts to zero. */
static int restart(atmo_session *s, atmo_err *e)
{
    cl_int err = CL_SUCCESS;
    size_t bytes = (size_t)s->plan.width * (size_t)s->plan.height * 4 * sizeof(float);
    if (!s->accum)
        s->accum = clCreateBuffer(s->cl.context, CL_MEM_READ_WRITE, bytes, NULL, &err);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clCreateBuffer(accumulation image)", err);
    if (!s->accum_sq)
        s->accum_sq = clCreateBuffer(s->cl.context, CL_MEM_READ_WRITE, bytes, NULL, &err);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clCreateBuffer(second moments)", err);
    if (!s->nonfinite)
        s->nonfinite = clCreateBuffer(s->cl.context, CL_MEM_READ_WRITE, sizeof(cl_uint), NULL,
                                      &err);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clCreateBuffer(counter)", err);
    float zero4[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    cl_uint zero = 0;
    err = clEnqueueFillBuffer(s->cl.queue, s->accum, zero4, sizeof zero4, 0, bytes, 0, NULL, NULL);
    if (err == CL_SUCCESS)
        err = clEnqueueFillBuffer(s->cl.queue, s->accum_sq, zero4, sizeof zero4, 0, bytes, 0,
                                  NULL, NULL);
    if (err == CL_SUCCESS)
        err = clEnqueueWriteBuffer(s->cl.queue, s->nonfinite, CL_TRUE, 0, sizeof zero, &zero, 0,
                                   NULL, NULL);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clear accumulation image", err);
    if (s->plan.pass_planes > 0 && (err = restart_passes(s, bytes)) != CL_SUCCESS)
        return atmo_cl_fail(e, "create and clear the render passes", err);
    atmo_tiles_reset(&s->tiles);
    s->info.nonfinite = 0;
    s->progress_start = atmo_now_seconds();
    s->rate_start = -1.0;
    return ATMO_OK;
}

/* The render kernel's arguments that stay for a whole session (until set_scene's new LUTs). */
static int bind_render(atmo_session *s, atmo_err *e)
{
    cl_uint arg = 0;
    int rc = atmo_session_bind(s, s->render, &arg, e);
    if (rc)
        return rc;
    cl_int err = clSetKernelArg(s->render, arg++, sizeof s->accum, &s->accum);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(s->render, arg++, sizeof s->accum_sq, &s->accum_sq);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(s->render, arg++, sizeof s->nonfinite, &s->nonfinite);
    if (err == CL_SUCCESS && s->passes)
        err = clSetKernelArg(s->render, arg, sizeof s->passes, &s->passes);
    return err == CL_SUCCESS ? ATMO_OK : atmo_cl_fail(e, "clSetKernelArg(sky_render)", err);
}

static double gib(cl_ulong bytes) { return (double)bytes / (1024.0 * 1024.0 * 1024.0); }

/* Refuse a plan whose buffers this device cannot allocate, naming the limit. */
static int check_device_memory(const atmo_session *s, atmo_err *e)
{
    cl_ulong max_alloc = 0;
    cl_int err = clGetDeviceInfo(s->cl.device, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof max_alloc,
                                 &max_alloc, NULL);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clGetDeviceInfo(CL_DEVICE_MAX_MEM_ALLOC_SIZE)", err);
    cl_ulong image = (cl_ulong)s->plan.width * (cl_ulong)s->plan.height * 4 * sizeof(float);
    cl_ulong total = (2 + (cl_ulong)s->plan.pass_planes) * image + sizeof s->plan.gpu +
                     sizeof(cl_uint);
    if (image > max_alloc)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "a %dx%d image needs %.2f GiB per accumulation buffer, more than the "
                         "largest buffer %s can allocate (CL_DEVICE_MAX_MEM_ALLOC_SIZE = %.2f "
                         "GiB); render fewer pixels",
                         s->plan.width, s->plan.height, gib(image), s->cl.device_name,
                         gib(max_alloc));
    for (int i = 0; i < s->plan.buffer_count; i++) {
        const atmo_plan_buffer *b = &s->plan.buffers[i];
        if (b->bytes > max_alloc)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "buffer '%s' needs %.2f GiB, more than the largest buffer %s can "
                             "allocate (CL_DEVICE_MAX_MEM_ALLOC_SIZE = %.2f GiB)",
                             b->name, gib(b->bytes), s->cl.device_name, gib(max_alloc));
        total += b->bytes;
    }
    if (total > s->cl.global_memory)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "a %dx%d image and its data need %.2f GiB of device memory, more than "
                         "%s has (CL_DEVICE_GLOBAL_MEM_SIZE = %.2f GiB); render fewer pixels",
                         s->plan.width, s->plan.height, gib(total), s->cl.device_name,
                         gib(s->cl.global_memory));
    return ATMO_OK;
}

int atmo_session_open(atmo_session **out, const atmo_plan *plan, const atmo_render_settings *rs,
                      atmo_err *e)
{
    int rc;
    cl_int err;
    atmo_session *s = calloc(1, sizeof *s);
    *out = NULL;
    if (!s)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for a render session");
    s->plan = *plan;
    s->settings = *rs;
    if ((rc = atmo_tiles_init_part(&s->tiles, plan->width, plan->height, rs->tile_size, rs->part,
                                    rs->parts, e)))
        goto cleanup;
    double t0 = atmo_now_seconds();
    if ((rc = atmo_cl_open(&s->cl, rs->device, e)))
        goto cleanup;
    s->cl_open = 1;
    snprintf(s->info.device_name, sizeof s->info.device_name, "%s", s->cl.device_name);
    snprintf(s->info.platform_name, sizeof s->info.platform_name, "%s", s->cl.platform_name);
    snprintf(s->info.driver_version, sizeof s->info.driver_version, "%s", s->cl.driver_version);
    s->info.seconds_device = atmo_now_seconds() - t0;
    if ((rc = check_device_memory(s, e)))
        goto cleanup;

    const char *texts[ATMO_PLAN_MAX_FRAGMENTS];
    atmo_plan_fragment_texts(plan, texts);
    atmo_cl_build_options bo = {plan->fragments, plan->fragment_count, plan->defines,
                                rs->dump_dir, rs->use_kernel_cache, NULL, plan->prelude, texts};
    atmo_cl_build_info bi;
    if ((rc = atmo_cl_build(&s->cl, &bo, &s->program, &bi, e)))
        goto cleanup;
    s->info.kernel_cache_hit = bi.cache_hit;
    s->info.seconds_build = bi.seconds;
    s->render = clCreateKernel(s->program, plan->render_kernel, &err);
    if (err != CL_SUCCESS) {
        char call[96];
        snprintf(call, sizeof call, "clCreateKernel(%s)", plan->render_kernel);
        rc = atmo_cl_fail(e, call, err);
        goto cleanup;
    }
    s->scene = clCreateBuffer(s->cl.context, CL_MEM_READ_ONLY, sizeof plan->gpu, NULL, &err);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "clCreateBuffer(scene)", err);
        goto cleanup;
    }
    if ((rc = precompute_all(s, e)))
        goto cleanup;
    *out = s;
    return ATMO_OK;
cleanup:
    atmo_session_close(s);
    return rc;
}

void atmo_session_close(atmo_session *s)
{
    if (!s)
        return;
    if (s->passes)
        clReleaseMemObject(s->passes);
    if (s->nonfinite)
        clReleaseMemObject(s->nonfinite);
    if (s->accum_sq)
        clReleaseMemObject(s->accum_sq);
    if (s->accum)
        clReleaseMemObject(s->accum);
    atmo_release_buffers(s->buffers);
    if (s->scene)
        clReleaseMemObject(s->scene);
    if (s->render)
        clReleaseKernel(s->render);
    if (s->program)
        clReleaseProgram(s->program);
    if (s->cl_open)
        atmo_cl_close(&s->cl);
    atmo_tiles_free(&s->tiles);
    free(s);
}

static int incomplete(atmo_err *e)
{
    return atmo_fail(e, ATMO_ERR_USAGE,
                     "the session's precompute was interrupted; set its view or scene again "
                     "before rendering");
}

/* One launch of the render kernel over a tile's batch, waited for. */
static int launch(atmo_session *s, const atmo_tile *t, atmo_err *e)
{
    cl_uint begin = (cl_uint)t->sample_begin, count = (cl_uint)t->sample_count;
    cl_uint arg = 1 + (cl_uint)s->plan.buffer_count + 3 + (s->passes ? 1 : 0);
    cl_int err = clSetKernelArg(s->render, arg++, sizeof(int), &t->x);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(s->render, arg++, sizeof(int), &t->y);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(s->render, arg++, sizeof(int), &t->w);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(s->render, arg++, sizeof(int), &t->h);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(s->render, arg++, sizeof begin, &begin);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(s->render, arg, sizeof count, &count);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clSetKernelArg(sky_render)", err);
    size_t local[2] = {SESSION_LOCAL_SIZE, SESSION_LOCAL_SIZE};
    size_t global[2] = {round_up(t->w, SESSION_LOCAL_SIZE), round_up(t->h, SESSION_LOCAL_SIZE)};
    err = clEnqueueNDRangeKernel(s->cl.queue, s->render, 2, NULL, global, local, 0, NULL, NULL);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clEnqueueNDRangeKernel(render)", err);
    err = clFinish(s->cl.queue);
    return err == CL_SUCCESS ? ATMO_OK : atmo_cl_fail(e, "clFinish(render)", err);
}

/* The relative standard error of tile t from its sums (atmo/session.h's noise target). */
static int tile_error(atmo_session *s, const atmo_tile *t, double *rse, atmo_err *e)
{
    size_t row = (size_t)s->plan.width * 4 * sizeof(float), n = (size_t)t->w * t->h * 4;
    float *s1 = malloc(2 * n * sizeof(float)), *s2 = s1 + n;
    if (!s1)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for a tile");
    size_t origin[3] = {(size_t)t->x * 4 * sizeof(float), (size_t)t->y, 0};
    size_t region[3] = {(size_t)t->w * 4 * sizeof(float), (size_t)t->h, 1};
    size_t zero[3] = {0, 0, 0};
    cl_int err = clEnqueueReadBufferRect(s->cl.queue, s->accum, CL_TRUE, origin, zero, region,
                                         row, 0, region[0], 0, s1, 0, NULL, NULL);
    if (err == CL_SUCCESS)
        err = clEnqueueReadBufferRect(s->cl.queue, s->accum_sq, CL_TRUE, origin, zero, region,
                                      row, 0, region[0], 0, s2, 0, NULL, NULL);
    if (err != CL_SUCCESS) {
        free(s1);
        return atmo_cl_fail(e, "clEnqueueReadBufferRect(tile)", err);
    }
    double k = t->samples, var = 0.0, mean = 0.0;
    for (size_t i = 0; i < n; i += 4)
        for (int c = 0; c < 3; c++) {
            double a = s1[i + c], b = s2[i + c];
            var += fmax(b - a * a / k, 0.0) / (k * (k - 1.0));
            mean += a / k;
        }
    free(s1);
    *rse = mean > 0.0 ? sqrt(var / (double)(3 * n / 4)) / (mean / (double)(3 * n / 4)) : 0.0;
    return ATMO_OK;
}

int atmo_session_step(atmo_session *s, const atmo_step *step, atmo_step_status *status,
                      atmo_err *e)
{
    int rc = ATMO_OK;
    memset(status, 0, sizeof *status);
    if (s->data_incomplete)
        return incomplete(e);
    if (!s->accum && ((rc = restart(s, e)) || (rc = bind_render(s, e))))
        return rc;
    int target = step->samples > 0 ? step->samples : s->plan.samples;
    double t0 = atmo_now_seconds();
    s->tiles.checkpoints = s->noise > 0.0;
    atmo_tile t;
    while (!atmo_cancel_requested(step->cancel)) {
        if (!atmo_tiles_next(&s->tiles, target, &t)) {
            status->complete = 1;
            break;
        }
        if (status->launches > 0 && step->budget_seconds > 0.0 &&
            atmo_now_seconds() - t0 >= step->budget_seconds)
            break;
        double tl = atmo_now_seconds();
        if ((rc = launch(s, &t, e)))
            break;
        atmo_tiles_done(&s->tiles, &t, 1e3 * (atmo_now_seconds() - tl), s->settings.launch_budget_ms,
                        s->settings.max_batch, s->settings.max_tiles);
        status->launches++;
        s->info.launches++;
        /* each tile of the launch is judged on its own sums, as a launch of it alone would be */
        for (int r = 0; s->noise > 0.0 && atmo_tiles_is_checkpoint(t.samples) &&
                        r < t.tiles_down && !rc; r++)
            for (int c = 0; c < t.tiles_across && !rc; c++) {
                atmo_tile one;
                double rse = 0.0;
                atmo_tiles_get(&s->tiles, t.index + r * s->tiles.columns + c, &one);
                if ((rc = tile_error(s, &one, &rse, e)))
                    break;
                if (rse <= s->noise)
                    atmo_tiles_converge(&s->tiles, one.index);
            }
        if (rc)
            break;
        if (step->on_tile)
            step->on_tile(step->user, &t);
        report_progress(s, target, 0);
    }
    status->cancelled = !status->complete && atmo_cancel_requested(step->cancel);
    s->info.seconds_render += atmo_now_seconds() - t0;
    if (rc)
        return rc;
    if (status->complete || status->cancelled)
        report_progress(s, target, 1);
    cl_int err = clEnqueueReadBuffer(s->cl.queue, s->nonfinite, CL_TRUE, 0, sizeof(cl_uint),
                                     &s->info.nonfinite, 0, NULL, NULL);
    return err == CL_SUCCESS ? ATMO_OK : atmo_cl_fail(e, "clEnqueueReadBuffer(counter)", err);
}

/* A plan the session's program can render: same kernels, -D flags and image size. */
static int check_program(const atmo_session *s, const atmo_plan *p, atmo_err *e)
{
    int same = p->fragment_count == s->plan.fragment_count &&
               strcmp(p->defines, s->plan.defines) == 0 &&
               strcmp(p->prelude, s->plan.prelude) == 0 && p->width == s->plan.width &&
               p->height == s->plan.height;
    for (int i = 0; same && i < p->fragment_count; i++)
        same = strcmp(p->fragments[i], s->plan.fragments[i]) == 0;
    if (!same)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "the new plan needs other kernels or another image size than the "
                         "session's; open a new session for it");
    return ATMO_OK;
}

int atmo_session_set_view(atmo_session *s, const atmo_plan *plan, atmo_err *e)
{
    int rc = check_program(s, plan, e);
    if (rc)
        return rc;
    /* everything but the view must be the session's: the other LUTs stay as they are */
    atmo_gpu_scene g = plan->gpu;
    g.camera = s->plan.gpu.camera;
    g.sun_direction = s->plan.gpu.sun_direction;
    g.cloud.observer = s->plan.gpu.cloud.observer;
    g.clouds.origin = s->plan.gpu.clouds.origin; /* follows the camera (and the time) */
    int same = memcmp(&g, &s->plan.gpu, sizeof g) == 0 && plan->pass_count == s->plan.pass_count &&
               plan->buffer_count == s->plan.buffer_count;
    for (int i = 0; same && i < plan->buffer_count; i++) {
        const atmo_plan_buffer *n = &plan->buffers[i], *o = &s->plan.buffers[i];
        same = n->bytes == o->bytes && !n->host_data == !o->host_data;
        /* a host table is uploaded once, before the passes: one that depends on the camera
         * (the objects' camera-relative rows) needs the new plan's table, i.e. set_scene */
        if (same && n->host_data && n->host_data != o->host_data)
            same = memcmp(n->host_data, o->host_data, n->bytes) == 0;
    }
    if (!same)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "the new plan changes more than the camera and the sun; use "
                         "atmo_session_set_scene for it");
    s->plan.gpu = plan->gpu;
    cl_int err = clEnqueueWriteBuffer(s->cl.queue, s->scene, CL_TRUE, 0, sizeof s->plan.gpu,
                                      &s->plan.gpu, 0, NULL, NULL);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clEnqueueWriteBuffer(scene)", err);
    if (s->data_incomplete == 2) { /* the view-independent buffers are unfinished too */
        if ((rc = precompute_all(s, e)) || !s->accum || (rc = restart(s, e)))
            return rc;
        return bind_render(s, e);
    }
    double seconds;
    atmo_precompute_control control = precompute_control(s);
    rc = atmo_precompute_view(&s->cl, s->program, &s->plan, s->scene, s->buffers, &control,
                              &seconds, e);
    s->data_incomplete = rc != ATMO_OK;
    if (rc)
        return rc;
    s->info.seconds_precompute += seconds;
    return s->accum ? restart(s, e) : ATMO_OK;
}

int atmo_session_set_scene(atmo_session *s, const atmo_plan *plan, atmo_err *e)
{
    int rc = check_program(s, plan, e);
    if (rc)
        return rc;
    s->plan = *plan;
    if ((rc = precompute_all(s, e)))
        return rc;
    if (!s->accum)
        return ATMO_OK;
    if ((rc = restart(s, e)))
        return rc;
    return bind_render(s, e); /* the LUT buffers are new */
}

float atmo_session_mean(float sum, int samples)
{
    return sum * (samples > 0 ? 1.0f / (float)samples : 0.0f);
}

/* The accumulators mapped for reading, 4 floats per pixel (*s2 only when want_s2): mapped, not
 * copied, since on a CPU device the map is the device's own memory. Release with unmap. */
static int map_accumulators(atmo_session *s, const float **s1, const float **s2, int want_s2,
                            atmo_err *e)
{
    int rc = ATMO_OK;
    size_t bytes = (size_t)s->plan.width * (size_t)s->plan.height * 4 * sizeof(float);
    *s1 = *s2 = NULL;
    if (s->data_incomplete)
        return incomplete(e);
    if (!s->accum && ((rc = restart(s, e)) || (rc = bind_render(s, e))))
        return rc;
    cl_int err = CL_SUCCESS;
    *s1 = clEnqueueMapBuffer(s->cl.queue, s->accum, CL_TRUE, CL_MAP_READ, 0, bytes, 0, NULL, NULL,
                             &err);
    if (err == CL_SUCCESS && want_s2)
        *s2 = clEnqueueMapBuffer(s->cl.queue, s->accum_sq, CL_TRUE, CL_MAP_READ, 0, bytes, 0,
                                 NULL, NULL, &err);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clEnqueueMapBuffer(accumulation image)", err);
    return ATMO_OK;
}

/* Unmap what map_accumulators mapped; rc is the caller's status so far (kept if not OK). */
static int unmap_accumulators(atmo_session *s, const float *s1, const float *s2, int rc,
                              atmo_err *e)
{
    cl_int err = s2 ? clEnqueueUnmapMemObject(s->cl.queue, s->accum_sq, (void *)s2, 0, NULL, NULL)
                    : CL_SUCCESS;
    cl_int err1 = s1 ? clEnqueueUnmapMemObject(s->cl.queue, s->accum, (void *)s1, 0, NULL, NULL)
                     : CL_SUCCESS;
    err = err != CL_SUCCESS ? err : err1;
    if (err == CL_SUCCESS && s1)
        err = clFinish(s->cl.queue);
    if (err != CL_SUCCESS && rc == ATMO_OK)
        rc = atmo_cl_fail(e, "clEnqueueUnmapMemObject(accumulation image)", err);
    return rc;
}

int atmo_session_read(atmo_session *s, float *mean, float *se, int *samples, atmo_err *e)
{
    int W = s->plan.width, H = s->plan.height;
    double t0 = atmo_now_seconds();
    const float *s1, *s2;
    int rc = map_accumulators(s, &s1, &s2, se != NULL, e);
    for (int y = 0; !rc && y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = (size_t)y * W + x;
            int n = atmo_tiles_pixel_samples(&s->tiles, x, y);
            if (samples)
                samples[i] = n;
            for (int c = 0; c < 3; c++) {
                if (mean)
                    mean[3 * i + c] = atmo_session_mean(s1[4 * i + c], n);
                if (!se)
                    continue;
                double a = s1[4 * i + c], b = s2[4 * i + c];
                double ss = n > 1 ? b - a * a / n : 0.0; /* sum of squared deviations */
                se[3 * i + c] = n > 1 ? (float)sqrt(fmax(ss, 0.0) / ((double)n * (n - 1)))
                                      : FLT_MAX;
            }
        }
    rc = unmap_accumulators(s, s1, s2, rc, e);
    s->info.seconds_read += atmo_now_seconds() - t0;
    return rc;
}

int atmo_session_read_sums(atmo_session *s, float *s1, float *s2, int *samples, atmo_err *e)
{
    int W = s->plan.width, H = s->plan.height;
    const float *a, *b;
    int rc = map_accumulators(s, &a, &b, s2 != NULL, e);
    for (int y = 0; !rc && y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = (size_t)y * W + x;
            if (samples)
                samples[i] = atmo_tiles_pixel_samples(&s->tiles, x, y);
            for (int c = 0; c < 3; c++) {
                if (s1)
                    s1[3 * i + c] = a[4 * i + c];
                if (s2)
                    s2[3 * i + c] = b[4 * i + c];
            }
        }
    return unmap_accumulators(s, a, b, rc, e);
}

void atmo_session_set_noise_target(atmo_session *s, double noise) { s->noise = noise; }

int atmo_session_read_passes(atmo_session *s, float *out, atmo_err *e)
{
    int W = s->plan.width, H = s->plan.height;
    size_t floats = (size_t)W * H * 4 * (size_t)s->plan.pass_planes;
    if (s->plan.pass_planes == 0)
        return atmo_fail(e, ATMO_ERR_USAGE, "the session's plan has no render passes");
    if (s->data_incomplete)
        return incomplete(e);
    int rc;
    if (!s->accum && ((rc = restart(s, e)) || (rc = bind_render(s, e))))
        return rc;
    cl_int err = clEnqueueReadBuffer(s->cl.queue, s->passes, CL_TRUE, 0, floats * sizeof(float),
                                     out, 0, NULL, NULL);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clEnqueueReadBuffer(render passes)", err);
    for (int k = 0; k < s->plan.pass_planes; k++)
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                int n = atmo_tiles_pixel_samples(&s->tiles, x, y);
                float inv = n > 0 ? 1.0f / (float)n : 0.0f, *v = out + 4 * (((size_t)k * H + y) * W + x);
                for (int c = 0; c < 4; c++)
                    v[c] *= inv;
            }
    return ATMO_OK;
}

const atmo_session_info *atmo_session_get_info(const atmo_session *s) { return &s->info; }
const atmo_plan *atmo_session_plan(const atmo_session *s) { return &s->plan; }
atmo_cl *atmo_session_cl(atmo_session *s) { return &s->cl; }
cl_program atmo_session_program(const atmo_session *s) { return s->program; }

void atmo_session_samples(const atmo_session *s, int *min, int *max)
{
    atmo_tiles_range(&s->tiles, min, max);
}
