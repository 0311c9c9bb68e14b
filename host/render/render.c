/* render.c — a whole render in one call over a session (atmo/render.h): its mean image, the
 * raw sums of one part of a split render (atmo/part.h), or the denoiser's guides alone. */
#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/clock.h"
#include "atmo/guides.h"
#include "atmo/render.h"
#include "atmo/tiles.h"

void atmo_render_result_free(atmo_render_result *r)
{
    free(r->rgb);
    free(r->passes);
    free(r->guides);
    r->guides = NULL;
    free(r->se);
    free(r->tile_rect);
    free(r->tile_noise);
    r->tile_rect = NULL;
    r->tile_noise = NULL;
    free(r->samples);
    r->rgb = r->passes = r->se = NULL;
    r->samples = NULL;
}

void atmo_render_result_from_session(const atmo_session *s, atmo_render_result *r)
{
    const atmo_session_info *in = atmo_session_get_info(s);
    const atmo_plan *p = atmo_session_plan(s);
    r->width = p->width;
    r->height = p->height;
    r->samples_requested = p->samples;
    atmo_session_samples(s, &r->samples_min, &r->samples_max);
    r->interrupted = r->samples_min < p->samples;
    r->nonfinite = in->nonfinite;
    r->launches = in->launches;
    r->kernel_cache_hit = in->kernel_cache_hit;
    r->lut_cache_hit = in->lut_cache_hit;
    r->seconds_device = in->seconds_device;
    r->seconds_build = in->seconds_build;
    r->seconds_precompute = in->seconds_precompute;
    r->seconds_render = in->seconds_render;
    r->seconds_read = in->seconds_read;
    memcpy(r->device_name, in->device_name, sizeof r->device_name);
    memcpy(r->platform_name, in->platform_name, sizeof r->platform_name);
    memcpy(r->driver_version, in->driver_version, sizeof r->driver_version);
}

/* The relative standard error each tile reached, from the image's means and standard errors:
 * e = sqrt(mean over its pixels and channels of se^2) / mean over them of the mean, the
 * measure the session stops a tile by (atmo/session.h). */
static int tile_noise(const atmo_render_settings *settings, atmo_render_result *res, atmo_err *e)
{
    atmo_tiles t;
    int rc = atmo_tiles_init_part(&t, res->width, res->height, settings->tile_size, 0, 0, e);
    if (rc)
        return rc;
    res->tile_rect = malloc(sizeof(int) * 5 * (size_t)t.count);
    res->tile_noise = malloc(sizeof(double) * (size_t)t.count);
    if (!res->tile_rect || !res->tile_noise) {
        atmo_tiles_free(&t);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d tiles", t.count);
    }
    res->noise_tiles = t.count;
    for (int i = 0; i < t.count; i++) {
        atmo_tile one;
        double var = 0.0, mean = 0.0;
        atmo_tiles_get(&t, i, &one);
        for (int y = one.y; y < one.y + one.h; y++)
            for (int x = one.x; x < one.x + one.w; x++)
                for (int c = 0; c < 3; c++) {
                    size_t k = 3 * ((size_t)y * (size_t)res->width + (size_t)x) + (size_t)c;
                    double se = res->se[k];
                    var += se * se;
                    mean += (double)res->rgb[k];
                }
        double n = 3.0 * one.w * one.h;
        int *r = res->tile_rect + 5 * i;
        r[0] = one.x, r[1] = one.y, r[2] = one.w, r[3] = one.h;
        r[4] = res->samples[(size_t)one.y * (size_t)res->width + (size_t)one.x];
        res->tile_noise[i] = mean > 0.0 ? sqrt(var / n) / (mean / n) : 0.0;
    }
    atmo_tiles_free(&t);
    return ATMO_OK;
}

/* The denoiser's guides of the session's image into res->guides. */
static int render_guides(atmo_session *s, atmo_render_result *res, atmo_err *e)
{
    const atmo_plan *p = atmo_session_plan(s);
    size_t pixels = (size_t)p->width * (size_t)p->height;
    if (!(res->guides = malloc(sizeof(float) * ATMO_GUIDES_FLOATS * pixels)))
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the denoiser's guides");
    double t0 = atmo_now_seconds();
    int rc = atmo_session_guides(s, res->guides, res->guides + 3 * pixels,
                                 res->guides + 6 * pixels, res->guides + 7 * pixels, NULL, e);
    res->seconds_guides = atmo_now_seconds() - t0;
    return rc;
}

