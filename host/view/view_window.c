/* view_window.c — the viewer's window and its OpenGL drawing.
 *
 * Context: OpenGL 3.3 core (forward compatible, with a vertex array object), or OpenGL 2.1 where
 * the driver offers no 3.3 context; the shaders of view_shader.c compile for either through a
 * prefix. The image is a GL_RGB32F texture holding the linear mean radiance (row 0 of the
 * image at texture coordinate v = 0, so the quad maps v = 0 to the top of the window); finished
 * tiles arrive as glTexSubImage2D updates of their rectangle (GL_UNPACK_ROW_LENGTH walks the
 * frame's rows), and the fragment shader applies the display pipeline per pixel, so exposure and
 * tone mapper changes only redraw. The image is fitted into the framebuffer with its aspect kept
 * (glViewport on the centred rectangle); texels are sampled nearest where the image is shown at
 * its own size (one texel per pixel: what the capture test reads back) and bilinearly when
 * scaled. The overlay is a list of triangles in window pixels, alpha blended over the image.
 *
 * The capture reads the back buffer after drawing (glReadPixels, GL_RGB, 8 bits, bottom row
 * first), flips it to top-first and writes it as a PNG through atmo_image_write_png_rgb8
 * (atomically, as every image file). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "view_shader.h"
#include "view_window.h"

static int gl_failure(atmo_err *e, const char *what, GLuint object, int program)
{
    char log[768] = "";
    if (program)
        glGetProgramInfoLog(object, sizeof log, NULL, log);
    else
        glGetShaderInfoLog(object, sizeof log, NULL, log);
    for (char *c = log; *c; c++)
        if (*c == '\n')
            *c = ' ';
    return atmo_fail(e, ATMO_ERR_RUNTIME, "OpenGL: %s failed: %s", what, log);
}

static GLuint compile(GLenum kind, const char *prefix, const char *body, atmo_err *e)
{
    const char *parts[2] = {prefix, body};
    GLuint sh = glCreateShader(kind);
    GLint ok = 0;
    glShaderSource(sh, 2, parts, NULL);
    glCompileShader(sh);
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        gl_failure(e, kind == GL_VERTEX_SHADER ? "compiling the vertex shader"
                                               : "compiling the fragment shader", sh, 0);
        glDeleteShader(sh);
        return 0;
    }
    return sh;
}

/* A program from two sources; attributes 0 and 1 are bound to the names given. */
static GLuint link_program(const char *prefix, const char *vs_src, const char *fs_src,
                           const char *attr0, const char *attr1, atmo_err *e)
{
    GLuint vs = compile(GL_VERTEX_SHADER, prefix, vs_src, e);
    GLuint fs = vs ? compile(GL_FRAGMENT_SHADER, prefix, fs_src, e) : 0;
    GLuint p = 0;
    GLint ok = 0;
    if (vs && fs) {
        p = glCreateProgram();
        glAttachShader(p, vs);
        glAttachShader(p, fs);
        glBindAttribLocation(p, 0, attr0);
        glBindAttribLocation(p, 1, attr1);
        glLinkProgram(p);
        glGetProgramiv(p, GL_LINK_STATUS, &ok);
        if (!ok) {
            gl_failure(e, "linking a shader program", p, 1);
            glDeleteProgram(p);
            p = 0;
        }
    }
    if (fs)
        glDeleteShader(fs);
    if (vs)
        glDeleteShader(vs);
    return p;
}

static GLFWwindow *create(int width, int height, int core)
{
    glfwDefaultWindowHints();
    if (core) {
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    } else {
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
    }
    return glfwCreateWindow(width, height, "atmo view", NULL, NULL);
}

