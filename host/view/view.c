/* view.c — atmo_view_run: the viewer's event loop (atmo/view.h).
 *
 * The main thread owns the window and never waits for the device: each turn of the loop waits
 * for events at most VIEW_EVENT_SECONDS (so input is handled at >= 60 Hz whatever the render
 * does), turns keys, held movement keys, mouse drags and the script's actions into changes of
 * the scene (view_controls.c), sends a changed scene to the render thread
 * (view_render_thread.c), uploads the tiles it finished since the last turn as sub-images,
 * draws the image through the tone-mapping shader and the overlay, and updates the title. The
 * turns while the render thread is busy are timed and summarised at exit (the "events at
 * >= 30 Hz" figure: the share of turns over 33 ms, and the longest), with the time from a change
 * to its first image on screen (the draft, or an error).
 *
 * The denoised display (key N) and the guides its denoised saves wait for: view_denoise.c.
 *
 * A screenshot (--screenshot-after N) is taken when the script, if any, has run to its end and
 * the current view's image has N samples per pixel: the image goes through view_save_image,
 * then the window as drawn (view_window_capture), and the viewer exits. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/clock.h"
#include "atmo/outputs.h"
#include "atmo/view.h"
#include "view_controls.h"
#include "view_denoise.h"
#include "view_mode.h"
#include "view_overlay.h"
#include "view_render_thread.h"
#include "view_save.h"
#include "view_script.h"
#include "view_window.h"

#define VIEW_EVENT_SECONDS (1.0 / 60.0)
#define VIEW_TITLE_SECONDS 0.25
#define VIEW_TILE_FPS 30.0
#define VIEW_HOLD_TICK (1.0 / 60.0)
#define VIEW_MAX_KEYS 64

typedef struct view_app {
    const atmo_view_options *o;
    view_window win;
    view_renderer *renderer;
    view_state state;
    view_overlay overlay;
    view_script script;
    unsigned generation;      /* of the last request */
    int keys[VIEW_MAX_KEYS][2]; /* presses since the last turn: key, mods */
    int key_count;
    double drag_dx, drag_dy, scroll, cursor_x, cursor_y;
    int dragging;
    int saves;
    view_frame shown;         /* the frame's statistics as of the last turn (rgb: NULL) */
    char message[1024];       /* the last error or notice, for the title and overlay */
    int redraw;               /* the window needs drawing (an expose, a change, new tiles) */
    double longest_turn;      /* seconds, while the render thread was busy */
    long turns, busy_turns, slow_turns; /* all; while busy; of those, over 1/30 s */
    double requested_at;      /* when the last request was sent, until its first image shows */
    double latency_sum, latency_max; /* request to its first image on screen, seconds */
    int latency_count;
    unsigned last_generation_shown; /* the newest request whose image was on screen */
    int changes, changes_shown;     /* requests; of those, with an image on screen */
    view_denoise denoise;           /* the denoised display (N) */
    int save_pending;               /* P waits for the guides of the view on display */
} view_app;

static volatile sig_atomic_t interrupted;
static void on_interrupt(int sig)
{
    (void)sig;
    interrupted = 1;
}

static void key_callback(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    view_app *a = glfwGetWindowUserPointer(w);
    int repeats = key == GLFW_KEY_UP || key == GLFW_KEY_DOWN || key == GLFW_KEY_LEFT ||
                  key == GLFW_KEY_RIGHT || key == GLFW_KEY_EQUAL || key == GLFW_KEY_MINUS;
    if ((action == GLFW_PRESS || (action == GLFW_REPEAT && repeats)) && a->key_count < VIEW_MAX_KEYS) {
        a->keys[a->key_count][0] = key;
        a->keys[a->key_count][1] = mods;
        a->key_count++;
    }
}

static void button_callback(GLFWwindow *w, int button, int action, int mods)
{
    view_app *a = glfwGetWindowUserPointer(w);
    if (button == GLFW_MOUSE_BUTTON_LEFT) {
        a->dragging = action == GLFW_PRESS;
        glfwGetCursorPos(w, &a->cursor_x, &a->cursor_y);
    }
}

static void cursor_callback(GLFWwindow *w, double x, double y)
{
    view_app *a = glfwGetWindowUserPointer(w);
    if (a->dragging) {
        a->drag_dx += x - a->cursor_x;
        a->drag_dy += y - a->cursor_y;
    }
    a->cursor_x = x;
    a->cursor_y = y;
}

static void scroll_callback(GLFWwindow *w, double dx, double dy)
{
    view_app *a = glfwGetWindowUserPointer(w);
    a->scroll += dy;
}

