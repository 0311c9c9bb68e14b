/* cmd_cache.c — `atmo cache [list|verify|clear]`: what the disk cache holds, and cleaning it.
 *
 * The cache directory is ATMO_CACHE_DIR, else $XDG_CACHE_HOME/atmo, else ~/.cache/atmo
 * (atmo_cache_dir). Its atmo files are the products "<kind>-<16 hex digits>.bin" (kernel
 * binaries, Mie tables, one feature's LUTs; atmo/cache_file.h) and their temporary files
 * "<product>.tmp.<pid>"; other files in the directory are never touched.
 *   list    each product's kind, size, age and name, then the count and total size
 *   verify  checks every product (header, kind against its name, lengths, checksum), deletes
 *           those that fail and temporary files whose writer is gone, and checks PoCL's
 *           programs in the folder "pocl" (atmo_cl_driver_cache_repair), deleting those with
 *           a file cut short; says how many went
 *   clear   deletes every atmo file in the directory (but the temporary files of running
 *           writers, which those writers rename or remove) and the folder "pocl", and says
 *           so; a PoCL cache the user chose (POCL_CACHE_DIR) is not atmo's: it is kept and
 *           named
 * Each exits 0 (1 when the directory cannot be read or a file cannot be removed); an unusable
 * cache directory is named with what is wrong with it. */
#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <ftw.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include "atmo/cache_file.h"
#include "atmo/cl_runtime.h"
#include "atmo/suggest.h"
#include "commands.h"

#define KEY_HEX_DIGITS 16
#define MAX_ENTRIES 65536

typedef struct entry {
    char name[256];
    char kind[ATMO_CACHE_KIND_MAX];
    long long pid; /* > 0 for a temporary file: its writer */
} entry;

static void print_usage(FILE *f)
{
    fprintf(f, "usage: atmo cache [list|verify|clear]\n\n"
               "The disk cache of compiled kernels, precomputed LUTs and Mie phase tables, in\n"
               "ATMO_CACHE_DIR, else $XDG_CACHE_HOME/atmo, else ~/.cache/atmo.\n\n"
               "  list     each cached file's kind, size and age, and the total (the default)\n"
               "  verify   check every file, and PoCL's compiled programs in the folder pocl,\n"
               "           and delete the damaged ones (renders also do this for the files\n"
               "           they read)\n"
               "  clear    delete every atmo file in the cache directory and the folder pocl\n"
               "           (other files stay, and so does a PoCL cache set by POCL_CACHE_DIR)\n"
               "  --help   this text\n");
}

/* "<kind>-<16 hex>.bin" with an optional ".tmp.<pid>": the kind and the pid (0 for a product);
 * 0 when the name is no atmo file. */
static int parse_name(const char *name, entry *out)
{
    const char *bin = strstr(name, ".bin");
    if (!bin || bin - name < KEY_HEX_DIGITS + 2)
        return 0;
    const char *hex = bin - KEY_HEX_DIGITS;
    if (hex[-1] != '-')
        return 0;
    for (int i = 0; i < KEY_HEX_DIGITS; i++)
        if (!isxdigit((unsigned char)hex[i]))
            return 0;
    size_t kind_len = (size_t)(hex - 1 - name);
    if (kind_len == 0 || kind_len >= ATMO_CACHE_KIND_MAX)
        return 0;
    for (size_t i = 0; i < kind_len; i++)
        if (!islower((unsigned char)name[i]) && !isdigit((unsigned char)name[i]) &&
            name[i] != '-' && name[i] != '_')
            return 0;
    out->pid = 0;
    if (bin[4] != 0) {
        char *end;
        if (strncmp(bin + 4, ".tmp.", 5) != 0)
            return 0;
        errno = 0;
        out->pid = strtoll(bin + 9, &end, 10);
        if (errno || end == bin + 9 || *end || out->pid <= 0)
            return 0;
    }
    snprintf(out->name, sizeof out->name, "%s", name);
    memcpy(out->kind, name, kind_len);
    out->kind[kind_len] = 0;
    return 1;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(((const entry *)a)->name, ((const entry *)b)->name);
}

/* The directory's atmo files, sorted by name; returns their count or -1. */
static int scan(const char *dir, entry **out)
{
    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "atmo cache: cannot read '%s': %s\n", dir, strerror(errno));
        return -1;
    }
    int n = 0, cap = 64;
    entry *list = malloc(sizeof *list * (size_t)cap);
    for (struct dirent *ent; list && (ent = readdir(d));) {
        if (!parse_name(ent->d_name, &list[n]))
            continue;
        if (++n == cap && cap < MAX_ENTRIES) {
            cap *= 2;
            entry *grown = realloc(list, sizeof *list * (size_t)cap);
            if (!grown)
                free(list);
            list = grown;
        } else if (n == cap) {
            break;
        }
    }
    closedir(d);
    if (!list) {
        fprintf(stderr, "atmo cache: out of memory listing '%s'\n", dir);
        return -1;
    }
    qsort(list, (size_t)n, sizeof *list, by_name);
    *out = list;
    return n;
}

static void format_size(double bytes, char *out, size_t size)
{
    const char *unit[] = {"B", "KiB", "MiB", "GiB", "TiB"};
    int u = 0;
    while (bytes >= 1024.0 && u < 4)
        bytes /= 1024.0, u++;
    snprintf(out, size, u ? "%.1f %s" : "%.0f %s", bytes, unit[u]);
}

static void format_age(double seconds, char *out, size_t size)
{
    if (seconds < 120.0)
        snprintf(out, size, "%.0f s", seconds < 0.0 ? 0.0 : seconds);
    else if (seconds < 7200.0)
        snprintf(out, size, "%.0f min", seconds / 60.0);
    else if (seconds < 172800.0)
        snprintf(out, size, "%.0f h", seconds / 3600.0);
    else
        snprintf(out, size, "%.0f d", seconds / 86400.0);
}

