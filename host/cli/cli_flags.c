/* cli_flags.c — the table-driven flag parser (cli_flags.h).
 *
 * A flag is found by its name or alias, through the tables a table includes (each with the
 * offset of its struct inside the command's). Its value is checked by type: whole numbers are
 * decimal digits (atmo_parse_decimal, the scene files' grammar), numbers must be finite, both
 * within the flag's range; names must be one of the choices. A shorthand for a scene key takes
 * its range, names and default from the scene's registry, so the flag and the key agree. Every
 * error is one line naming the flag, the value, what is valid and an example; a mistyped flag
 * or choice gets the nearest one as a hint (atmo/suggest.h). The help is generated from the
 * same tables, with every default: the flag's own text, else the value its destination holds
 * before parsing, else for a scene key its value in the scene the command starts from (the
 * defaults and the command's scene_preset). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/scene.h"
#include "atmo/suggest.h"
#include "cli_flags.h"

#define CLI_HELP_COLUMN 24
#define CLI_HELP_WIDTH 96 /* a default that would pass this column goes on a line of its own */

static void *field(void *args, size_t offset) { return (char *)args + offset; }
static const void *cfield(const void *args, size_t offset) { return (const char *)args + offset; }

/* The flag named `name` (or aliased) in the table or the tables it includes; *offset gets the
 * offset of the struct its destination is in. */
static const cli_flag *find_flag(const cli_flag *t, const char *name, size_t base, size_t *offset)
{
    for (; t->type != CLI_END; t++) {
        if (t->type == CLI_INCLUDE) {
            const cli_flag *f = find_flag(t->include, name, base + t->offset, offset);
            if (f)
                return f;
        } else if (t->name && (strcmp(t->name, name) == 0 ||
                               (t->alias && strcmp(t->alias, name) == 0))) {
            *offset = base;
            return t;
        }
    }
    return NULL;
}

static void offer_flags(const cli_flag *t, atmo_suggest *s)
{
    for (; t->type != CLI_END; t++) {
        if (t->type == CLI_INCLUDE)
            offer_flags(t->include, s);
        else if (t->name)
            atmo_suggest_offer(s, t->name);
    }
}

/* The scene that a keyed flag's default comes from: the defaults and, for a command whose
 * scene starts from a preset, that preset. */
static void default_scene(const cli_command *c, atmo_scene *s)
{
    atmo_err e;
    atmo_scene_defaults(s);
    if (c->scene_preset)
        atmo_scene_apply_preset(s, *c->scene_preset, &e);
}

/* A flag's range and choices: its own, or its scene key's. */
typedef struct cli_limits {
    double min, max;
    int open_min;
    const char *const *choices;
} cli_limits;

static cli_limits flag_limits(const cli_flag *f)
{
    cli_limits l = {f->min, f->max, f->open_min, f->choices};
    const atmo_param *p = f->key ? atmo_param_find(f->key) : NULL;
    if (p) {
        l.min = p->min, l.max = p->max, l.open_min = 0;
        l.choices = p->names;
    }
    return l;
}

static void choices_text(const char *const *choices, const char *sep, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    for (const char *const *c = choices; c && *c && used < n; c++)
        used += (size_t)snprintf(buf + used, n - used, "%s%s", c == choices ? "" : sep, *c);
}

/* The default as the help states it and errors use as the example; "" when there is none. */
static void default_text(const cli_command *c, const cli_flag *f, const void *args, char *buf,
                         size_t n)
{
    const void *dest = cfield(args, f->offset);
    buf[0] = '\0';
    if (f->def) {
        snprintf(buf, n, "%s", f->def);
    } else if (f->def_var) {
        snprintf(buf, n, "%s", *f->def_var);
    } else if (f->key) {
        const atmo_param *p = atmo_param_find(f->key);
        double v[3];
        if (!p)
            return;
        atmo_scene scene;
        default_scene(c, &scene);
        atmo_param_get(&scene, p, v);
        if (p->type == ATMO_PARAM_ENUM)
            snprintf(buf, n, "%s", p->names[(int)v[0]]);
        else
            snprintf(buf, n, "%.15g", v[0]);
    } else if (f->repeat || f->take || f->type == CLI_BOOL) {
        return;
    } else if (f->type == CLI_INT) {
        snprintf(buf, n, "%d", *(const int *)dest);
    } else if (f->type == CLI_FLOAT) {
        snprintf(buf, n, "%.15g", *(const double *)dest);
    } else if (f->type == CLI_ENUM) {
        snprintf(buf, n, "%s", f->choices[*(const int *)dest]);
    } else if (*(const char *const *)dest) {
        snprintf(buf, n, "%s", *(const char *const *)dest);
    }
}

