"""Where the data bundled with the package lies, as plain paths, and whether a card is named
from it: a module of its own, so that what needs only that (the command line's matrix store
reads the profile files' bytes) does not import the reader of what is in them (`effects.d3d9.caps`
and PyYAML)."""
from __future__ import annotations

import os

PROFILE_FOLDER = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                              "caps_profiles")


def names_a_profile_file(name: str) -> bool:
    """Whether a card named `name` is a YAML file given by path, not a bundled profile's name."""
    return name.endswith((".yaml", ".yml")) or "/" in name or "\\" in name
