/* plan_cloud.h — the plan's part for the homogeneous cloud shell and the observer sphere
 * (kernels/media/cloud_shell.h; host/plan_cloud.c). */
#ifndef ATMO_PLAN_CLOUD_H
#define ATMO_PLAN_CLOUD_H
#include "atmo/plan.h"

/* Steps equal in optical depth per cloud segment of a view ray. */
#define ATMO_CLOUD_STEPS 32

/* When the scene enables the cloud or the observer: checks that the method is single or march,
 * builds (or loads from the cache) the Mie tables at the render wavelengths, uploads them behind
 * the transmittance LUT (owned by the plan: atmo_plan_free), fills the gpu scene's cloud fields
 * (the observer's centre camera-relative in the world's axes), inserts kernels/media/observer.h
 * and kernels/media/cloud_shell.h before kernels/media/media.h and defines ATMO_CLOUD. Does
 * nothing otherwise. */
int atmo_plan_cloud(const atmo_scene *s, atmo_plan *p, atmo_err *e);

#endif
