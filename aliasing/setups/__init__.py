"""Engines in their own words: one profile per engine and release, and the setup value built from it.

An engine developer comes with the engine's own settings (three.js ``shadowBias``, Babylon's
``lambda``, Godot's ``shadow_normal_bias``, Unity's cascade splits).  A profile holds those
settings as the engine spells them, with units, defaults and the clamps the engine applies,
each read from the engine's source at a pinned release, and says what shadow pipeline they
build for a camera: the splits, the fit and snap, the map layout, the blend band, the bias rule
with the faces that cast, and the filter.  A :class:`Setup` (engine, release, settings, camera
with image size, sun) is built and validated once and carried through every command.

Modules
-------
setting
    One setting (:class:`Setting`): key, unit, default, range, the engine's other spellings of its values.
profile
    The types: :class:`BiasTerm`, :class:`BiasRule`, :class:`Filter`,
    :class:`Pipeline`, :class:`Profile`.
spec
    The setup value (:class:`Setup`) and the camera and sun specs of the command line.
threejs, babylon, playcanvas, godot, unity_urp, bevy, filament, unreal
    One module per engine: its profiles (one per release that differs), each citing the
    files it was read from.

Example
-------
>>> s = build("threejs", camera="near=0.1,far=500,fov=50,aspect=16:9,height=1080", sun="15..60")
>>> s.release, s.settings["cascades"], s.pipeline.k
('r187', 3, 3)
>>> get("threejs@r184").release
'r184'
"""

from __future__ import annotations

import argparse
import importlib
import warnings
from collections.abc import Mapping
from typing import Any

from .. import _validation as check
from . import files
from .profile import FACES, KINDS, ROLES, BiasRule, BiasTerm, Filter, Pipeline, Profile, Setting, Tunable
from .spec import (CAMERA_SPEC, SUN_SPEC, Camera, Setup, Sun, camera_items, load_settings, parse_camera,
                   parse_set, parse_sun)

#: The engines, by the toolkit's name, and the module that holds their profiles (newest release first).
ENGINES: dict[str, str] = {
    "threejs": "threejs",
    "babylon": "babylon",
    "playcanvas": "playcanvas",
    "godot": "godot",
    "unity-urp": "unity_urp",
    "bevy": "bevy",
    "filament": "filament",
    "unreal": "unreal",
}

__all__ = ["ENGINES", "FACES", "KINDS", "BiasRule", "BiasTerm", "CAMERA_SPEC", "Camera", "Filter", "Pipeline", "Profile",
           "ROLES", "SUN_SPEC", "Setting", "Tunable", "Setup", "Sun", "add_arguments", "build", "from_args", "get",
           "ProjectNote", "load_settings", "parse_camera", "parse_set", "parse_sun", "profiles", "project", "resolve"]


def profiles(engine: str) -> tuple[Profile, ...]:
    """Every profile of ``engine`` (newest release first)."""
    name = check.choice(engine, "engine", [e for e in ENGINES if _available(e)])
    return importlib.import_module(f"{__name__}.{ENGINES[name]}").PROFILES


def _available(engine: str) -> bool:
    try:
        importlib.import_module(f"{__name__}.{ENGINES[engine]}")
    except ModuleNotFoundError:
        return False
    return True


def get(spec: str) -> Profile:
    """The profile of ``NAME[@RELEASE]`` (no release: the newest the toolkit knows).

    Raises
    ------
    ValueError
        Naming ``engine`` (with the known engines) or ``release`` (with the engine's releases).

    Example
    -------
    >>> get("threejs").name
    'threejs@r187'
    """
    if not isinstance(spec, str) or not spec.strip():
        raise ValueError(f"engine must be NAME[@RELEASE] with NAME one of: {', '.join(e for e in ENGINES if _available(e))}; got {spec!r}")
    name, _, release = spec.strip().partition("@")
    options = profiles(name.strip().lower())
    if not release:
        return options[0]
    want = release.strip().lower()
    for p in options:
        if want in {p.release.lower(), *map(str.lower, p.releases)}:
            return p
    known = [r for p in options for r in (p.release, *p.releases)]
    raise ValueError(f"unknown {options[0].title} release {release!r}{check.did_you_mean(release, known)}; "
                     f"the toolkit reproduces: {', '.join(known)}")


