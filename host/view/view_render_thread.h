/* view_render_thread.h — the viewer's render sessions on a thread of their own
 * (view_render_thread.c). */
#ifndef ATMO_VIEW_RENDER_THREAD_H
#define ATMO_VIEW_RENDER_THREAD_H
#include "atmo/scene.h"
#include "atmo/session.h"
#include "atmo/status.h"

#define VIEW_MAX_RECTS 64

typedef struct view_rect {
    int x, y, w, h;
} view_rect;

enum { VIEW_PHASE_IDLE, VIEW_PHASE_PREPARING, VIEW_PHASE_DRAFT, VIEW_PHASE_REFINING,
       VIEW_PHASE_DONE, VIEW_PHASE_ERROR };

/* The image on display and what changed in it since the main thread last took it. */
typedef struct view_frame {
    int width, height;          /* the rendered scene's image size */
    float *rgb;                 /* linear mean, 3 floats per pixel, row 0 = top */
    int all_dirty;              /* the whole image changed (new size, a draft) */
    int rect_count;             /* else these rectangles (finished tiles) changed */
    view_rect rects[VIEW_MAX_RECTS];
    unsigned generation;        /* of the request the image shows */
    int phase;                  /* VIEW_PHASE_* */
    int samples_min, samples_max; /* of the full-size image (0 while the draft shows) */
    int target;                 /* samples per pixel it converges to */
    double noise;               /* mean relative standard error over pixels with 2+ samples */
    double seconds;             /* since the request */
    int launches;               /* since the request */
    double precompute_seconds;  /* from the request to the refinement's start: both sessions
                                   brought to it (set_view, set_scene or a new session, with
                                   their precompute passes) and the draft */
    char message[1024];         /* the error, in phase ERROR */
    float *guides;              /* the denoiser's guides of request guides_generation's view
                                   (atmo/guides.h: ATMO_GUIDES_FLOATS planes of the full-size
                                   image), or NULL */
    unsigned guides_generation; /* the request they are of (0: none made yet) */
    int guides_apply;           /* 0: that request's scene takes no guides (atmo_guides_apply;
                                   guides is then NULL) */
    double guides_seconds;      /* their guide pass */
} view_frame;

typedef struct view_renderer view_renderer;

int view_renderer_start(view_renderer **out, const atmo_render_settings *rs, int lut_cache,
                        atmo_err *e);
/* Render `scene` (validated) to `samples` per pixel from now on: the step in flight stops after
 * its launch and the accumulation restarts. */
void view_renderer_request(view_renderer *r, const atmo_scene *scene, int samples,
                           unsigned generation);
/* Whether the guides of each request's view are wanted (the denoised display, a denoised
 * save): while they are, the thread renders them once per request, when the request's
 * full-size image has a sample in every pixel (or at once when they become wanted later), on
 * the full-size session and into buffers of their own, so the accumulation goes on
 * undisturbed. */
void view_renderer_want_guides(view_renderer *r, int on);
/* The frame, locked until view_renderer_release; release with taken = 1 clears the changes. */
view_frame *view_renderer_acquire(view_renderer *r);
void view_renderer_release(view_renderer *r, int taken);
/* Stop the thread (after the launch in flight) and release everything. NULL is fine. */
void view_renderer_stop(view_renderer *r);

#endif
