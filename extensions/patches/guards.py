"""What the patches' guards ask of a library: its major version, and the shape of what a patch
replaces or reads. Each returns None when the library is the one the patch was written for,
else why not (shown by `patches.status()`)."""

from __future__ import annotations

import inspect
import types

# The library versions the patches were written and tested for; another turns them off.
COPIER_MAJOR = 9
JINJA_MAJOR = 3
PROMPT_TOOLKIT_MAJOR = 3


def major_differs(library: str, version: str, major: int) -> str | None:
    head = version.split(".")[0]
    return None if head.isdigit() and int(head) == major else f"{library} {version or '(unknown)'} is not {major}.x"


def copier_differs() -> str | None:
    import copier

    return major_differs("Copier", getattr(copier, "__version__", ""), COPIER_MAJOR)


def jinja_differs() -> str | None:
    import jinja2

    return major_differs("Jinja", jinja2.__version__, JINJA_MAJOR)


def parameters(function) -> list[str] | None:
    try:
        return list(inspect.signature(function).parameters)
    except (TypeError, ValueError):
        return None


def method_differs(owner: type, method: str, expected: list[str] | None) -> str | None:
    """Whether `owner.method` is a plain function of these parameters (or, `expected` None, a property)."""
    member = inspect.getattr_static(owner, method, None)
    if expected is None:
        return None if isinstance(member, property) else f"{owner.__name__}.{method} is not a property"
    if not isinstance(member, types.FunctionType) or parameters(member) != expected:
        return f"{owner.__name__}.{method} is not the method it was"
    return None


def members_missing(owner: type, names: tuple[str, ...]) -> str | None:
    """Whether `owner` lacks one of these members (dataclass fields count)."""
    fields = getattr(owner, "__dataclass_fields__", {})
    missing = [name for name in names if name not in fields and inspect.getattr_static(owner, name, None) is None]
    return f"{owner.__name__} has no {', '.join(missing)}" if missing else None


def looked_up_by_name(function, name: str) -> bool:
    """Whether `function` reads the global `name` when it runs (so replacing it there is seen)."""
    code = getattr(function, "__code__", None)
    return code is not None and name in code.co_names