int atmo_render(const atmo_plan *plan, const atmo_render_settings *settings,
                atmo_render_result *res, atmo_err *e)
{
    atmo_session *s = NULL;
    atmo_step step = {plan->samples, settings->time_limit_s, NULL, NULL, settings->cancel};
    atmo_step_status st;
    memset(res, 0, sizeof *res);
    int rc = atmo_session_open(&s, plan, settings, e);
    if (!rc) {
        atmo_session_set_noise_target(s, settings->noise_target);
        rc = atmo_session_step(s, &step, &st, e);
    }
    if (!rc && !(res->rgb = malloc(sizeof(float) * 3 * (size_t)plan->width * plan->height)))
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for a %dx%d image", plan->width,
                       plan->height);
    if (!rc && plan->pass_planes > 0) { /* the passes, with the samples and errors per pixel */
        size_t pixels = (size_t)plan->width * plan->height;
        res->pass_planes = plan->pass_planes;
        res->passes = malloc(sizeof(float) * 4 * pixels * (size_t)plan->pass_planes);
        if (!res->passes)
            rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the render passes");
        if (!rc)
            rc = atmo_session_read_passes(s, res->passes, e);
    }
    if (!rc && (plan->pass_planes > 0 || settings->noise_target > 0.0)) { /* errors per pixel */
        size_t pixels = (size_t)plan->width * plan->height;
        res->se = malloc(sizeof(float) * 3 * pixels);
        res->samples = malloc(sizeof(int) * pixels);
        if (!res->se || !res->samples)
            rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the standard errors");
    }
    if (!rc)
        rc = atmo_session_read(s, res->rgb, res->se, res->samples, e);
    if (!rc && settings->guides)
        rc = render_guides(s, res, e);
    if (!rc) {
        atmo_render_result_from_session(s, res);
        /* with a noise target or a time limit, fewer samples than requested are the point;
         * only the cancel token makes the result partial */
        if (settings->noise_target > 0.0 || settings->time_limit_s > 0.0)
            res->interrupted = st.cancelled;
        if (settings->noise_target > 0.0)
            rc = tile_noise(settings, res, e);
    }
    if (rc)
        atmo_render_result_free(res);
    atmo_session_close(s);
    return rc;
}

int atmo_render_part(const atmo_plan *plan, const atmo_render_settings *settings,
                     atmo_render_result *res, atmo_part *part, atmo_err *e)
{
    atmo_session *s = NULL;
    atmo_step step = {plan->samples, 0.0, NULL, NULL, settings->cancel};
    atmo_step_status st;
    size_t pixels = (size_t)plan->width * (size_t)plan->height;
    float *s1 = malloc(sizeof(float) * 3 * pixels), *s2 = malloc(sizeof(float) * 3 * pixels);
    int *samples = malloc(sizeof(int) * pixels);
    memset(res, 0, sizeof *res);
    int rc = s1 && s2 && samples ? atmo_session_open(&s, plan, settings, e)
                                 : atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for a %dx%d "
                                             "image", plan->width, plan->height);
    if (!rc)
        rc = atmo_session_step(s, &step, &st, e);
    if (!rc)
        rc = atmo_session_read_sums(s, s1, s2, samples, e);
    if (!rc) {
        atmo_part_pack(part, s1, s2, samples);
        part->input_hash =
            atmo_part_input_hash(plan->dem.width, plan->dem.height, plan->dem.heights_m);
        atmo_render_result_from_session(s, res);
        snprintf(part->device, sizeof part->device, "%s / %s / %s", res->platform_name,
                 res->device_name, res->driver_version);
    }
    atmo_session_close(s);
    free(samples);
    free(s2);
    free(s1);
    return rc;
}

int atmo_render_guides(const atmo_plan *plan, const atmo_render_settings *settings,
                       atmo_render_result *res, atmo_err *e)
{
    atmo_session *s = NULL;
    memset(res, 0, sizeof *res);
    int rc = atmo_session_open(&s, plan, settings, e);
    if (!rc)
        rc = render_guides(s, res, e);
    if (!rc) {
        atmo_render_result_from_session(s, res);
        res->interrupted = 0;
    }
    if (rc)
        atmo_render_result_free(res);
    atmo_session_close(s);
    return rc;
}
