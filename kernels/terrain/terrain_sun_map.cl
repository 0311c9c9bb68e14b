/* terrain_sun_map.cl — the sun-height map's pass (terrain_sun_map.h): work item j of the
 * first dimension bakes row j (N rows, N = sun_map_size); it reads the scene and the
 * heightmap and writes the buffer terrain_sun_map. Padding items return at once. */

__kernel void terrain_sun_map_rows(__global const atmo_gpu_scene *s, ATMO_LUT_OUT_PARAMS,
                                   int arg)
{
    int j = get_global_id(0);
    if (j >= s->terrain.sun_map_size || get_global_id(1) > 0)
        return;
    terrain_sun_map_row(s, heightmap, j, terrain_sun_map);
}