def build(engine: str | Profile, settings: Mapping[str, Any] | None = None, camera: str | Mapping | Camera | None = None,
          sun: str | Sun | float = "15..60") -> Setup:
    """The :class:`Setup` of an engine with ``settings`` (engine keys; the rest at the defaults).

    Parameters
    ----------
    engine : str or Profile
        ``NAME[@RELEASE]`` (:data:`ENGINES`).
    settings : mapping, optional
        The engine's settings by the engine's own keys; values are typed and range-checked.
    camera : str, mapping or Camera, optional
        :data:`CAMERA_SPEC` (default near 0.1, far 500, fov 50°, 16:9, 1080 rows).
    sun : str, float or Sun
        :data:`SUN_SPEC` (default the band 15..60° ahead).
    """
    profile = engine if isinstance(engine, Profile) else get(engine)
    if settings is not None and not isinstance(settings, Mapping):
        raise ValueError(f"settings must be a mapping of {profile.title} setting names to values, got {type(settings).__name__}")
    return Setup(profile, dict(settings or {}), parse_camera(camera), parse_sun(sun))


class ProjectNote(UserWarning):
    """A conversion or a choice made reading the engine's own project files (one line, on the command line's stderr)."""


class _Default(str):
    """``--sun``'s default, told apart from the same text typed by the user (a project's sun replaces the default only)."""


def add_arguments(parser: argparse.ArgumentParser, *, sun: str | None = "15..60", required: bool = False, camera: bool = True,
                  uses: str = "") -> None:
    """The setup vocabulary on a subcommand: ``--engine``, ``--project``, ``--light-node``, ``--camera-node``, ``--settings``,
    ``--set``, ``--camera``, ``--sun``.

    ``sun=None``: no default (a command whose old ``--light`` stays the default without ``--sun``);
    ``camera=False``: the command has its own ``--camera`` that also takes the camera spec;
    ``required``: the command needs an engine, named by ``--engine`` or by the ``--project`` files (:func:`from_args` refuses
    neither in one line);
    ``uses``: what the command takes from the engine's pipeline, appended to ``--engine``'s help.
    """
    parser.add_argument("--engine", metavar="NAME[@RELEASE]",
                        help="the engine and release: " + ", ".join(ENGINES) + " (no release: the newest known; with --project: the "
                        "files' engine)" + (" (needed, or --project)" if required else "") + (f"; {uses}" if uses else ""))
    parser.add_argument("--project", action="append", metavar="FILE",
                        help="the engine's own project file, read in the engine's names and units (repeatable: Godot's project.godot "
                        "and a .tscn scene; a .babylon scene; three.js Object JSON; a PlayCanvas scene JSON; a Unity URP asset and a .unity scene; "
                        "Unreal's DefaultEngine.ini; Filament's viewer settings JSON); --settings, --set, "
                        "--camera and --sun go over its values")
    parser.add_argument("--light-node", metavar="NAME", help="the light (Babylon: its shadow generator's light) to take from --project "
                        "where the files hold several")
    parser.add_argument("--camera-node", metavar="NAME", help="the camera to take from --project where the files hold several")
    parser.add_argument("--settings", metavar="FILE", help="the engine's settings, JSON or TOML, in the engine's own keys")
    parser.add_argument("--set", dest="set_", action="append", metavar="KEY=VALUE", help="one setting in the engine's own key (repeatable)")
    if camera:
        parser.add_argument("--camera", metavar="SPEC", help=f"camera: {CAMERA_SPEC} (fov vertical in degrees, or radians with rad; hfov=… for the "
                            "horizontal one; minZ/maxZ for near/far; height the image's rows in pixels, or size=1920x1080 for aspect "
                            "and height; default near=0.1,far=500,fov=50,aspect=16:9,height=1080, or the --project camera's)")
    parser.add_argument("--sun", default=None if sun is None else _Default(sun), metavar="ELEV[..ELEV][@AZ]",
                        help=f"sun: {SUN_SPEC} (default {'the --project light, else ' if sun else ''}{sun if sun else '15..60 with --engine'})")


