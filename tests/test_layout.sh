#!/usr/bin/env bash
# test_layout — the source tree keeps its architecture: the host modules (the folders of host/)
# include each other without circles, the kernel headers likewise, and no identifier in host/,
# include/ or kernels/ is one that C11 and OpenCL C reserve.
# labels: unit
#
# Oracle: the rules of docs/architecture.md and C11 7.1.3 (identifiers that begin with two
# underscores, or an underscore and a capital, are reserved for the implementation). The check is
# exact: a circle is a circle, a reserved name is a name; there is no tolerance.
#
# The include graph. Its nodes are
#   - each folder F of host/ (a module),
#   - gpu: the structs shared byte for byte with the kernels (include/atmo/gpu_*.h),
#   - each kernel file, by its path (kernels/media/medium.h): the kernel folders group files by
#     concern (media/ integrates the atmosphere of atmosphere/, whose methods call media/'s
#     integrator), so their order is per file, and the program is assembled in registry order.
# A public header include/atmo/X.h belongs to the module that implements it:
#   1. the folder F with host/F/X.c (session.h -> render, status.h -> base, embedded.h -> cl),
#   2. else gpu, for X = gpu_*,
#   3. else the folder named by X's prefix up to the first '_' (atmosphere.h -> atmosphere,
#      bench.h -> bench);
# a header that none of these maps fails the test, so a new header needs a home.
# The edges are the #include "..." lines: a file of host/F/ gives F -> the owner of the header it
# includes ("atmo/X.h" -> that header's module, "D/Y.h" -> kernels/D/Y.h, a header of host/F/
# itself -> no edge); a public header's includes are edges of its module; a kernel file's are
# edges of that file. Any other quoted include fails the test. tsort(1) orders the graph and
# names the nodes of a circle; each edge of the circle is printed with the lines that make it.
# Before the tree is checked, the same detector must find the circle of a synthetic graph.
set -u
src=${ATMO_SOURCE_DIR:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$src" || exit 1
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

# owner HEADER_BASENAME: the module of include/atmo/HEADER_BASENAME.h, or nothing
owner() {
    local x=$1 impl
    impl=$(ls host/*/"$x".c 2>/dev/null | head -n 1)
    if [ -n "$impl" ]; then
        basename "$(dirname "$impl")"
    elif [ "${x#gpu_}" != "$x" ]; then
        echo gpu
    elif [ -d "host/${x%%_*}" ]; then
        echo "${x%%_*}"
    fi
}

# Every quoted include as "FILE LINE TARGET".
includes() {
    grep -rnE '^[[:space:]]*#[[:space:]]*include[[:space:]]+"' host include kernels |
        sed -E 's/^([^:]*):([0-9]+):[^"]*"([^"]*)".*/\1 \2 \3/'
}

# Edges "FROM TO FILE:LINE" of the tree's include graph; unresolvable includes go to stderr.
edges() {
    local file line target from to dir
    while read -r file line target; do
        case $file in
        host/*) from=$(echo "$file" | cut -d/ -f2) ;;
        include/atmo/*)
            from=$(owner "$(basename "$file" .h)")
            [ -n "$from" ] || { echo "unmapped public header $file" >&2; continue; } ;;
        kernels/*) from=$file ;;
        *) continue ;;
        esac
        dir=$(dirname "$file")
        if [ "${target#atmo/}" != "$target" ] && [ -f "include/$target" ]; then
            to=$(owner "$(basename "$target" .h)")
            [ -n "$to" ] || { echo "unmapped public header include/$target" >&2; continue; }
        elif [ -f "kernels/$target" ]; then
            to=kernels/$target
        elif [ "${file#host/}" != "$file" ] && [ -f "$dir/$target" ]; then
            continue # a header of the module itself
        else
            echo "unresolved include \"$target\" in $file:$line" >&2
            continue
        fi
        [ "$from" = "$to" ] || echo "$from $to $file:$line"
    done
}

# cycles: reads edges "FROM TO ..." on stdin; prints each circle tsort finds as
# "a -> b -> ... -> a"; exits 1 when there is one.
cycles() {
    local report
    report=$(awk '{print $1, $2}' | sort -u | tsort 2>&1 >/dev/null)
    [ -z "$report" ] && return 0
    echo "$report" | awk '
        /input contains a loop/ { if (n) print path " -> " first; n = 0; next }
        { sub(/^tsort: /, ""); if (n++ == 0) { first = $0; path = $0 } else path = path " -> " $0 }
        END { if (n) print path " -> " first }'
    return 1
}

# The detector on a synthetic graph: cli -> render -> plan -> cli, and a branch without a circle.
synthetic=$(printf '%s\n' "cli render" "render plan" "plan cli" "plan scene" | cycles)
if [ $? -eq 1 ] && echo "$synthetic" | grep -q 'cli' && echo "$synthetic" | grep -q 'plan' &&
    ! echo "$synthetic" | grep -q scene; then
    ok
else
    bad "the cycle detector missed the synthetic circle cli -> render -> plan -> cli: '$synthetic'"
fi

# The tree's graph.
graph=$(includes | edges 2>"${TMPDIR:-/tmp}/test_layout.$$")
problems=$(cat "${TMPDIR:-/tmp}/test_layout.$$")
rm -f "${TMPDIR:-/tmp}/test_layout.$$"
if [ -n "$problems" ]; then
    bad "includes the layout cannot place:"
    echo "$problems" >&2
else
    ok
fi
nmodules=$(echo "$graph" | awk '$1 !~ /^kernels\// {print $1} $2 !~ /^kernels\// {print $2}' |
    sort -u | wc -l)
if [ "$nmodules" -lt 10 ]; then
    bad "only $nmodules host modules in the include graph (host/ has $(ls -d host/*/ | wc -l))"
else
    ok
fi
circles=$(echo "$graph" | cycles)
if [ $? -ne 0 ]; then
    bad "include circles:"
    echo "$circles" | while read -r circle; do
        echo "  $circle" >&2
        nodes=$(echo "$circle" | sed 's/ -> /\n/g')
        echo "$nodes" | paste -d' ' - <(echo "$nodes" | tail -n +2) | head -n -1 |
            while read -r a b; do
                echo "$graph" | awk -v a="$a" -v b="$b" '$1 == a && $2 == b {print "    " a " -> " b ": " $3}' >&2
            done
    done
else
    ok
    echo "host modules, each after those it includes:" \
        $(echo "$graph" | awk '{print $2, $1}' | tsort | grep -v '^kernels/')
fi

# Reserved identifiers. Allowed: the OpenCL C address-space and function qualifiers, the GNU
# attribute syntax (OpenCL C 6.11), OpenCL's and the compilers' predefined macros read in #if
# tests, C's __VA_ARGS__, builtins, C11's own keywords that begin with an underscore and a
# capital, and POSIX's pathconf/sysconf names (_PC_*, _SC_*).
allowed='^(__kernel|__global|__constant|__local|__private|__read_only|__write_only|__attribute__|__OPENCL_VERSION__|__OPENCL_C_VERSION__|__VA_ARGS__|__func__|__FILE__|__LINE__|__STDC__|__STDC_VERSION__|__GNUC__|__clang__|__linux__|__x86_64__|__builtin_[A-Za-z0-9_]*|_Static_assert|_Alignas|_Alignof|_Bool|_Noreturn|_Atomic|_Generic|_Thread_local|_PC_[A-Z_]*|_SC_[A-Z_]*)$'
reserved=$(grep -rnoE '(^|[^A-Za-z0-9_])(__[A-Za-z0-9_]*|_[A-Z][A-Za-z0-9_]*)' host include kernels |
    sed -E 's/^([^:]*:[0-9]+):[^_]*/\1 /' | awk -v allowed="$allowed" '$2 !~ allowed')
if [ -n "$reserved" ]; then
    bad "reserved identifiers (rename them; static helpers need no prefix):"
    echo "$reserved" | sed 's/^/    /' >&2
else
    ok
fi

echo "test_layout: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
