/* plan_clouds.h — the plan's part for the fBm cloud layer (kernels/media/cloud_layer.h,
 * cloud_march.h; host/plan/plan_clouds.c). */
#ifndef ATMO_PLAN_CLOUDS_H
#define ATMO_PLAN_CLOUDS_H
#include "atmo/plan.h"

/* 1 where the layer is the path tracer's volume alone (render.mode = path, path.clouds = volume,
 * -DATMO_CLOUDS_VOLUME): no method sees it as a medium, and the air's sunlight passes it by
 * ratio tracking (kernels/media/visibility.h's visibility_air_volume). */
int atmo_plan_clouds_volume(const atmo_scene *s);

/* When the scene has clouds.enabled: checks the method (single, march or reference) and the
 * layer's altitudes, builds (or loads from the cache) the Mie tables of clouds.dsd into the
 * buffers clouds_phase_table and clouds_phase_cdf and fills gpu.clouds (feature "clouds" of
 * features.c). */
int atmo_plan_clouds(const atmo_scene *s, atmo_plan *p, atmo_err *e);

/* With clouds and method reference: the majorant grid of the Monte Carlo walk, the buffer
 * clouds_majorant (CLOUDS_GRID_NX x NY x NZ floats, kernels/media/cloud_majorant.h) and its pass
 * clouds_majorant_grid; it follows the view (feature "clouds_majorant" of features.c). */
int atmo_plan_clouds_majorant(const atmo_scene *s, atmo_plan *p, atmo_err *e);

/* The noise's origin: the camera's world position minus the wind's displacement by
 * clouds.time_s (what gpu.clouds.origin holds; it follows the view). */
void atmo_plan_clouds_origin(const atmo_scene *s, float4 *origin);

#endif
