/* cl_driver_cache.c — the checks of the cache directory and of PoCL's compiled programs in it
 * (atmo/cl_runtime.h).
 *
 * A cache directory is usable when it is (or can be made) a directory in which a file can be
 * created, written and removed: the probe "<dir>/.atmo-probe.<pid>" with one byte, which also
 * sees a full file system (ENOSPC) and a read-only one (EROFS), where access(2) would not.
 *
 * PoCL trusts its cache: a program's LLVM bitcode ("program.bc") or a kernel's shared object
 * ("<kernel>.so") that is cut short makes it abort (an assertion, or a failed dlopen) on every
 * later run. Before atmo opens the platform, every such file under atmo's own PoCL directory
 * is checked for completeness, and a program whose files are not complete is removed whole
 * (the folder "<2 letters>/<hash>" that holds it), so PoCL builds it again:
 *   - a shared object: the ELF magic, and the program header and section header tables lie
 *     inside the file (ELF, System V gABI: e_phoff + e_phnum * e_phentsize and e_shoff +
 *     e_shnum * e_shentsize); the section headers come last, so a cut removes them;
 *   - bitcode: the magic "BC" 0xC0DE (inside the optional wrapper 0x0B17C0DE, whose offset and
 *     size must lie inside the file), then the top-level blocks of the bitstream (LLVM Bitcode
 *     File Format: abbreviation width 2, ENTER_SUBBLOCK = 1, block id vbr8, abbreviation width
 *     vbr4, align to 32 bits, the block's length in 32-bit words), each of which must end
 *     inside the file, followed by nothing but zero padding.
 * Bytes changed in place without changing a length are not seen; what is seen is what the
 * reported failures were: files cut short or left empty by a killed writer or a full disk. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include "atmo/cl_runtime.h"
#include "atmo/fileio.h"

int atmo_cache_dir_usable(const char *dir, char *why, size_t size)
{
    struct stat st;
    char probe[4200];
    if (stat(dir, &st) != 0) {
        snprintf(why, size, "%s", strerror(errno));
        return 0;
    }
    if (!S_ISDIR(st.st_mode)) {
        snprintf(why, size, "it is not a directory");
        return 0;
    }
    snprintf(probe, sizeof probe, "%s/.atmo-probe.%ld", dir, (long)getpid());
    int fd = open(probe, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd < 0) {
        snprintf(why, size, "cannot create a file in it: %s", strerror(errno));
        return 0;
    }
    int ok = write(fd, "x", 1) == 1, err = errno;
    ok &= close(fd) == 0;
    err = ok ? 0 : (err ? err : errno);
    unlink(probe);
    if (!ok)
        snprintf(why, size, "cannot write a file in it: %s", strerror(err));
    return ok;
}

static uint64_t read_le(const unsigned char *p, int bytes)
{
    uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; i--)
        v = v << 8 | p[i];
    return v;
}

/* NULL when the shared object's header tables lie inside its n bytes, else why not. */
static const char *check_elf(const unsigned char *p, size_t n)
{
    if (n < 52 || memcmp(p, "\177ELF", 4) != 0)
        return "not an ELF file (empty or cut before its header)";
    int wide = p[4] == 2, w = wide ? 8 : 4;
    if (p[5] != 1 || (wide && n < 64))
        return "an ELF header atmo cannot read";
    size_t at = wide ? 32 : 28; /* e_phoff, then e_shoff, e_flags, e_ehsize, e_phentsize... */
    uint64_t phoff = read_le(p + at, w), shoff = read_le(p + at + w, w);
    const unsigned char *sizes = p + at + 2 * w + 6;
    uint64_t phent = read_le(sizes, 2), phnum = read_le(sizes + 2, 2);
    uint64_t shent = read_le(sizes + 4, 2), shnum = read_le(sizes + 6, 2);
    if (phoff + phent * phnum > n || shoff + shent * shnum > n)
        return "cut short (its header tables end beyond the file)";
    return NULL;
}

typedef struct bits {
    const unsigned char *p;
    uint64_t at, end; /* in bits */
} bits;

static int take(bits *b, int width, uint64_t *v)
{
    *v = 0;
    if (b->at + (uint64_t)width > b->end)
        return -1;
    for (int i = 0; i < width; i++, b->at++)
        *v |= (uint64_t)(b->p[b->at >> 3] >> (b->at & 7) & 1) << i;
    return 0;
}

static int take_vbr(bits *b, int width, uint64_t *v)
{
    uint64_t chunk, hi = 1ull << (width - 1);
    *v = 0;
    for (int shift = 0; shift < 64; shift += width - 1) {
        if (take(b, width, &chunk))
            return -1;
        *v |= (chunk & (hi - 1)) << shift;
        if (!(chunk & hi))
            return 0;
    }
    return -1;
}

