/* plan_fast.c — method "fast" (atmo/plan_fast.h): the Psi_ms LUT (buffer a, shared with
 * "march"), then the sky-view LUT around the camera (buffer b), built only when the camera is
 * inside the atmosphere; from above it every ray falls back to the march
 * (kernels/atmosphere/method_fast.h), so no sky-view LUT is computed or allocated. */
#include "atmo/plan_fast.h"
#include "atmo/plan_march.h"

int atmo_plan_fast(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    static const char *const fragments[] = {"kernels/atmosphere/method_fast.h", "kernels/atmosphere/fast_luts.cl"};
    int rc;
    if ((rc = atmo_plan_ms_lut(s, p, e)) || (rc = atmo_plan_add_fragments(p, fragments, 2, e)))
        return rc;
    if (p->gpu.camera.local_up.w > p->gpu.atmosphere.top_radius)
        return ATMO_OK;
    int w = ATMO_SKY_VIEW_WIDTH, h = 2 * ATMO_SKY_VIEW_HALF_HEIGHT;
    p->gpu.lut_dims[1][0] = w;
    p->gpu.lut_dims[1][1] = h;
    p->gpu.method_int[3] = ATMO_SKY_VIEW_STEPS;
    p->lut_bytes[2] = 3 * sizeof(float4) * (size_t)w * (size_t)h; /* fast_luts.cl's planes */
    p->lut_follows_view[2] = 1; /* the sky-view LUT is made for this camera and sun */
    if ((rc = atmo_plan_add_pass(p, "sky_view_lut", w, h, 1, 0, e)))
        return rc;
    p->passes[p->pass_count - 1].follows_view = 1;
    return ATMO_OK;
}
