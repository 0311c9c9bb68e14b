/* render.c — device setup, precompute and the tile scheduler (atmo/render.h). */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "atmo/render.h"

#define ATMO_LOCAL_SIZE 8

static volatile sig_atomic_t render_stop_requested;

void atmo_render_interrupt(void) { render_stop_requested = 1; }
void atmo_render_clear_interrupt(void) { render_stop_requested = 0; }

void atmo_render_settings_default(atmo_render_settings *s)
{
    memset(s, 0, sizeof *s);
    s->tile_size = 64;
    s->launch_budget_ms = 100.0;
    s->use_kernel_cache = 1;
}

void atmo_render_result_free(atmo_render_result *r)
{
    free(r->rgb);
    r->rgb = NULL;
}

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static size_t round_up(int n, int m) { return (size_t)((n + m - 1) / m * m); }

/* Progress on stderr: a bar redrawn in place on a terminal, a line every few seconds otherwise. */
typedef struct progress {
    int mode;
    double start, last;
} progress;

static void report_progress(progress *p, double done, double total, int finished)
{
    double t = now_seconds();
    if (!p->mode || (!finished && t - p->last < (p->mode == 2 ? 0.2 : 5.0)))
        return;
    p->last = t;
    double f = total > 0 ? done / total : 1.0;
    double eta = f > 0 ? (t - p->start) * (1.0 - f) / f : 0.0;
    if (p->mode == 2) {
        char bar[41];
        int n = (int)(f * 40.0);
        for (int i = 0; i < 40; i++)
            bar[i] = i < n ? '#' : '.';
        bar[40] = 0;
        fprintf(stderr, "\rrender [%s] %5.1f%%  %.1fs elapsed  ETA %.1fs ", bar, 100.0 * f,
                t - p->start, eta);
        if (finished)
            fputc('\n', stderr);
    } else {
        fprintf(stderr, "render: %.1f%% done, %.1fs elapsed, ETA %.1fs\n", 100.0 * f,
                t - p->start, eta);
    }
}

#define CL_CHECK(call, what)                                                                       \
    do {                                                                                          \
        cl_int cl_check_err = (call);                                                                    \
        if (cl_check_err != CL_SUCCESS) {                                                                \
            rc = atmo_cl_fail(e, what, cl_check_err);                                                    \
            goto cleanup;                                                                         \
        }                                                                                         \
    } while (0)

