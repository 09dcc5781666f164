"""Where the data bundled with the package lies, as plain paths: a module of its own, so that
what needs only a folder (the command line's matrix store reads the profile files' bytes)
does not import the reader of what is in it (`effects.caps` and PyYAML)."""
from __future__ import annotations

import os

PROFILE_FOLDER = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                              "caps_profiles")
