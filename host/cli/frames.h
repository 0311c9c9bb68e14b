/* frames.h — animations for `atmo render --frames A..B` (frames.c): scene keys that move
 * linearly from the first frame to the last. */
#ifndef ATMO_FRAMES_H
#define ATMO_FRAMES_H
#include <stddef.h>
#include "atmo/scene.h"
#include "atmo/status.h"

#define FRAMES_MAX_KEYS 64
#define FRAMES_LAST 9999 /* frame numbers have 4 digits: NAME.0001.exr */

typedef struct frames_key {
    const atmo_param *param;
    double v0[3], v1[3]; /* at the first and at the last frame */
} frames_key;

typedef struct frames_animation {
    int first, last;
    int count;
    frames_key keys[FRAMES_MAX_KEYS];
} frames_animation;

/* "A..B" with 1 <= A <= B <= FRAMES_LAST. */
int frames_parse_range(const char *text, int *first, int *last, atmo_err *e);
/* "KEY=V0..V1" for a float key (the values in the key's unit, as --set takes them). */
int frames_add_animate(frames_animation *a, const char *text, atmo_err *e);
/* Every key in which `end` differs from `start`: float and vec3 keys move, any other differing
 * key is a usage error (a count or a choice cannot move linearly). `where` names the end file. */
int frames_add_scene_end(frames_animation *a, const atmo_scene *start, const atmo_scene *end,
                         const char *where, atmo_err *e);
/* The scene of `frame`: start with every animated key at (1 - t) v0 + t v1, t = (frame - first)
 * / (last - first) (0 for a single frame), each value checked as --set checks it, then the
 * whole scene validated. */
int frames_scene(const frames_animation *a, const atmo_scene *start, int frame, atmo_scene *out,
                 atmo_err *e);
/* path with ".NNNN" before its extension (sky.exr -> sky.0007.exr); 0 if it does not fit. */
int frames_path(const char *path, int frame, char *out, size_t size);

#endif
