"""Old PIL's top-level `Image` module, as an alias of Pillow's (see README.md)."""
from PIL.Image import *  # noqa: F401,F403
