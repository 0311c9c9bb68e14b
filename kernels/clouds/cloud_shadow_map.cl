/* cloud_shadow_map.cl — the precompute pass of the fBm cloud layer's sun shadow map
 * (cloud_shadow_map.h): work item (i, j, k) of the clouds.shadow_map_size x levels x size nodes
 * writes the density integral toward the sun from its node to
 * clouds_shadow_map[(j size + k) size + i]. The map is placed at the camera's foot and
 * integrates the noise where the wind has moved it, toward the scene's sun, so it follows the
 * view (it is rebuilt for each camera, sun and time, never cached). Items outside the map
 * (padding) return at once. */

__kernel void clouds_shadow_map_nodes(__global const atmo_gpu_scene *s, ATMO_LUT_OUT_PARAMS,
                                      int arg)
{
    int i = get_global_id(0), j = get_global_id(1), k = get_global_id(2);
    int n = s->clouds.shadow_map_size;
    (void)arg;
    if (i >= n || j >= s->clouds.shadow_map_levels || k >= n)
        return;
    clouds_grid_frame f = clouds_grid_frame_make(s);
    clouds_shadow_map[((size_t)j * (size_t)n + (size_t)k) * (size_t)n + (size_t)i] =
        clouds_shadow_map_node(s, &f, i, j, k);
}