/* "use a whole number in [8, 4096], e.g. --tile-size 64", after "image.width: " for a key */
static void valid_text(const cli_command *c, const cli_flag *f, const cli_limits *l,
                       const void *args, char *buf, size_t n)
{
    char def[128], *end;
    default_text(c, f, args, def, sizeof def);
    double x = strtod(def, &end);
    if (!def[0] || *end || x < l->min || x > l->max || (l->open_min && x == l->min))
        snprintf(def, sizeof def, "%.15g", l->open_min ? fmin(l->max, l->min + 1.0) : l->min);
    snprintf(buf, n, "%s%suse %s %c%.15g, %.15g], e.g. %s %s", f->key ? f->key : "",
             f->key ? ": " : "", f->type == CLI_INT ? "a whole number in" : "a number in",
             l->open_min ? '(' : '[', l->min, l->max, f->name, def);
}

/* Check the value by the flag's type and range; the number (INT, FLOAT) or the choice's index
 * (ENUM) goes to *number. */
static int check_value(const cli_command *c, const cli_flag *f, const void *args, const char *v,
                       double *number, atmo_err *e)
{
    cli_limits l = flag_limits(f);
    char valid[256];
    if (f->type == CLI_INT || f->type == CLI_FLOAT) {
        char *end;
        double x = 0.0;
        int parsed = f->type == CLI_INT ? atmo_parse_decimal(v, &x) && x == floor(x)
                                        : (x = strtod(v, &end), *v && !*end && isfinite(x));
        valid_text(c, f, &l, args, valid, sizeof valid);
        if (!parsed)
            return atmo_fail(e, ATMO_ERR_USAGE, "%s: '%s' is not %s (%s)", f->name, v,
                             f->type == CLI_INT ? "an integer" : "a number", valid);
        if (x > l.max || x < l.min || (l.open_min && x == l.min))
            return atmo_fail(e, ATMO_ERR_USAGE, "%s: %s is out of range (%s)", f->name, v,
                             valid);
        *number = x;
    } else if (f->type == CLI_ENUM) {
        for (int i = 0; l.choices[i]; i++)
            if (strcmp(v, l.choices[i]) == 0) {
                *number = i;
                return ATMO_OK;
            }
        const char *near = atmo_suggest_among(v, l.choices);
        choices_text(l.choices, ", ", valid, sizeof valid);
        return atmo_fail(e, ATMO_ERR_USAGE, "%s: '%s' is not one of %s%s%s%s", f->name, v, valid,
                         near ? " (did you mean '" : "", near ? near : "", near ? "'?)" : "");
    } else if (!*v) {
        return atmo_fail(e, ATMO_ERR_USAGE, "%s: the value is empty (%s %s)", f->name, f->name,
                         f->type == CLI_PATH ? "FILE" : "VALUE");
    }
    return ATMO_OK;
}

/* Check and store one flag's value (NULL for a CLI_BOOL) in args. */
static int take_value(const cli_command *c, const cli_flag *f, void *args, const char *v,
                      atmo_err *e)
{
    double x = 0.0;
    if (f->type == CLI_BOOL) {
        *(int *)field(args, f->offset) = 1;
        return ATMO_OK;
    }
    int rc = check_value(c, f, args, v, &x, e);
    if (rc || f->take)
        return rc ? rc : f->take(args, f, v, e);
    if (f->repeat) {
        int *count = field(args, f->count_offset);
        if (*count == f->repeat)
            return atmo_fail(e, ATMO_ERR_USAGE, "more than %d %s options (atmo %s --help)",
                             f->repeat, f->name, c->name);
        ((const char **)field(args, f->offset))[(*count)++] = v;
    } else if (f->type == CLI_INT || f->type == CLI_ENUM) {
        *(int *)field(args, f->offset) = (int)x;
    } else if (f->type == CLI_FLOAT) {
        *(double *)field(args, f->offset) = x;
    } else {
        *(const char **)field(args, f->offset) = v;
    }
    return ATMO_OK;
}

static int unknown_flag(const cli_command *c, const char *a, atmo_err *e)
{
    atmo_suggest s;
    atmo_suggest_begin(&s, a);
    offer_flags(c->flags, &s);
    const char *near = atmo_suggest_result(&s);
    return atmo_fail(e, ATMO_ERR_USAGE, "unknown option '%s' (%s%s%satmo %s --help)", a,
                     near ? "did you mean '" : "", near ? near : "", near ? "'? " : "", c->name);
}

/* argv[*i], a flag: its value (inline after '=', or the next argument) into args. */
static int parse_flag(const cli_command *c, void *args, int argc, char **argv, int *i,
                      atmo_err *e)
{
    char name[64];
    const char *a = argv[*i], *eq = strncmp(a, "--", 2) == 0 ? strchr(a, '=') : NULL;
    size_t len = eq ? (size_t)(eq - a) : strlen(a), base = 0;
    snprintf(name, sizeof name, "%.*s", (int)(len < sizeof name ? len : sizeof name - 1), a);
    const cli_flag *f = len < sizeof name ? find_flag(c->flags, name, 0, &base) : NULL;
    if (!f)
        return unknown_flag(c, eq ? name : a, e);
    if (f->type == CLI_BOOL && eq)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s takes no value (atmo %s --help)", f->name,
                         c->name);
    if (f->type != CLI_BOOL && !eq && *i + 1 >= argc)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s needs a value (atmo %s --help)", a, c->name);
    const char *v = f->type == CLI_BOOL ? NULL : eq ? eq + 1 : argv[++*i];
    return take_value(c, f, field(args, base), v, e);
}

