"""The ``aliasing`` command: argument parsing only; every action is a library call.

Errors in the input (``ValueError`` from the library, bad arguments) print one line on
stderr and exit with status 2.
"""

from __future__ import annotations

import argparse
import math
import sys
import warnings
from collections.abc import Sequence


from . import _table as _tables
from . import _validation
from ._version import __version__


def _one_line(text: str) -> str:
    """``text`` with line breaks and other control characters escaped (user input is echoed in messages)."""
    return "".join(ch if ch.isprintable() else ch.encode("unicode_escape").decode() for ch in text)


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose usage errors are one line on stderr, exit status 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        self.exit(2, _one_line(f"{self.prog}: error: {message}") + "\n")

    def _check_value(self, action: argparse.Action, value: object) -> None:
        """An unknown subcommand or choice: the message suggests the closest known names."""
        if action.choices is not None and value not in action.choices:
            choices = ", ".join(map(repr, action.choices))
            hint = _validation.did_you_mean(value, [str(c) for c in action.choices])
            raise argparse.ArgumentError(action, f"invalid choice: {value!r}{hint} (choose from {choices})")


def _reproduce(args: argparse.Namespace) -> int:
    from . import reproduce

    if args.list:
        for target in reproduce.TARGETS.values():
            print(f"{target.name:20s} {target.description}")
        return 0
    for path in reproduce.reproduce(args.targets, args.out):
        print(path)
    print(reproduce.NEXT, file=sys.stderr)  # stdout stays the list of files written
    return 0


def _derive(args: argparse.Namespace) -> int:
    from . import symbolic

    symbolic._load()
    if args.list:
        for d in symbolic.DERIVATIONS.values():
            print(f"{d.name:40s} {d.source}: {d.summary}")
        return 0
    names = args.names or list(symbolic.DERIVATIONS)
    chosen = [symbolic.get(name) for name in names]  # validate all names before any work
    for d in chosen:
        print(f"# {d.name}  ({d.source}): {d.summary}")
        print(symbolic.display(d.func(), latex=args.latex))
    return 0


def _finite(value: object, flag: str) -> float:
    """A finite number from an option's text or a config value; ±inf and NaN refused by their names."""
    if isinstance(value, bool):
        raise ValueError(f"{flag} must be a number, got {value!r}")
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{flag} must be a number, got {value!r}") from None
    if not math.isfinite(number):
        raise ValueError(f"{flag} must be finite, got {number}")
    return number


def _whole(value: object, flag: str, low: int, high: int, what: str) -> int:
    """A whole number in [low, high] from an option's text or a config value."""
    if isinstance(value, str):
        text = value.strip()
        try:
            number: object = int(text)
        except ValueError:
            number = _finite(text, flag)
    elif isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{flag} must be a whole number >= {low} and <= {high} ({what}), got {value!r}")
    else:
        number = value if isinstance(value, int) else _finite(value, flag)
    if isinstance(number, float):
        if not number.is_integer():
            raise ValueError(f"{flag} must be a whole number >= {low} and <= {high} ({what}), got {value!r}")
        number = int(number)
    if not low <= number <= high:  # type: ignore[operator]
        raise ValueError(f"{flag} must be a whole number >= {low} and <= {high} ({what}), got {value!r}")
    return number  # type: ignore[return-value]


def _sweep_options(args: argparse.Namespace, cfg: dict) -> dict:
    """Every scalar option of ``aliasing sweep``, from the command line or the config, parsed and checked once."""
    from .sweep import limits, runner
    from .sweep.grid import DEFAULT_BLOCK

    def pick(name: str, default: object) -> object:
        value = getattr(args, name)
        return value if value is not None else cfg.get(name, default)

    near = _finite(pick("near", 1.0), "--near")
    if not near > 0:
        raise ValueError(f"--near must be > 0 (a distance), got {near:g}")
    cap = runner.max_jobs()
    jobs = _whole(pick("jobs", 1), "--jobs", 1, cap, f"local processes, at most 4 x {runner.cores()} cores")
    block = _whole(pick("block", DEFAULT_BLOCK), "--block", 1, 10**9, "light directions per chunk")
    max_memory = limits.parse_memory(args.max_memory, "--max-memory") if args.max_memory is not None else limits.DEFAULT_MAX_MEMORY
    fmt = pick("format", "csv")
    if fmt not in ("csv", "json", "netcdf", "parquet"):
        raise ValueError(f"--format must be one of csv, json, netcdf, parquet, got {fmt!r}")
    out = pick("out", None)
    dask = pick("dask", None)
    return {"near": near, "jobs": jobs, "block": block, "max_memory": max_memory, "format": fmt, "out": out, "dask": dask}


