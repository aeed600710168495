#!/usr/bin/env python3
"""Number formats per block on the stress scenes (docs/numerical-stability.md).

For each block with a format of its own (pipeline.<block>.format), the others staying
float32, on every stress scene where the block does work — normalize three times: the
radicand direct (exact mode), and by forward differences seeded per packet and per
raster line:
  * float16: the largest colour difference from the float32 frame, and the non-finite
    values, overflows and invalid operations the block met;
  * fixed point, per scene: I, the fewest integer bits with no saturation (at
    F = min(40, 52 − I)), then F, the fewest fraction bits at that I that keep every
    covered pixel's colour within 1/255 (and 2^-12) of the float32 frame, by bisection;
    per block, the widest I and F over the scenes some width up to 52 bits serves,
    checked on them together, and the scenes none serves.
The difference is taken from the pipeline's own float32 frame, so that it measures the
format alone (each method's error against the golden model is in the other reports).

With --bump, the bump-mapping paper's two datapaths instead (claim 2's precision, seed
000): on scenes/bump/*.json, each block of the classic path (bump-classic: bump_fetch's
Fu, Fv, bump_perturb, normalize, lighting) and of the proposed one (bump-tangent:
bump_fetch's N', vector_interp's L and H in tangent space, normalize, lighting) under a
point light and a local viewer, so that L and H are interpolated.

Usage: scripts/format-report.py SHADETLM ROOT [--bump]"""
import concurrent.futures
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile


def fail(message):
    """A bad argument: one line, exit 2, before anything is made."""
    print("format-report: " + message, file=sys.stderr)
    sys.exit(2)


if not 3 <= len(sys.argv) <= 4 or sys.argv[3:] not in ([], ["--bump"]):
    fail("usage: scripts/format-report.py SHADETLM ROOT [--bump]")
BIN, ROOT = sys.argv[1], sys.argv[2]
if not (os.path.isfile(BIN) and os.access(BIN, os.X_OK)):
    fail("%s: no such program (the shadetlm binary, e.g. build/app/shadetlm)" % BIN)
if not os.path.isdir(os.path.join(ROOT, "scenes")):
    fail("%s: not the checkout (it has no scenes/)" % ROOT)
BUMP = "--bump" in sys.argv[3:]
TMP = tempfile.mkdtemp(prefix="formats-")
# (label, block, the settings it runs under, in its float32 baseline too)
FD = "pipeline.normalize.mode=forward-difference"
VARIANTS = [("normal_interp", "normal_interp", []), ("normalize", "normalize", []),
            ("normalize, forward-difference per packet", "normalize", [FD]),
            ("normalize, forward-difference per line", "normalize", [FD, "pipeline.normalize.seed=line"]),
            ("vector_interp", "vector_interp", []), ("lighting", "lighting", []),
            ("texel_project", "texel_project", []), ("parallax", "parallax", []),
            ("bump_fetch", "bump_fetch", []), ("bump_perturb", "bump_perturb", [])]
if BUMP:
    LOCAL = ["camera.local_viewer=true", 'lights=[{"type":"point","position":[2,2,3]}]']
    PATHS = [("classic", "bump-classic", ["bump_fetch", "bump_perturb", "normalize", "lighting"]),
             ("proposed", "bump-tangent", ["bump_fetch", "vector_interp", "normalize", "lighting"])]
    VARIANTS = [("%s, %s" % (block, name), block, ["materials.bumpy.path=" + path] + LOCAL)
                for name, path, blocks in PATHS for block in blocks]
BLOCK = {label: block for label, block, _ in VARIANTS}
SETS = {label: sets for label, _, sets in VARIANTS}
BOUNDS = [("1/255", 1 / 255), ("2^-12", 2 ** -12)]
SCENES = sorted(glob.glob(os.path.join(ROOT, "scenes/bump/*.json" if "--bump" in sys.argv[3:] else "scenes/stress/*.json")))
JOBS = max(1, os.cpu_count() or 1)
renders = 0


def render(scene, sets, tag):
    """Renders `scene` with `sets`; returns (frame path, stats)."""
    global renders
    renders += 1
    out = os.path.join(TMP, tag + ".exr")
    stats = os.path.join(TMP, tag + ".json")
    args = [BIN, "render", scene, "-o", out, "--stats", stats, "--allow-nonfinite", "--allow-overflow"]  # counted in the stats
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    with open(stats) as f:
        return out, json.load(f)


def difference(frame, base):
    r = subprocess.run([BIN, "compare", frame, base, "--layer", "RGB", "--json"], stdout=subprocess.PIPE, text=True)
    return float(json.loads(r.stdout)["layers"]["RGB"]["max"])


def name(scene):
    return os.path.splitext(os.path.basename(scene))[0]


# The float32 frames (one per set of settings), and where each block works.
base, works = {}, {label: [] for label, _, _ in VARIANTS}
for scene in SCENES:
    for label, b, sets in VARIANTS:
        key = (scene, tuple(sets))
        if key not in base:
            base[key] = render(scene, sets, "%s-float32-%d" % (name(scene), len(base)))
        frame, stats = base[key]
        s = stats["blocks"].get(b)
        if not s:
            continue
        worked = s["details"].get("texels", 0) > 0 if b == "texel_project" else s["pixels"] > 0
        if worked:
            works[label].append(scene)


def run(label, fmt, scene):
    block = BLOCK[label]
    tag = "%s-%s-%s" % (name(scene), label.replace(" ", "_").replace(",", ""), fmt.replace(":", "_"))
    frame, stats = render(scene, SETS[label] + ["pipeline.%s.format=%s" % (block, fmt)], tag)
    numbers = stats["blocks"][block]["numbers"]
    d = difference(frame, base[(scene, tuple(SETS[label]))][0])
    os.remove(frame)
    return d, numbers


