/* view.h — the live viewer (`atmo view`): a GLFW window that shows a render session's image
 * as it converges and lets the user move the camera and turn the sun.
 *
 * The viewer is optional: it is built only where GLFW 3 and OpenGL are found (host/view/, the
 * atmo_view library), and only the `atmo` binary links it. The caller (host/cli/cmd_view.c)
 * assembles and validates the start scene; atmo_view_run opens the window, renders through
 * render sessions on a thread of its own (atmo/session.h) and returns the process exit status.
 *
 * Modes. The viewer renders one of two configurations of the user's scene (view_mode.c):
 * preview (method `fast` at half the image size) and quality (the scene as given). A camera,
 * sun or mode change restarts the accumulation at once; the first image after it is a
 * quarter-size draft of one sample per pixel, then the full-size image refines tile by tile.
 *
 * Outputs. P writes the image on display through atmo_image_write (the formats and atomic
 * writes of `atmo render`) and the scene file beside it (atmo_scene_save_json), so that
 * `atmo render --scene FILE` reproduces the shot. With screenshot_after N the viewer waits until
 * every pixel of the current view has N samples (after the script, if any, has run), writes
 * `output` the same way and exits; `window_capture` is then also written: a PNG of the window's
 * framebuffer as the shader tone-mapped it (glReadPixels), which the tests compare with the
 * offline writer's PNG. */
#ifndef ATMO_VIEW_H
#define ATMO_VIEW_H
#include "atmo/scene.h"
#include "atmo/session.h"
#include "atmo/status.h"

typedef struct atmo_view_options {
    atmo_scene scene;              /* the start scene, validated */
    const char *const *sets;       /* the user's --set assignments, reapplied over a thesis */
    int set_count;                 /*   view chosen with keys 1-9 */
    atmo_render_settings render;   /* device, tile size, launch budget, kernel cache */
    int lut_cache;                 /* 0/1: the LUT and Mie table disk caches */
    int screenshot_after;          /* 0: off; else samples per pixel before writing `output` */
    const char *output;            /* image written after screenshot_after samples */
    const char *window_capture;    /* PNG of the window written with `output`, or NULL */
    const char *script;            /* timed synthetic key events (view_script.c), or NULL */
    const char *save_path;         /* where P saves; a counter goes before the extension */
    int window_width, window_height; /* 0: the image size, scaled down to fit 1280 x 800 */
    int quiet;                     /* no status lines on stderr */
} atmo_view_options;

/* The keys, one per line (host/view/view_controls.c), for --help and the overlay. */
extern const char atmo_view_keys[];

/* Run the viewer until the window closes, Esc, the script's `quit`, SIGINT/SIGTERM or the
 * screenshot. Returns ATMO_OK, ATMO_ERR_USAGE (a bad script, before the window opens) or
 * ATMO_ERR_RUNTIME (no display, OpenGL, the render, writing), with e set. */
int atmo_view_run(const atmo_view_options *o, atmo_err *e);

#endif