def _sweep(args: argparse.Namespace) -> int:
    from . import sweep
    from .sweep import limits

    cfg = sweep.read_config(args.config) if args.config else {}
    opts = _sweep_options(args, cfg)
    fmt, out, jobs = opts["format"], opts["out"], opts["jobs"]
    if out is not None:
        sweep.store.resolve_out(out, "--out")  # refuse a device, FIFO or unwritable file before any work
    schemes = args.schemes if args.schemes is not None else cfg.get("schemes")
    if schemes is None:
        raise ValueError("sweep needs --schemes (or a --config file with schemes)")
    params = dict(cfg.get("params", {}))
    for item in args.param:
        key, sep, value = item.partition("=")
        if not sep or not key.strip():
            raise ValueError(f"--param takes KEY=VALUES (numbers or ranges), got {item!r}")
        params[key.strip()] = value
    axes = {}
    for name, flag, default in (("f_over_n", "--f-over-n", "1000"), ("fov", "--fov", "60"), ("aspect", "--aspect", "1")):
        given = getattr(args, name)
        axes[name] = given if given is not None else cfg.get(name, default)
    light = args.light if args.light is not None else cfg.get("light", "overhead")
    k = args.k if args.k is not None else cfg.get("k")
    summary = args.summary or cfg.get("summary", False)
    held = out is None or summary or fmt == "netcdf" or sweep.store.resolve_out(out) is None
    limits.check_request(schemes, axes["f_over_n"], axes["fov"], light, aspect=axes["aspect"], k=k, params=params, block=opts["block"], jobs=jobs, in_memory=held, limit=opts["max_memory"])
    for name, flag in (("f_over_n", "--f-over-n"), ("fov", "--fov"), ("aspect", "--aspect")):
        if getattr(args, name) is not None:
            axes[name] = sweep.grid_values(axes[name], flag)
    grid = sweep.plan(
        schemes,
        axes["f_over_n"],
        axes["fov"],
        light,
        aspect=axes["aspect"],
        k=k,
        params=params,
        near=opts["near"],
        summary=summary,
        block=opts["block"],
        max_memory=opts["max_memory"],
    )
    if args.dry_run:
        sys.stdout.write(sweep.dry_run(grid, fmt, jobs, in_memory=held, max_memory=opts["max_memory"]))
        return 0
    command = grid.command(fmt) + (f"  # from --config {args.config}" if args.config else "")
    return sweep.run_command(grid, fmt, out, name="sweep", jobs=jobs, dask=opts["dask"], resume=args.resume, command=command)


def _splits(args: argparse.Namespace) -> int:
    from . import budgets, partitioning, sweep

    if args.list:
        width = max(len(name) for name in partitioning.SPLIT_METHODS)
        for m in partitioning.SPLIT_METHODS.values():
            k = f"k={m.default_k}" if m.default_k else "k required"
            print(f"{m.name:{width}s} {k:10s} {m.summary}  [{m.source}]")
            if m.release:  # engine presets: the release they reproduce, NAME@RELEASE names
                tags = f" (as {', '.join(m.name.partition('@')[0] + '@' + r for r in m.releases)})" if m.releases else ""
                print(f"{'':{width}s} {'':10s} release: {m.release}{tags}")
        return 0
    from . import setups

    setup, camera, sun = setups.resolve(args)
    if setup is not None:  # the engine's own split, cascade count and map size
        pl = setup.pipeline
        split = {"logarithmic": "log"}.get(pl.split, pl.split)
        try:
            args.method = partitioning.resolve_name(split)
        except ValueError:
            raise ValueError(f"--engine {setup.profile.name}: its split {pl.split!r} (with these settings) is not a split method of the toolkit; "
                             "'aliasing check' reports its cascades") from None
        args.k, args.far = pl.k, max(pl.far_i)
        if args.budget is None:
            args.budget = float(pl.k * pl.resolution**2)
    if camera is not None:  # --image-res here is the image's rows: the camera's height
        args.near, args.fov, args.aspect, args.image_res = camera.near, camera.fov, camera.aspect, float(camera.height)
        args.far = args.far if setup is not None else camera.far
    if sun is not None:
        args.light = sun.direction(sun.elevations(7))  # eye-space vectors towards the sun over the band
    missing = [flag for flag, value in (("--near", args.near), ("--far", args.far)) if value is None]
    if missing:
        raise ValueError(f"splits needs {', '.join(missing)} (or --list)")
    from .sweep import limits

    limit = limits.parse_memory(args.max_memory, "--max-memory") if args.max_memory is not None else None
    if args.k is not None and args.k >= 1:  # k maps over the light directions: refuse before allocating
        size, _ = limits.estimate_bytes(1, 1, 1, limits.light_count(args.light), args.k, 20_000)
        limits.check_bytes(size, "-k", limit)
    params = partitioning.split_params(args.lam, args.param)
    rows = budgets.splits_report(
        args.method, args.near, args.far, args.k, fov=args.fov, aspect=args.aspect, light=args.light, warp=args.warp,
        budget=args.budget, res_image=args.image_res, allocations=tuple(a for a in args.allocations.split(",") if a), **params,
    )
    if args.format == "table":
        sys.stdout.write(_table(rows))
    else:
        sys.stdout.write(sweep.format_rows(rows, args.format))
    return 0