static int list_files(const char *dir, const entry *list, int n)
{
    time_t now = time(NULL);
    double total = 0.0;
    char size[32], age[32], path[4096];
    for (int i = 0; i < n; i++) {
        struct stat st;
        snprintf(path, sizeof path, "%s/%s", dir, list[i].name);
        if (stat(path, &st) != 0)
            continue;
        total += (double)st.st_size;
        format_size((double)st.st_size, size, sizeof size);
        format_age(difftime(now, st.st_mtime), age, sizeof age);
        printf("%-16s %10s %8s  %s%s\n", list[i].kind, size, age, list[i].name,
               list[i].pid ? "  (temporary)" : "");
    }
    format_size(total, size, sizeof size);
    printf("%d file%s, %s in %s\n", n, n == 1 ? "" : "s", size, dir);
    return ATMO_OK;
}

static int remove_file(const char *path)
{
    if (remove(path) == 0 || errno == ENOENT)
        return 0;
    fprintf(stderr, "atmo cache: cannot remove '%s': %s\n", path, strerror(errno));
    return -1;
}

/* A temporary file whose writer is no running process (kill(pid, 0) fails with ESRCH). */
static int writer_gone(const entry *e)
{
    return e->pid > 0 && kill((pid_t)e->pid, 0) == -1 && errno == ESRCH;
}

static int verify_files(const char *dir, const entry *list, int n)
{
    int removed = 0, products = 0, rc = ATMO_OK;
    char path[4096];
    for (int i = 0; i < n; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, list[i].name);
        const char *why = NULL;
        char kind[ATMO_CACHE_KIND_MAX];
        if (list[i].pid) {
            if (writer_gone(&list[i]))
                why = "a temporary file whose writer is gone";
        } else {
            products++;
            if (atmo_cache_file_check(path, kind, &why) == 0)
                why = strcmp(kind, list[i].kind) ? "its kind does not match its name" : NULL;
        }
        if (!why)
            continue;
        if (remove_file(path)) {
            rc = ATMO_ERR_RUNTIME;
            continue;
        }
        printf("removed %s (%s)\n", list[i].name, why);
        removed++;
    }
    char driver[4200];
    if (atmo_cl_driver_cache_is_own() && snprintf(driver, sizeof driver, "%s/pocl", dir) > 0)
        removed += atmo_cl_driver_cache_repair(driver, stdout);
    printf("verified %d cached file%s in %s: %d removed\n", products, products == 1 ? "" : "s",
           dir, removed);
    return rc;
}

static int remove_tree_entry(const char *path, const struct stat *st, int flag,
                             struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static int clear_files(const char *dir, const entry *list, int n)
{
    int removed = 0, rc = ATMO_OK;
    char path[4096];
    for (int i = 0; i < n; i++) {
        if (list[i].pid && !writer_gone(&list[i]))
            continue; /* a running writer's: it renames it into place or removes it itself */
        snprintf(path, sizeof path, "%s/%s", dir, list[i].name);
        if (remove_file(path))
            rc = ATMO_ERR_RUNTIME;
        else
            removed++;
    }
    printf("removed %d file%s from %s\n", removed, removed == 1 ? "" : "s", dir);
    char driver[4200];
    struct stat st;
    if (!atmo_cl_driver_cache_is_own()) {
        if (atmo_cl_driver_cache_dir(driver, sizeof driver) == 0)
            printf("kept PoCL's cache in %s (POCL_CACHE_DIR, not atmo's; delete that folder to "
                   "compile from scratch)\n", driver);
    } else if (snprintf(driver, sizeof driver, "%s/pocl", dir) > 0 && lstat(driver, &st) == 0) {
        if (nftw(driver, remove_tree_entry, 16, FTW_DEPTH | FTW_PHYS) != 0) {
            fprintf(stderr, "atmo cache: cannot remove '%s': %s\n", driver, strerror(errno));
            rc = ATMO_ERR_RUNTIME;
        } else {
            printf("removed PoCL's compiled programs in %s\n", driver);
        }
    }
    return rc;
}

int cmd_cache(int argc, char **argv)
{
    const char *action = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            print_usage(stdout);
            return ATMO_OK;
        }
        if (action || (strcmp(argv[i], "list") && strcmp(argv[i], "verify") &&
                       strcmp(argv[i], "clear"))) {
            static const char *const actions[] = {"list", "verify", "clear", NULL};
            const char *near = action ? NULL : atmo_suggest_among(argv[i], actions);
            fprintf(stderr, "atmo cache: unexpected argument '%s' (%s%s%sactions: list, verify, "
                            "clear; run 'atmo cache --help')\n", argv[i],
                    near ? "did you mean '" : "", near ? near : "", near ? "'? " : "");
            return ATMO_ERR_USAGE;
        }
        action = argv[i];
    }
    char dir[4000], why[256];
    if (atmo_cache_dir_find(dir, sizeof dir, why, sizeof why) != 0 &&
        (!action || strcmp(action, "list") != 0 || strcmp(dir, "(none)") == 0)) {
        fprintf(stderr, "atmo cache: cache directory '%s' is unusable: %s (set ATMO_CACHE_DIR "
                        "to a writable directory)\n", dir, why);
        return ATMO_ERR_RUNTIME;
    }
    entry *list = NULL;
    int n = scan(dir, &list);
    if (n < 0)
        return ATMO_ERR_RUNTIME;
    int rc = !action || strcmp(action, "list") == 0 ? list_files(dir, list, n)
             : strcmp(action, "verify") == 0        ? verify_files(dir, list, n)
                                                    : clear_files(dir, list, n);
    free(list);
    return rc;
}
