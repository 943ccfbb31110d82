"""ssrt: a deterministic CPU renderer (see docs/embedding.md, "Python").

Scenes (built-in names, glTF files, shot files) and settings as keyword arguments in; frames
of named float32 planes out, as read-only numpy views of the renderer's memory, bit-identical
to the `ssrt` command's EXR layers. The extension module is ssrt._ssrt, whose names this
package re-exports; numpy is imported only when a plane is first asked for.
"""

from ssrt import _ssrt
from ssrt._ssrt import *  # noqa: F401,F403 (the package's API is the extension's)

__all__ = [name for name in dir(_ssrt) if not name.startswith("_")]