int cli_parse(const cli_command *c, void *args, int argc, char **argv, const char **positional,
              int *n_positional, int *exit_code)
{
    atmo_err e = {{0}};
    int rc = ATMO_OK, n_pos = 0;
    for (int i = 1; i < argc && !rc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            cli_print_help(c, args, stdout);
            *exit_code = ATMO_OK;
            return 0;
        }
        if (a[0] == '-' && a[1])
            rc = parse_flag(c, args, argc, argv, &i, &e);
        else if (n_pos < c->max_positional)
            positional[n_pos++] = a;
        else
            rc = atmo_fail(&e, ATMO_ERR_USAGE, "unexpected argument '%s' (atmo %s --help)", a,
                           c->name);
    }
    if (n_positional)
        *n_positional = n_pos;
    if (rc) {
        *exit_code = cli_fail(c, rc, &e);
        return 0;
    }
    return 1;
}

/* "--width N", "--output, -o FILE", "--camera perspective|panorama" */
static void flag_left(const cli_flag *f, char *buf, size_t n)
{
    char meta[160];
    if (f->type == CLI_BOOL)
        meta[0] = '\0';
    else if (f->metavar)
        snprintf(meta, sizeof meta, " %s", f->metavar);
    else if (f->type == CLI_ENUM || (f->key && flag_limits(f).choices)) {
        meta[0] = ' ';
        choices_text(flag_limits(f).choices, "|", meta + 1, sizeof meta - 1);
    } else
        snprintf(meta, sizeof meta, " %s",
                 f->type == CLI_INT     ? "N"
                 : f->type == CLI_FLOAT ? "X"
                 : f->type == CLI_PATH  ? "FILE"
                                        : "TEXT");
    snprintf(buf, n, "%s%s%s%s", f->name, f->alias ? ", " : "", f->alias ? f->alias : "", meta);
}

static void print_flag(const cli_command *c, const cli_flag *f, const void *args, FILE *out)
{
    char left[192], def[160];
    flag_left(f, left, sizeof left);
    default_text(c, f, args, def, sizeof def);
    char tail[256] = "";
    if (def[0] && f->key && c->scene_preset)
        snprintf(tail, sizeof tail, "(default: the scene's; %s in %s)", def, *c->scene_preset);
    else if (def[0] && f->key)
        snprintf(tail, sizeof tail, "(default: the scene's; %s)", def);
    else if (def[0])
        snprintf(tail, sizeof tail, "(default %s)", def);
    if (strlen(left) + 3 > CLI_HELP_COLUMN)
        fprintf(out, "  %s\n%*s", left, CLI_HELP_COLUMN, "");
    else
        fprintf(out, "  %-*s", CLI_HELP_COLUMN - 2, left);
    size_t column = CLI_HELP_COLUMN;
    for (const char *h = f->help; *h; h++, column++) {
        fputc(*h, out);
        if (*h == '\n') {
            fprintf(out, "%*s", CLI_HELP_COLUMN, "");
            column = CLI_HELP_COLUMN - 1;
        }
    }
    if (tail[0] && column + 1 + strlen(tail) > CLI_HELP_WIDTH)
        fprintf(out, "\n%*s%s", CLI_HELP_COLUMN, "", tail);
    else if (tail[0])
        fprintf(out, " %s", tail);
    fputc('\n', out);
}

static void print_flags(const cli_command *c, const cli_flag *t, const void *args, FILE *out)
{
    for (; t->type != CLI_END; t++) {
        if (t->type == CLI_SECTION)
            fprintf(out, "%s\n", t->help);
        else if (t->type == CLI_INCLUDE)
            print_flags(c, t->include, cfield(args, t->offset), out);
        else
            print_flag(c, t, args, out);
    }
}

void cli_print_help(const cli_command *c, const void *args, FILE *f)
{
    fprintf(f, "usage: atmo %s %s\n\n", c->name, c->synopsis);
    if (c->about)
        fprintf(f, "%s\n", c->about);
    print_flags(c, c->flags, args, f);
    fprintf(f, "  %-*s%s\n", CLI_HELP_COLUMN - 2, "--help, -h", "this text");
    if (c->epilogue)
        fprintf(f, "\n%s", c->epilogue);
}

int cli_fail(const cli_command *c, int rc, const atmo_err *e)
{
    fprintf(stderr, "atmo %s: %s\n", c->name, e->msg);
    return rc;
}
