/* test_reliability_merge_text — atmo_part_merge's refusal of an interrupted part states the
 * sample counts its pixels really hold.
 * labels: reliability unit
 *
 * Oracle: the counts put into the synthetic parts. A part whose pixels all hold 2 of the
 * scene's 4 samples is "2 samples in every pixel" (the range once began at the scene's count,
 * so it read "2 to 4 of 4", as if some pixels were complete); one whose pixels hold 1 to 3 is
 * "1 to 3"; complete parts merge. */
#include <stdio.h>
#include <string.h>
#include "atmo/part.h"
#include "atmo/tiles.h"
#include "testlib.h"

/* Parts 1 and 2 of a 4 x 16 image (bands of ATMO_PART_BAND_ROWS rows), part 1's pixels
 * holding counts lo, lo + 1, ... up to hi, part 2's `samples`; the merge's message in msg. */
static int merge_with(int lo, int hi, int samples, char *msg, size_t size)
{
    atmo_part parts[2], out;
    const char *paths[2] = {"p1.exr", "p2.exr"};
    atmo_err e = {{0}};
    for (int k = 0; k < 2; k++) {
        CHECK(atmo_part_alloc(&parts[k], 4, 2 * ATMO_PART_BAND_ROWS, k + 1, 2, "{}", &e) ==
              ATMO_OK);
        for (int i = 0; i < 4 * parts[k].rows; i++)
            parts[k].samples[i] = k == 0 ? lo + i % (hi - lo + 1) : samples;
    }
    int rc = atmo_part_merge(parts, paths, 2, samples, &out, &e);
    snprintf(msg, size, "%.*s", (int)size - 1, rc ? e.msg : "");
    if (!rc)
        atmo_part_free(&out);
    atmo_part_free(&parts[0]);
    atmo_part_free(&parts[1]);
    return rc;
}

int main(void)
{
    char msg[2048];
    CHECK(merge_with(2, 2, 4, msg, sizeof msg) == ATMO_ERR_USAGE);
    CHECK(strstr(msg, "'p1.exr' (part 1/2) is incomplete: 2 samples in every pixel, its scene 4") != NULL);
    printf("all 2 of 4: %s\n", msg);
    CHECK(merge_with(1, 3, 4, msg, sizeof msg) == ATMO_ERR_USAGE);
    CHECK(strstr(msg, "is incomplete: 1 to 3 samples per pixel, its scene 4 in every pixel") != NULL);
    printf("1 to 3 of 4: %s\n", msg);
    CHECK(merge_with(4, 4, 4, msg, sizeof msg) == ATMO_OK);
    return test_finish();
}