def _table(rows: list[dict]) -> str:
    """Rows as an aligned plain-text table."""
    return _tables.table(rows, digits=6)


def _engine_validate(p: argparse.ArgumentParser) -> None:
    """``validate --scene FILE --engine E``: the engine's own cascades (its ranges, fit, snap and map size) on the scene,
    measured against the analytic bounds (:func:`aliasing.engines.scene.cascades_on_scene`); the other cases as before."""
    plain = p.get_default("run")

    def run(args: argparse.Namespace) -> int:
        if not (getattr(args, "engine", None) and getattr(args, "scene", None)):
            return plain(args)
        import json

        from . import setups
        from .engines.scene import cascades_on_scene
        from .raster.scenes import setup as scene_setup
        from .raster.scenes.world import json_safe

        setup = setups.from_args(argparse.Namespace(**{**vars(args), "camera": args.camera if "=" in (args.camera or "") else None}))
        pl = setup.pipeline
        if pl.fit == "fixed" or pl.grow or pl.rows:
            why = "a fixed shadow box" if pl.fit == "fixed" else "a fade margin on the fit" if pl.grow else "maps of unequal sides (an atlas)"
            raise ValueError(f"validate --scene --engine {setup.profile.name}: this pipeline has {why}, which the scene validation of "
                             "engine fits does not draw; aliasing check --scene evaluates it")
        if args.format not in (None, "text", "json"):
            raise ValueError(f"--format with --scene must be text or json, got {args.format!r}")
        cam, far = setup.camera, max(pl.far_i)
        light = None if args.light_dir is not None else setup.sun.light() if args.sun else args.light
        st = scene_setup(args.scene, eye=args.eye, target=args.target, up=args.up, near=cam.near, far=far, fov=cam.fov,
                         light_dir=args.light_dir, light=light, aspect=cam.aspect)
        r = cascades_on_scene(st, (list(pl.near_i), list(pl.far_i)), res=args.res, fit=pl.fit, snap=pl.snap,
                              resolution=float(pl.resolution))
        r = {"engine": setup.engine, "release": setup.release, "fit": pl.fit, "snap": pl.snap, "resolution": pl.resolution} | r
        if args.format == "json":
            sys.stdout.write(json.dumps(json_safe(r), indent=1) + "\n")
        else:
            head = f"{setup.profile.title} {setup.release}: its cascades (fit {pl.fit}, snap {pl.snap}, {pl.resolution}² texels) on {args.scene}\n"
            rows = "".join(f"{i:>4d}{a:>10.4g}{b:>10.4g}{n:>9d}{x:>10.4f}{z:>10.4f}\n" for i, (a, b, n, x, z) in
                           enumerate(zip(r["near_i"], r["far_i"], r["pixels"], r["ratio_x"], r["ratio_z"])))
            verdict = "PASS" if r["passed"] else "FAIL"
            sys.stdout.write(head + f"{'map':>4s}{'near':>10s}{'far':>10s}{'pixels':>9s}{'ratio_x':>10s}{'ratio_z':>10s}\n" + rows
                             + f"{verdict}: max ratio {r['max_ratio']:.6f} <= 1 + {r['tolerance']:g} (measured error over the analytic bound)\n")
        return 0 if r["passed"] else 1

    p.set_defaults(run=run)


