/* plan_fast.h — plan of the atmosphere method "fast" (kernels/atmosphere/method_fast.h). */
#ifndef ATMO_PLAN_FAST_H
#define ATMO_PLAN_FAST_H
#include "atmo/plan.h"

/* Sky-view LUT: columns of azimuth, rows per half (sky, ground), segments per texel ray. */
#define ATMO_SKY_VIEW_WIDTH 128
#define ATMO_SKY_VIEW_HALF_HEIGHT 64
#define ATMO_SKY_VIEW_STEPS 64

int atmo_plan_fast(const atmo_scene *s, atmo_plan *p, atmo_err *e);

#endif
