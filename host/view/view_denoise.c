/* view_denoise.c — the viewer's denoised display (key N, view_state.denoise) and the guides its
 * denoised saves wait for (view_denoise.h).
 *
 * While the frame has fewer than VIEW_DENOISE_MAX_SPP samples per pixel, the texture holds the
 * frame through Open Image Denoise (atmo_outputs_denoise_rgb at quality fast) with the albedo
 * and normal guides of the view, as `atmo render` denoises: the render thread renders them once
 * per view while they are wanted (view_renderer_want_guides: N is on, or a save is denoised),
 * when the view's image has a sample in every pixel, so the display waits for them after a
 * change (the draft and the frames before them show as rendered; a screenshot waits for them
 * too), and a scene that takes none (atmo_guides_apply: a thin lens, the spectral mode) is
 * denoised on the colour alone. It is redone whenever the frame's request, phase or fewest
 * samples change, in place of the finished tiles' sub-images; the render thread's accumulation
 * keeps the image as rendered, and the saves (P, --output) are the files `atmo render` writes:
 * denoised as output.denoise says, with the same guides. From VIEW_DENOISE_MAX_SPP samples on,
 * or with the key off again, the texture gets the rendered frame back. A missing library turns
 * it off with its message in the title. */
#include <stdlib.h>
#include <string.h>
#include "atmo/denoise.h"
#include "atmo/guides.h"
#include "view_denoise.h"
#include "view_mode.h"

/* the denoised display's limit: at 64 samples a path-traced frame is about as clean as the
 * denoised 4 (docs/guide/denoise.md) */
#define VIEW_DENOISE_MAX_SPP 64

/* Whether output.denoise denoises `path`, saved from v's rendered scene, and the library
 * loads. */
static int save_denoised(const view_state *v, const char *path)
{
    atmo_scene rendered;
    const char *outputs[1] = {path};
    atmo_err le;
    view_mode_scene(&v->scene, v->mode, &rendered);
    return path && atmo_outputs_any_denoised(&rendered, outputs, 1) && atmo_denoise_load(&le) == 0;
}

/* *g pointing into the guide pass's planes (atmo/guides.h) of an image of `pixels` pixels. */
static void point_into(atmo_outputs_guides *g, const float *planes, size_t pixels)
{
    *g = (atmo_outputs_guides){planes, planes + 3 * pixels, planes + 6 * pixels,
                               planes + 7 * pixels, 1};
}

/* The guides of f's view for the denoiser, in *g (no guides where its scene takes none):
 * 1 once the render thread made them for f's request and f is its full-size image, else 0. */
static int frame_guides(const view_frame *f, atmo_outputs_guides *g)
{
    memset(g, 0, sizeof *g);
    if (f->guides_generation != f->generation ||
        (f->phase != VIEW_PHASE_REFINING && f->phase != VIEW_PHASE_DONE))
        return 0;
    if (f->guides)
        point_into(g, f->guides, (size_t)f->width * (size_t)f->height);
    return 1;
}

/* Whether f is to be shown denoised: the key is on, the library loads (else the key goes off,
 * with its message), f has few samples and the guides of its view are made (*g:
 * atmo_outputs_denoise_rgb's guides, none where its scene takes none). */
static int wanted(view_state *v, const view_frame *f, atmo_outputs_guides *g, atmo_err *note)
{
    atmo_err le;
    if (!v->denoise || f->samples_max >= VIEW_DENOISE_MAX_SPP)
        return 0;
    if (atmo_denoise_load(&le)) {
        v->denoise = 0;
        atmo_fail(note, ATMO_ERR_RUNTIME, "N (denoise): %.900s", le.msg);
        return 0;
    }
    return frame_guides(f, g);
}

/* f denoised into the texture, when f differs from the frame it was made from or the texture
 * holds something else. A failing filter turns the key off, with its message. Returns 1 when
 * the texture changed. */
static int show(view_denoise *d, view_state *v, view_window *w, const view_frame *f,
                const atmo_outputs_guides *g, int resized, atmo_err *note)
{
    atmo_err de;
    if (d->on_screen && !resized && f->generation == d->generation && f->phase == d->phase &&
        f->samples_min == d->samples)
        return 0;
    float *out = realloc(d->image, sizeof(float) * 3 * (size_t)f->width * f->height);
    if (!out || atmo_outputs_denoise_rgb(f->rgb, f->width, f->height, g, ATMO_DENOISE_FAST,
                                         out, &de)) {
        atmo_fail(note, ATMO_ERR_RUNTIME, "N (denoise): %.900s",
                  out ? de.msg : "out of memory for the denoised image");
        v->denoise = 0;
        if (out)
            d->image = out;
        return 0;
    }
    d->image = out;
    view_window_upload(w, out, f->width, 0, 0, f->width, f->height);
    d->on_screen = 1;
    d->guided = g->albedo != NULL;
    d->generation = f->generation;
    d->phase = f->phase;
    d->samples = f->samples_min;
    return 1;
}

int view_denoise_upload(view_denoise *d, view_state *v, view_window *w, const view_frame *f,
                        int resized, atmo_err *note)
{
    atmo_outputs_guides g;
    if (wanted(v, f, &g, note))
        return show(d, v, w, f, &g, resized, note);
    if (resized || f->all_dirty || d->on_screen) {
        view_window_upload(w, f->rgb, f->width, 0, 0, f->width, f->height);
        d->on_screen = 0;
        return 1;
    }
    for (int i = 0; i < f->rect_count; i++)
        view_window_upload(w, f->rgb, f->width, f->rects[i].x, f->rects[i].y, f->rects[i].w,
                           f->rects[i].h);
    return 0;
}

int view_denoise_guides_wanted(const view_state *v, int save_pending,
                               const char *screenshot_output)
{
    return v->denoise || save_pending || save_denoised(v, screenshot_output);
}

int view_denoise_save_ready(const view_state *v, view_renderer *r, const char *save_path)
{
    atmo_outputs_guides g;
    if (!save_denoised(v, save_path))
        return 1;
    view_frame *f = view_renderer_acquire(r);
    int ready = frame_guides(f, &g) || f->phase == VIEW_PHASE_ERROR;
    view_renderer_release(r, 0);
    return ready;
}

int view_denoise_settled(const view_state *v, const view_frame *shown, const char *output)
{
    atmo_outputs_guides g;
    return frame_guides(shown, &g) || (!v->denoise && !save_denoised(v, output));
}

int view_denoise_copy_guides(const view_frame *f, atmo_outputs_guides *g, float **block,
                             atmo_err *e)
{
    size_t pixels = (size_t)f->width * (size_t)f->height;
    atmo_outputs_guides shared;
    *block = NULL;
    memset(g, 0, sizeof *g);
    if (!frame_guides(f, &shared) || !shared.albedo)
        return ATMO_OK;
    *block = malloc(sizeof(float) * ATMO_GUIDES_FLOATS * pixels);
    if (!*block)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the denoiser's guides");
    memcpy(*block, f->guides, sizeof(float) * ATMO_GUIDES_FLOATS * pixels);
    point_into(g, *block, pixels);
    return ATMO_OK;
}

void view_denoise_free(view_denoise *d)
{
    free(d->image);
    d->image = NULL;
}
