/* sky.cl — the kernels that render with whichever method the plan assembled (sky_method.h).
 *
 * sky_render: one tile, a batch of samples. Work item (x, y) renders pixel (tile_x + x,
 * tile_y + y); global sizes are padded to the local size, so items outside the tile return at
 * once. Samples sample_begin .. sample_begin + sample_count - 1 are added one by one, in order,
 * to the pixel's running sum in `accum` (xyz; w unused), and their squares to the running sum
 * in `accum_sq` (xyz; w unused: the second moment for the standard error, atmo/session.h).
 * Because the sums are built in the same order whatever the batches, and the random numbers
 * depend only on (seed, pixel, sample, dimension), the image is bitwise the same for any tile
 * size and any split of samples into launches. A non-finite sample (which should never happen)
 * is dropped and counted in `nonfinite`. The sample's stage-0 random stream (rng.h) places it
 * in the pixel (the camera's CAMERA_RNG_DIMS numbers) and goes on to the method's sky_trace
 * along the camera-relative ray, through the features' camera stages that the plan composes
 * (render_camera_trace: the preview's objects, render/objects_stage.h, end a pixel's ray at the
 * object; the terrain, terrain/terrain_stage.h, adds the water's mirror and, under fast or
 * lut, integrates the air in front of it), or the method's sky_trace where no stage takes it.
 *
 * sky_probe: the mean of `samples` samples of sky_radiance (sky_cosines.h) for a list of rays
 * given as (r, mu, mu_s, nu), for `atmo radiance` and the tests; ray i uses pixel index i.
 * sky_probe_segment: the same for sky_segment, ray i ending at distance[i] (m): the mean
 * in-scattered radiance in inscatter[i] and the mean transmittance in transmittance[i].
 * sky_probe_sun: the sun's visibility at each ray's origin, visibility_sun (visibility.h: the
 * occluders and the shadowing media toward the sun, per wavelength; the atmosphere's own
 * transmittance not included), the query every kernel's sunlight goes through. */

__kernel void sky_render(__global const atmo_gpu_scene *scene, ATMO_LUT_PARAMS,
                         __global float4 *accum, __global float4 *accum_sq,
                         __global uint *nonfinite, int tile_x, int tile_y, int tile_w, int tile_h,
                         uint sample_begin, uint sample_count)
{
    int lx = get_global_id(0), ly = get_global_id(1);
    if (lx >= tile_w || ly >= tile_h)
        return;
    __global const atmo_gpu_camera *cam = &scene->camera;
    int x = tile_x + lx, y = tile_y + ly;
    uint pixel = (uint)(y * cam->width + x);
    float4 sum = accum[pixel], sum_sq = accum_sq[pixel];
    for (uint k = 0; k < sample_count; k++) {
        rng_stream g = rng_stream_stage(scene->seed, pixel, sample_begin + k, 0u);
        float jx = rng_next(&g);
        float jy = rng_next(&g);
        float3 dir = camera_ray(cam, (float)x + jx, (float)y + jy);
        float3 L = (float3)(0.0f); /* a fisheye's corners outside its circle see nothing */
        if (dot(dir, dir) > 0.0f) {
            medium_ray ray = medium_ray_from_camera(scene, dir);
            float3 sky, sun, view_t;
            render_camera_trace(scene, ATMO_LUT_ARGS, &ray, &g, &sky, &sun, &view_t);
            L = sky * scene->sky_factor.xyz + sun * scene->sun_factor.xyz;
        }
        if (any(isnan(L)) || any(isinf(L))) {
            atomic_inc(nonfinite);
            L = (float3)(0.0f);
        }
        sum.xyz += L;
        sum_sq.xyz += L * L;
    }
    accum[pixel] = sum;
    accum_sq[pixel] = sum_sq;
}

__kernel void sky_probe(__global const atmo_gpu_scene *scene, ATMO_LUT_PARAMS,
                        __global const float4 *rays, __global float4 *out, uint n, uint samples)
{
    uint i = get_global_id(0);
    if (i >= n)
        return;
    float4 q = rays[i];
    float3 sum = (float3)(0.0f);
    for (uint s = 0; s < samples; s++) {
        float3 sky, sun;
        sky_radiance(scene, ATMO_LUT_ARGS, q.x, q.y, q.z, q.w, i, s, &sky, &sun);
        sum += sky;
    }
    out[i] = (float4)(sum / (float)samples, 0.0f);
}

__kernel void sky_probe_segment(__global const atmo_gpu_scene *scene, ATMO_LUT_PARAMS,
                                __global const float4 *rays, __global const float *distance,
                                __global float4 *inscatter, __global float4 *transmittance,
                                uint n, uint samples)
{
    uint i = get_global_id(0);
    if (i >= n)
        return;
    float4 q = rays[i];
    float3 sum_l = (float3)(0.0f), sum_t = (float3)(0.0f);
    for (uint s = 0; s < samples; s++) {
        float3 l, t;
        sky_segment(scene, ATMO_LUT_ARGS, q.x, q.y, q.z, q.w, distance[i], i, s, &l, &t);
        sum_l += l;
        sum_t += t;
    }
    inscatter[i] = (float4)(sum_l / (float)samples, 0.0f);
    transmittance[i] = (float4)(sum_t / (float)samples, 0.0f);
}

__kernel void sky_probe_sun(__global const atmo_gpu_scene *scene, ATMO_LUT_PARAMS,
                            __global const float4 *rays, __global float4 *out, uint n)
{
    uint i = get_global_id(0);
    if (i >= n)
        return;
    float4 q = rays[i];
    medium_ray m = medium_ray_from_cosines(scene, q.x, q.y, q.z, q.w);
    medium_point p = medium_ray_at(&m, 0.0f, scene->atmosphere.bottom_radius);
    out[i] = (float4)(visibility_sun(scene, ATMO_LUT_ARGS, &p), 0.0f);
}
