"""The shared pieces of the PLCopen XML reader: the abort of one item, element names without
their namespace, and the variable sections (used by
:mod:`plclab.lang.frontends.plcopen` and its mixins ``plcopen_types`` and ``plcopen_graphic``).
"""

from __future__ import annotations

SECTIONS = {"inputVars": "VAR_INPUT", "outputVars": "VAR_OUTPUT", "inOutVars": "VAR_IN_OUT",
            "localVars": "VAR", "tempVars": "VAR_TEMP", "externalVars": "VAR_EXTERNAL",
            "globalVars": "VAR_GLOBAL"}
IGNORED = {"documentation", "addData", "comment"}


class Bad(Exception):
    """Abandon the current item (a diagnostic was recorded)."""


def local_name(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]