static void refresh_callback(GLFWwindow *w)
{
    view_app *a = glfwGetWindowUserPointer(w);
    a->redraw = 1;
}

/* The render thread makes the guides of each view only while something will denoise with them
 * (a guide pass costs about as much as a few samples). */
static void want_guides(view_app *a)
{
    const char *screenshot = a->o->screenshot_after > 0 ? a->o->output : NULL;
    view_renderer_want_guides(a->renderer,
                              view_denoise_guides_wanted(&a->state, a->save_pending, screenshot));
}

static void request(view_app *a)
{
    atmo_scene r;
    view_mode_scene(&a->state.scene, a->state.mode, &r);
    want_guides(a);
    int samples = a->o->screenshot_after > 0 ? a->o->screenshot_after : r.image.samples;
    view_renderer_request(a->renderer, &r, samples, ++a->generation);
    a->requested_at = atmo_now_seconds();
    a->changes++;
}

static int current(const view_app *a) { return a->shown.generation == a->generation; }

static int busy(const view_app *a)
{
    return !current(a) || a->shown.phase == VIEW_PHASE_PREPARING ||
           a->shown.phase == VIEW_PHASE_DRAFT || a->shown.phase == VIEW_PHASE_REFINING;
}

/* Every pixel of the current view has n samples (or all the view renders to). */
static int reached(const view_app *a, double n)
{
    return current(a) && (a->shown.phase == VIEW_PHASE_DONE ||
                          (a->shown.phase == VIEW_PHASE_REFINING && a->shown.samples_min >= n));
}

/* The image on display, copied out of the frame (img->rgb malloc'd), and its view's guides
 * where the render thread made them (*guide_block malloc'd, else NULL; *g points into it). */
static int copy_image(view_app *a, atmo_image *img, int *samples_min, atmo_outputs_guides *g,
                      float **guide_block, atmo_err *e)
{
    view_frame *f = view_renderer_acquire(a->renderer);
    size_t n = (size_t)f->width * (size_t)f->height * 3;
    memset(img, 0, sizeof *img); /* no extra layers */
    img->width = f->width;
    img->height = f->height;
    img->rgb = n ? malloc(n * sizeof(float)) : NULL;
    if (img->rgb)
        memcpy(img->rgb, f->rgb, n * sizeof(float));
    *samples_min = f->samples_min;
    int rc = view_denoise_copy_guides(f, g, guide_block, e);
    view_renderer_release(a->renderer, 0);
    if (!img->rgb) {
        free(*guide_block);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "no image to save yet");
    }
    if (rc)
        free(img->rgb);
    return rc;
}

/* P: the image on display and the user's scene beside it. */
static int save(view_app *a, atmo_err *e)
{
    char image[VIEW_PATH_MAX], scene[VIEW_PATH_MAX];
    atmo_image img;
    atmo_scene rendered;
    atmo_outputs_guides guides;
    float *guide_block;
    int spp, rc = view_save_names(a->o->save_path, ++a->saves, image, scene, e);
    if (rc || (rc = copy_image(a, &img, &spp, &guides, &guide_block, e)))
        return rc;
    view_mode_scene(&a->state.scene, a->state.mode, &rendered);
    rc = view_save_image(image, &img, &guides, &rendered, spp,
                         spp < a->shown.target || !current(a), e);
    free(guide_block);
    free(img.rgb);
    if (!rc)
        rc = atmo_scene_save_json(&a->state.scene, scene, e);
    if (!rc)
        snprintf(a->message, sizeof a->message, "saved %.500s and %.500s", image, scene);
    return rc;
}

static void held_move(view_app *a, int key, int mods, double seconds, int *change)
{
    int f = key == 'W' ? 1 : key == 'S' ? -1 : 0, r = key == 'D' ? 1 : key == 'A' ? -1 : 0,
        u = key == 'E' ? 1 : key == 'Q' ? -1 : 0;
    long ticks = lround(seconds / VIEW_HOLD_TICK);
    for (long i = 0; i < ticks; i++)
        *change |= view_controls_move(&a->state, f, r, u, mods, VIEW_HOLD_TICK);
}

