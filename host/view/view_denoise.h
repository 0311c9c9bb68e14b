/* view_denoise.h — the viewer's denoised display (key N) and the guides its denoised saves wait
 * for (view_denoise.c). */
#ifndef ATMO_VIEW_DENOISE_H
#define ATMO_VIEW_DENOISE_H
#include "atmo/outputs.h"
#include "atmo/status.h"
#include "view_controls.h"
#include "view_render_thread.h"
#include "view_window.h"

/* The denoised frame the window's texture holds, or held last. */
typedef struct view_denoise {
    float *image;          /* the denoised frame (malloc'd), or NULL */
    int on_screen;         /* the texture holds it */
    unsigned generation;   /* the frame it was made from: request, phase, fewest samples */
    int phase, samples;
    int guided;            /* it was made with the guides */
} view_denoise;

/* The frame f (of the size the texture has now; resized: it has just changed) into the
 * window's texture: denoised while v->denoise is on and f has few samples once the guides of
 * its view are made, else as rendered (the whole image after a change of size, a draft, or the
 * denoised one; else the finished tiles). A library that does not load or a failing filter
 * turns v->denoise off and says why in note. Returns 1 when the window needs drawing. */
int view_denoise_upload(view_denoise *d, view_state *v, view_window *w, const view_frame *f,
                        int resized, atmo_err *note);
/* Whether the render thread is to make the guides of each view: v->denoise is on, a P save
 * waits for them, or the screenshot's screenshot_output (NULL: no screenshot) is denoised. */
int view_denoise_guides_wanted(const view_state *v, int save_pending,
                               const char *screenshot_output);
/* Whether a P save to save_path can be written now: its image is not denoised, or the guides
 * of the view on r's frame are made (or the frame failed). */
int view_denoise_save_ready(const view_state *v, view_renderer *r, const char *save_path);
/* Whether the screenshot to `output` may be taken: neither the display nor `output` waits for
 * the guides of `shown` (the frame as last taken, whose image the window shows). */
int view_denoise_settled(const view_state *v, const view_frame *shown, const char *output);
/* The guides of f's view copied out for a save where the render thread made them (*block
 * malloc'd, *g points into it), else none (*g zeroed, *block NULL). ATMO_ERR_RUNTIME when out
 * of memory. */
int view_denoise_copy_guides(const view_frame *f, atmo_outputs_guides *g, float **block,
                             atmo_err *e);
void view_denoise_free(view_denoise *d);

#endif
