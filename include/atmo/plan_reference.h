/* plan_reference.h — the plan of atmosphere method "reference" (kernels/atmosphere/method_reference.h):
 * the Monte Carlo path tracer that is the oracle of the other methods. */
#ifndef ATMO_PLAN_REFERENCE_H
#define ATMO_PLAN_REFERENCE_H
#include "atmo/plan.h"

/* Sets gpu.reference from reference.min_order and reference.max_order (0 = all orders). No
 * buffers or passes of its own. */
int atmo_plan_reference(const atmo_scene *s, atmo_plan *p, atmo_err *e);

#endif