/* Run the script's actions that are due; a wait stops the turn's share. */
static void run_script(view_app *a, double now, int *change)
{
    view_script *s = &a->script;
    while (s->next < s->count && !(*change & VIEW_CHANGE_QUIT) && !a->save_pending) {
        const view_action *act = &s->actions[s->next];
        atmo_err e = {{0}};
        if (act->kind == VIEW_ACT_WAIT) {
            if (s->started < 0.0)
                s->started = now;
            if (now - s->started < act->value)
                return;
            s->started = -1.0;
        } else if (act->kind == VIEW_ACT_WAIT_SAMPLES) {
            if (!reached(a, act->value) || (*change & VIEW_CHANGE_RENDER))
                return;
        } else if (act->kind == VIEW_ACT_PRESS) {
            int c = view_controls_key(&a->state, act->key, act->mods, &e);
            if (e.msg[0])
                snprintf(a->message, sizeof a->message, "%s", e.msg);
            *change |= c;
            if (c & VIEW_CHANGE_SAVE) { /* save what the previous actions asked for */
                s->next++;
                return;
            }
        } else if (act->kind == VIEW_ACT_HOLD) {
            held_move(a, act->key, act->mods, act->value, change);
        } else if (act->kind == VIEW_ACT_LOOK) {
            *change |= view_controls_look(&a->state, act->value, act->value2);
        } else {
            *change |= VIEW_CHANGE_QUIT;
        }
        s->next++;
    }
}

static void title(view_app *a)
{
    const view_frame *f = &a->shown;
    const atmo_scene *s = &a->state.scene;
    atmo_scene r;
    view_mode_scene(s, a->state.mode, &r);
    const atmo_param *m = atmo_param_find("atmosphere.method");
    const atmo_param *t = atmo_param_find("post.tonemap");
    char state[160];
    if (f->phase == VIEW_PHASE_ERROR && current(a))
        snprintf(state, sizeof state, "error (see the terminal)");
    else if (!current(a) || f->phase == VIEW_PHASE_PREPARING)
        snprintf(state, sizeof state, "preparing");
    else if (f->phase == VIEW_PHASE_DRAFT)
        snprintf(state, sizeof state, "draft");
    else
        snprintf(state, sizeof state, "%d/%d spp%s, noise %.2f%%, %.1f s", f->samples_min, f->target,
                 f->phase == VIEW_PHASE_DONE ? " (done)" : "", 100.0 * f->noise, f->seconds);
    char text[512];
    snprintf(text, sizeof text,
             "atmo view | %s %s %dx%d | %s%s | h %.4g m | sun %.1f/%.1f deg | exposure %.3g %s",
             view_mode_name(a->state.mode), m->names[r.atmosphere.method], r.image.width,
             r.image.height, state,
             !a->denoise.on_screen ? ""
             : a->denoise.guided   ? ", denoised with guides"
                                   : ", denoised",
             view_altitude_m(s), s->sun.zenith_deg, s->sun.azimuth_deg, s->post.exposure,
             t->names[s->post.tonemap]);
    view_window_title(&a->win, text);
}

static void overlay(view_app *a)
{
    const view_frame *f = &a->shown;
    const atmo_scene *s = &a->state.scene;
    const double *p = s->camera.position_m;
    char text[4096];
    snprintf(text, sizeof text,
             "atmo view - keys\n%s\n"
             "mode %s   samples %d-%d of %d   noise %.2f%%   %.1f s, %d launches   "
             "draft and sessions ready in %.2f s\n"
             "camera (%.6g, %.6g, %.6g) m, altitude %.6g m, pitch %.2f, yaw %.2f, fov %.1f deg\n"
             "sun zenith %.2f deg, azimuth %.2f deg   speed %.3g m/s\n%s\n",
             atmo_view_keys, view_mode_name(a->state.mode), f->samples_min, f->samples_max,
             f->target, 100.0 * f->noise, f->seconds, f->launches, f->precompute_seconds, p[0],
             p[1], p[2],
             view_altitude_m(s), s->camera.pitch_deg, s->camera.yaw_deg, s->camera.fov_deg,
             s->sun.zenith_deg, s->sun.azimuth_deg, view_speed_m_per_s(s, 0), a->message);
    if (view_overlay_build(&a->overlay, text))
        a->overlay.count = 0;
}

