/* plan_cloud.h — the plan's part for the homogeneous cloud shell and the observer sphere
 * (kernels/media/cloud_shell.h; host/plan/plan_cloud.c). */
#ifndef ATMO_PLAN_CLOUD_H
#define ATMO_PLAN_CLOUD_H
#include "atmo/plan.h"

/* Steps equal in optical depth per cloud segment of a view ray. */
#define ATMO_CLOUD_STEPS 32

/* When the scene enables the cloud or the observer: checks that the method is single or march,
 * builds (or loads from the cache) the Mie tables at the render wavelengths into the buffer
 * cloud_phase_table and fills gpu.cloud (feature "cloud" of features.c, which is planned only
 * when the scene has a cloud or an observer). */
int atmo_plan_cloud(const atmo_scene *s, atmo_plan *p, atmo_err *e);

#endif
