"""Where the tests find the repository's files, wherever a test module sits."""
from pathlib import Path

TESTS = Path(__file__).resolve().parent
ROOT = TESTS.parent
