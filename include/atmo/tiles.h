/* tiles.h — the tile scheduler of a render session: which tiles get the next launch, and how
 * many samples.
 *
 * The image is cut into square tiles of one size (the last column and row partial), the unit
 * of the sample counts. Samples are added in round-robin passes over the tiles: the next launch
 * starts at the first tile at or after the cursor that has fewer samples than the target, so
 * every tile gets a batch before any gets a second. One launch covers several tiles when tiles
 * are cheap: a rectangle of tiles that hold the same sample count (a run within a tile row, or
 * whole tile rows from a row's first tile). How many tiles and how many samples per launch
 * follow one adapted quantity, the work per launch, so that a launch takes about the launch
 * budget (tiles.c says how). The scheduler holds the per-tile sample counts; it never touches
 * the device, so the split of samples into launches is its only effect on the image, and the
 * kernel makes that split invisible (sums in sample order). */
#ifndef ATMO_TILES_H
#define ATMO_TILES_H
#include "atmo/status.h"

/* One launch, or a finished one as the session's tile callback sees it. */
typedef struct atmo_tile {
    int index;          /* the launch's first tile, row-major */
    int tiles_across;   /* its tiles: tiles_across columns from index's, */
    int tiles_down;     /* in tiles_down rows from index's */
    int x, y, w, h;     /* rectangle in pixels of all its tiles, row 0 = top */
    int sample_begin;   /* first sample index of the launch */
    int sample_count;   /* samples in the launch */
    int samples;        /* samples per pixel its tiles have once the launch is done */
} atmo_tile;

typedef struct atmo_tiles {
    int width, height, size;
    int columns, count;
    int *samples;       /* per tile */
    int cursor;         /* where the next search starts */
    int batch;          /* samples per launch, adapted */
    int group;          /* tiles per launch, adapted */
} atmo_tiles;

int atmo_tiles_init(atmo_tiles *t, int width, int height, int size, atmo_err *e);
void atmo_tiles_free(atmo_tiles *t);
/* Every tile back to 0 samples and the cursor to tile 0 (the adapted sizes stay). */
void atmo_tiles_reset(atmo_tiles *t);
/* The next launch towards `target` samples per pixel; 0 when every tile has them. */
int atmo_tiles_next(atmo_tiles *t, int target, atmo_tile *launch);
/* Record a finished launch that took ms milliseconds; adapt the tiles and samples per launch
 * to budget_ms (at most max_tiles tiles and max_batch samples where those are > 0). */
void atmo_tiles_done(atmo_tiles *t, atmo_tile *launch, double ms, double budget_ms, int max_batch,
                     int max_tiles);
/* Samples of the tile that holds pixel (x, y). */
int atmo_tiles_pixel_samples(const atmo_tiles *t, int x, int y);
/* Fewest and most samples over the tiles. */
void atmo_tiles_range(const atmo_tiles *t, int *min, int *max);

#endif
