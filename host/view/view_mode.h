/* view_mode.h — what the viewer renders in each of its modes (view_mode.c). */
#ifndef ATMO_VIEW_MODE_H
#define ATMO_VIEW_MODE_H
#include "atmo/scene.h"

enum { VIEW_MODE_PREVIEW = 0, VIEW_MODE_QUALITY = 1, VIEW_MODE_COUNT = 2 };

/* The scene rendered in `mode` for the user's scene `user` (validated). */
void view_mode_scene(const atmo_scene *user, int mode, atmo_scene *out);
/* The quarter-size draft of a mode's scene: one sample per pixel, shown after every change. */
void view_mode_draft(const atmo_scene *rendered, atmo_scene *out);
const char *view_mode_name(int mode);

#endif
