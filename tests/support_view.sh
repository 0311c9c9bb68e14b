# support_view.sh — shared by the viewer's tests (sourced): an X server for the window, and a
# comparison of two 8-bit PNGs.
#
# view_start_x: exits 77 (ctest "not run") when this atmo has no viewer or no X server can be
# started; otherwise starts Xvfb (24-bit screen, so the framebuffer holds 8 bits per channel, as
# the PNG writer does) on a display it picks itself (-displayfd), exports DISPLAY, and stops the
# server when the test exits. Mesa's software OpenGL (llvmpipe, libgl1-mesa-dri) renders in it.
#
# png_compare A B: decodes both PNGs (8-bit RGB or RGBA, any filter, with Python's zlib: no
# imaging package needed) and prints "WIDTH HEIGHT MAX_DIFF DIFFERING" over R, G, B, where
# MAX_DIFF is the largest absolute difference in 1/255 steps and DIFFERING the number of
# channel values that differ; it fails when the sizes differ.

view_start_x() {
    local atmo=$1 out
    out=$("$atmo" view --help 2>&1)
    if echo "$out" | grep -q "built without GLFW"; then
        echo "SKIP: this atmo was built without the viewer" >&2
        exit 77
    fi
    if ! command -v Xvfb >/dev/null; then
        echo "SKIP: no Xvfb (install xvfb)" >&2
        exit 77
    fi
    local fifo
    fifo=$(mktemp -u)
    mkfifo "$fifo"
    Xvfb -displayfd 3 -screen 0 1024x768x24 -nolisten tcp 3>"$fifo" 2>/dev/null &
    VIEW_XVFB_PID=$!
    local display
    display=$(timeout 20 head -n 1 "$fifo")
    rm -f "$fifo"
    if [ -z "$display" ]; then
        kill "$VIEW_XVFB_PID" 2>/dev/null
        echo "SKIP: Xvfb did not start" >&2
        exit 77
    fi
    export DISPLAY=:$display
}

view_stop_x() {
    [ -n "${VIEW_XVFB_PID:-}" ] && kill "$VIEW_XVFB_PID" 2>/dev/null && wait "$VIEW_XVFB_PID" 2>/dev/null
    VIEW_XVFB_PID=
}

png_compare() {
    python3 - "$1" "$2" <<'PY'
import struct, sys, zlib

def decode(path):
    data = open(path, 'rb').read()
    assert data[:8] == b'\x89PNG\r\n\x1a\n', path + ': not a PNG'
    i, idat = 8, b''
    while i < len(data):
        n, = struct.unpack('>I', data[i:i + 4])
        kind, body = data[i + 4:i + 8], data[i + 8:i + 8 + n]
        i += 12 + n
        if kind == b'IHDR':
            w, h, depth, colour = struct.unpack('>IIBB', body[:10])
            assert depth == 8 and colour in (2, 6), path + ': not 8-bit RGB(A)'
        elif kind == b'IDAT':
            idat += body
    raw, ch = zlib.decompress(idat), (3 if colour == 2 else 4)
    stride, rows, prev, k = w * ch, [], bytearray(w * ch), 0
    for _ in range(h):
        f, line = raw[k], bytearray(raw[k + 1:k + 1 + stride])
        k += 1 + stride
        for x in range(stride):
            a = line[x - ch] if x >= ch else 0
            b = prev[x]
            c = prev[x - ch] if x >= ch else 0
            if f == 1: line[x] = (line[x] + a) & 255
            elif f == 2: line[x] = (line[x] + b) & 255
            elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, ch, rows

wa, ha, ca, A = decode(sys.argv[1])
wb, hb, cb, B = decode(sys.argv[2])
if (wa, ha) != (wb, hb):
    print('sizes differ: %dx%d and %dx%d' % (wa, ha, wb, hb))
    sys.exit(1)
worst = differing = 0
for y in range(ha):
    for x in range(wa):
        for c in range(3):
            d = abs(A[y][x * ca + c] - B[y][x * cb + c])
            worst = max(worst, d)
            differing += d > 0
print(wa, ha, worst, differing)
PY
}
