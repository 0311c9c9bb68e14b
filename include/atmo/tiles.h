/* tiles.h — the tile scheduler of a render session: which tiles get the next launch, and how
 * many samples.
 *
 * The image is cut into square tiles of one size (the last column and row partial), the unit
 * of the sample counts. Samples are added in round-robin passes over the tiles: the next launch
 * starts at the first tile at or after the cursor that has fewer samples than the target, so
 * every tile gets a batch before any gets a second (the first pass takes its rows spread over
 * the image instead, tiles.c). One launch covers several tiles when tiles
 * are cheap: a rectangle of tiles that hold the same sample count (a run within a tile row, or
 * whole tile rows from a row's first tile). How many tiles and how many samples per launch
 * follow one adapted quantity, the work per launch, so that a launch takes about the launch
 * budget (tiles.c says how). The scheduler holds the per-tile sample counts; it never touches
 * the device, so the split of samples into launches is its only effect on the image, and the
 * kernel makes that split invisible (sums in sample order).
 *
 * Parts. A render can be split into `parts` pieces that separate processes render and
 * `atmo merge` joins (atmo/part.h): the image's rows are cut into bands of ATMO_PART_BAND_ROWS
 * rows (the last one shorter), band b belongs to part b mod parts + 1, and a part's scheduler
 * holds only the tiles of its own bands: each band cut into rows of at most `size` pixels,
 * each row into columns of `size`. The bands do not depend on the tile size, so parts rendered
 * with different tile sizes or budgets still cover the image exactly once; interleaving thin
 * bands spreads the costly rows (the horizon, the ground, the sun) over all parts. A band is
 * the session's local size high (8), so every tile is still whole work-groups high; on the
 * scenes of docs/notes/split_render.md 8-row bands balance 4 parts within a few per cent of a
 * split of the sample range, which could not merge bit for bit (atmo/part.h). A launch spans
 * several tile rows only where they touch, so a part's launches stay within its bands. Pixels
 * outside the part have 0 samples. parts = 0 is the whole image, tiled as above.
 *
 * Noise target (the progressive mode): a tile can be marked converged (atmo_tiles_converge)
 * and then gets no more launches whatever the target. So that the decision does not depend on
 * the batches, the caller asks it only at checkpoints, the sample counts 2^k >= 16
 * (ATMO_TILES_FIRST_CHECKPOINT), and with `checkpoints` set the scheduler ends every launch at
 * or before the tile's next checkpoint: a tile is then judged on the same sums whatever the
 * tile size or launch budget, and a noise-targeted image is as deterministic as any other. */
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

#define ATMO_PART_BAND_ROWS 8

typedef struct atmo_tiles {
    int width, height, size;
    int part, parts;    /* part (1 .. parts) of the image, or parts = 0: all of it */
    int columns, rows, count;
    int *row_y, *row_h; /* the tile rows: top and height in pixels */
    int *row_of_y;      /* per pixel row: its tile row, -1 outside the part */
    int *samples;       /* per tile */
    int cursor;         /* where the next search starts */
    int spread;         /* the first pass: the next position in its order of rows (tiles.c) */
    int batch;          /* samples per launch, adapted */
    int group;          /* tiles per launch, adapted */
    unsigned char *converged; /* per tile: 1 once its noise target is met */
    int checkpoints;    /* 1: launches end at the checkpoints (noise target) */
} atmo_tiles;

#define ATMO_TILES_FIRST_CHECKPOINT 16

/* 1 when n samples is a checkpoint: a power of two >= ATMO_TILES_FIRST_CHECKPOINT. */
int atmo_tiles_is_checkpoint(int n);
/* Mark tile `index` converged: no more launches for it until atmo_tiles_reset. */
void atmo_tiles_converge(atmo_tiles *t, int index);

int atmo_tiles_init(atmo_tiles *t, int width, int height, int size, atmo_err *e);
/* Only the tiles of part `part` of `parts` (parts = 0: the whole image). Usage error when the
 * part is out of range or when the image has fewer bands than parts (a part would be empty). */
int atmo_tiles_init_part(atmo_tiles *t, int width, int height, int size, int part, int parts,
                         atmo_err *e);
/* Which part (1 .. parts) renders pixel row y. */
int atmo_part_of_row(int y, int parts);
/* The rectangle of tile `index` (< t->count) and its samples so far. */
void atmo_tiles_get(const atmo_tiles *t, int index, atmo_tile *tile);
void atmo_tiles_free(atmo_tiles *t);
/* Every tile back to 0 samples, not converged, and the cursor to tile 0 (the adapted sizes
 * stay). */
void atmo_tiles_reset(atmo_tiles *t);
/* The next launch towards `target` samples per pixel; 0 when every tile has them or has
 * converged. */
int atmo_tiles_next(atmo_tiles *t, int target, atmo_tile *launch);
/* Record a finished launch that took ms milliseconds; adapt the tiles and samples per launch
 * to budget_ms (at most max_tiles tiles and max_batch samples where those are > 0). */
void atmo_tiles_done(atmo_tiles *t, atmo_tile *launch, double ms, double budget_ms, int max_batch,
                     int max_tiles);
/* Samples of the tile that holds pixel (x, y); 0 outside the part. */
int atmo_tiles_pixel_samples(const atmo_tiles *t, int x, int y);
/* Fewest and most samples over the tiles. */
void atmo_tiles_range(const atmo_tiles *t, int *min, int *max);

#endif
