#!/usr/bin/env bash
# The RTL in the loop against the TLM pipeline, in run time (docs/rtl.md, "Speed"):
# the benchmark scene at 480×270 with normalize in the RTL's format, each mode rendered
# with the C++ kernel and with the verilated unit (pipeline.normalize.impl=rtl), the
# two alternating, five times each; the pipeline's own wall time (the statistics'
# wall_s: no scene loading, no writing) as the median and the spread (min … max), and
# their ratio. Also the RTL's clock cycles stepped per pixel.
# Usage: scripts/rtl-bench.sh [--doc]   (--doc: the table into docs/rtl.md between its
# <!-- rtl-bench:1 --> markers). About 2 minutes.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${SHADETLM:-$root/build/app/shadetlm}
[[ -x $bin ]] || "$root/scripts/build.sh" >/dev/null
doc=0
[[ ${1:-} == --doc ]] && doc=1
format=$("$bin" --version | sed -n 's/^rtl: \(fixed:[0-9.]*\);.*/\1/p')
[[ -n $format ]] || { echo "rtl-bench.sh: this build has no RTL ($("$bin" --version | tail -1))" >&2; exit 2; }
out=$root/out/rtl-bench
mkdir -p "$out"
python3 - "$bin" "$root" "$out" "$format" <<'PY' | tee "$out/rtl-bench.txt"
import json, statistics, subprocess, sys
bin, root, out, fmt = sys.argv[1:5]
scene = f"{root}/scenes/bench-1080p.json"

def run(mode, impl):
    subprocess.run([bin, "render", scene, "-o", f"{out}/f.exr", "--stats", f"{out}/s.json",
                    "--set", "camera.resolution=[480,270]", "--set", f"pipeline.normalize.mode={mode}",
                    "--set", f"pipeline.normalize.format={fmt}", "--set", f"pipeline.normalize.impl={impl}",
                    "--allow-overflow"],  # (a narrow format saturates: counted, and not what is timed)
                   check=True, capture_output=True)
    s = json.load(open(f"{out}/s.json"))
    block = s["blocks"]["normalize"]
    return s["wall_s"], block.get("details", {}).get("rtl_cycles", 0) / max(block["pixels"], 1)

print(f"| mode (`{fmt}`) | TLM kernel: s, median (min … max) | RTL in the loop: s, median (min … max) | ratio | RTL cycles a pixel |")
print("|---|---:|---:|---:|---:|")
for mode in ["exact", "forward-difference", "rsqrt0", "rsqrt1", "rsqrt2"]:
    times = {"kernel": [], "rtl": []}
    cycles = 0
    for _ in range(5):
        for impl in times:
            t, c = run(mode, impl)
            times[impl].append(t)
            cycles = c or cycles
    k, r = times["kernel"], times["rtl"]
    cell = lambda v: f"{statistics.median(v):.3f} ({min(v):.3f} … {max(v):.3f})"
    print(f"| {mode} | {cell(k)} | {cell(r)} | {statistics.median(r) / statistics.median(k):.1f} | {cycles:.2f} |")
PY
if ((doc)); then
  python3 "$root/scripts/doc-tables.py" "$out/rtl-bench.txt" "$root/docs/rtl.md" rtl-bench 1
  echo "docs/rtl.md updated"
fi
