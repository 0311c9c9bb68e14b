#!/usr/bin/env bash
# test_layout — the source tree keeps its architecture: the host modules (the folders of host/)
# include each other without circles, the kernel headers likewise, no kernel file declares a
# function that another kernel file defines, the generic integrator names no feature and tests
# no feature's flag, and no identifier in host/, include/ or kernels/ is one that C11 and OpenCL
# C reserve.
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

# The feature folders host/features/NAME/ hold the plan's part of each feature (its registry
# rows, its plan functions), which belongs to the module plan, whose registry and composition
# it fills, and its scene parameters (NAME_params.c), which belong to the module scene.
# owner HEADER_BASENAME: the module of include/atmo/HEADER_BASENAME.h, or nothing
owner() {
    local x=$1 impl
    impl=$(ls host/*/"$x".c 2>/dev/null | head -n 1)
    if ls host/features/*/"$x".c > /dev/null 2>&1; then
        echo plan
    elif [ -n "$impl" ]; then
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
        host/features/*/*_params.c) from=scene ;;
        host/features/*) from=plan ;;
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

# ---- Symbols of the kernels -------------------------------------------------------------------
# The program is assembled from the kernel files in registry order, so a file may call only what
# files before it define: a prototype of a function that another kernel file defines ("defined
# after this file") is a circle in the call graph that the include graph cannot see. The plan's
# generated composition (host/plan/compose.c) is what joins the features to the generic
# integrator, so the generic files name no feature and test no feature's flag.
generic_files="kernels/media/media.h kernels/media/medium.h kernels/media/visibility.h
    kernels/media/ray.h
    kernels/media/tracking.h kernels/media/majorant_walk.h kernels/media/media_walk.h
    kernels/media/quadrature_walk.h"
# the registry's feature flags (its -D strings) and the features' identifier prefixes
flags=$(cat host/plan/features.c host/features/*/*_feature.c |
    grep -oE '"-D[A-Z_ =0-9-]*"' | tr -d '"' | tr ' ' '\n' |
    sed -n 's/^-D\([A-Z_0-9]*\).*/\1/p' | sort -u | paste -sd'|')
feature_names='cloud|clouds|terrain|observer|ms_lut|lut|objects?|path'

# strip_comments FILE: the file without its /* */ and // comments (lines kept, for numbers).
strip_comments() {
    awk '{ line = $0; out = ""
           while (length(line)) {
               if (c) { i = index(line, "*/"); if (i) { line = substr(line, i + 2); c = 0 } else line = "" }
               else { i = index(line, "/*"); j = index(line, "//")
                      if (j && (!i || j < i)) { out = out substr(line, 1, j - 1); line = "" }
                      else if (i) { out = out substr(line, 1, i - 1); line = substr(line, i + 2); c = 1 }
                      else { out = out line; line = "" } } }
           print out }' "$1"
}

