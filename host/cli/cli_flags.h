/* cli_flags.h — the table-driven flag parser of the atmo commands (cli_flags.c).
 *
 * A command describes its flags once, in a table of cli_flag: name, type, range or choices,
 * default, help line and where the value goes (an offset into the command's own argument
 * struct). cli_parse reads argv by that table, checks each value's type and range, and prints
 * a one-line error (what, which flag, how to fix it, a "did you mean" for a mistyped flag or
 * choice) with exit status 2; --help prints the help generated from the same table, every
 * default stated. */
#ifndef ATMO_CLI_FLAGS_H
#define ATMO_CLI_FLAGS_H
#include <stddef.h>
#include <stdio.h>
#include "atmo/status.h"

typedef enum {
    CLI_END = 0, /* ends a table */
    CLI_SECTION, /* a heading in the help ("scene:"), in `help` */
    CLI_INCLUDE, /* the flags of `include`, their destinations at `offset` in this struct */
    CLI_BOOL,    /* no value: the int at `offset` becomes 1 */
    CLI_INT,     /* a whole number in [min, max], decimal digits -> int */
    CLI_FLOAT,   /* a finite number in [min, max] (or (min, max] with open_min) -> double */
    CLI_STRING,  /* text -> const char * */
    CLI_PATH,    /* a file name -> const char * */
    CLI_ENUM     /* one of `choices` -> int, its index */
} cli_type;

struct cli_flag;
/* A flag whose value is more than a type (a list, I/N, a percentage, a scene assignment): it
 * gets the checked value and stores it itself. Returns ATMO_OK or fails with a message. */
typedef int (*cli_take_fn)(void *args, const struct cli_flag *f, const char *value, atmo_err *e);

typedef struct cli_flag {
    cli_type type;
    const char *name;            /* "--width" */
    const char *alias;           /* "-o", or NULL */
    const char *metavar;         /* the value in the help ("N", "FILE"); NULL: from the type */
    size_t offset;               /* the destination in the command's argument struct */
    double min, max;             /* CLI_INT, CLI_FLOAT: the valid range */
    int open_min;                /* CLI_FLOAT: min itself is not valid */
    const char *const *choices;  /* CLI_ENUM: NULL-terminated names */
    int repeat;                  /* repeatable this many times: destination is an array of
                                    `repeat` values, their count the int at count_offset */
    size_t count_offset;
    const char *key;             /* a scene key this flag is shorthand for: its range or names
                                    come from the scene's registry, its default is the scene's */
    const char *def;             /* the default as the help states it; NULL: the destination's
                                    value before parsing (numbers, a non-NULL string) */
    const char *const *def_var;  /* or the default held in this variable */
    const char *help;            /* help text; '\n' continues it on the next line */
    cli_take_fn take;            /* set: the value goes to take, not to the destination */
    const struct cli_flag *include; /* CLI_INCLUDE */
} cli_flag;

typedef struct cli_command {
    const char *name;     /* "render": messages say "atmo render: ..." */
    const char *synopsis; /* the usage line(s) after "usage: atmo NAME " */
    const char *about;    /* the paragraph(s) before the flags, or NULL */
    const cli_flag *flags;
    const char *epilogue; /* the text after the flags, or NULL */
    int max_positional;   /* arguments that are not flags: at most this many (0: none) */
    const char *const *scene_preset; /* the preset the command's scene starts from, where a
                                        keyed flag's default is read; NULL: the defaults alone */
} cli_command;

/* Parse argv[1..argc-1] into args (already holding the defaults). Arguments that are not
 * flags go to positional[] (at most c->max_positional; *n_positional counts them; both may be
 * NULL when none is taken). Returns 1 when the command goes on; 0 when it must return
 * *exit_code at once: 0 after --help (printed on stdout), ATMO_ERR_USAGE after an error
 * (printed on stderr as one line "atmo NAME: ..."). "--flag=value" is taken as "--flag value". */
int cli_parse(const cli_command *c, void *args, int argc, char **argv, const char **positional,
              int *n_positional, int *exit_code);

/* The help text: synopsis, about, each flag with its value, help and default, epilogue. */
void cli_print_help(const cli_command *c, const void *args, FILE *f);

/* Print "atmo NAME: MESSAGE" on stderr and return rc (the commands' error exit). */
int cli_fail(const cli_command *c, int rc, const atmo_err *e);

#endif
