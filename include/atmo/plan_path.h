/* plan_path.h — the plan's part for the path tracer (kernels/render/path.h;
 * host/features/path/). */
#ifndef ATMO_PLAN_PATH_H
#define ATMO_PLAN_PATH_H
#include "atmo/plan.h"

/* Feature "path" (render.mode = path): gpu.path's settings and the render kernel path_render. */
int atmo_plan_path(const atmo_scene *s, atmo_plan *p, atmo_err *e);
/* Feature "path_air" (render.mode = path, path.air = medium): checks that the scene has the
 * air to scatter in (path.sky = atmosphere). */
int atmo_plan_path_air(const atmo_scene *s, atmo_plan *p, atmo_err *e);

#endif
