/* view_render_thread.c — the viewer's render sessions, on a thread of their own, so the window
 * handles events while a launch is in flight.
 *
 * Two sessions (atmo/session.h): a draft at a quarter of the image size (view_mode_draft) and
 * the full-size image. On each request the thread brings both to the new scene (set_view when
 * only the camera and sun changed, which keeps the LUTs and reruns only what follows the view;
 * set_scene when the program is the same; a new session otherwise, e.g. another method),
 * renders the draft to one sample per pixel and shows it enlarged (nearest pixel), then refines
 * the full-size image in steps of at most VIEW_STEP_SECONDS, each followed by a read of the
 * mean and a copy of the tiles it finished into the shared frame; the main thread uploads those
 * tiles as sub-images. A new request sets the cancel token (atmo_cancel): the step, or the
 * precompute, stops after the launch in flight, and the thread starts over with the new scene.
 * A draft under way is let finish and shown, unless it has already taken twice as long as the
 * last draft that reused its session (at least VIEW_DRAFT_PATIENCE): while the camera moves
 * continuously, each request would otherwise cancel the one before and nothing would show
 * until the movement stops; this way the drafts follow the movement at the rate the device
 * makes them, and a kernel build or a full precompute (after a change of method or size) is
 * still cut short by the next change.
 * The launch budget of the caller's settings keeps each launch short.
 *
 * The denoiser's guides (view_renderer_want_guides) follow the view, not the samples: while
 * they are wanted the thread renders them once per request on the full-size session
 * (atmo_session_guides, buffers of their own) as soon as the refined image has a sample in
 * every pixel (so the first refined image is not held back: the pass costs about as much as a
 * few samples), and hands them over in the frame; a camera, sun or scene change is a new
 * request and gets new guides. A new request cancels the pass as it cancels a step.
 *
 * On Linux the thread lowers its own scheduling priority (nice 10) before its first OpenCL
 * call, so the CPU device's worker threads, which it creates, inherit it: where the device is
 * the CPU the window then still gets the CPU at once whenever an event arrives. (Elsewhere, or
 * if refused, nothing changes but that.)
 *
 * The noise estimate shown is the mean over pixels and channels with two or more samples of the
 * relative standard error se / mean (atmo_session_read's se = sqrt((S2 - S1^2/n) / (n (n-1)))),
 * computed at most every VIEW_NOISE_SECONDS and when the image is complete.
 *
 * Plans and sessions. A session keeps a copy of its plan, whose host tables the plan owns:
 * after set_view the session still uses its old plan's tables (the new plan is freed), after
 * set_scene the new plan's (the old one is freed; also when set_scene's precompute was
 * cancelled, since the session holds the new tables from its start), a new session its own
 * plan. set_view refuses a plan whose host tables differ (a scene with objects: their rows are
 * camera-relative, so a camera move changes them), and such a move takes set_scene. */
#include <sys/resource.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/clock.h"
#include "atmo/guides.h"
#include "atmo/plan.h"
#include "view_mode.h"
#include "view_render_thread.h"

#define VIEW_STEP_SECONDS (1.0 / 30.0)
#define VIEW_NOISE_SECONDS 0.5
#define VIEW_DRAFT_PATIENCE 0.5 /* seconds */

typedef struct slot {
    atmo_session *session;
    atmo_plan plan; /* the plan the session was opened or last set_scene'd with */
} slot;

struct view_renderer {
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t wake;
    atmo_render_settings rs;
    int lut_cache;
    atmo_cancel cancel;
    /* shared, under lock */
    int quit, pending;
    int want_guides;      /* view_renderer_want_guides */
    int draft_shown;      /* the current request's draft is on screen */
    double draft_started; /* when the current request was taken up */
    double draft_seconds; /* the last draft that reused its session took this long */
    atmo_scene next;
    int next_samples;
    unsigned next_generation;
    view_frame frame;
    /* the thread's own */
    slot draft, full;
    unsigned full_generation; /* the request the full-size session is brought to */
    float *mean, *se;
    size_t pixels;
    view_rect rects[VIEW_MAX_RECTS];
    int rect_count, rect_overflow;
    double noise_time;
};

