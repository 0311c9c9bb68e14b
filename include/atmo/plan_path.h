/* plan_path.h — the plan's part for the scene's objects and the path tracer
 * (kernels/render/objects.h, kernels/render/path.h; host/plan/plan_path.c). */
#ifndef ATMO_PLAN_PATH_H
#define ATMO_PLAN_PATH_H
#include "atmo/plan.h"

/* Feature "objects" (a scene with objects): the host table of atmo_gpu_object, camera-relative,
 * in the buffer `objects`, and gpu.path.object_count. */
int atmo_plan_objects(const atmo_scene *s, atmo_plan *p, atmo_err *e);
/* Feature "path" (render.mode = path): gpu.path's settings and the render kernel path_render. */
int atmo_plan_path(const atmo_scene *s, atmo_plan *p, atmo_err *e);
/* Feature "path_air" (render.mode = path, path.air = medium): checks that the scene has the
 * air to scatter in (path.sky = atmosphere). */
int atmo_plan_path_air(const atmo_scene *s, atmo_plan *p, atmo_err *e);

#endif
