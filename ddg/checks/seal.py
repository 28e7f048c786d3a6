"""Sealing the answer's process: what the exercise asks for switched off, the checks' own code gone.

:func:`switch_off` makes the ``DiscreteCurve`` quantities an exercise asks for, and the callables
that implement or measure them (``ddg``'s helpers, shapely's compiled buffer), raise
:class:`WriteItYourself`; every reference to an original is replaced, so ``gc`` finds none, and a
compiled module cannot be loaded a second time. :func:`drop_checks` empties the checks' modules and
refuses any new import of ``ddg`` or reload. ``runner.py`` calls both in the processes it starts;
the grader's harness switches off before a submission's first cell.
"""

import contextlib
import gc
import importlib
import sys

SEALED = ("ddg.checks", "ddg.explore")
"""Modules the answer's process loses: the checks' drawing, measuring and judging code."""


class WriteItYourself(Exception):
    """Raised when an answer uses the quantity its exercise asks for."""


def switch_off(forbidden, measures):
    """Make the ``DiscreteCurve`` quantities ``forbidden`` and the callables ``measures`` raise
    :class:`WriteItYourself` in this process (the grader does this before a submission's cells run).

    ``measures`` names callables by ``"module.attribute"``: where a quantity is implemented (``ddg``'s
    own helpers, so that a copy of ``DiscreteCurve`` made by running its source again is switched off
    too) and what measures it (shapely's buffer, down to its compiled ``shapely.lib.buffer``, which
    every other entry point calls). Their modules are imported first where they are not yet, and
    cannot be loaded again afterwards (``ddg``'s modules by the checks' seal, compiled extensions here).
    """
    from ..curve import DiscreteCurve

    private = {"turning_angles": ("tan_half_psi",), "curvature": ("_curvatures",)}
    for name in forbidden:
        def refuse(*args, _name=name, **kwargs):
            raise WriteItYourself(f"it uses ddg's `{_name}`, which this exercise asks you to write yourself")
        for attribute in (name, *private.get(name, ())):
            setattr(DiscreteCurve, attribute, property(refuse))
    roots, replaced = set(), {}  # the packages of what is switched off; id(original) -> (original, refusal)
    for dotted in measures:
        module_name, _, attribute = dotted.rpartition(".")
        try:
            module = importlib.import_module(module_name)
        except ImportError:  # nothing to switch off: the answer cannot use it either
            continue
        roots.add(module_name.split(".")[0])
        if module_name.startswith("ddg."):
            why = f"it uses `{dotted}`, ddg's own computation of what this exercise asks you to write yourself"
        else:
            why = f"it uses `{dotted}`, which measures what this exercise asks you to compute"

        def refuse(*args, _why=why, **kwargs):
            raise WriteItYourself(_why)
        refuse.switched_off = True
        original = getattr(module, attribute, None)
        setattr(module, attribute, refuse)
        for cls in vars(module).values():  # shapely.Polygon.buffer and the like
            if isinstance(cls, type) and attribute in vars(cls):
                setattr(cls, attribute, refuse)
        if original is not None and not getattr(original, "switched_off", False):  # once per process tree
            replaced[id(original)] = (original, refuse)
    _replace_everywhere(replaced)
    if roots - {"ddg"}:
        _imp = importlib.import_module("_imp")
        create = _imp.create_dynamic

        def no_second_copy(spec, *args):  # a compiled module loaded again would bring its functions back
            loaded = {getattr(m, "__file__", None) for m in list(sys.modules.values())}
            if spec.name in sys.modules or getattr(spec, "origin", None) in loaded:
                raise ImportError(f"{spec.name} cannot be loaded again while a check runs")
            return create(spec, *args)
        _imp.create_dynamic = no_second_copy


def _replace_everywhere(replaced):
    """Wherever a dict or a list holds an original of ``replaced`` (``{id: (original, refusal)}``), put its
    refusal instead (the copy of a compiled module's namespace that Python keeps to initialise it again
    among them), so that nothing leads back to it; one pass over the objects for all of them."""
    if not replaced:
        return
    def swap(v):
        entry = replaced.get(id(v))
        return entry[1] if entry is not None and entry[0] is v else v
    for holder in gc.get_referrers(*(original for original, _ in replaced.values())):
        if isinstance(holder, dict):
            for key, value in list(holder.items()):
                if swap(value) is not value:
                    holder[key] = swap(value)
        elif isinstance(holder, list):
            holder[:] = [swap(v) for v in holder]


def drop_checks():
    """Empty the checks' modules, make them unimportable, and refuse any new import of ``ddg``."""
    for name in [m for m in sys.modules if m.startswith(SEALED) and m not in (__name__, "ddg.checks.runner")]:
        module = sys.modules[name]
        for value in list(vars(module).values()):  # the exercises' methods, wherever they are kept
            if isinstance(value, type) and value.__module__.startswith(SEALED):
                for attribute in [a for a in vars(value) if not a.startswith("__")]:
                    with contextlib.suppress(AttributeError, TypeError):
                        delattr(value, attribute)
        vars(module).clear()
        sys.modules[name] = None  # `import` raises ImportError
    package = sys.modules.get("ddg")
    for name in ("checks", "explore"):
        with contextlib.suppress(AttributeError):
            delattr(package, name)
    sys.meta_path.insert(0, _NoNew(("ddg",)))

    def no_reload(module):
        raise ImportError("reloading a module is switched off while a check runs")
    importlib.reload = no_reload


class _NoNew:
    """An import hook that refuses to load any part of the packages ``roots`` anew (what is loaded stays)."""

    def __init__(self, roots):
        self.roots = roots

    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in self.roots:
            raise ImportError(f"{name} cannot be imported afresh while a check runs")
        return None