static void slot_close(slot *s)
{
    if (s->session) {
        atmo_session_close(s->session);
        atmo_plan_free(&s->plan);
    }
    s->session = NULL;
}

/* Bring the slot's session to `scene`: set_view, set_scene or a new session (*opened). */
static int prepare(view_renderer *r, slot *s, const atmo_scene *scene, int *opened, atmo_err *e)
{
    *opened = 0;
    atmo_plan p;
    int rc = atmo_plan_make_cached(scene, r->lut_cache, r->lut_cache, &p, e);
    if (rc)
        return rc;
    if (s->session) {
        atmo_err why;
        rc = atmo_session_set_view(s->session, &p, &why);
        if (rc != ATMO_ERR_USAGE) { /* the session keeps its plan's tables */
            atmo_plan_free(&p);
            if (rc)
                *e = why;
            return rc;
        }
        rc = atmo_session_set_scene(s->session, &p, &why);
        if (rc != ATMO_ERR_USAGE) {
            /* the session took the new plan's tables, also when its precompute stopped (the
             * next set_view or set_scene completes it from them) */
            atmo_plan_free(&s->plan);
            s->plan = p;
            if (rc)
                *e = why;
            return rc;
        }
        slot_close(s); /* other kernels or another image size */
    }
    *opened = 1;
    rc = atmo_session_open(&s->session, &p, &r->rs, e);
    if (rc) {
        atmo_plan_free(&p);
        return rc;
    }
    s->plan = p;
    return ATMO_OK;
}

static int ensure_buffers(view_renderer *r, size_t pixels, atmo_err *e)
{
    if (pixels <= r->pixels)
        return ATMO_OK;
    float *m = realloc(r->mean, pixels * 3 * sizeof(float));
    if (m)
        r->mean = m;
    float *s = m ? realloc(r->se, pixels * 3 * sizeof(float)) : NULL;
    if (s)
        r->se = s;
    if (!m || !s)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the viewer's image");
    r->pixels = pixels;
    return ATMO_OK;
}

/* Under the lock: the frame gets the request's size (a new image) if it has another. */
static int frame_size(view_frame *f, int w, int h, atmo_err *e)
{
    if (f->width == w && f->height == h && f->rgb)
        return ATMO_OK;
    float *p = calloc((size_t)w * (size_t)h * 3, sizeof(float));
    if (!p)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for a %dx%d frame", w, h);
    free(f->rgb);
    f->rgb = p;
    f->width = w;
    f->height = h;
    f->all_dirty = 1;
    return ATMO_OK;
}

/* The draft to one sample per pixel, shown enlarged over the whole frame. */
static int render_draft(view_renderer *r, unsigned generation, const atmo_scene *scene,
                        int samples, double t0, atmo_err *e)
{
    atmo_step step = {1, 0.0, NULL, NULL, &r->cancel};
    atmo_step_status st;
    int dw = r->draft.plan.width, dh = r->draft.plan.height;
    int W = scene->image.width, H = scene->image.height;
    int rc = atmo_session_step(r->draft.session, &step, &st, e);
    if (rc || st.cancelled)
        return rc;
    if ((rc = ensure_buffers(r, (size_t)dw * dh, e)) ||
        (rc = atmo_session_read(r->draft.session, r->mean, NULL, NULL, e)))
        return rc;
    pthread_mutex_lock(&r->lock);
    view_frame *f = &r->frame;
    if ((rc = frame_size(f, W, H, e)) == ATMO_OK) { /* shown even if a newer request waits */
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                const float *src = r->mean + 3 * ((size_t)(y * dh / H) * dw + (size_t)(x * dw / W));
                memcpy(f->rgb + 3 * ((size_t)y * W + x), src, 3 * sizeof(float));
            }
        f->all_dirty = 1;
        f->generation = generation;
        f->phase = VIEW_PHASE_DRAFT;
        f->samples_min = f->samples_max = 0;
        f->target = samples;
        f->noise = 0.0;
        f->seconds = atmo_now_seconds() - t0;
        f->launches = st.launches;
        r->draft_shown = 1;
    }
    pthread_mutex_unlock(&r->lock);
    return rc;
}

