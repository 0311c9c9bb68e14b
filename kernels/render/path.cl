/* path.cl — path_render: the path tracer's image kernel (path.h), with sky_render's
 * accumulation contract (render/sky.cl): work item (x, y) of a tile adds samples sample_begin
 * .. sample_begin + sample_count - 1 of pixel (tile_x + x, tile_y + y), in order, to its sum in
 * `accum` and the sum of squares in `accum_sq` (xyz; w unused), so the image is bitwise the
 * same for any tile size and split into launches; a non-finite sample is dropped (zero, its
 * passes too) and counted in `nonfinite`. A session launches it in place of sky_render in
 * path mode.
 * Render passes (-DATMO_RENDER_PASSES, path.passes = true): one more buffer `passes` of
 * PATH_PASS_SLOTS planes of W x H float4 sums, plane k at passes[k W H + pixel], built in
 * the same order: the light passes (planes 0 .. PATH_LIGHT_PASSES - 1, xyz), then the primary
 * hit's normal (xyz) with its distance (w), then its albedo (xyz). A scene without passes has
 * neither the argument nor the stores.
 * path_sky_env and path_sky_cdf are the precompute passes of the sky's radiance table that
 * the sky sampling reads (render/light_sky.h); they follow the view (camera, sun). */

#define PATH_PASS_SLOTS (PATH_LIGHT_PASSES + 2)
/* the host sizes the buffer by gpu_path.h's count: the two must agree */
typedef char path_pass_slots_match[PATH_PASS_SLOTS == ATMO_PATH_PASS_PLANES ? 1 : -1];

__kernel void path_render(__global const atmo_gpu_scene *scene, ATMO_LUT_PARAMS,
                          __global float4 *accum, __global float4 *accum_sq,
                          __global uint *nonfinite,
#ifdef ATMO_RENDER_PASSES
                          __global float4 *passes,
#endif
                          int tile_x, int tile_y, int tile_w, int tile_h, uint sample_begin,
                          uint sample_count)
{
    int lx = get_global_id(0), ly = get_global_id(1);
    if (lx >= tile_w || ly >= tile_h)
        return;
    int x = tile_x + lx, y = tile_y + ly;
    uint pixel = (uint)(y * scene->camera.width + x);
    float4 sum = accum[pixel], sum_sq = accum_sq[pixel];
#ifdef ATMO_RENDER_PASSES
    uint plane = (uint)(scene->camera.width * scene->camera.height);
    float4 part[PATH_PASS_SLOTS];
    for (int k = 0; k < PATH_PASS_SLOTS; k++)
        part[k] = passes[k * plane + pixel];
#endif
    for (uint k = 0; k < sample_count; k++) {
        path_parts parts;
        path_sample(scene, ATMO_LUT_ARGS, x, y, pixel, sample_begin + k, &parts);
        float3 L = path_total(&parts);
        if (any(isnan(L)) || any(isinf(L))) {
            atomic_inc(nonfinite);
            continue;
        }
        sum.xyz += L;
        sum_sq.xyz += L * L;
#ifdef ATMO_RENDER_PASSES
        for (int j = 0; j < PATH_LIGHT_PASSES; j++)
            part[j].xyz += parts.light[j];
        part[PATH_LIGHT_PASSES] += (float4)(parts.normal, parts.depth);
        part[PATH_LIGHT_PASSES + 1].xyz += parts.albedo;
#endif
    }
    accum[pixel] = sum;
    accum_sq[pixel] = sum_sq;
#ifdef ATMO_RENDER_PASSES
    for (int k = 0; k < PATH_PASS_SLOTS; k++)
        passes[k * plane + pixel] = part[k];
#endif
}

/* path_sky_env: texel (x, y) of the sky's radiance table (render/light_sky.h) from the camera,
 * by the scene's method along the ray through its centre (without the sun's disc; the stream
 * of "pixel" y W + x, sample 0), and its weight (L_R + L_G + L_B) Omega_texel. */
__kernel void path_sky_env(__global const atmo_gpu_scene *scene, ATMO_LUT_OUT_PARAMS, int arg)
{
    int i = get_global_id(0), j = get_global_id(1);
    if (i >= LIGHT_SKY_W || j >= LIGHT_SKY_H)
        return;
    float3 L = (float3)(0.0f);
    if (scene->path.sky == ATMO_PATH_SKY_ATMOSPHERE) {
        float3 d = light_sky_direction(scene->camera.local_up.xyz, i, j, 0.5f, 0.5f);
        medium_ray ray = medium_ray_from_camera(scene, d);
        rng_stream g = rng_stream_stage(scene->seed, (uint)(j * LIGHT_SKY_W + i), 0u, 0u);
        float3 sky, sun, view_t;
        sky_trace(scene, ATMO_LUT_ARGS, &ray, INFINITY, &g, &sky, &sun, &view_t);
        L = sky * scene->sky_factor.xyz;
    }
    float w = (L.x + L.y + L.z) * light_sky_texel_omega(j);
    sky_env[j * LIGHT_SKY_W + i] = (float4)(L, isfinite(w) && w > 0.0f ? w : 0.0f);
}

/* path_sky_cdf: the table's CDFs from its weights (one work item). */
__kernel void path_sky_cdf(__global const atmo_gpu_scene *scene, ATMO_LUT_OUT_PARAMS, int arg)
{
    if (get_global_id(0) == 0 && get_global_id(1) == 0)
        light_sky_build(sky_env);
}
