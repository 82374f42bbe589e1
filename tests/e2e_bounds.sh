#!/bin/sh
# End to end: issue 21's smaller defects that the bad-input corpus cannot hold (it needs files
# made on the fly): a job too big for memory is refused at its width's line:col; merge refuses
# parts whose size is not the job's, even when their header, length and checksum agree.
. tests/lib.sh
root=$(pwd)

# the memory limit's error names the job file, line and column (where the machine has less than
# the 16 GB a 32768x32768 framebuffer would need twice over)
avail=$(awk '/^MemAvailable:/ { print $2 }' /proc/meminfo 2>/dev/null)
if [ -n "$avail" ] && [ "$avail" -lt 30000000 ]; then
    printf 'scene: %s/scenes/checker.yaml\nwidth: 32768\nheight: 32768\nsampler: uniform\nthreshold: 100\nlight_threshold: 100\n' \
        "$root" >"$T/mem.yaml"
    "$WORKER" --out "$T/omem" "$T/mem.yaml" 2>"$T/mem.log"; rc=$?
    check "memory: exit 2 (got $rc)" [ "$rc" -eq 2 ]
    check "memory: file:line:col: width: $(cat "$T/mem.log")" \
        grep -q "^$T/mem.yaml:2:8: width: 32768x32768 pixels: the framebuffer needs" "$T/mem.log"
    check "memory: nothing written" [ ! -e "$T/omem" ]
else
    skip "memory: this machine has 30 GB free or says nothing"
fi

# parts rewritten to 8x16 (header, rows and CRC consistent) for a 16x16 job: merge refuses them
printf 'scene: %s/scenes/checker.yaml\nwidth: 16\nheight: 16\nthreshold: 50\nlight_threshold: 50\nprocesses: 1\n' \
    "$root" >"$T/p.yaml"
"$WORKER" --quiet --part 0/2 --out "$T/o" "$T/p.yaml" && "$WORKER" --quiet --part 1/2 --out "$T/o" "$T/p.yaml"
for f in "$T"/o/p/p.part-*; do
    python3 - "$f" <<'PY'
import struct, sys, zlib
path = sys.argv[1]
b = bytearray(open(path, 'rb').read())
w, h, part, parts = struct.unpack_from('<4I', b, 12)
rows = len(range(part, h, parts))
struct.pack_into('<I', b, 12, w // 2)
body = bytes(b[:160]) + b''.join(bytes(b[160 + r * w * 12:160 + r * w * 12 + (w // 2) * 12]) for r in range(rows))
open(path, 'wb').write(body + struct.pack('<I', zlib.crc32(body) & 0xffffffff))
PY
done
"$WORKER" merge --out "$T/o" "$T/p.yaml" 2>"$T/merge.log"; rc=$?
check "merge: parts of another size refused (exit $rc): $(cat "$T/merge.log")" [ "$rc" -ne 0 ]
check "merge: the error names the sizes" grep -q "8x16.*16x16" "$T/merge.log"
check "merge: no image written" [ ! -e "$T/o/p/p.png" ]
finish
