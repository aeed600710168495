"""Shards of independent runs, here or on a cluster (docs/benchmarks.md, "On a cluster").

A run plan (the sweep's runs, the regression's configurations) is cut into N shards, shard
I taking the runs whose position is I modulo N. Each shard writes its results into the
results folder's shards/ as one file, "<name>-<I>-of-<N>.<ext>", written whole or not at
all (a temporary named by host and process, then renamed), so a folder shared by the
nodes of a cluster never holds half a shard. The merge takes the shards only when all N
are there, else it names the missing ones and exits 2 having written nothing.

A bad argument or file stops a script with one line on stderr, "<script>: <what>", and
exit 2 (fail)."""
import json
import os
import re
import socket
import sys

# More shards than any sweep or regression has runs: a count beyond it is a mistake (and
# listing that many shards would not end).
MAX_SHARDS = 100000


def fail(message):
    """One line on stderr, prefixed with the script's name (sweep, regress, slurm), and exit 2."""
    print("%s: %s" % (os.path.splitext(os.path.basename(sys.argv[0]))[0], message), file=sys.stderr)
    sys.exit(2)


def run_main(main):
    """main(), a file or folder that cannot be read, made or written (OSError) reported as
    one line naming it, exit 2, not as a traceback."""
    try:
        return main()
    except OSError as e:
        fail("%s%s" % (e.filename + ": " if isinstance(e.filename, str) else "", e.strerror or e))


def parse(text):
    """'I/N' as (I, N); exits 2 when it is not 0 <= I < N <= MAX_SHARDS."""
    m = re.fullmatch(r"([0-9]+)/([0-9]+)", text or "")
    if not m or not int(m.group(1)) < int(m.group(2)) <= MAX_SHARDS:
        fail("--shard takes I/N with 0 <= I < N <= %d, not %r" % (MAX_SHARDS, text))
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
    """The shards of N whose file is not in the results folder (one listing of the folder,
    not a look per shard: on a cluster's filesystem each look is a round trip)."""
    try:
        there = set(os.listdir(os.path.join(results, "shards")))
    except (FileNotFoundError, NotADirectoryError):
        there = set()
    return [i for i in range(shards) if os.path.basename(shard_path(results, name, i, shards, ext)) not in there]


def manifest(results):
    """The results folder's manifest.json (what was asked: kind, shards, arguments; a Slurm
    submission's also program, jobs …); exits 2 when it is missing, or lacks those or
    holds them of another type (args: a list of strings)."""
    path = os.path.join(results, "manifest.json")
    try:
        with open(path) as f:
            m = json.load(f)
    except (OSError, ValueError) as e:
        fail("%s: cannot read the manifest (%s): not a results folder of scripts/sweep.sh or scripts/slurm.py"
             % (path, e.strerror if isinstance(e, OSError) else e))
    if not isinstance(m, dict) or m.get("kind") not in ("sweep", "regress"):
        fail("%s: the manifest lacks its kind (sweep, regress)" % path)
    if type(m.get("shards")) is not int or not 1 <= m["shards"] <= MAX_SHARDS:
        fail("%s: the manifest's count of shards is %s, not a count from 1 to %d"
             % (path, json.dumps(m.get("shards"))[:40], MAX_SHARDS))
    if not isinstance(m.get("args", []), list) or not all(isinstance(a, str) for a in m.get("args", [])):
        fail("%s: the manifest's args are not a list of strings" % path)
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
        fail("%s: %d of %d shards missing (%s): nothing merged; %s"
             % (results, len(gone), shards, ", ".join(map(str, gone[:20])) + (" …" if len(gone) > 20 else ""), again))
    return [shard_path(results, name, i, shards, ext) for i in range(shards)]
