/* plan_reference.c — plan of the Monte Carlo reference method (atmo/plan_reference.h).
 *
 * The path tracer needs nothing precomputed (it must not depend on the LUTs it is used to
 * test), so the plan only sets the order window (atmo_gpu_reference). */
#include "atmo/plan_reference.h"

int atmo_plan_reference(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    int lo = s->atmosphere.reference_min_order, hi = s->atmosphere.reference_max_order;
    if (hi != 0 && hi < lo)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "reference.max_order=%d is below reference.min_order=%d; set "
                         "max_order >= min_order, or 0 for all orders",
                         hi, lo);
    p->gpu.reference.min_order = lo;
    p->gpu.reference.max_order = hi;
    return ATMO_OK;
}