# forward_prototypes FILE...: "FILE:LINE NAME" of each prototype (ATMO_FN ... name(...); with no
# body) whose function another of the files defines.
forward_prototypes() {
    local f
    for f in "$@"; do
        strip_comments "$f" | awk -v f="$f" '
            /^ATMO_FN/ { decl = ""; start = NR; open = 1 }
            open { decl = decl " " $0
                   if ($0 ~ /\{/) { open = 0; if (match(decl, /[A-Za-z_][A-Za-z0-9_]*[ ]*\(/)) {
                       n = substr(decl, RSTART, RLENGTH); sub(/[ ]*\($/, "", n); print "def", f, start, n } }
                   else if ($0 ~ /\)[ ]*;[ ]*$/) { open = 0; if (match(decl, /[A-Za-z_][A-Za-z0-9_]*[ ]*\(/)) {
                       n = substr(decl, RSTART, RLENGTH); sub(/[ ]*\($/, "", n); print "proto", f, start, n } } }'
    done | awk '$1 == "def" { where[$4] = $2 } $1 == "proto" { p[++k] = $0 }
        END { for (i = 1; i <= k; i++) { split(p[i], a, " ")
                  if ((a[4] in where) && where[a[4]] != a[2]) print a[2] ":" a[3], a[4] } }'
}

# feature_identifiers FILE...: "FILE:LINE NAME" of each identifier in the code that belongs to a
# feature (a prefix of feature_names, or a feature flag), the generated buffer lists aside.
feature_identifiers() {
    local f
    for f in "$@"; do
        strip_comments "$f" | grep -noE '[A-Za-z_][A-Za-z0-9_]*' |
            grep -vE ':(ATMO_LUT_PARAMS|ATMO_LUT_OUT_PARAMS|ATMO_LUT_ARGS)$' |
            grep -iE ":(atmo_)?($feature_names)(_[A-Za-z0-9_]*)?$|:($flags)$" | sed "s|^|$f:|"
    done
}

# feature_ifs FILE...: "FILE:LINE" of each #if / #ifdef / #elif that tests a feature flag.
feature_ifs() {
    local f
    for f in "$@"; do
        grep -nE "^[[:space:]]*#[[:space:]]*(if|ifdef|ifndef|elif)\b.*\b($flags)\b" "$f" |
            sed "s|^|$f:|"
    done
}

# stage_ifs FILE...: "FILE:LINE" of each #if / #ifdef / #ifndef / #elif that is neither the
# file's include guard nor the host-only include block (#ifndef __OPENCL_VERSION__): a stage
# that runs on the composed media (render/volume_stage.h) builds the same for every scene.
stage_ifs() {
    local f
    for f in "$@"; do
        grep -nE '^[[:space:]]*#[[:space:]]*(if|ifdef|ifndef|elif)\b' "$f" |
            grep -vE '#[[:space:]]*ifndef[[:space:]]+(ATMO_[A-Z0-9_]*_H|__OPENCL_VERSION__)[[:space:]]*$' |
            sed "s|^|$f:|"
    done
}

# The detectors on synthetic files: a prototype of a function defined in another file (and
# one defined in the same file, which is not forward), a feature's identifier and a feature's
# flag in code (and both in comments, which do not count).
syn=$(mktemp -d "${TMPDIR:-/tmp}/test_layout.XXXXXX")
printf '%s\n' '/* medium_x() uses cloud_y, ATMO_CLOUD */' 'ATMO_FN vec3 cloud_sun(int a,' \
    '                      int b);' 'ATMO_FN int own(int a);' 'ATMO_FN int own(int a) { return a; }' \
    'ATMO_FN float medium_x(void)' '{' '    return cloud_sun(1, 2).x;' '}' \
    '#ifdef ATMO_CLOUD' '#endif' >"$syn/generic.h"
printf '%s\n' 'ATMO_FN vec3 cloud_sun(int a, int b)' '{' '    return v3(a, b, 0);' '}' >"$syn/feature.h"
found=$(forward_prototypes "$syn/generic.h" "$syn/feature.h")
if [ "$found" = "$syn/generic.h:2 cloud_sun" ]; then ok; else
    bad "the forward-prototype detector on a synthetic pair found '$found'"; fi
found=$(feature_identifiers "$syn/generic.h" | sed "s|$syn/||" | paste -sd' ')
if [ "$found" = "generic.h:2:cloud_sun generic.h:8:cloud_sun generic.h:10:ATMO_CLOUD" ]; then ok; else
    bad "the feature-name detector on a synthetic file found '$found'"; fi
found=$(feature_ifs "$syn/generic.h" | sed "s|$syn/||")
if [ "$found" = "generic.h:10:#ifdef ATMO_CLOUD" ]; then ok; else
    bad "the feature-#if detector on a synthetic file found '$found'"; fi
printf '%s\n' '#ifndef ATMO_RENDER_X_H' '#define ATMO_RENDER_X_H' '#ifndef __OPENCL_VERSION__' \
    '#endif' '#if MEDIA_VOLUME > 0' '#endif' '#endif' >"$syn/stage.h"
found=$(stage_ifs "$syn/stage.h" | sed "s|$syn/||")
if [ "$found" = "stage.h:5:#if MEDIA_VOLUME > 0" ]; then ok; else
    bad "the stage-#if detector on a synthetic file found '$found'"; fi
rm -rf "$syn"

kernel_files=$(find kernels -name '*.h' -o -name '*.cl' | sort)
found=$(forward_prototypes $kernel_files)
if [ -n "$found" ]; then
    bad "prototypes of functions another kernel file defines (a circle between files: move the" \
        "function before its caller, or make it a slot of the plan's composition):"
    echo "$found" | sed 's/^/    /' >&2
else ok; fi
found=$(feature_identifiers $generic_files)
if [ -n "$found" ]; then
    bad "feature names in the generic integrator (give the feature a slot in atmo_slots instead):"
    echo "$found" | sed 's/^/    /' >&2
else ok; fi
found=$(feature_ifs $generic_files)
if [ -n "$found" ]; then
    bad "feature #if in the generic integrator (compose the feature instead):"
    echo "$found" | sed 's/^/    /' >&2
else ok; fi

# A feature's flags are tested in its own folder only (kernels/terrain, kernels/clouds,
# kernels/cloud_shell, and the objects' render/objects*): the generic integrator, the render
# stages (the preview's camera rays, the path tracer, the guides) and the methods take the
# features through the plan's composition.
stage_files=$(find kernels -name '*.h' -o -name '*.cl' |
    grep -vE '^kernels/(terrain|clouds|cloud_shell)/|^kernels/render/objects' | sort)
found=$(feature_ifs $stage_files)
if [ -n "$found" ]; then
    bad "feature #if outside the feature's folder (give the feature a slot of the composition):"
    echo "$found" | sed 's/^/    /' >&2
else ok; fi

# The path tracer's volume stage runs on the one majorant walk over the composed volume medium:
# no #if and no feature's name in it.
found=$( (stage_ifs kernels/render/volume_stage.h; feature_identifiers kernels/render/volume_stage.h) )
if [ -n "$found" ]; then
    bad "render/volume_stage.h tests a flag or names a feature (compose the volume medium instead):"
    echo "$found" | sed 's/^/    /' >&2
else ok; fi

# A feature registers itself from its folder (host/features/NAME/NAME_feature.c): the engine's
# registry (host/plan/) holds no feature's row, so it names no feature flag and no fragment
# of a feature's kernels.
found=$(grep -nE '"-D|"kernels/(terrain|clouds|cloud_shell)/|"kernels/render/(objects|path)' \
    host/plan/*.c)
if [ -n "$found" ]; then
    bad "a feature's row in the engine's registry (move it to its folder's NAME_feature.c):"
    echo "$found" | sed 's/^/    /' >&2
else ok; fi

echo "test_layout: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
