"""The scene as a static, self-contained HTML page (viser's embedded player with the serialized scene)."""
from __future__ import annotations

import os
import tempfile


def save_html(viewer, path) -> str:
    """Writes the viewer's current scene to `path` (one HTML file, no server needed), atomically."""
    html = viewer.server.get_scene_serializer().as_html()
    path = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=".octoreach-", suffix=".html")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(html)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path