int view_window_open(view_window *w, int width, int height, atmo_err *e)
{
    memset(w, 0, sizeof *w);
    if (!glfwInit()) {
        const char *why = NULL;
        glfwGetError(&why);
        return atmo_fail(e, ATMO_ERR_RUNTIME,
                         "cannot open a window: %s (is DISPLAY set? under no X server run "
                         "xvfb-run -a atmo view ...)", why ? why : "glfwInit failed");
    }
    w->core = 1;
    w->window = create(width, height, 1);
    if (!w->window) {
        w->core = 0;
        w->window = create(width, height, 0);
    }
    if (!w->window) {
        const char *why = NULL;
        glfwGetError(&why);
        glfwTerminate();
        return atmo_fail(e, ATMO_ERR_RUNTIME,
                         "cannot create an OpenGL 3.3 or 2.1 window: %s", why ? why : "unknown");
    }
    glfwMakeContextCurrent(w->window);
    glfwSwapInterval(0); /* the event loop paces itself (view.c); vsync would hold it */
    const char *prefix = w->core ? view_glsl_core : view_glsl_legacy;
    w->image_program = link_program(prefix, view_glsl_image_vertex, view_glsl_image_fragment,
                                    "position", "texcoord", e);
    w->text_program = w->image_program
                          ? link_program(prefix, view_glsl_text_vertex, view_glsl_text_fragment,
                                         "position", "colour", e)
                          : 0;
    if (!w->text_program) {
        view_window_close(w);
        return ATMO_ERR_RUNTIME;
    }
    w->u_image = glGetUniformLocation(w->image_program, "image");
    w->u_exposure = glGetUniformLocation(w->image_program, "exposure");
    w->u_tonemap = glGetUniformLocation(w->image_program, "tonemap");
    w->u_white_point = glGetUniformLocation(w->image_program, "white_point");
    w->u_white_balance = glGetUniformLocation(w->image_program, "white_balance");
    w->u_white_balance_rgb = glGetUniformLocation(w->image_program, "white_balance_rgb");
    w->u_transfer = glGetUniformLocation(w->image_program, "transfer");
    w->u_viewport = glGetUniformLocation(w->text_program, "viewport");
    if (w->core) {
        glGenVertexArrays(1, &w->vao);
        glBindVertexArray(w->vao);
    }
    /* a strip over the viewport: NDC position, then texture coordinate (v = 0 at the top) */
    static const float quad[16] = {-1.0f, -1.0f, 0.0f, 1.0f, 1.0f, -1.0f, 1.0f, 1.0f,
                                   -1.0f, 1.0f,  0.0f, 0.0f, 1.0f, 1.0f,  1.0f, 0.0f};
    glGenBuffers(1, &w->quad);
    glBindBuffer(GL_ARRAY_BUFFER, w->quad);
    glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STATIC_DRAW);
    glGenBuffers(1, &w->text_buffer);
    glGenTextures(1, &w->texture);
    GLenum err = glGetError();
    if (err != GL_NO_ERROR) {
        view_window_close(w);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "OpenGL error 0x%x while setting up the window",
                         err);
    }
    return ATMO_OK;
}

void view_window_close(view_window *w)
{
    if (!w->window)
        return;
    if (w->texture)
        glDeleteTextures(1, &w->texture);
    if (w->text_buffer)
        glDeleteBuffers(1, &w->text_buffer);
    if (w->quad)
        glDeleteBuffers(1, &w->quad);
    if (w->vao)
        glDeleteVertexArrays(1, &w->vao);
    if (w->text_program)
        glDeleteProgram(w->text_program);
    if (w->image_program)
        glDeleteProgram(w->image_program);
    glfwDestroyWindow(w->window);
    glfwTerminate();
    memset(w, 0, sizeof *w);
}

void view_window_title(view_window *w, const char *title) { glfwSetWindowTitle(w->window, title); }

int view_window_image(view_window *w, int width, int height, atmo_err *e)
{
    if (width == w->tex_width && height == w->tex_height)
        return ATMO_OK;
    glBindTexture(GL_TEXTURE_2D, w->texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, width, height, 0, GL_RGB, GL_FLOAT, NULL);
    GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return atmo_fail(e, ATMO_ERR_RUNTIME,
                         "OpenGL error 0x%x creating a %dx%d float texture (GL_RGB32F)", err,
                         width, height);
    w->tex_width = width;
    w->tex_height = height;
    return ATMO_OK;
}