def project(args: argparse.Namespace) -> files.Found | None:
    """The :class:`aliasing.setups.files.Found` of ``--project`` (None without it), its settings typed by the engine's profile.

    Raises
    ------
    ValueError
        A file that cannot be read or is damaged (naming the file and the line or key), or a setting the profile refuses
        (naming where in the file it is).
    """
    paths = getattr(args, "project", None)
    if not paths:
        for flag, name in (("--light-node", "light_node"), ("--camera-node", "camera_node")):
            if getattr(args, name, None):
                raise ValueError(f"{flag} picks a node of --project FILE: give the project file too")
        return None
    found = files.read(paths, getattr(args, "light_node", None), getattr(args, "camera_node", None))
    profile = get(found.engine)
    typed = {}
    for key, value in found.settings.items():
        try:
            typed[key] = profile.setting(key).coerce(value)
        except ValueError as exc:
            raise ValueError(f"{found.where.get(key, key)}: {exc}") from None
    return files.Found(found.engine, typed, found.camera, found.sun, found.light, found.camera_name, found.where, found.notes)


def _namespace(args: object) -> None:
    if not isinstance(args, argparse.Namespace):
        raise ValueError(f"args must be the argparse.Namespace of a parser given add_arguments, got {type(args).__name__}")


def from_args(args: argparse.Namespace) -> Setup:
    """The :class:`Setup` of parsed :func:`add_arguments` options: the ``--project`` files' values, the settings file over
    them, ``--set`` over that; the files' camera fields, then ``--camera``'s; the files' sun unless ``--sun`` is typed.

    Each conversion from the engine's conventions is a :class:`ProjectNote` warning.
    """
    _namespace(args)
    found = project(args)
    engine = getattr(args, "engine", None)
    if found is not None:
        if engine and get(engine).engine != found.engine:
            raise ValueError(f"--engine {engine} names another engine than the --project files ({found.engine}): drop --engine or name {found.engine}")
        engine = engine or found.engine
    if not engine:
        raise ValueError(f"an engine is needed: --engine NAME[@RELEASE] (one of {', '.join(ENGINES)}) or --project FILE (the engine's own "
                         "project file)")
    settings: dict[str, Any] = dict(found.settings) if found is not None else {}
    if getattr(args, "settings", None):
        settings.update(load_settings(args.settings))
    settings.update(parse_set(getattr(args, "set_", None)))
    camera = getattr(args, "camera", None)
    sun = getattr(args, "sun", None)
    notes: tuple[str, ...] = ()
    if found is not None:
        fields, converted = files.merge_camera(found.camera, camera_items(camera))
        camera, notes = fields, found.notes + converted
        if found.sun is not None and (sun is None or isinstance(sun, _Default)):
            sun = Sun((found.sun[0], found.sun[0]), found.sun[1])
    setup = build(engine, settings, camera, sun or "15..60")
    for note in notes:  # after the setup is built: a refusal stays one line
        warnings.warn(f"--project: {note}", ProjectNote, stacklevel=2)
    return setup


def resolve(args: argparse.Namespace) -> tuple[Setup | None, Camera | None, Sun | None]:
    """(setup, camera, sun) of a command's :func:`add_arguments` options: the :class:`Setup` with
    ``--engine`` or ``--project``; without them the camera and sun where given (None where not), and ``--settings`` or
    ``--set`` refused (they need an engine).

    A command whose own ``--camera`` names a glTF camera (``add_arguments(..., camera=False)``)
    takes a camera spec there too: a value with ``=`` is the spec; a name is left in
    ``args.camera`` for the command.
    """
    _namespace(args)
    camera_text = getattr(args, "camera", None)
    if isinstance(camera_text, str) and "=" not in camera_text:  # a glTF camera's name: not ours
        args = argparse.Namespace(**{**vars(args), "camera": None})
    if getattr(args, "engine", None) or getattr(args, "project", None):
        s = from_args(args)
        return s, s.camera, s.sun
    for flag, name in (("--settings", "settings"), ("--set", "set_"), ("--light-node", "light_node"), ("--camera-node", "camera_node")):
        if getattr(args, name, None):
            raise ValueError(f"{flag} needs --engine NAME[@RELEASE] or --project FILE (the settings are the engine's own; engines: "
                             f"{', '.join(ENGINES)})")
    camera = getattr(args, "camera", None)
    sun = getattr(args, "sun", None)
    return None, parse_camera(camera) if camera else None, parse_sun(sun) if sun else None
