/* path.cl — path_render: the path tracer's image kernel (path.h), with sky_render's
 * accumulation contract (render/sky.cl): work item (x, y) of a tile adds samples sample_begin
 * .. sample_begin + sample_count - 1 of pixel (tile_x + x, tile_y + y), in order, to its sum in
 * `accum` and the sum of squares in `accum_sq` (xyz; w unused), so the image is bitwise the
 * same for any tile size and split into launches; a non-finite sample is dropped (zero) and
 * counted in `nonfinite`. A session launches it in place of sky_render in path mode. */

__kernel void path_render(__global const atmo_gpu_scene *scene, ATMO_LUT_PARAMS,
                          __global float4 *accum, __global float4 *accum_sq,
                          __global uint *nonfinite, int tile_x, int tile_y, int tile_w,
                          int tile_h, uint sample_begin, uint sample_count)
{
    int lx = get_global_id(0), ly = get_global_id(1);
    if (lx >= tile_w || ly >= tile_h)
        return;
    int x = tile_x + lx, y = tile_y + ly;
    uint pixel = (uint)(y * scene->camera.width + x);
    float4 sum = accum[pixel], sum_sq = accum_sq[pixel];
    for (uint k = 0; k < sample_count; k++) {
        float3 L = path_radiance(scene, ATMO_LUT_ARGS, x, y, pixel, sample_begin + k);
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