/* The frame into the texture (view_denoise_upload); its statistics into a->shown. */
static int take_frame(view_app *a, atmo_err *e)
{
    view_frame *f = view_renderer_acquire(a->renderer);
    int rc = ATMO_OK;
    if (f->rgb && f->width > 0) {
        int resized = f->width != a->win.tex_width || f->height != a->win.tex_height;
        rc = view_window_image(&a->win, f->width, f->height, e);
        a->redraw |= resized || f->all_dirty || f->rect_count > 0;
        atmo_err note = {{0}};
        if (!rc)
            a->redraw |= view_denoise_upload(&a->denoise, &a->state, &a->win, f, resized, &note);
        if (note.msg[0])
            snprintf(a->message, sizeof a->message, "%s", note.msg);
    }
    a->shown = *f;
    a->shown.rgb = NULL;
    a->shown.guides = NULL;
    if (f->generation > a->last_generation_shown && f->phase != VIEW_PHASE_PREPARING) {
        a->last_generation_shown = f->generation;
        a->changes_shown++;
    }
    if (a->requested_at > 0.0 && current(a) && f->phase != VIEW_PHASE_PREPARING) {
        double latency = atmo_now_seconds() - a->requested_at;
        a->latency_sum += latency;
        a->latency_max = latency > a->latency_max ? latency : a->latency_max;
        a->latency_count++;
        a->requested_at = 0.0;
    }
    view_renderer_release(a->renderer, rc == ATMO_OK);
    return rc;
}

static int screenshot(view_app *a, atmo_err *e)
{
    atmo_image img;
    atmo_scene rendered;
    atmo_outputs_guides guides;
    float *guide_block;
    int spp, rc = copy_image(a, &img, &spp, &guides, &guide_block, e);
    if (rc)
        return rc;
    view_mode_scene(&a->state.scene, a->state.mode, &rendered);
    rc = view_save_image(a->o->output, &img, &guides, &rendered, spp, 0, e);
    free(guide_block);
    free(img.rgb);
    if (!rc && a->o->window_capture)
        rc = view_window_capture(&a->win, a->o->window_capture, e);
    return rc;
}

static int loop(view_app *a, atmo_err *e)
{
    double last = atmo_now_seconds(), last_title = 0.0, last_draw = 0.0;
    int rc = ATMO_OK;
    request(a);
    while (!glfwWindowShouldClose(a->win.window) && !interrupted) {
        glfwWaitEventsTimeout(VIEW_EVENT_SECONDS);
        double now = atmo_now_seconds(), dt = now - last;
        last = now;
        if (busy(a) && a->turns > 0) {
            a->busy_turns++;
            a->slow_turns += dt > 1.0 / 30.0;
            if (dt > a->longest_turn)
                a->longest_turn = dt;
        }
        a->turns++;
        int change = 0;
        for (int i = 0; i < a->key_count; i++) {
            atmo_err ke = {{0}};
            change |= view_controls_key(&a->state, a->keys[i][0], a->keys[i][1], &ke);
            if (ke.msg[0])
                snprintf(a->message, sizeof a->message, "%s", ke.msg);
        }
        a->key_count = 0;
        GLFWwindow *w = a->win.window;
        int held_mods = (glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT)
                             ? VIEW_MOD_SHIFT : 0) |
                        (glfwGetKey(w, GLFW_KEY_LEFT_CONTROL) || glfwGetKey(w, GLFW_KEY_RIGHT_CONTROL)
                             ? VIEW_MOD_CONTROL : 0);
        change |= view_controls_move(&a->state, glfwGetKey(w, GLFW_KEY_W) - glfwGetKey(w, GLFW_KEY_S),
                                     glfwGetKey(w, GLFW_KEY_D) - glfwGetKey(w, GLFW_KEY_A),
                                     glfwGetKey(w, GLFW_KEY_E) - glfwGetKey(w, GLFW_KEY_Q),
                                     held_mods, dt < 0.1 ? dt : 0.1);
        change |= view_controls_look(&a->state, a->drag_dx, a->drag_dy);
        change |= view_controls_zoom(&a->state, a->scroll);
        a->drag_dx = a->drag_dy = a->scroll = 0.0;
        run_script(a, now, &change);
        a->save_pending |= (change & VIEW_CHANGE_SAVE) != 0;
        if (change & VIEW_CHANGE_RENDER)
            request(a);
        else
            want_guides(a);
        if (a->save_pending && view_denoise_save_ready(&a->state, a->renderer, a->o->save_path)) {
            atmo_err se = {{0}};
            a->save_pending = 0;
            if (save(a, &se))
                snprintf(a->message, sizeof a->message, "%s", se.msg);
            if (!a->o->quiet)
                fprintf(stderr, "atmo view: %s\n", a->message);
        } else if (change & VIEW_CHANGE_SAVE) {
            snprintf(a->message, sizeof a->message,
                     "P: saving once the denoiser's guides of this view are made");
        }
        if (change & VIEW_CHANGE_QUIT)
            break;
        if ((rc = take_frame(a, e)))
            break;
        if (current(a) && a->shown.phase == VIEW_PHASE_ERROR) {
            snprintf(a->message, sizeof a->message, "%s", a->shown.message);
            if (a->o->screenshot_after > 0 || a->o->script) {
                rc = atmo_fail(e, ATMO_ERR_RUNTIME, "%s", a->shown.message);
                break;
            }
        }
        int status_due = now - last_title >= VIEW_TITLE_SECONDS;
        if (status_due) {
            title(a);
            last_title = now;
        }
        int shoot = a->o->screenshot_after > 0 && a->script.next >= a->script.count &&
                    reached(a, a->o->screenshot_after) && !(change & VIEW_CHANGE_RENDER) &&
                    view_denoise_settled(&a->state, &a->shown, a->o->output);
        /* Drawing only what changed, and new tiles at most VIEW_TILE_FPS times a second, leaves
         * the CPU to the render where the device (and Mesa's OpenGL) is the CPU. */
        int tiles_due = a->redraw && now - last_draw >= 1.0 / VIEW_TILE_FPS;
        if (!(tiles_due || change || shoot || (a->state.help && status_due)))
            continue;
        last_draw = now;
        if (a->state.help)
            overlay(a);
        atmo_post post;
        atmo_outputs_post(&a->state.scene, &post);
        view_window_draw(&a->win, &post, a->overlay.vertices, a->state.help ? a->overlay.count : 0);
        a->redraw = 0;
        if (shoot) {
            rc = screenshot(a, e);
            break;
        }
        glfwSwapBuffers(w);
    }
    return rc;
}

