"""What a service server's starter code answers, so that a caller sees a real response.

A default-constructed response says `success: false` to a std_srvs caller, which reads
as a failure; the starter says it worked instead, and fills the yes/no fields of the
package's own services the same way. Types of other packages keep their defaults.
"""

from __future__ import annotations

from collections.abc import Iterable

from .definitions import Definition
from .interfaces import InterfaceType

# std_srvs' responses say whether the request worked, and a message.
STANDARD: dict[tuple[str, str], tuple[tuple[str, object], ...]] = {
    ("std_srvs", "Trigger"): (("success", True), ("message", "done")),
    ("std_srvs", "SetBool"): (("success", True), ("message", "done")),
}


def replies(service_type: InterfaceType, definitions: Iterable[Definition] = (),
            home: str = "") -> tuple[tuple[str, object], ...]:
    """(field, value) pairs the starter sets in the response of a service of this type."""
    standard = STANDARD.get((service_type.package, service_type.name))
    if standard:
        return standard
    if service_type.package != home:
        return ()
    for definition in definitions:
        if definition.kind == "srv" and definition.name == service_type.name:
            response = definition.sections[1] if len(definition.sections) > 1 else ()
            return tuple((field.name, True) for field in response if field.type == "bool" and not field.constant)
    return ()
