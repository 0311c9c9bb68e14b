/* plan_fast.c — method "fast" (atmo/plan_fast.h): the sky-view LUT around the camera (buffer
 * sky_view_lut, after the Psi_ms LUT of feature "ms_lut"), made only when the camera is inside
 * the atmosphere and the air is lit without the path tracer's cloud volume (path.clouds =
 * volume shadows the air's sunlight point by point, which a table of the sky around the sun's
 * vertical plane cannot hold); otherwise every ray falls back to the march
 * (kernels/atmosphere/method_fast.h), so the buffer is declared empty and no pass runs. */
#include "atmo/plan_clouds.h"
#include "atmo/plan_fast.h"

int atmo_plan_fast(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    if (p->gpu.camera.local_up.w > p->gpu.atmosphere.top_radius || atmo_plan_clouds_volume(s))
        return atmo_plan_add_buffer(p, "sky_view_lut", "float4", 0, 1, NULL, e);
    int w = ATMO_SKY_VIEW_WIDTH, h = 2 * ATMO_SKY_VIEW_HALF_HEIGHT;
    p->gpu.sky_view.width = w;
    p->gpu.sky_view.height = h;
    p->gpu.sky_view.steps = ATMO_SKY_VIEW_STEPS;
    /* three planes (fast_luts.cl), made for this camera and sun */
    int rc = atmo_plan_add_buffer(p, "sky_view_lut", "float4",
                                  3 * sizeof(float4) * (size_t)w * (size_t)h, 1, NULL, e);
    return rc ? rc : atmo_plan_add_pass(p, "sky_view_lut", w, h, 1, 0, e);
}