static void on_tile(void *user, const atmo_tile *t)
{
    view_renderer *r = user;
    if (r->rect_count == VIEW_MAX_RECTS) {
        r->rect_overflow = 1;
        return;
    }
    view_rect q = {t->x, t->y, t->w, t->h};
    r->rects[r->rect_count++] = q;
}

static double noise_estimate(const float *mean, const float *se, const int *n, size_t pixels)
{
    double sum = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < pixels; i++) {
        if (n[i] < 2)
            continue;
        for (int c = 0; c < 3; c++)
            if (mean[3 * i + c] > 0.0f) {
                sum += (double)se[3 * i + c] / (double)mean[3 * i + c];
                count++;
            }
    }
    return count ? sum / (double)count : 0.0;
}

/* One step of the full-size image; *done when it reached its samples. */
static int refine(view_renderer *r, unsigned generation, int samples, double t0, int *launches,
                  int *done, atmo_err *e)
{
    atmo_session *s = r->full.session;
    int W = r->full.plan.width, H = r->full.plan.height;
    size_t pixels = (size_t)W * H;
    atmo_step step = {samples, VIEW_STEP_SECONDS, on_tile, r, &r->cancel};
    atmo_step_status st;
    r->rect_count = r->rect_overflow = 0;
    int rc = atmo_session_step(s, &step, &st, e);
    if (rc || st.cancelled)
        return rc;
    *launches += st.launches;
    double now = atmo_now_seconds();
    int with_noise = st.complete || now - r->noise_time >= VIEW_NOISE_SECONDS;
    int *counts = NULL;
    if ((rc = ensure_buffers(r, pixels, e)))
        return rc;
    if (with_noise && !(counts = malloc(pixels * sizeof(int))))
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the sample counts");
    rc = atmo_session_read(s, r->mean, with_noise ? r->se : NULL, counts, e);
    double noise = rc == ATMO_OK && with_noise ? noise_estimate(r->mean, r->se, counts, pixels)
                                               : -1.0;
    free(counts);
    if (rc)
        return rc;
    if (with_noise)
        r->noise_time = now;
    int lo, hi;
    atmo_session_samples(s, &lo, &hi);
    pthread_mutex_lock(&r->lock);
    view_frame *f = &r->frame;
    if (!r->pending && f->width == W && f->height == H) {
        if (r->rect_overflow || f->rect_count + r->rect_count > VIEW_MAX_RECTS) {
            memcpy(f->rgb, r->mean, pixels * 3 * sizeof(float));
            f->all_dirty = 1;
        } else {
            for (int k = 0; k < r->rect_count; k++) {
                view_rect q = r->rects[k];
                for (int y = q.y; y < q.y + q.h; y++)
                    memcpy(f->rgb + 3 * ((size_t)y * W + q.x), r->mean + 3 * ((size_t)y * W + q.x),
                           (size_t)q.w * 3 * sizeof(float));
                f->rects[f->rect_count++] = q;
            }
        }
        f->generation = generation;
        f->phase = st.complete ? VIEW_PHASE_DONE : VIEW_PHASE_REFINING;
        f->samples_min = lo;
        f->samples_max = hi;
        if (noise >= 0.0)
            f->noise = noise;
        f->seconds = now - t0;
        f->launches = *launches;
    }
    pthread_mutex_unlock(&r->lock);
    *done = st.complete;
    return ATMO_OK;
}

/* Under the lock: the current request's guides are wanted and not made yet, and its image
 * on display has a sample in every pixel (the first refined image is not held back by them). */
