#!/usr/bin/env python3
"""The sweep and the golden regression as Slurm job arrays (docs/benchmarks.md, "On a
cluster").

  scripts/slurm.py submit sweep RESULTS [--match RE] [--resolution W,H] [--map-cache DIR]
                                        [--repeats R] [common options]
  scripts/slurm.py submit regress RESULTS [--scene NAME ...] [common options]
      common options: [--shards N] [--max-parallel K] [--wait] [-- SBATCH_ARGS ...]
  scripts/slurm.py status RESULTS
  scripts/slurm.py resubmit RESULTS [--wait] [-- SBATCH_ARGS ...]
  scripts/slurm.py merge RESULTS          (the merge job runs it; by hand once all shards are in)

submit checks that Slurm answers and that RESULTS (a new folder) can be written and is on
a filesystem the nodes share, copies the program into RESULTS/bin (a rebuild meanwhile
changes nothing), writes RESULTS/manifest.json, and submits an array of shards (each runs
scripts/sweep.py or scripts/regress.py --shard I/N, writing its results whole or not at
all into RESULTS/shards) and a merge job that starts once every shard succeeded: it writes
RESULTS/sweep.csv (and RESULTS/plots when gnuplot is there) or the regression report,
RESULTS/index.html, as a local run would. Unless --shards says, the shards are as many as
4 per CPU of the partition (so that uneven shards even out), at most one per run and at
most the cluster's MaxArraySize. resubmit runs again the shards whose results are missing
(failed, cancelled, timed out) and the merge. --wait stays until the merge job ended and
exits with its status. Exit 2, with one line on stderr: a bad option, no Slurm, no
controller, a results folder that cannot be used, a manifest that is not what submit
wrote, or (merge) shards missing; nothing is half-merged.
The program is SHADETLM if set, else build/app/shadetlm; the checkout (scripts, scenes)
must be on the shared filesystem too."""
import argparse
import json
import math
import os
import shlex
import shutil
import subprocess
import sys
import time

import shards

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# As `stat -f -c %T` names them. FUSE mounts show as "fuse" or "fuseblk", local or not:
# SHADETLM_SHARED=1 vouches for one.
SHARED_FILESYSTEMS = {"nfs", "nfs4", "lustre", "gpfs", "beegfs", "ceph", "cifs", "smb2", "smb3", "9p", "panfs",
                      "wekafs", "glusterfs", "afs", "gfs2", "ocfs2"}
SHARDS_PER_CPU = 4


def die(message):
    print("slurm: " + message, file=sys.stderr)
    sys.exit(2)


def last_line(text):
    """A tool's message in one line: its last (Slurm's tools end with the fatal one)."""
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    return lines[-1] if lines else "no message"


class Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit 2 (no usage block)
        die(message)


