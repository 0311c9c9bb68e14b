/* test_suggest.c — the "did you mean" helper (host/base/suggest.c).
 * labels: unit cli
 *
 * Oracle: distances worked by hand from the definition of the optimal string alignment
 * distance (insert, delete, substitute, swap two neighbours; no substring edited twice):
 * kitten/sitting 3 (Levenshtein's textbook case), a swap costs 1 where Levenshtein counts 2,
 * "ca"/"abc" is 3 (the case that tells OSA from unrestricted Damerau-Levenshtein, which gives 2),
 * case is ignored. The hints: a near miss within the length-scaled limit is suggested, the
 * nearest wins, a far word gets none, a prefix of a name and a key without its group are found. */
#include <string.h>
#include "atmo/suggest.h"
#include "testlib.h"

int main(void)
{
    CHECK(atmo_edit_distance("kitten", "sitting") == 3);
    CHECK(atmo_edit_distance("", "abc") == 3);
    CHECK(atmo_edit_distance("abc", "") == 3);
    CHECK(atmo_edit_distance("piz", "pzi") == 1);
    CHECK(atmo_edit_distance("ca", "abc") == 3);
    CHECK(atmo_edit_distance("Render", "render") == 0);
    CHECK(atmo_edit_distance("thesis1", "thesis-1") == 1);

    CHECK(atmo_suggest_limit("abcd") == 1);
    CHECK(atmo_suggest_limit("abcdef") == 2);
    CHECK(atmo_suggest_limit("abcdefghi") == 3);

    static const char *const presets[] = {"sky-noon", "sky-sunset", "thesis-1", "thesis-2",
                                          "space", NULL};
    const char *s = atmo_suggest_among("thesis1", presets);
    CHECK(s && strcmp(s, "thesis-1") == 0);
    s = atmo_suggest_among("sky-sunst", presets);
    CHECK(s && strcmp(s, "sky-sunset") == 0);
    CHECK(atmo_suggest_among("xyzzy", presets) == NULL);
    CHECK(atmo_suggest_among("nope", presets) == NULL);
    s = atmo_suggest_among("spa", presets); /* a prefix: a name typed in part */
    CHECK(s && strcmp(s, "space") == 0);

    static const char *const keys[] = {"sun.zenith_deg", "sun.azimuth_deg", "image.width", NULL};
    s = atmo_suggest_among("zenith_deg", keys); /* the group left out */
    CHECK(s && strcmp(s, "sun.zenith_deg") == 0);
    s = atmo_suggest_among("sun.zenit", keys);
    CHECK(s && strcmp(s, "sun.zenith_deg") == 0);
    s = atmo_suggest_among("image.widht", keys);
    CHECK(s && strcmp(s, "image.width") == 0);
    CHECK(atmo_suggest_among("camera.fov", keys) == NULL);
    return test_finish();
}
