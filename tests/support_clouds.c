/* The host-built cloud marcher's test scene: see testclouds.h. */
#include <math.h>
#include <string.h>
#include "atmo/gpu_enums.h"
#include "testclouds.h"

void test_overcast_scene(atmo_gpu_scene *s)
{
    memset(s, 0, sizeof *s);
    s->atmosphere.bottom_radius = 6360e3f;
    s->atmosphere.top_radius = 6420e3f;
    s->atmosphere.rayleigh_scale_height = 8000.0f;
    s->atmosphere.mie_scale_height = 1200.0f;
    s->atmosphere.solar_irradiance.x = s->atmosphere.solar_irradiance.y = 1.0f;
    s->atmosphere.solar_irradiance.z = 1.0f;
    s->transmittance_width = s->transmittance_height = 4;
    s->camera.local_up.y = 1.0f;
    s->camera.local_up.w = 6360e3f + 500.0f;
    double sun_el = 45.0 * M_PI / 180.0;
    s->sun_direction.x = (float)cos(sun_el), s->sun_direction.y = (float)sin(sun_el);
    s->sun_direction.w = cosf(0.0047f);
    atmo_gpu_clouds *c = &s->clouds;
    c->extinction.x = c->extinction.y = c->extinction.z = 10.354e-3f;
    c->albedo.x = c->albedo.y = c->albedo.z = 0.9512f;
    c->g.x = c->g.y = c->g.z = 0.85f;
    c->origin.x = 23796.0f, c->origin.y = 500.0f, c->origin.z = 16636.0f;
    c->frequency.x = 8e-5f, c->frequency.y = 16e-5f, c->frequency.z = 8e-5f;
    c->frequency.w = 1.0f / 5e5f;
    c->bottom_m = 1000.0f, c->top_m = 3000.0f, c->fade_m = 500.0f;
    c->coverage = 1.0f, c->density = 0.4f, c->sharpness = 1.05f, c->warp_m = 3000.0f;
    c->light_distance_m = 1e6f, c->max_distance_m = 1e6f;
    c->majorant = c->density;
    c->phase = ATMO_CLOUD_PHASE_HG;
    c->table_size = 1;
    c->octaves = 6;
    c->steps = 100000;
    c->ms_octaves = 1;
    c->look = ATMO_CLOUDS_LOOK_PHYSICAL;
}
