/* view_overlay.h — the help and status overlay as triangles (view_overlay.c). */
#ifndef ATMO_VIEW_OVERLAY_H
#define ATMO_VIEW_OVERLAY_H

typedef struct view_overlay {
    float *vertices; /* VIEW_TEXT_FLOATS per vertex, triangles */
    int count, capacity;
} view_overlay;

/* Lay out `text` (lines separated by '\n') in a translucent box at the window's top left.
 * Returns 0, or -1 when out of memory (the overlay is then empty). */
int view_overlay_build(view_overlay *o, const char *text);
void view_overlay_free(view_overlay *o);

#endif