static int guides_due(const view_renderer *r, unsigned generation)
{
    const view_frame *f = &r->frame;
    return r->want_guides && r->full_generation == generation &&
           f->guides_generation != generation && f->generation == generation &&
           (f->phase == VIEW_PHASE_REFINING || f->phase == VIEW_PHASE_DONE) &&
           f->samples_min >= 1;
}

/* The guides of the full-size session's view into the frame. */
static int make_guides(view_renderer *r, unsigned generation, const atmo_scene *scene,
                       atmo_err *e)
{
    int apply = atmo_guides_apply(scene);
    size_t pixels = (size_t)r->full.plan.width * (size_t)r->full.plan.height;
    float *block = apply ? malloc(sizeof(float) * ATMO_GUIDES_FLOATS * pixels) : NULL;
    if (apply && !block)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the denoiser's guides");
    double t0 = atmo_now_seconds();
    int rc = apply ? atmo_session_guides(r->full.session, block, block + 3 * pixels,
                                         block + 6 * pixels, block + 7 * pixels, &r->cancel,
                                         e)
                   : ATMO_OK;
    if (rc) {
        free(block);
        return rc;
    }
    pthread_mutex_lock(&r->lock);
    free(r->frame.guides);
    r->frame.guides = block;
    r->frame.guides_generation = generation;
    r->frame.guides_apply = apply;
    r->frame.guides_seconds = atmo_now_seconds() - t0;
    pthread_mutex_unlock(&r->lock);
    return ATMO_OK;
}

static void publish_error(view_renderer *r, unsigned generation, const atmo_err *e)
{
    pthread_mutex_lock(&r->lock);
    r->frame.phase = VIEW_PHASE_ERROR;
    r->frame.generation = generation;
    snprintf(r->frame.message, sizeof r->frame.message, "%s", e->msg);
    pthread_mutex_unlock(&r->lock);
}

/* A newer request waits (the thread then starts over with it). */
static int superseded(view_renderer *r)
{
    pthread_mutex_lock(&r->lock);
    int p = r->pending;
    pthread_mutex_unlock(&r->lock);
    return p || atmo_cancel_requested(&r->cancel);
}

static void *render_main(void *arg)
{
    view_renderer *r = arg;
#ifdef __linux__
    /* Linux keeps the nice value per thread, and who = 0 is the calling thread: the window's
     * thread keeps its own. A hint: a refusal changes nothing else. */
    (void)setpriority(PRIO_PROCESS, 0, 10);
#endif
    enum { STAGE_NONE, STAGE_START, STAGE_REFINE } stage = STAGE_NONE;
    atmo_scene scene, draft;
    int samples = 0, launches = 0;
    unsigned generation = 0;
    double t0 = 0.0;
    for (;;) {
        pthread_mutex_lock(&r->lock);
        while (!r->quit && !r->pending && stage == STAGE_NONE && !guides_due(r, generation))
            pthread_cond_wait(&r->wake, &r->lock);
        if (r->quit) {
            pthread_mutex_unlock(&r->lock);
            break;
        }
        if (r->pending) {
            scene = r->next;
            samples = r->next_samples;
            generation = r->next_generation;
            r->pending = 0;
            atmo_cancel_clear(&r->cancel);
            r->frame.phase = VIEW_PHASE_PREPARING;
            r->draft_shown = 0;
            r->draft_started = atmo_now_seconds();
            stage = STAGE_START;
            launches = 0;
            t0 = atmo_now_seconds();
        }
        int guides = guides_due(r, generation);
        pthread_mutex_unlock(&r->lock);
        atmo_err e = {{0}};
        int rc = ATMO_OK, done = 0;
        if (guides) {
            rc = make_guides(r, generation, &scene, &e);
        } else if (stage == STAGE_START) {
            double tp = atmo_now_seconds();
            view_mode_draft(&scene, &draft);
            int opened;
            rc = prepare(r, &r->draft, &draft, &opened, &e);
            if (!rc && !atmo_cancel_requested(&r->cancel))
                rc = render_draft(r, generation, &scene, samples, t0, &e);
            if (!rc && !opened && r->draft_shown) {
                pthread_mutex_lock(&r->lock);
                r->draft_seconds = atmo_now_seconds() - t0;
                pthread_mutex_unlock(&r->lock);
            }
            if (!rc && !superseded(r))
                rc = prepare(r, &r->full, &scene, &opened, &e);
            if (!rc && !superseded(r)) {
                stage = STAGE_REFINE;
                r->full_generation = generation;
                r->noise_time = atmo_now_seconds();
                pthread_mutex_lock(&r->lock);
                r->frame.precompute_seconds = atmo_now_seconds() - tp;
                pthread_mutex_unlock(&r->lock);
            }
        } else if (stage == STAGE_REFINE) {
            rc = refine(r, generation, samples, t0, &launches, &done, &e);
            if (!rc && done)
                stage = STAGE_NONE;
        }
        if (rc && !atmo_cancel_requested(&r->cancel)) {
            publish_error(r, generation, &e);
            stage = STAGE_NONE;
        }
    }
    slot_close(&r->full);
    slot_close(&r->draft);
    return NULL;
}

