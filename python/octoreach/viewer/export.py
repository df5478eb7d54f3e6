"""The scene as a static, self-contained HTML page (viser's embedded player with the serialized scene)."""
from __future__ import annotations

import os

from ..atomic_write import write_atomically


def save_html(viewer, path) -> str:
    """Writes the viewer's current scene to `path` (one HTML file, no server needed), atomically; a device, FIFO or
    symbolic link there is refused (OSError), never replaced."""
    html = viewer.server.get_scene_serializer().as_html()
    write_atomically(path, html, "HTML page")
    return os.fspath(path)
