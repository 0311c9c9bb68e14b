/* plan_clouds.h — the plan's part for the fBm cloud layer (kernels/clouds/cloud_layer.h,
 * cloud_march.h; host/features/clouds/plan_clouds.c). */
#ifndef ATMO_PLAN_CLOUDS_H
#define ATMO_PLAN_CLOUDS_H
#include "atmo/plan.h"

/* 1 where the layer is the path tracer's volume medium alone (render.mode = path, path.clouds =
 * volume): no method sees it as a medium, and the air's sunlight passes it by ratio tracking
 * (kernels/media/media_walk.h's media_walk_volume_sun). */
int atmo_plan_clouds_volume(const atmo_scene *s);

/* When the scene has clouds.enabled: checks the method (single, march or reference) and the
 * layer's altitudes, builds (or loads from the cache) the Mie tables of clouds.dsd into the
 * buffers clouds_phase_table and clouds_phase_cdf and fills gpu.clouds (feature "clouds" of
 * features.c). */
int atmo_plan_clouds(const atmo_scene *s, atmo_plan *p, atmo_err *e);

/* With clouds and method reference: the majorant grid of the Monte Carlo walk, the buffer
 * clouds_majorant (CLOUDS_GRID_NX x NY x NZ floats, kernels/clouds/cloud_majorant.h) and its pass
 * clouds_majorant_grid; it follows the view (feature "clouds_majorant" of host/features/). */
int atmo_plan_clouds_majorant(const atmo_scene *s, atmo_plan *p, atmo_err *e);

/* The largest sun shadow map clouds.shadow_map_size^2 x clouds.shadow_map_levels floats may
 * take (a larger one is refused with a usage error). */
#define ATMO_CLOUDS_SHADOW_MAP_MAX_BYTES ((size_t)512 << 20)

/* With clouds.shadow_map and a method other than reference (which ratio-tracks the sun's
 * transmittance): checks its size against ATMO_CLOUDS_SHADOW_MAP_MAX_BYTES, fills gpu.clouds'
 * shadow_map_* fields, the buffer clouds_shadow_map (size^2 x levels floats,
 * kernels/clouds/cloud_shadow_map.h) and its pass clouds_shadow_map_nodes; it follows the view
 * (feature "clouds_shadow_map" of host/features/, flag -DATMO_CLOUDS_SHADOW_MAP). */
int atmo_plan_clouds_shadow_map(const atmo_scene *s, atmo_plan *p, atmo_err *e);

/* The noise's origin: the camera's world position minus the wind's displacement by
 * clouds.time_s (what gpu.clouds.origin holds; it follows the view). */
void atmo_plan_clouds_origin(const atmo_scene *s, float4 *origin);

#endif