int atmo_render(const atmo_plan *plan, const atmo_render_settings *settings,
                atmo_render_result *res, atmo_err *e)
{
    int rc = ATMO_OK;
    cl_int err;
    atmo_cl cl;
    cl_program program = NULL;
    cl_kernel k_render = NULL;
    cl_mem b_scene = NULL, b_accum = NULL, b_nonfinite = NULL,
           b_buffers[ATMO_PLAN_MAX_BUFFERS] = {NULL};
    float *accum = NULL;
    int *tile_samples = NULL;
    const atmo_gpu_scene *g = &plan->gpu;
    int W = plan->width, H = plan->height, ts = settings->tile_size;

    memset(res, 0, sizeof *res);
    res->width = W;
    res->height = H;
    res->samples_requested = plan->samples;

    double t0 = now_seconds();
    if ((rc = atmo_cl_open(&cl, settings->device, e)))
        return rc;
    snprintf(res->device_name, sizeof res->device_name, "%s", cl.device_name);
    snprintf(res->platform_name, sizeof res->platform_name, "%s", cl.platform_name);
    snprintf(res->driver_version, sizeof res->driver_version, "%s", cl.driver_version);
    res->seconds_device = now_seconds() - t0;

    atmo_cl_build_options bo = {plan->fragments, plan->fragment_count, plan->defines,
                                settings->dump_dir, settings->use_kernel_cache, NULL,
                                plan->prelude};
    atmo_cl_build_info bi;
    if ((rc = atmo_cl_build(&cl, &bo, &program, &bi, e)))
        goto cleanup;
    res->kernel_cache_hit = bi.cache_hit;
    res->seconds_build = bi.seconds;

    k_render = clCreateKernel(program, "sky_render", &err);
    CL_CHECK(err, "clCreateKernel(sky_render)");

    size_t pixels = (size_t)W * (size_t)H;
    b_scene = clCreateBuffer(cl.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof *g,
                             (void *)g, &err);
    CL_CHECK(err, "clCreateBuffer(scene)");
    atmo_precompute_info pi;
    if ((rc = atmo_precompute(&cl, program, plan, b_scene, b_buffers, &pi, e)))
        goto cleanup;
    res->seconds_precompute = pi.seconds;
    res->lut_cache_hit = pi.cache_hit;
    b_accum = clCreateBuffer(cl.context, CL_MEM_READ_WRITE, pixels * 4 * sizeof(float), NULL, &err);
    CL_CHECK(err, "clCreateBuffer(accumulation image)");
    cl_uint zero = 0;
    b_nonfinite = clCreateBuffer(cl.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                                 sizeof zero, &zero, &err);
    CL_CHECK(err, "clCreateBuffer(counter)");
    float zero4[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    CL_CHECK(clEnqueueFillBuffer(cl.queue, b_accum, zero4, sizeof zero4, 0,
                                 pixels * sizeof zero4, 0, NULL, NULL),
             "clEnqueueFillBuffer(accumulation image)");

    /* render: passes over the tiles, each launch a batch of samples of one tile */
    int tiles_x = (W + ts - 1) / ts, tiles_y = (H + ts - 1) / ts, tiles = tiles_x * tiles_y;
    tile_samples = calloc((size_t)tiles, sizeof *tile_samples);
    if (!tile_samples) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory");
        goto cleanup;
    }
    CL_CHECK(clSetKernelArg(k_render, 0, sizeof b_scene, &b_scene), "clSetKernelArg");
    int arg = atmo_bind_buffers(k_render, 1, plan, b_buffers, e); /* then sky_render's own */
    if (arg < 0) {
        rc = ATMO_ERR_RUNTIME;
        goto cleanup;
    }
    CL_CHECK(clSetKernelArg(k_render, arg, sizeof b_accum, &b_accum), "clSetKernelArg");
    CL_CHECK(clSetKernelArg(k_render, arg + 1, sizeof b_nonfinite, &b_nonfinite), "clSetKernelArg");

    progress prog = {settings->progress, now_seconds(), 0.0};
    double t2 = now_seconds();
    double total_work = (double)plan->samples * (double)pixels, done_work = 0.0;
    int batch = 1, spp = plan->samples;
    for (int pass_done = 0; !pass_done && !render_stop_requested;) {
        pass_done = 1;
        for (int t = 0; t < tiles && !render_stop_requested; t++) {
            int remaining = spp - tile_samples[t];
            if (remaining <= 0)
                continue;
            pass_done = 0;
            int tx = t % tiles_x * ts, ty = t / tiles_x * ts;
            int tw = W - tx < ts ? W - tx : ts, th = H - ty < ts ? H - ty : ts;
            cl_uint begin = (cl_uint)tile_samples[t];
            cl_uint count = (cl_uint)(batch < remaining ? batch : remaining);
            CL_CHECK(clSetKernelArg(k_render, arg + 2, sizeof(int), &tx), "clSetKernelArg");
            CL_CHECK(clSetKernelArg(k_render, arg + 3, sizeof(int), &ty), "clSetKernelArg");
            CL_CHECK(clSetKernelArg(k_render, arg + 4, sizeof(int), &tw), "clSetKernelArg");
            CL_CHECK(clSetKernelArg(k_render, arg + 5, sizeof(int), &th), "clSetKernelArg");
            CL_CHECK(clSetKernelArg(k_render, arg + 6, sizeof(cl_uint), &begin), "clSetKernelArg");
            CL_CHECK(clSetKernelArg(k_render, arg + 7, sizeof(cl_uint), &count), "clSetKernelArg");
            size_t local[2] = {ATMO_LOCAL_SIZE, ATMO_LOCAL_SIZE};
            size_t global[2] = {round_up(tw, ATMO_LOCAL_SIZE), round_up(th, ATMO_LOCAL_SIZE)};
            double tl = now_seconds();
            CL_CHECK(clEnqueueNDRangeKernel(cl.queue, k_render, 2, NULL, global, local, 0, NULL,
                                            NULL),
                     "clEnqueueNDRangeKernel(render)");
            CL_CHECK(clFinish(cl.queue), "clFinish(render)");
            double ms = 1e3 * (now_seconds() - tl);
            res->launches++;
            tile_samples[t] += (int)count;
            done_work += (double)count * tw * th;
            /* adapt the batch towards the budget, at most doubling per launch; full-size tiles
             * only, since edge tiles are cheaper and would overshoot */
            if (tw == ts && th == ts) {
                double target = (double)count * settings->launch_budget_ms / (ms > 1e-3 ? ms : 1e-3);
                int next = (int)target;
                next = next > 2 * batch ? 2 * batch : next;
                batch = next < 1 ? 1 : next;
                if (settings->max_batch > 0 && batch > settings->max_batch)
                    batch = settings->max_batch;
            }
            report_progress(&prog, done_work, total_work, 0);
        }
    }
    report_progress(&prog, done_work, total_work, 1);
    res->seconds_render = now_seconds() - t2;

    accum = malloc(pixels * 4 * sizeof(float));
    res->rgb = malloc(pixels * 3 * sizeof(float));
    if (!accum || !res->rgb) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for a %dx%d image", W, H);
        goto cleanup;
    }
    CL_CHECK(clEnqueueReadBuffer(cl.queue, b_accum, CL_TRUE, 0, pixels * 4 * sizeof(float), accum,
                                 0, NULL, NULL),
             "clEnqueueReadBuffer(accumulation image)");
    CL_CHECK(clEnqueueReadBuffer(cl.queue, b_nonfinite, CL_TRUE, 0, sizeof(cl_uint),
                                 &res->nonfinite, 0, NULL, NULL),
             "clEnqueueReadBuffer(counter)");
    res->samples_min = spp;
    res->samples_max = 0;
    for (int t = 0; t < tiles; t++) {
        res->samples_min = tile_samples[t] < res->samples_min ? tile_samples[t] : res->samples_min;
        res->samples_max = tile_samples[t] > res->samples_max ? tile_samples[t] : res->samples_max;
    }
    res->interrupted = res->samples_min < spp;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = (size_t)y * W + x;
            int n = tile_samples[(y / ts) * tiles_x + x / ts];
            float inv = n > 0 ? 1.0f / (float)n : 0.0f;
            for (int c = 0; c < 3; c++)
                res->rgb[3 * i + c] = accum[4 * i + c] * inv;
        }

cleanup:
    free(accum);
    free(tile_samples);
    if (rc)
        atmo_render_result_free(res);
    if (b_nonfinite)
        clReleaseMemObject(b_nonfinite);
    if (b_accum)
        clReleaseMemObject(b_accum);
    atmo_release_buffers(b_buffers);
    if (b_scene)
        clReleaseMemObject(b_scene);
    if (k_render)
        clReleaseKernel(k_render);
    if (program)
        clReleaseProgram(program);
    atmo_cl_close(&cl);
    return rc;
}