def slurm(*args, timeout=60):
    """A Slurm command's output; exits 2 with its message when it fails."""
    try:
        r = subprocess.run(list(args), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        die("%s took over %d s: is the Slurm controller reachable?" % (" ".join(args), timeout))
    if r.returncode != 0:
        die("%s failed (exit %d): %s" % (" ".join(args), r.returncode, last_line(r.stderr or r.stdout)))
    return r.stdout


def check_slurm():
    """Slurm's commands are here and its controller answers."""
    for tool in ["sbatch", "squeue", "sinfo", "scontrol"]:
        if not shutil.which(tool):
            die("no Slurm on this machine: %s is not on the PATH (a login node of the cluster has it; "
                "scripts/slurm-local.sh starts a single-node Slurm for tests)" % tool)
    try:
        r = subprocess.run(["scontrol", "ping"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
    except subprocess.TimeoutExpired:
        die("the Slurm controller does not answer (scontrol ping took over 120 s); SLURM_CONF=%s" %
            os.environ.get("SLURM_CONF", "(default)"))
    if r.returncode != 0 or "is UP" not in r.stdout:
        die("the Slurm controller does not answer (scontrol ping: %s); SLURM_CONF=%s" % (
            " ".join(w for w in r.stdout.split() if w.strip("*")) or "exit %d" % r.returncode, os.environ.get("SLURM_CONF", "(default)")))


def filesystem(path):
    return subprocess.run(["stat", "-f", "-c", "%T", path], stdout=subprocess.PIPE, text=True).stdout.strip()


def check_folder(path, what, nodes):
    """`path` (an existing folder) takes files, and the nodes can see it."""
    probe = os.path.join(path, ".slurm-probe")
    try:
        shards.write_atomically(probe, "probe\n")
        os.remove(probe)
    except OSError as e:
        die("%s %s cannot be written: %s" % (what, path, e.strerror or e))
    fs = filesystem(path)
    if nodes > 1 and fs not in SHARED_FILESYSTEMS and os.environ.get("SHADETLM_SHARED") != "1":
        die("%s %s is on a %s filesystem, local to this machine, and the partition has %d nodes: give a folder "
            "on a filesystem they share (NFS, Lustre, GPFS, BeeGFS, CephFS …), or set SHADETLM_SHARED=1 if it "
            "is shared in a way this check does not know" % (what, path, fs or "local", nodes))


def cluster(partition):
    """(nodes, CPUs) of the partition: the one named, else the default one (sinfo marks
    it with a '*'), where the jobs go."""
    nodes = cpus = 0
    found = False
    for line in slurm("sinfo", "-h", "-o", "%P %D %C").splitlines():
        name, count, load = line.split()
        if name.rstrip("*") == partition or (partition is None and name.endswith("*")):
            found = True
            nodes += int(count)
            cpus += int(load.split("/")[3])  # allocated/idle/other/total
    if not found or nodes == 0:
        die("the partition %s has no nodes (sinfo)" % (partition or "(the default one)"))
    return nodes, cpus


def max_array_size():
    for line in slurm("scontrol", "show", "config").splitlines():
        if line.split("=")[0].strip() == "MaxArraySize":
            return int(line.split("=")[1])
    return 1001  # Slurm's default


def choose_shards(work, cpus, limit):
    """SHARDS_PER_CPU shards per CPU, so that one long shard does not leave the others idle
    at the end; never more shards than runs, nor than an array may hold."""
    return max(1, min(work, SHARDS_PER_CPU * cpus, limit))


def program():
    path = os.environ.get("SHADETLM") or os.path.join(ROOT, "build", "app", "shadetlm")
    if not os.access(path, os.X_OK):
        die("%s: no program to run; build it (scripts/build.sh) or set SHADETLM" % path)
    return os.path.abspath(path)


def script(kind):
    return os.path.join(ROOT, "scripts", "sweep.py" if kind == "sweep" else "regress.py")


def count_work(kind, binary, results, args):
    cmd = ["python3", script(kind), binary, ROOT] + (["--list"] if kind == "sweep" else [results, "--list"]) + args
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        die("counting the runs failed: " + last_line(r.stderr))
    return int(r.stdout)


def write_manifest(results, m):
    shards.write_atomically(os.path.join(results, "manifest.json"), json.dumps(m, indent=1) + "\n")


def write_job_scripts(results, m):
    """RESULTS/shard.sh (one array task) and RESULTS/merge.sh."""
    q = shlex.quote
    check = ('[ -r %s ] || { printf "slurm: %%s is not visible on %%s: the results folder must be on a '
             'filesystem every node shares\\n" %s "$(hostname)" >&2; exit 2; }\n'
             % (q(os.path.join(results, "manifest.json")), q(results)))
    if m["kind"] == "sweep":
        shard = "exec python3 %s %s %s --shard \"$SLURM_ARRAY_TASK_ID/%d\" --results %s %s\n" % (
            q(script("sweep")), q(m["program"]), q(ROOT), m["shards"], q(results), " ".join(map(q, m["args"])))
    else:
        shard = "exec python3 %s %s %s %s --shard \"$SLURM_ARRAY_TASK_ID/%d\" %s\n" % (
            q(script("regress")), q(m["program"]), q(ROOT), q(results), m["shards"], " ".join(map(q, m["args"])))
    merge = "exec python3 %s merge %s\n" % (q(os.path.abspath(__file__)), q(results))
    for name, body in [("shard.sh", shard), ("merge.sh", merge)]:
        path = os.path.join(results, name)
        shards.write_atomically(path, "#!/bin/sh\n# written by scripts/slurm.py\nset -e\n" + check + body)
        os.chmod(path, 0o755)


def array_spec(indices):
    """[0, 1, 2, 5, 7, 8] as '0-2,5,7-8'."""
    parts, start = [], None
    for k, i in enumerate(indices):
        if start is None:
            start = i
        if k + 1 == len(indices) or indices[k + 1] != i + 1:
            parts.append(str(start) if start == i else "%d-%d" % (start, i))
            start = None
    return ",".join(parts)


def submit_jobs(results, m, indices, sbatch_args):
    """The array of the given shards (none: the merge alone) and the merge after it; their
    ids into the manifest."""
    logs = os.path.join(results, "logs")
    os.makedirs(logs, exist_ok=True)
    name = "shadetlm-" + m["kind"]
    array, after = None, []
    if indices:
        spec = array_spec(indices) + ("%%%d" % m["max_parallel"] if m.get("max_parallel") else "")
        array = slurm("sbatch", "--parsable", "--array=" + spec, "--job-name=" + name, "--cpus-per-task=1",
                      "--output=" + os.path.join(logs, "shard-%a.%A.out"), *sbatch_args,
                      os.path.join(results, "shard.sh")).strip().split(";")[0]
        after = ["--dependency=afterok:" + array, "--kill-on-invalid-dep=yes"]
    merge = slurm("sbatch", "--parsable", *after, "--job-name=" + name + "-merge", "--cpus-per-task=1",
                  "--output=" + os.path.join(logs, "merge.%j.out"), *sbatch_args,
                  os.path.join(results, "merge.sh")).strip().split(";")[0]
    m["jobs"].append({"array": array, "shards": indices, "merge": merge, "submitted": time.time()})
    write_manifest(results, m)
    if indices:
        print("submitted %d shard%s as job %s (array %s), the merge as job %s; results: %s" % (
            len(indices), "" if len(indices) == 1 else "s", array, array_spec(indices), merge, results))
    else:
        print("every shard is in: submitted the merge as job %s; results: %s" % (merge, results))


def queued(job_ids):
    """(id, state) of those of the jobs still in the queue. A job Slurm has forgotten
    (finished longer ago than MinJobAge) is no longer queued: squeue calls its id invalid."""
    if not job_ids:
        return []
    try:
        r = subprocess.run(["squeue", "-h", "-o", "%i %T", "-j", ",".join(job_ids)], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True, timeout=60)
    except subprocess.TimeoutExpired:
        die("squeue took over 60 s: is the Slurm controller reachable?")
    if r.returncode != 0 and "Invalid job id" not in r.stderr:
        die("squeue failed (exit %d): %s" % (r.returncode, last_line(r.stderr)))
    return [line.split() for line in r.stdout.splitlines() if line.strip()]


def wait(results, m):
    """Until the last submission's jobs left the queue; exits with the merge's status."""
    last = m["jobs"][-1]
    while queued([j for j in (last["array"], last["merge"]) if j]):
        time.sleep(1)
    status = merge_status(results)
    if status is None:
        gone = shards.missing(results, m["kind"], m["shards"], extension(m))
        why = ("%d shard%s failed or were cancelled (%s)" % (len(gone), "" if len(gone) == 1 else "s", array_spec(gone))
               if gone else "the merge job failed")
        print("slurm: no merged results: %s; logs in %s; scripts/slurm.py resubmit %s" % (
            why, os.path.join(results, "logs"), results), file=sys.stderr)
        sys.exit(1)
    sys.exit(status)


def extension(m):
    return "csv" if m["kind"] == "sweep" else "json"


def submission(results):
    """The manifest of a folder scripts/slurm.py submitted; exits 2 for another's, or for
    one whose fields are not of the types submit writes."""
    m = shards.manifest(results)
    if not all(k in m for k in ("program", "jobs", "args", "runs", "repeats")):
        die("%s was not submitted by scripts/slurm.py (scripts/sweep.sh writes its own shards): "
            "nothing to do here" % results)

    def count(x, least):
        return type(x) is int and x >= least

    def job_id(x):
        return x is None or isinstance(x, str) and x != ""

    checks = [("program", isinstance(m["program"], str)), ("runs", count(m["runs"], 1)), ("repeats", count(m["repeats"], 0)),
              ("max_parallel", m.get("max_parallel") is None or count(m["max_parallel"], 1)),
              ("sbatch", isinstance(m.get("sbatch", []), list) and all(isinstance(x, str) for x in m.get("sbatch", []))),
              ("jobs", isinstance(m["jobs"], list) and all(
                  isinstance(j, dict) and job_id(j.get("array")) and job_id(j.get("merge")) and j.get("merge") for j in m["jobs"]))]
    bad = [name for name, ok in checks if not ok]
    if bad:
        die("%s: the manifest's %s %s not what scripts/slurm.py submit writes" % (
            os.path.join(results, "manifest.json"), ", ".join(bad), "is" if len(bad) == 1 else "are"))
    return m


def merge_status(results):
    try:
        with open(os.path.join(results, "merge.status")) as f:
            return int(f.read())
    except (OSError, ValueError):
        return None


def submit(a, sbatch_args):
    check_slurm()
    results = os.path.abspath(a.results)
    if os.path.exists(os.path.join(results, "manifest.json")):
        die("%s already holds a submission: scripts/slurm.py status or resubmit it, or give a new folder" % results)
    try:
        os.makedirs(results, exist_ok=True)
    except OSError as e:
        die("the results folder %s cannot be made: %s" % (results, e.strerror or e))
    if not os.path.isdir(results):
        die("the results folder %s is not a folder" % results)
    nodes, cpus = cluster(a.partition)
    check_folder(results, "the results folder", nodes)
    check_folder(ROOT, "the checkout", nodes)
    args = []
    if a.kind == "sweep":
        for flag, value in [("--match", a.match), ("--resolution", a.resolution)]:
            if value is not None:
                args += [flag, value]
        cache = os.path.abspath(a.map_cache or os.environ.get("SHADETLM_MAP_CACHE") or os.path.join(ROOT, "out", "map-cache"))
        try:
            os.makedirs(cache, exist_ok=True)
        except OSError as e:
            die("the map cache %s cannot be made: %s" % (cache, e.strerror or e))
        check_folder(cache, "the map cache", nodes)
        args += ["--map-cache", cache]
    else:
        for s in a.scene:
            args += ["--scene", s]
    binary = program()
    work = count_work(a.kind, binary, results, args)
    if work == 0:
        die("no run matches %s" % " ".join(args))
    limit = max_array_size()
    count = a.shards or choose_shards(work, cpus, limit)
    if count > work or count > limit:
        die("--shards %d: more shards than the %d runs or than MaxArraySize (%d)" % (count, work, limit))
    os.makedirs(os.path.join(results, "bin"), exist_ok=True)
    copy = os.path.join(results, "bin", "shadetlm")
    shutil.copy2(binary, copy)
    m = {"kind": a.kind, "shards": count, "runs": work, "args": args, "program": copy, "root": ROOT,
         "repeats": a.repeats, "max_parallel": a.max_parallel, "sbatch": sbatch_args, "jobs": []}
    write_manifest(results, m)
    write_job_scripts(results, m)
    print("%d runs in %d shards of %d or %d (%s; %d CPUs on %d node%s)" % (
        work, count, work // count, math.ceil(work / count), "as asked" if a.shards else
        "%d per CPU, at most one per run" % SHARDS_PER_CPU, cpus, nodes, "" if nodes == 1 else "s"))
    submit_jobs(results, m, list(range(count)), sbatch_args)
    if a.wait:
        wait(results, m)


def status(a):
    results = os.path.abspath(a.results)
    m = submission(results)
    gone = shards.missing(results, m["kind"], m["shards"], extension(m))
    print("%s: %s, %d runs in %d shards: %d done, %d missing%s" % (
        results, m["kind"], m["runs"], m["shards"], m["shards"] - len(gone), len(gone),
        " (%s)" % array_spec(gone) if gone else ""))
    s = merge_status(results)
    print("merge: " + ("not run" if s is None else "done (exit %d)" % s))
    if shutil.which("squeue") and m["jobs"]:
        last = m["jobs"][-1]
        jobs = queued([j for j in (last["array"], last["merge"]) if j])
        print("queue: " + (", ".join("%s %s" % tuple(j) for j in jobs) if jobs else "none of its jobs"))


def resubmit(a, sbatch_args):
    check_slurm()
    results = os.path.abspath(a.results)
    m = submission(results)
    last = m["jobs"][-1] if m["jobs"] else None
    running = queued([j for j in (last["array"], last["merge"]) if j]) if last else []
    if running:
        die("jobs %s of %s are still queued or running: wait for them, or scancel them first" % (
            ", ".join(j[0] for j in running), results))
    gone = shards.missing(results, m["kind"], m["shards"], extension(m))
    if not gone and merge_status(results) is not None:
        print("%s: every shard is in and the merge ran (exit %d): nothing to do" % (results, merge_status(results)))
        return
    try:  # a status from before shards went missing would pass for this merge's
        os.remove(os.path.join(results, "merge.status"))
    except FileNotFoundError:
        pass
    # The partition of the submission stays; other sbatch arguments may be given anew.
    partition = [x for x in m.get("sbatch", []) if x.startswith("--partition=")]
    submit_jobs(results, m, gone, partition + sbatch_args if sbatch_args else m.get("sbatch", []))
    if a.wait:
        wait(results, m)


def merge(a):
    """The merge: the sweep's CSV (and plots), or the regression's report; its status into
    RESULTS/merge.status (0 done; regress: 1 when a configuration fails). Without a status
    (shards missing, a failure) resubmit runs the merge again."""
    results = os.path.abspath(a.results)
    m = submission(results)
    shards.collect(results, m["kind"], extension(m))  # exits 2 when one is missing
    if m["kind"] == "sweep":
        cmd = ["python3", script("sweep"), m["program"], ROOT, "--merge", results, "--repeats", str(m["repeats"])]
    else:
        cmd = ["python3", script("regress"), m["program"], ROOT, results, "--merge"]
    rows = os.path.join(results, "rows.json")  # regress: written only by a merge that ran to its end
    if os.path.exists(rows):
        os.remove(rows)
    rc = subprocess.run(cmd + m["args"]).returncode
    if rc == 0 and m["kind"] == "sweep":
        plots = os.path.join(results, "plots")
        if not shutil.which("gnuplot"):
            print("no gnuplot on this node: scripts/plot.py %s %s draws the plots" % (
                os.path.join(results, "sweep.csv"), plots))
        elif subprocess.run(["python3", os.path.join(ROOT, "scripts", "plot.py"), os.path.join(results, "sweep.csv"),
                             plots], stdout=subprocess.DEVNULL).returncode != 0:
            print("slurm: the plots failed (the CSV is merged): scripts/plot.py %s %s" % (
                os.path.join(results, "sweep.csv"), plots), file=sys.stderr)
    if rc == 0 or (rc == 1 and m["kind"] == "regress" and os.path.exists(rows)):  # regress.py's 1: a configuration fails
        shards.write_atomically(os.path.join(results, "merge.status"), "%d\n" % rc)
    return rc


def main():
    argv = sys.argv[1:]
    sbatch_args = argv[argv.index("--") + 1:] if "--" in argv else []
    argv = argv[:argv.index("--")] if "--" in argv else argv
    parser = Parser(description="sweeps and regressions as Slurm job arrays (see the docstring)")
    sub = parser.add_subparsers(dest="command", required=True)
    s = sub.add_parser("submit")
    s.add_argument("kind", choices=["sweep", "regress"])
    s.add_argument("results")
    s.add_argument("--shards", type=int)
    s.add_argument("--max-parallel", type=int, help="at most K shards at once (sbatch --array=…%%K)")
    s.add_argument("--partition")
    s.add_argument("--wait", action="store_true")
    s.add_argument("--match")
    s.add_argument("--resolution")
    s.add_argument("--map-cache")
    s.add_argument("--repeats", type=int, default=0, help="sweep: the merge times every run R times (default 0)")
    s.add_argument("--scene", action="append", default=[])
    for name in ["status", "merge"]:
        sub.add_parser(name).add_argument("results")
    r = sub.add_parser("resubmit")
    r.add_argument("results")
    r.add_argument("--wait", action="store_true")
    a = parser.parse_args(argv)
    if a.command == "submit":
        if a.shards is not None and not 1 <= a.shards <= shards.MAX_SHARDS or \
                a.max_parallel is not None and a.max_parallel < 1 or not 0 <= a.repeats <= 1000:
            die("--shards (1 to %d), --max-parallel (1 or more) and --repeats (0 to 1000) take counts" % shards.MAX_SHARDS)
        if a.kind == "regress" and (a.match or a.resolution or a.map_cache or a.repeats):
            die("--match, --resolution, --map-cache and --repeats are the sweep's; the regression takes --scene")
        if a.kind == "sweep" and a.scene:
            die("--scene is the regression's; the sweep takes --match")
        if any(x == "-p" or x.startswith(("--partition", "-p")) for x in sbatch_args):
            die("give the partition as --partition P (before --): the shard count and the checks follow it")
        if a.partition:
            sbatch_args = ["--partition=" + a.partition] + sbatch_args
        submit(a, sbatch_args)
    elif a.command == "status":
        status(a)
    elif a.command == "resubmit":
        resubmit(a, sbatch_args)
    else:
        sys.exit(merge(a))


shards.run_main(main)
