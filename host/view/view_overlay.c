/* view_overlay.c — help and status text over the image.
 *
 * The glyphs come from stb_easy_font (Debian's libstb): each character is a few axis-aligned
 * quads in a cell about 6 x 12 font units, no texture needed. Each quad becomes two triangles, scaled by
 * VIEW_TEXT_SCALE and drawn in window pixels (y down) over a box of translucent black, so the
 * text reads on any sky. */
#include <stdlib.h>
#include <string.h>
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop
#include "view_overlay.h"
#include "view_window.h"

#define VIEW_TEXT_SCALE 1.5f
#define VIEW_TEXT_MARGIN 8.0f
#define VIEW_TEXT_MAX_QUADS 4000 /* per field */
#define VIEW_TEXT_CELL 6.0f  /* font units per character column (stb_easy_font's advance) */
#define VIEW_TEXT_LINE 12.0f /* font units per line */

static int reserve(view_overlay *o, int more)
{
    if (o->count + more <= o->capacity)
        return 0;
    int cap = o->capacity ? o->capacity : 1024;
    while (cap < o->count + more)
        cap *= 2;
    float *v = realloc(o->vertices, (size_t)cap * VIEW_TEXT_FLOATS * sizeof(float));
    if (!v)
        return -1;
    o->vertices = v;
    o->capacity = cap;
    return 0;
}

/* The rectangle (x0, y0)-(x1, y1) as two triangles of one colour. */
static int rect(view_overlay *o, float x0, float y0, float x1, float y1, const float rgba[4])
{
    if (reserve(o, 6))
        return -1;
    const float corners[6][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y0}, {x1, y1}, {x0, y1}};
    for (int k = 0; k < 6; k++) {
        float *v = o->vertices + (size_t)(o->count++) * VIEW_TEXT_FLOATS;
        v[0] = corners[k][0];
        v[1] = corners[k][1];
        memcpy(v + 2, rgba, 4 * sizeof(float));
    }
    return 0;
}

/* Draw one field of a line at (x, y) in font units: its quads as pairs of triangles. */
static int field(view_overlay *o, float *quads, float x, float y, char *text, const float ink[4])
{
    int n = stb_easy_font_print(x, y, text, NULL, quads,
                                VIEW_TEXT_MAX_QUADS * 4 * 4 * (int)sizeof(float));
    for (int q = 0; q < n; q++) {
        const float *c = quads + (size_t)q * 16; /* corners 0..3 at floats 0, 4, 8, 12 */
        if (rect(o, VIEW_TEXT_MARGIN + c[0] * VIEW_TEXT_SCALE, VIEW_TEXT_MARGIN + c[1] * VIEW_TEXT_SCALE,
                 VIEW_TEXT_MARGIN + c[8] * VIEW_TEXT_SCALE, VIEW_TEXT_MARGIN + c[9] * VIEW_TEXT_SCALE,
                 ink))
            return -1;
    }
    return 0;
}

int view_overlay_build(view_overlay *o, const char *text)
{
    static const float box[4] = {0.0f, 0.0f, 0.0f, 0.6f}, ink[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    o->count = 0;
    char *copy = strdup(text);
    /* stb_easy_font: 4 vertices of 16 bytes (x, y, z, rgba8) per quad */
    float *quads = malloc((size_t)VIEW_TEXT_MAX_QUADS * 4 * 4 * sizeof(float));
    int rc = copy && quads ? rect(o, 0.0f, 0.0f, 0.0f, 0.0f, box) : -1; /* sized below */
    float width = 0.0f, y = 0.0f;
    /* The text is laid out for a fixed-width terminal (--help prints it too): a field after a
     * run of two or more blanks starts at its character column times the font's cell width,
     * so the columns line up in this proportional font as well. */
    for (char *line = copy; !rc && line && *line; y += VIEW_TEXT_LINE) {
        char *end = strchr(line, '\n');
        if (end)
            *end = 0;
        for (char *f = line; !rc && *f;) {
            while (*f == ' ')
                f++;
            if (!*f)
                break;
            char *stop = strstr(f, "  ");
            char saved = stop ? *stop : 0;
            if (stop)
                *stop = 0;
            float x = (float)(f - line) * VIEW_TEXT_CELL;
            rc = field(o, quads, x, y, f, ink);
            float right = x + (float)stb_easy_font_width(f);
            width = right > width ? right : width;
            if (!stop)
                break;
            *stop = saved;
            f = stop;
        }
        line = end ? end + 1 : NULL;
    }
    if (!rc) { /* the box behind: the first six vertices */
        float x1 = width * VIEW_TEXT_SCALE + 2.0f * VIEW_TEXT_MARGIN;
        float y1 = y * VIEW_TEXT_SCALE + 2.0f * VIEW_TEXT_MARGIN;
        const float corners[6][2] = {{0, 0}, {x1, 0}, {x1, y1}, {0, 0}, {x1, y1}, {0, y1}};
        for (int k = 0; k < 6; k++) {
            o->vertices[k * VIEW_TEXT_FLOATS] = corners[k][0];
            o->vertices[k * VIEW_TEXT_FLOATS + 1] = corners[k][1];
        }
    }
    free(quads);
    free(copy);
    if (rc)
        o->count = 0;
    return rc;
}

void view_overlay_free(view_overlay *o)
{
    free(o->vertices);
    memset(o, 0, sizeof *o);
}