/* NULL when the bitcode's top-level blocks all end inside its n bytes, else why not. */
static const char *check_bitcode(const unsigned char *p, size_t n)
{
    if (n >= 20 && read_le(p, 4) == 0x0B17C0DEu) {
        uint64_t off = read_le(p + 8, 4), size = read_le(p + 12, 4);
        if (off + size > n)
            return "cut short (its wrapper says more bytes than the file has)";
        p += off;
        n = (size_t)size;
    }
    if (n < 4 || memcmp(p, "BC\xC0\xDE", 4) != 0)
        return "not LLVM bitcode (empty or cut before its magic)";
    bits b = {p, 32, (uint64_t)n * 8};
    uint64_t abbrev, id, width, words;
    while (b.end - b.at >= 2) {
        uint64_t mark = b.at;
        if (take(&b, 2, &abbrev) || abbrev != 1) {
            for (b.at = mark; b.at < b.end; b.at++)
                if (b.p[b.at >> 3] >> (b.at & 7) & 1)
                    return "damaged (something other than a block at its top level)";
            return NULL;
        }
        if (take_vbr(&b, 8, &id) || take_vbr(&b, 4, &width))
            return "cut short (inside a block header)";
        b.at = (b.at + 31) & ~(uint64_t)31;
        if (take(&b, 32, &words) || b.at + words * 32 > b.end)
            return "cut short (a block ends beyond the file)";
        b.at += words * 32;
    }
    return NULL;
}

/* NULL when the file at path is complete as far as its kind can tell, else why not. */
static const char *check_file(const char *path)
{
    size_t len = strlen(path);
    int elf = len > 3 && strcmp(path + len - 3, ".so") == 0;
    int bc = len > 3 && strcmp(path + len - 3, ".bc") == 0;
    if (!elf && !bc)
        return NULL;
    const char *why = NULL;
    int fd = atmo_open_regular_fd(path, &why);
    struct stat st;
    if (fd < 0)
        return why;
    if (fstat(fd, &st) != 0 || st.st_size == 0) {
        close(fd);
        return elf ? "not an ELF file (empty)" : "not LLVM bitcode (empty)";
    }
    void *map = mmap(NULL, (size_t)st.st_size, PROT_READ, MAP_PRIVATE, fd, 0);
    close(fd);
    if (map == MAP_FAILED)
        return "cannot be read";
    why = elf ? check_elf(map, (size_t)st.st_size) : check_bitcode(map, (size_t)st.st_size);
    munmap(map, (size_t)st.st_size);
    return why;
}

/* The first damaged file under dir (its name into bad) and why; NULL when all are complete. */
static const char *check_tree(const char *dir, char *bad, size_t size, int depth)
{
    DIR *d = opendir(dir);
    const char *why = NULL;
    if (!d)
        return NULL;
    for (struct dirent *ent; !why && (ent = readdir(d));) {
        char path[8192];
        struct stat st;
        if (strcmp(ent->d_name, ".") == 0 || strcmp(ent->d_name, "..") == 0)
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, ent->d_name);
        if (lstat(path, &st) != 0)
            continue;
        if (S_ISDIR(st.st_mode) && depth < 8)
            why = check_tree(path, bad, size, depth + 1);
        else if (!S_ISDIR(st.st_mode) && (why = check_file(path)))
            snprintf(bad, size, "%.*s", (int)(size - 1), path);
    }
    closedir(d);
    return why;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

int atmo_cl_driver_cache_repair(const char *pocl_dir, FILE *say)
{
    DIR *top = opendir(pocl_dir);
    int removed = 0;
    if (!top)
        return 0;
    for (struct dirent *a; (a = readdir(top));) {
        char level1[4200];
        if (a->d_name[0] == '.')
            continue;
        snprintf(level1, sizeof level1, "%s/%s", pocl_dir, a->d_name);
        DIR *mid = opendir(level1);
        for (struct dirent *b; mid && (b = readdir(mid));) {
            char program[4500], bad[4600];
            if (b->d_name[0] == '.')
                continue;
            snprintf(program, sizeof program, "%s/%s", level1, b->d_name);
            const char *why = check_tree(program, bad, sizeof bad, 0);
            if (!why)
                continue;
            int gone = nftw(program, remove_entry, 16, FTW_DEPTH | FTW_PHYS) == 0;
            removed += gone;
            if (say)
                fprintf(say, "atmo: PoCL's cached program %s is damaged (%s: %s); %s\n",
                        program, bad + strlen(program) + 1, why,
                        gone ? "removed, it is compiled again"
                             : "it cannot be removed; delete it, or run atmo cache clear");
        }
        if (mid)
            closedir(mid);
    }
    closedir(top);
    return removed;
}