void view_window_upload(view_window *w, const float *rgb, int stride, int x, int y, int rw, int rh)
{
    glBindTexture(GL_TEXTURE_2D, w->texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, stride);
    glTexSubImage2D(GL_TEXTURE_2D, 0, x, y, rw, rh, GL_RGB, GL_FLOAT,
                    rgb + 3 * ((size_t)y * (size_t)stride + (size_t)x));
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
}

void view_window_draw(view_window *w, const atmo_post *post, const float *text, int count)
{
    int fw, fh;
    glfwGetFramebufferSize(w->window, &fw, &fh);
    glViewport(0, 0, fw, fh);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    if (w->tex_width > 0 && fw > 0 && fh > 0) {
        /* the largest rectangle of the image's aspect, centred */
        int vw = fw, vh = (int)((double)fw * w->tex_height / w->tex_width + 0.5);
        if (vh > fh) {
            vh = fh;
            vw = (int)((double)fh * w->tex_width / w->tex_height + 0.5);
        }
        glViewport((fw - vw) / 2, (fh - vh) / 2, vw, vh);
        int same = vw == w->tex_width && vh == w->tex_height;
        glBindTexture(GL_TEXTURE_2D, w->texture);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, same ? GL_NEAREST : GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, same ? GL_NEAREST : GL_LINEAR);
        glUseProgram(w->image_program);
        glUniform1i(w->u_image, 0);
        glUniform1f(w->u_exposure, post->exposure);
        glUniform1i(w->u_tonemap, post->tonemap);
        glUniform1f(w->u_white_point, post->white_point);
        glUniform1i(w->u_white_balance, post->white_balance);
        glUniform3fv(w->u_white_balance_rgb, 1, post->white_balance_rgb);
        glUniform1i(w->u_transfer, post->transfer);
        glActiveTexture(GL_TEXTURE0);
        glBindBuffer(GL_ARRAY_BUFFER, w->quad);
        glEnableVertexAttribArray(0);
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 4 * sizeof(float), (void *)0);
        glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 4 * sizeof(float),
                              (void *)(2 * sizeof(float)));
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
        glViewport(0, 0, fw, fh);
    }
    if (count > 0) {
        int ww, wh;
        glfwGetWindowSize(w->window, &ww, &wh);
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        glUseProgram(w->text_program);
        glUniform2f(w->u_viewport, (float)ww, (float)wh);
        glBindBuffer(GL_ARRAY_BUFFER, w->text_buffer);
        glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)count * VIEW_TEXT_FLOATS * sizeof(float), text,
                     GL_STREAM_DRAW);
        glEnableVertexAttribArray(0);
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, VIEW_TEXT_FLOATS * sizeof(float), (void *)0);
        glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, VIEW_TEXT_FLOATS * sizeof(float),
                              (void *)(2 * sizeof(float)));
        glDrawArrays(GL_TRIANGLES, 0, count);
        glDisable(GL_BLEND);
    }
}

int view_window_capture(view_window *w, const char *path, atmo_err *e)
{
    int fw, fh, rc = ATMO_OK;
    glfwGetFramebufferSize(w->window, &fw, &fh);
    size_t row = (size_t)fw * 3;
    unsigned char *pixels = malloc(row * (size_t)fh), *flipped = malloc(row * (size_t)fh);
    if (!pixels || !flipped) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory capturing the window");
        goto cleanup;
    }
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, fw, fh, GL_RGB, GL_UNSIGNED_BYTE, pixels);
    GLenum err = glGetError();
    if (err != GL_NO_ERROR) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "OpenGL error 0x%x reading the framebuffer", err);
        goto cleanup;
    }
    for (int y = 0; y < fh; y++)
        memcpy(flipped + (size_t)y * row, pixels + (size_t)(fh - 1 - y) * row, row);
    rc = atmo_image_write_png_rgb8(path, fw, fh, flipped, NULL, NULL, e);
cleanup:
    free(flipped);
    free(pixels);
    return rc;
}