def over_scenes(block, fmt, scenes=None):
    """(largest difference, scene of it, summed numbers) over `scenes` (default: the
    block's scenes)."""
    with concurrent.futures.ThreadPoolExecutor(JOBS) as pool:
        results = list(pool.map(lambda s: (s, run(block, fmt, s)), scenes or works[block]))
    worst = max(results, key=lambda r: r[1][0])
    total = {k: sum(r[1][1][k] for r in results) for k in ("nonfinite", "overflows", "invalid")}
    return worst[1][0], name(worst[0]), total


def fixed(i, f):
    return "fixed:%d.%d" % (i, f)


def widest_f(i):
    return min(40, 52 - i)


def requirement(block, scene):
    """For one scene: the integer bits without saturation (None past 30) and, at those,
    the fewest fraction bits for each bound (None if not even the widest does)."""
    memo = {}

    def at(i, f):
        if (i, f) not in memo:
            d, n = run(block, fixed(i, f), scene)
            memo[(i, f)] = (d, n["overflows"])
        return memo[(i, f)]

    if at(30, widest_f(30))[1] > 0:
        return None, {label: None for label, _ in BOUNDS}
    lo, hi = 0, 30
    while lo < hi:
        mid = (lo + hi) // 2
        if at(mid, widest_f(mid))[1] == 0:
            hi = mid
        else:
            lo = mid + 1
    i = lo
    fraction = {}
    for label, bound in BOUNDS:
        if at(i, widest_f(i))[0] > bound:
            fraction[label] = None
            continue
        lo, hi = 1, widest_f(i)
        while lo < hi:
            mid = (lo + hi) // 2
            if at(i, mid)[0] <= bound:
                hi = mid
            else:
                lo = mid + 1
        fraction[label] = lo
    return i, fraction


rows, matrix = [], {}
for block, _, _ in VARIANTS:
    if not works[block]:
        continue
    half = over_scenes(block, "float16")
    with concurrent.futures.ThreadPoolExecutor(JOBS) as pool:
        needs = dict(zip(works[block], pool.map(lambda sc: requirement(block, sc), works[block])))
    matrix[block] = needs
    combined = {}
    for label, bound in BOUNDS:
        # The scenes some width serves; the combined format is the widest of their needs.
        served = [sc for sc, (i, f) in needs.items() if i is not None and f[label] is not None]
        unserved = [name(sc) for sc in works[block] if sc not in served]
        if not served:
            combined[label] = (None, None, unserved)
            continue
        i = max(needs[sc][0] for sc in served)
        f = max(needs[sc][1][label] for sc in served)
        i_scene = name(max(served, key=lambda sc: needs[sc][0]))
        f_scene = name(max(served, key=lambda sc: needs[sc][1][label]))
        # Checked on those scenes together (saturation may appear where another scene set I).
        worst = over_scenes(block, fixed(i, f), served)[0]
        combined[label] = ((i, f, i_scene, f_scene, worst <= bound), worst, unserved)
    rows.append((block, half, combined))
    print("... %s done (%d renders so far)" % (block, renders), file=sys.stderr)

print("### Per block, on every %s scene it works on\n" % ("bump" if BUMP else "stress"))
print("The fewest bits 1 + I + F of `fixed:I.F` for the block alone (the others float32) that keep "
      "every covered pixel's colour within the bound of the float32 frame, on every scene a width "
      "of at most 52 bits can serve; the scenes none can are listed. I: no saturation on any of "
      "them (the scene that needs the most named); F: the most any of them needs.\n")
print("| block | float16: largest colour difference (scene) | float16: non-finite / overflows / invalid "
      "| within 1/255 | within 2^-12 | scenes no width serves (1/255; 2^-12) |")
print("|---|---|---|---|---|---|")
for block, half, combined in rows:
    def cell(c):
        if c[0] is None:
            return "none"
        i, f, i_scene, f_scene, ok = c[0]
        return "%d: `%s` (I: %s, F: %s)%s" % (1 + i + f, fixed(i, f), i_scene, f_scene, "" if ok else " — fails together")
    n = half[2]
    unserved = "; ".join(", ".join(combined[label][2]) or "—" for label, _ in BOUNDS)
    print("| %s | %.1e (%s) | %d / %d / %d | %s | %s | %s |" % (
        block, half[0], half[1], n["nonfinite"], n["overflows"], n["invalid"], cell(combined["1/255"]),
        cell(combined["2^-12"]), unserved))
print("\n### Per block and scene: fewest bits for 1/255 (and for 2^-12)\n")
print("`I.F` as in `fixed:I.F`; × where no width up to 52 bits serves; — where the block does no work.\n")
print("| scene | " + " | ".join(matrix) + " |")
print("|---|" + "---|" * len(matrix))
for scene in SCENES:
    cells = []
    for block, needs in matrix.items():
        if scene not in needs:
            cells.append("—")
            continue
        i, f = needs[scene]
        def one(label):
            return "×" if i is None or f[label] is None else "%d.%d" % (i, f[label])
        cells.append("%s (%s)" % (one("1/255"), one("2^-12")))
    print("| %s | %s |" % (name(scene), " | ".join(cells)))
print("\n%d renders, %d %s scenes." % (renders, len(SCENES), "bump" if BUMP else "stress"))
shutil.rmtree(TMP, ignore_errors=True)
