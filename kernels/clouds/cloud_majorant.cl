/* cloud_majorant.cl — the precompute pass of the fBm cloud layer's majorant grid
 * (cloud_majorant.h): work item (i, j, k) of the CLOUDS_GRID_NX x NY x NZ grid writes the
 * density bound of its cell to clouds_majorant[(k NY + j) NX + i]. The grid is placed at the
 * camera's foot and bounds the noise where the wind has moved it, so it follows the view (it is
 * rebuilt for each camera and time, never cached). Items outside the grid (padding) return at
 * once. */

__kernel void clouds_majorant_grid(__global const atmo_gpu_scene *s, ATMO_LUT_OUT_PARAMS, int arg)
{
    int i = get_global_id(0), j = get_global_id(1), k = get_global_id(2);
    (void)arg;
    if (i >= CLOUDS_GRID_NX || j >= CLOUDS_GRID_NY || k >= CLOUDS_GRID_NZ)
        return;
    clouds_grid_frame f = clouds_grid_frame_make(s);
    clouds_majorant[(k * CLOUDS_GRID_NY + j) * CLOUDS_GRID_NX + i] =
        clouds_grid_cell_bound(s, &f, i, j, k);
}
