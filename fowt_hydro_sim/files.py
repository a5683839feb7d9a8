"""Writing files that readers may open at any moment."""
from __future__ import annotations

from pathlib import Path


def replace_text(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` whole: staged beside it, then renamed over it (atomic on one
    file system), so a reader, or an interruption, never finds it half written. On an
    OSError the staged file is removed and the error raised."""
    staged = path.with_name(path.name + ".part")
    try:
        staged.write_text(text, newline="")
        staged.replace(path)
    except OSError:
        staged.unlink(missing_ok=True)
        raise
