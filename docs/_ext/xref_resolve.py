"""Resolve cross-references written with a name's public path to where it is documented.

Docstrings refer to names the way users import them (``aliasing.View``,
``aliasing.raster.shadow_map``, or ``shadow_map`` inside ``aliasing.raster``), while the API pages
document each object once, in the module that defines it. On a missing ``py`` reference this
imports the name relative to the referring module and its parent packages, and links it to the
object's defining module when that is documented. Only names that really import are resolved;
anything else still fails the ``-W -n`` build. Private names (a component starting with ``_``)
have no page by design and are shown as plain code.
"""

from __future__ import annotations

import importlib
import inspect
import re

from docutils import nodes
from sphinx.application import Sphinx
from sphinx.util.nodes import make_refnode


def _lookup(path: str):
    parts = path.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except Exception:
            continue
        try:
            for attr in parts[i:]:
                obj = getattr(obj, attr)
        except AttributeError:
            return None
        return obj
    return None


def _candidates(target: str, module: str | None) -> list[str]:
    out = [target]
    if module:
        parts = module.split(".")
        out += [".".join(parts[:i] + [target]) for i in range(len(parts), 0, -1)]
    out.append(f"aliasing.{target}")
    return out


def _canonical(obj, fallback: str) -> list[str]:
    names = []
    mod, qual = getattr(obj, "__module__", None), getattr(obj, "__qualname__", None)
    if isinstance(mod, str) and isinstance(qual, str):
        names.append(f"{mod}.{qual}")
    if hasattr(obj, "__name__") and not isinstance(obj, type) and hasattr(obj, "__file__"):
        names.append(obj.__name__)  # a module
    names.append(fallback)
    return names


def resolve(app: Sphinx, env, node, contnode):
    if node.get("refdomain") != "py":
        return None
    target = node.get("reftarget", "")
    if not target.startswith(("aliasing", "_")) and "." not in target and not target[:1].isalpha():
        return None
    domain = env.get_domain("py")
    if target.startswith("aliasing.figures.") and target.count(".") == 2:  # a figure script: its gallery page
        docname = f"auto_gallery/plot_{target.rsplit('.', 1)[1]}"
        if docname in env.all_docs:
            return make_refnode(app.builder, node["refdoc"], docname, None, contnode, target)
    for cand in _candidates(target.lstrip("~."), node.get("py:module")):
        obj = _lookup(cand)
        if obj is None:
            continue
        names = _canonical(obj, cand)
        if any(part.startswith("_") for part in names[0].split(".") if not part.startswith("__")):
            return nodes.literal("", contnode.astext())  # private: no page by design
        for name in names:
            if name in domain.objects or name in domain.modules:
                objtype = "module" if name in domain.modules else domain.objects[name].objtype
                role = {"function": "func", "class": "class", "data": "data", "method": "meth",
                        "attribute": "attr", "module": "mod", "property": "attr"}.get(objtype, "obj")
                new = node.deepcopy()
                new["reftarget"], new["reftype"] = name, role
                return domain.resolve_xref(env, node["refdoc"], app.builder, role, name, new, contnode)
    return _by_suffix(app, env, node, contnode, target, domain)


def _by_suffix(app, env, node, contnode, target, domain):
    """A name documented exactly once under this short name (``CONFIG_KEYS``, ``Class.attr``)."""
    short = target.lstrip("~.")
    wanted = next((o for c in _candidates(short, node.get("py:module")) if (o := _lookup(c)) is not None), None)
    if wanted is not None:  # it imports: the documented binding of that very object
        last = short.rsplit(".", 1)[-1]
        hits = [k for k in domain.objects if k.rsplit(".", 1)[-1] == last and _lookup(k) is wanted][:1]
    else:
        hits = [k for k in domain.objects if k == short or k.endswith("." + short)]
    if len(hits) == 1:
        return domain.resolve_xref(env, node["refdoc"], app.builder, "obj", hits[0], node, contnode)
    if "." in short or node.get("py:class"):  # an attribute described in its class's "Attributes"
        owner, attr = short.rsplit(".", 1) if "." in short else (node["py:class"], short)
        owners = [k for k in domain.objects if domain.objects[k].objtype == "class"
                  and (k == owner or k.endswith("." + owner))]
        if len(owners) == 1:
            cls = _lookup(owners[0])
            if cls is not None and (attr in getattr(cls, "__annotations__", {}) or re.search(rf"\b{attr}\b", cls.__doc__ or "")
                                    or re.search(rf"self\.{attr}\b", _source(cls))):
                return domain.resolve_xref(env, node["refdoc"], app.builder, "class", owners[0], node, contnode)
    return None


def _source(obj) -> str:
    try:
        return inspect.getsource(obj)
    except (OSError, TypeError):
        return ""


def setup(app: Sphinx) -> dict:
    app.connect("missing-reference", resolve)
    return {"parallel_read_safe": True, "version": "1"}