def build_parser(full: bool = True) -> argparse.ArgumentParser:
    """The ``aliasing`` parser; ``full=False`` leaves out the subcommands whose parsers import
    the rasterizer and the engines (validate, render, engines), for ``aliasing derive``,
    which would otherwise spend most of its start-up importing them."""
    parser = _Parser(prog="aliasing", description="Analytic study of shadow-map perspective aliasing.")
    parser.add_argument("--version", action="version", version=f"aliasing {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    rep = sub.add_parser("reproduce", help="write reproduced figures and tables", description="Reproduce the papers' figures and tables into a folder.")
    rep.add_argument("targets", nargs="*", metavar="TARGET", help="target names, or 'all' (default)")
    rep.add_argument("--out", default="out", help="output folder (default: out)")
    rep.add_argument("--list", action="store_true", help="list the targets and exit")
    rep.set_defaults(run=_reproduce)

    der = sub.add_parser("derive", help="print symbolic derivations", description="Print the symbolic (sympy) results, derived from the papers' definitions.")
    der.add_argument("names", nargs="*", metavar="NAME", help="derivation names (default: all); see --list")
    der.add_argument("--latex", action="store_true", help="print LaTeX instead of plain text")
    der.add_argument("--list", action="store_true", help="list the derivations and exit")
    der.set_defaults(run=_derive)

    swp = sub.add_parser(
        "sweep",
        help="evaluate schemes over depth ratios, fields of view, aspect ratios and light directions",
        description="M_x, M_z and S of shadow-map schemes for directional lights (unit resolutions), over the product "
        "of every parameter's values. Numbers take lists and ranges START:STOP:lin|log:COUNT (e.g. 10:10000:log:7). "
        "With --out, finished chunks are kept in <out>.parts until the output is complete (see --resume).",
        epilog="schemes: Standard | P | Po | LogP (Log) | Sopt | LogSopt | <warping rule> | ZP<k> | ZP<k>+<any>.  "
        "lights: overhead | behind | front | gamma:DEG[@azimuth:DEG] | sphere:N | hemisphere:N, comma-separated; "
        "gamma and azimuth also take ranges, e.g. gamma:0:180:lin:19@azimuth:0:90:lin:4.  "
        "Config keys: schemes, k, f_over_n, fov, aspect, light, near, params (table), summary, format, out, block, jobs, dask; "
        "command-line options override them.",
    )
    swp.add_argument("--config", metavar="TOML", help="read the sweep's parameters from a TOML file")
    swp.add_argument("--schemes", help="comma-separated scheme names, e.g. Standard,P,ZP5+LogP (required here or in --config)")
    swp.add_argument("--k", help="numbers of z-partitions (list or range): each scheme B becomes ZP<k>+B (k = 1 keeps B)")
    swp.add_argument("--param", action="append", default=[], metavar="KEY=VALUES", help="warping-rule option swept for the schemes that take it, e.g. eta=-1:1:lin:5, c_fraction=0.2,0.4")
    swp.add_argument("--f-over-n", help="depth ratios far/near: list or range (default 1000)")
    swp.add_argument("--fov", help="FULL fields of view in degrees, list or range (the papers' θ is half: θ = 30° is --fov 60; default 60); vertical when --aspect is not 1")
    swp.add_argument("--aspect", help="image width/height, > 0, list or range (default 1, a square view; 16:9 is 1.777777778); "
                     "other values add an aspect column after fov; a scheme of square views only (face partitions, rules written with θ alone) is then refused")
    swp.add_argument("--light", help="light directions, comma-separated specs (default overhead)")
    swp.add_argument("--near", help="near distance (default 1; results depend on f/n only)")
    swp.add_argument("--summary", action="store_true", help="min, max, max/min and mean of S over the directions (Lloyd 2007 Table 3 layout)")
    swp.add_argument("--format", choices=["csv", "json", "netcdf", "parquet"], help="output format (default csv; netcdf and parquet need --out and the xarray or parquet extra)")
    swp.add_argument("--out", help="output file (default or '-': standard output); written atomically (through a symbolic link: its target), never truncated by a failed run; devices, FIFOs and sockets are refused")
    swp.add_argument("--jobs", help="local worker processes (default 1; at most 4 x cores, and never more than chunks); the output does not depend on it")
    swp.add_argument("--dask", metavar="ADDRESS", help="compute the chunks on a running Dask scheduler, e.g. tcp://host:8786 (dask extra)")
    swp.add_argument("--block", help="light directions per chunk (default 20000)")
    swp.add_argument("--resume", action="store_true", help="continue an interrupted sweep from <out>.parts without recomputing finished chunks")
    swp.add_argument("--dry-run", action="store_true", help="print the grid size, an estimated time and memory, compute nothing")
    swp.add_argument("--max-memory", metavar="SIZE", help="refuse a request estimated to need more memory than this, e.g. 8G (default 4G); checked before anything is allocated")
    swp.set_defaults(run=_sweep)

    spl = sub.add_parser(
        "splits",
        help="split distances of cascaded maps, their storage factors, resolutions and errors",
        description="Where the split planes go, each partition's S over the light directions, and with a texel budget "
        "the resolution and maximum perspective aliasing error of each allocation.",
    )
    spl.add_argument("--list", action="store_true", help="list split methods and presets and exit")
    spl.add_argument("--method", default="log", help="split method (default log; see --list)")
    spl.add_argument("--lambda", dest="lam", type=float, help="blend λ in [0, 1] for practical-style methods")
    spl.add_argument("--param", action="append", default=[], metavar="KEY=VALUE", help="other method parameters, e.g. ratio=2, bias=0, resolution_ratio=2, padding=1, exponent=3")
    spl.add_argument("--near", type=float, help="near distance")
    spl.add_argument("--far", type=float, help="far distance (for engine presets: the shadow distance)")
    spl.add_argument("-k", type=int, help="number of partitions (default: the preset's own; required for log, uniform, practical)")
    spl.add_argument("--fov", type=float, default=60.0, help="FULL (vertical) field of view in degrees (default 60)")
    spl.add_argument("--aspect", type=float, default=1.0, help="image width/height, > 0 (default 1, a square view; 16:9 is 1.7778)")
    spl.add_argument("--light", default="overhead", help="light directions (default overhead)")
    spl.add_argument("--warp", default="Standard", help="warp inside each partition: Standard, P, LogP or a warping rule (default Standard)")
    spl.add_argument("--budget", type=float, help="total texels over all maps (with --image-res; with --engine default: cascades × map size²)")
    spl.add_argument("--image-res", type=float, help="the image's HEIGHT in pixels (rows; with --budget; --camera's height)")
    spl.add_argument("--allocations", default="error,equal", help="allocations to compare (default error,equal)")
    spl.add_argument("--format", default="table", choices=["table", "csv", "json"], help="output format (default table)")
    spl.add_argument("--max-memory", metavar="SIZE", help="refuse a -k estimated to need more memory than this, e.g. 8G (default 4G)")
    from .setups import add_arguments as setup_arguments

    setup_arguments(spl, sun=None)  # --engine: its split, k, far and map size; --camera, --sun: near, far, fov, aspect, --image-res, --light
    spl.set_defaults(run=_splits)
    if not full:
        return parser

    from .raster.validate import add_validate_parser

    _engine_validate(add_validate_parser(sub))

    from .pictures import add_render_parser

    add_render_parser(sub)
    __import__("aliasing.engines.compare", fromlist=["add_engines_parser"]).add_engines_parser(sub)  # aliasing engines
    from .bias.command import add_bias_parser

    bias = add_bias_parser(sub)
    plain_bias = bias.get_default("run")

    def _bias(args: argparse.Namespace) -> int:  # with --engine or --project: the engine's own rule, through aliasing.check (a layer above bias)
        if (getattr(args, "engine", None) or getattr(args, "project", None)) and not args.list:
            from .check.command import run_bias

            return run_bias(args)
        return plain_bias(args)

    bias.set_defaults(run=_bias)
    from .temporal.command import add_shimmer_parser

    add_shimmer_parser(sub)  # aliasing shimmer
    from .check.command import add_check_parser

    add_check_parser(sub)  # aliasing check
    __import__("aliasing.tune.command", fromlist=["add_tune_parser"]).add_tune_parser(sub)  # aliasing tune
    __import__("aliasing.frames.command", fromlist=["add_frames_parser"]).add_frames_parser(sub)  # aliasing frames
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``aliasing`` console script; returns the exit status."""
    words = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser(full=words[:1] != ["derive"])
    args = parser.parse_args(argv)
    def one_line(message, category, filename, lineno, file=None, line=None) -> None:  # noqa: ANN001
        print(_one_line(f"aliasing {args.command}: warning: {message}"), file=sys.stderr)

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # numpy's warning text never precedes the one error line
            warnings.showwarning = one_line  # the toolkit's warnings: one line each, as the errors
            return args.run(args)
    except ValueError as exc:
        message = str(exc)
    except OSError as exc:
        message = f"{exc.filename!r}: {exc.strerror}" if exc.filename else str(exc.strerror or exc)
    except (OverflowError, RecursionError, UnicodeError, MemoryError) as exc:
        message = f"{type(exc).__name__}: {exc}"
    print(_one_line(f"aliasing {args.command}: error: {message}"), file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
