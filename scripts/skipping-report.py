#!/usr/bin/env python3
"""What the pipeline skips under overdraw (docs/pipeline.md, "What the pipeline skips"):
quads of one size stacked along the view axis, drawn front to back and back to front,
at 256×256: shaded and hidden pixels, the lighting block's operations, frame cycles.

Usage: scripts/skipping-report.py SHADETLM ROOT [--doc]   (--doc: the table into
docs/pipeline.md, between its markers)"""
import json
import os
import shutil
import subprocess
import sys
import tempfile


def fail(message):
    """A bad argument: one line, exit 2, before anything is made."""
    print("skipping-report: " + message, file=sys.stderr)
    sys.exit(2)


if not 3 <= len(sys.argv) <= 4 or sys.argv[3:] not in ([], ["--doc"]):
    fail("usage: scripts/skipping-report.py SHADETLM ROOT [--doc]")
BIN, ROOT = sys.argv[1], sys.argv[2]
if not (os.path.isfile(BIN) and os.access(BIN, os.X_OK)):
    fail("%s: no such program (the shadetlm binary, e.g. build/app/shadetlm)" % BIN)
if not os.path.isdir(os.path.join(ROOT, "scenes")):
    fail("%s: not the checkout (it has no scenes/)" % ROOT)
TMP = tempfile.mkdtemp(prefix="skipping-")


def stacked_quads(layers, front_to_back):
    objects = [{"shape": "plane", "size": [2, 2],
                "transform": {"translate": [0, 0, -0.1 * (k if front_to_back else layers - 1 - k)]}} for k in range(layers)]
    return {"format": 1, "camera": {"position": [0, 0, 3], "target": [0, 0, 0], "resolution": [256, 256],
                                    "local_viewer": False},
            "lights": [{"type": "directional", "direction": [0, 0, -1]}], "objects": objects}


def run(layers, front_to_back):
    scene, stats = os.path.join(TMP, "s.json"), os.path.join(TMP, "s.stats.json")
    with open(scene, "w") as f:
        json.dump(stacked_quads(layers, front_to_back), f)
    subprocess.run([BIN, "render", scene, "-o", os.path.join(TMP, "f.exr"), "--stats", stats], check=True,
                   stdout=subprocess.DEVNULL)
    s = json.load(open(stats))
    return s["pixels"]["shaded"], s["pixels"]["hidden"], sum(s["blocks"]["lighting"]["ops"].values()), s["frame_cycles"]


lines = ["| stacked quads | front to back: shaded | hidden | lighting ops | frame cycles | back to front: shaded "
         "| lighting ops | frame cycles |", "|---|---|---|---|---|---|---|---|"]
for layers in [1, 4, 16]:
    front, back = run(layers, True), run(layers, False)
    lines.append("| %d | %d | %d | %d | %d | %d | %d | %d |" % ((layers,) + front + (back[0], back[2], back[3])))
shutil.rmtree(TMP, ignore_errors=True)
print("\n".join(lines))
if "--doc" in sys.argv[3:]:
    report = tempfile.NamedTemporaryFile("w", suffix=".txt", delete=False)
    report.write("\n".join(lines) + "\n")
    report.close()
    subprocess.run([sys.executable, os.path.join(ROOT, "scripts/doc-tables.py"), report.name,
                    os.path.join(ROOT, "docs/pipeline.md"), "skipping", "1"], check=True)
    os.remove(report.name)
