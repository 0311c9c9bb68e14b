/* view_window.h — the viewer's window: GLFW, an OpenGL context, the image texture and its
 * tone-mapping shader, the overlay's triangles (view_window.c). */
#ifndef ATMO_VIEW_WINDOW_H
#define ATMO_VIEW_WINDOW_H
#define GLFW_INCLUDE_GLEXT
#define GL_GLEXT_PROTOTYPES
#include <GLFW/glfw3.h>
#include "atmo/image.h"
#include "atmo/status.h"

typedef struct view_window {
    GLFWwindow *window;
    int core;                 /* 1: OpenGL 3.3 core, 0: OpenGL 2.1 */
    GLuint image_program, text_program, vao, quad, text_buffer, texture;
    GLint u_image, u_exposure, u_tonemap, u_white_point, u_white_balance, u_white_balance_rgb,
        u_transfer, u_viewport;
    int tex_width, tex_height; /* 0 until the first image */
} view_window;

/* Floats per overlay vertex: x, y (window pixels, y down), r, g, b, a. */
#define VIEW_TEXT_FLOATS 6

/* Open a width x height window (GLFW initialised here) with an OpenGL 3.3 core context, or 2.1
 * where 3.3 is not available. On failure nothing is left open. */
int view_window_open(view_window *w, int width, int height, atmo_err *e);
void view_window_close(view_window *w);
void view_window_title(view_window *w, const char *title);
/* A texture of this size (recreated, black, when the size changes). */
int view_window_image(view_window *w, int width, int height, atmo_err *e);
/* Upload the rectangle (x, y, rw, rh) of an image `stride` pixels wide (row 0 = top, 3 floats
 * per pixel) into the texture at the same place: a sub-image update. */
void view_window_upload(view_window *w, const float *rgb, int stride, int x, int y, int rw,
                        int rh);
/* Draw the image (fitted to the framebuffer, aspect kept) through the display pipeline of
 * `post`, then `count` overlay vertices (triangles) on top; the caller swaps. */
void view_window_draw(view_window *w, const atmo_post *post, const float *text, int count);
/* The drawn framebuffer (before the swap) as a PNG, written atomically. */
int view_window_capture(view_window *w, const char *path, atmo_err *e);

#endif
