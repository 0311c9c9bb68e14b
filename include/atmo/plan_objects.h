/* plan_objects.h — the plan's part for the scene's spheres and boxes (kernels/render/objects*.h;
 * host/features/objects/). */
#ifndef ATMO_PLAN_OBJECTS_H
#define ATMO_PLAN_OBJECTS_H
#include "atmo/plan.h"

/* Feature "objects" (a scene with objects): the host table of atmo_gpu_object, camera-relative,
 * in the buffer `objects`, and gpu.path.object_count. */
int atmo_plan_objects(const atmo_scene *s, atmo_plan *p, atmo_err *e);

#endif
