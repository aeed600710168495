#!/usr/bin/env python3
"""The figures docs/benchmarks.md's prose draws on, from a sweep's CSV (scripts/sweep.sh),
as Markdown tables: what spans how much per scene, each normalize mode's cycles and
operations, each filter's bytes against trilinear, object-space against screen-space
texturing, and each parallax tracer at its least error. scripts/plot.sh --doc prints them
into the page between its `findings` markers, so no figure there is typed by hand.

Usage: scripts/sweep-findings.py SWEEP_CSV
Exit 2, one line on stderr: a CSV that cannot be read or is not a sweep's."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot  # noqa: E402  (the sweep's reader, labels and Pareto fronts)

plot.PROGRAM = "sweep-findings"


def ms(r):
    return 1000 * r["wall_s"]


def span(values, fmt):
    lo, hi = min(values), max(values)
    return fmt % lo if lo == hi else (fmt + "–" + fmt) % (lo, hi)


def setting(r, key):
    """A configuration's value of setting `key` (its name, or the name's last parts:
    "normalize.mode", "filter"), or None."""
    for kv in r["configuration"].split(";"):
        name, value = kv.split("=", 1)
        if name == key or name.endswith("." + key):
            return value
    return None


def by_scene(rows, family):
    runs = [r for r in rows if r["family"] == family]
    return [(plot.short(s), [r for r in runs if r["scene"] == s]) for s in sorted(set(r["scene"] for r in runs))]


def spans(rows):
    out = ["| family | scene | runs | wall time (ms), medians | cycles | operations | bytes read | RMSE |",
           "|---|---|---|---|---|---|---|---|"]
    for family in sorted(set(r["family"] for r in rows)):
        for scene, runs in by_scene(rows, family):
            out.append("| %s | %s | %d | %s | %s | %s | %s | %s |" % (
                family, scene, len(runs), span([ms(r) for r in runs], "%.1f"),
                span([r["frame_cycles"] for r in runs], "%d"), span([r["ops"] for r in runs], "%d"),
                span([r["bytes"] for r in runs], "%d"), span([r["err_rmse"] for r in runs], "%.1e")))
    return "\n".join(out)


def normalize_modes(rows):
    """Per scene and mode (perspective interpolation): cycles, operations against
    forward difference's, RMSE."""
    out = ["| scene | normalize mode | cycles | operations against forward-difference | RMSE |",
           "|---|---|---|---|---|"]
    for scene, runs in by_scene(rows, "normal"):
        runs = [r for r in runs if setting(r, "normal_interp.mode") == "perspective"]
        base = [r["ops"] for r in runs if setting(r, "normalize.mode") == "forward-difference"]
        for r in sorted(runs, key=lambda r: r["frame_cycles"]):
            ratio = "%+.0f %%" % (100 * (r["ops"] / base[0] - 1)) if base else "–"
            out.append("| %s | %s | %d | %s | %.1e |" % (scene, setting(r, "normalize.mode"), r["frame_cycles"], ratio,
                                                          r["err_rmse"]))
    return "\n".join(out)


def filters(rows):
    """Bump scenes: per filter, the bytes read (the least over the paths) against
    trilinear's, the cycles and the least RMSE."""
    out = ["| scene | filter | bytes read (least over the paths) | against trilinear | cycles | least RMSE |",
           "|---|---|---|---|---|---|"]
    for scene, runs in by_scene(rows, "bump"):
        per = {}
        for r in runs:
            per.setdefault(setting(r, "filter"), []).append(r)
        tri = min(r["bytes"] for r in per.get("trilinear", runs))
        for f, rs in sorted(per.items(), key=lambda kv: min(r["bytes"] for r in kv[1])):
            b = min(r["bytes"] for r in rs)
            out.append("| %s | %s | %d | %+.0f %% | %s | %.1e |" % (
                scene, f, b, 100 * (b / tri - 1), span([r["frame_cycles"] for r in rs], "%d"),
                min(r["err_rmse"] for r in rs)))
    return "\n".join(out)


def texturing(rows):
    out = ["| scene | configuration | bytes read | cycles | operations | wall time (ms) | RMSE |",
           "|---|---|---|---|---|---|---|"]
    for scene, runs in by_scene(rows, "texture"):
        for r in sorted(runs, key=lambda r: r["bytes"]):
            out.append("| %s | %s | %d | %d | %d | %.1f | %.1e |" % (
                scene, r["label"], r["bytes"], r["frame_cycles"], r["ops"], ms(r), r["err_rmse"]))
    return "\n".join(out)


def tracers(rows):
    """Per parallax tracer: its least error and the cheapest run (fewest cycles) that has it."""
    out = ["| scene | tracer | least RMSE | its cheapest run | cycles | wall time (ms) |",
           "|---|---|---|---|---|---|"]
    for scene, runs in by_scene(rows, "parallax"):
        per = {}
        for r in runs:
            per.setdefault(r["label"].rsplit(" ", 1)[0] if r["label"] != "offset" else "offset", []).append(r)
        best = []
        for tracer, rs in per.items():
            least = min(r["err_rmse"] for r in rs)
            best.append(min((r for r in rs if r["err_rmse"] == least), key=lambda r: r["frame_cycles"]))
        for r in sorted(best, key=lambda r: (r["err_rmse"], r["frame_cycles"])):
            tracer = r["label"].rsplit(" ", 1)[0] if r["label"] != "offset" else "offset"
            out.append("| %s | %s | %.2e | %s | %d | %.1f |" % (scene, tracer, r["err_rmse"], r["label"],
                                                                 r["frame_cycles"], ms(r)))
    return "\n".join(out)


def main():
    if len(sys.argv) != 2:
        plot.fail("usage: scripts/sweep-findings.py SWEEP_CSV")
    rows = plot.load(sys.argv[1])
    for title, table in [("What each scene's runs span", spans(rows)),
                         ("The normal family: each normalize mode (perspective interpolation)", normalize_modes(rows)),
                         ("The bump family: each filter", filters(rows)),
                         ("The texture family: each configuration", texturing(rows)),
                         ("The parallax family: each tracer at its least error", tracers(rows))]:
        print("%s:\n\n%s\n" % (title, table))


if __name__ == "__main__":
    main()
