"""Shards of independent runs, here or on a cluster (docs/benchmarks.md, "On a cluster").

A run plan (the sweep's runs, the regression's configurations) is cut into N shards, shard
I taking the runs whose position is I modulo N. Each shard writes its results into the
results folder's shards/ as one file, "<name>-<I>-of-<N>.<ext>", written whole or not at
all (a temporary named by host and process, then renamed), so a folder shared by the
nodes of a cluster never holds half a shard. The merge takes the shards only when all N
are there, else it names the missing ones and exits 2 having written nothing."""
import json
import os
import re
import socket
import sys


def parse(text):
    """'I/N' as (I, N); exits 2 when it is not 0 <= I < N."""
    m = re.fullmatch(r"(\d+)/(\d+)", text or "")
    if not m or not int(m.group(1)) < int(m.group(2)):
        print("shards: --shard takes I/N with 0 <= I < N, not %r" % text, file=sys.stderr)
        sys.exit(2)
    return int(m.group(1)), int(m.group(2))


def mine(items, shard, shards):
    """The items of shard I of N: every N-th from position I (mixed costs spread evenly)."""
    return [x for k, x in enumerate(items) if k % shards == shard]


def temporary(path):
    host = re.sub(r"[^A-Za-z0-9-]", "-", socket.gethostname()) or "host"
    return "%s.tmp.%s.%d" % (path, host, os.getpid())


def write_atomically(path, text):
    """`text` into `path`, whole or not at all."""
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    tmp = temporary(path)
    try:
        with open(tmp, "w") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise


def shard_path(results, name, shard, shards, ext):
    return os.path.join(results, "shards", "%s-%d-of-%d.%s" % (name, shard, shards, ext))


def missing(results, name, shards, ext):
    """The shards of N whose file is not in the results folder."""
    return [i for i in range(shards) if not os.path.exists(shard_path(results, name, i, shards, ext))]


def manifest(results):
    """The results folder's manifest.json (what was asked: kind, shards, arguments; a Slurm
    submission's also program, jobs …); exits 2 when it is missing or lacks those."""
    path = os.path.join(results, "manifest.json")
    try:
        with open(path) as f:
            m = json.load(f)
    except (OSError, ValueError) as e:
        print("shards: %s: cannot read the manifest (%s): not a results folder of scripts/sweep.sh or "
              "scripts/slurm.py" % (path, e), file=sys.stderr)
        sys.exit(2)
    if not isinstance(m, dict) or m.get("kind") not in ("sweep", "regress") or \
            not isinstance(m.get("shards"), int) or m["shards"] < 1:
        print("shards: %s: the manifest lacks its kind (sweep, regress) or its count of shards" % path, file=sys.stderr)
        sys.exit(2)
    return m


def collect(results, name, ext):
    """The paths of all N shards (N from the manifest), in shard order; exits 2 naming the
    missing ones."""
    m = manifest(results)
    shards = m["shards"]
    gone = missing(results, name, shards, ext)
    if gone:
        again = ("scripts/slurm.py resubmit %s runs them again" % results if "jobs" in m else
                 "a shard failed: its message is above")
        print("merge: %s: %d of %d shards missing (%s): nothing merged; %s"
              % (results, len(gone), shards, ", ".join(map(str, gone[:20])) + (" …" if len(gone) > 20 else ""),
                 again), file=sys.stderr)
        sys.exit(2)
    return [shard_path(results, name, i, shards, ext) for i in range(shards)]