int view_renderer_start(view_renderer **out, const atmo_render_settings *rs, int lut_cache,
                        atmo_err *e)
{
    view_renderer *r = calloc(1, sizeof *r);
    *out = NULL;
    if (!r)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the viewer");
    r->rs = *rs;
    r->rs.progress = 0;
    r->rs.cancel = &r->cancel;
    r->lut_cache = lut_cache;
    if (pthread_mutex_init(&r->lock, NULL)) {
        free(r);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "pthread_mutex_init failed");
    }
    if (pthread_cond_init(&r->wake, NULL)) {
        pthread_mutex_destroy(&r->lock);
        free(r);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "pthread_cond_init failed");
    }
    if (pthread_create(&r->thread, NULL, render_main, r)) {
        pthread_cond_destroy(&r->wake);
        pthread_mutex_destroy(&r->lock);
        free(r);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "pthread_create failed for the render thread");
    }
    *out = r;
    return ATMO_OK;
}

void view_renderer_request(view_renderer *r, const atmo_scene *scene, int samples,
                           unsigned generation)
{
    pthread_mutex_lock(&r->lock);
    r->next = *scene;
    r->next_samples = samples;
    r->next_generation = generation;
    r->pending = 1;
    double patience = 2.0 * r->draft_seconds > VIEW_DRAFT_PATIENCE ? 2.0 * r->draft_seconds
                                                                   : VIEW_DRAFT_PATIENCE;
    if (r->draft_shown || atmo_now_seconds() - r->draft_started > patience)
        atmo_cancel_request(&r->cancel);
    pthread_cond_signal(&r->wake);
    pthread_mutex_unlock(&r->lock);
}

void view_renderer_want_guides(view_renderer *r, int on)
{
    pthread_mutex_lock(&r->lock);
    if (on != r->want_guides) {
        r->want_guides = on;
        pthread_cond_signal(&r->wake);
    }
    pthread_mutex_unlock(&r->lock);
}

view_frame *view_renderer_acquire(view_renderer *r)
{
    pthread_mutex_lock(&r->lock);
    return &r->frame;
}

void view_renderer_release(view_renderer *r, int taken)
{
    if (taken) {
        r->frame.all_dirty = 0;
        r->frame.rect_count = 0;
    }
    pthread_mutex_unlock(&r->lock);
}

void view_renderer_stop(view_renderer *r)
{
    if (!r)
        return;
    pthread_mutex_lock(&r->lock);
    r->quit = 1;
    atmo_cancel_request(&r->cancel);
    pthread_cond_signal(&r->wake);
    pthread_mutex_unlock(&r->lock);
    pthread_join(r->thread, NULL);
    pthread_cond_destroy(&r->wake);
    pthread_mutex_destroy(&r->lock);
    free(r->frame.rgb);
    free(r->frame.guides);
    free(r->se);
    free(r->mean);
    free(r);
}