int atmo_view_run(const atmo_view_options *o, atmo_err *e)
{
    view_app *a = calloc(1, sizeof *a);
    if (!a)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the viewer");
    a->o = o;
    /* the controls move the camera in world metres: its y above the terrain made absolute */
    int rc = atmo_plan_place_camera(&o->scene, &a->state.scene, e);
    if (rc) {
        free(a);
        return rc;
    }
    a->state.start = a->state.scene;
    a->state.sets = o->sets;
    a->state.set_count = o->set_count;
    a->state.mode = VIEW_MODE_QUALITY;
    rc = o->script ? view_script_load(&a->script, o->script, e) : ATMO_OK;
    if (rc) {
        free(a);
        return rc;
    }
    int ww = o->window_width, wh = o->window_height;
    if (ww <= 0 || wh <= 0) {
        double k = fmin(1.0, fmin(1280.0 / o->scene.image.width, 800.0 / o->scene.image.height));
        ww = (int)fmax(1.0, floor(o->scene.image.width * k));
        wh = (int)fmax(1.0, floor(o->scene.image.height * k));
    }
    if ((rc = view_window_open(&a->win, ww, wh, e)))
        goto cleanup;
    if (!o->quiet)
        fprintf(stderr, "atmo view: OpenGL %s (%s), %s\n",
                (const char *)glGetString(GL_VERSION), (const char *)glGetString(GL_RENDERER),
                a->win.core ? "core profile, GLSL 3.30" : "2.1 context, GLSL 1.20");
    glfwSetWindowUserPointer(a->win.window, a);
    glfwSetKeyCallback(a->win.window, key_callback);
    glfwSetMouseButtonCallback(a->win.window, button_callback);
    glfwSetCursorPosCallback(a->win.window, cursor_callback);
    glfwSetScrollCallback(a->win.window, scroll_callback);
    glfwSetWindowRefreshCallback(a->win.window, refresh_callback);
    if ((rc = view_renderer_start(&a->renderer, &o->render, o->lut_cache, e)))
        goto cleanup;
    interrupted = 0;
    void (*old_int)(int) = signal(SIGINT, on_interrupt);
    void (*old_term)(int) = signal(SIGTERM, on_interrupt);
    rc = loop(a, e);
    signal(SIGINT, old_int);
    signal(SIGTERM, old_term);
    if (!o->quiet)
        fprintf(stderr, "atmo view: %ld event-loop turns, %ld while rendering: %ld of those "
                        "over 33 ms, the longest %.1f ms; %d changes, %d of them shown; the "
                        "first image of the last of a burst came in %.0f ms on average, %.0f ms "
                        "at most\n", a->turns, a->busy_turns, a->slow_turns,
                1e3 * a->longest_turn, a->changes, a->changes_shown,
                a->latency_count ? 1e3 * a->latency_sum / a->latency_count : 0.0,
                1e3 * a->latency_max);
cleanup:
    view_renderer_stop(a->renderer);
    view_window_close(&a->win);
    view_overlay_free(&a->overlay);
    view_script_free(&a->script);
    view_denoise_free(&a->denoise);
    free(a);
    return rc;
}
