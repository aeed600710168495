#!/usr/bin/env python3
"""Each block's share of a run, from `callgrind_annotate` output (self costs) on stdin.

Every function is put to the block whose code it is, by its name (a kernel, its SystemC
module, or the helpers only it calls); the SystemC wrapping (sockets, the stages'
bookkeeping, the simulation kernel) and what no block owns are shown apart. Self costs
add up to the whole, unlike inclusive ones (the raster calls every block after it).
"""
import re
import sys

# block: pattern of the function names that are its code (first match wins)
OWNERS = [
    # A stage's module code (its b_transport and bookkeeping) is the wrapping, whichever
    # block it wraps; the kernel it calls is the block's.
    ("SystemC wrapping", r"Stage<|modules::forward \[|Schedule::|\bsc_core::|\btlm(_utils)?::|libsystemc"),
    ("setup", r"SetupKernel|modules::Setup::|core::Mesh::|clip_triangle|snap_triangle|to_screen|to_world|llround|lround"),
    ("raster", r"RasterKernel|modules::Raster::|row_span"),
    ("parallax", r"Parallax|march_cells"),
    ("normal_interp", r"NormalInterp"),
    ("bump_fetch", r"BumpFetch"),
    ("bump_perturb", r"BumpPerturb"),
    ("normal_mux", r"NormalMux"),
    ("normalize", r"Normalize|normalize_span"),
    ("vector_interp", r"VectorInterp"),
    ("texture_fetch", r"TextureFetch|Sampler"),
    ("lighting", r"Lighting"),
    ("framebuffer", r"Framebuffer"),
    ("texel_project", r"TexelProject"),
]

if len(sys.argv) > 1 or sys.stdin.isatty():
    print("block-share: reads callgrind_annotate's output on stdin, and takes no arguments", file=sys.stderr)
    sys.exit(2)
costs = {}
total = 0
for line in sys.stdin:
    m = re.match(r"\s*([\d,]+)\s+\([\s\d.]+%\)\s+(.*)", line)
    if not m or "PROGRAM TOTALS" in line:
        continue
    cost, where = int(m.group(1).replace(",", "")), m.group(2)
    # "file:function(arguments) [object]": matched on the function's name and the object
    # (the arguments name other blocks' types).
    file_function, _, obj = where.rpartition(" [")
    function = file_function.split(":", 1)[-1].split("(")[0]
    name = function + " [" + obj
    owner = next((block for block, pattern in OWNERS if re.search(pattern, name)), "other (libc, libm, run loop)")
    costs[owner] = costs.get(owner, 0) + cost
    total += cost
for block, cost in sorted(costs.items(), key=lambda kv: -kv[1]):
    print(f"  {block:30s} {100.0 * cost / total:5.1f} %")
