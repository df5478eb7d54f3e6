"""`octoreach cache` and `octoreach build-many`: the map cache and many maps on a cluster."""
from __future__ import annotations

from .args import cache_args


def _cmd_cache(args) -> int:
    from ..cache import MapCache

    store = MapCache(args.cache_dir)
    if args.action == "clear":
        print(f"deleted {store.clear()} maps from {store.directory}")
        return 0
    entries = store.entries()
    print(f"{store.directory}: {len(entries)} maps, {sum(e['bytes'] for e in entries) / 1e6:.1f} MB")
    for e in entries:
        size, created = e["bytes"] / 1e3, _plain(e.get("created", ""))
        print(f"  {e['kind']:10s} {e['key'][:12]}  {_described(e)}  {size:.0f} KB  {created}")
    return 0


def _plain(v) -> str:
    """A value of a cache note as one short line (a note is a file anyone may have written)."""
    from .._checks import shown

    return " ".join(v.split())[:120] if isinstance(v, str) else shown(v)


def _described(entry: dict) -> str:
    """Robot, arm, resolution (and surface, height) of an entry from its note; what is missing says so."""
    def get(d, *keys):
        for k in keys:
            d = d.get(k) if isinstance(d, dict) else None
        return d if d is not None else "?"

    f = entry.get("fields") or {}
    if not f:
        return "(note missing or damaged)"
    cap = f if entry["kind"] == "capability" else get(f, "capability") or {}
    what = f"{_plain(get(cap, 'robot'))} {_plain(get(cap, 'arm', 'base_link'))} -> " \
           f"{_plain(get(cap, 'arm', 'tip_link'))} at {_plain(get(cap, 'options', 'resolution'))} m"
    if entry["kind"] == "surface":
        what += f" surface {_plain(get(f, 'surface'))} z {_plain(get(f, 'height'))}"
    return what


def _cmd_build_many(args) -> int:
    from .. import cluster

    report = cluster.build_many(args.job, cluster=args.cluster, out=args.out,
                                cache=None if args.no_cache else (args.cache_dir or True), progress=not args.quiet,
                                task_cpus=args.task_cpus)
    built = len(report.files) - report.cache_hits
    print(f"{len(report.files)} maps ({built} built, {report.cache_hits} from the cache) in {report.seconds:.1f} s")
    for name, path in report.files.items():
        print(f"  {name} -> {path}")
    return 0


def add_commands(sub):
    """cache, build-many: the map cache and many maps on a cluster."""
    sp = sub.add_parser("cache", help="list or clear the map cache")
    sp.add_argument("action", choices=["list", "clear"], help="list the cached maps, or delete them all")
    sp.add_argument("--cache-dir", help="map cache folder (default $OCTOREACH_CACHE_DIR or ~/.cache/octoreach/maps)")
    sp.set_defaults(func=_cmd_cache)

    sp = sub.add_parser("build-many", help="build many maps (robots x arms x surfaces x resolutions) as tasks on a "
                                           "Ray cluster (the cluster extra); see octoreach.jobs for the job file")
    sp.add_argument("job", help="job file (YAML or JSON): robots, arms, resolutions, capability, surfaces, surface, "
                                "base_heights, out")
    sp.add_argument("--cluster", default="local",
                    help="local (default: Ray on this machine), none (in this process, no Ray), auto (the cluster "
                         "this machine joined) or HOST:PORT of a Ray head")
    sp.add_argument("--out", help="output folder (default: the job file's 'out', else build_many_out)")
    sp.add_argument("--task-cpus", type=int, default=1, help="CPUs (and threads) per task (default 1)")
    sp.add_argument("--quiet", action="store_true", help="no progress line")
    cache_args(sp)
    sp.set_defaults(func=_cmd_build_many)
