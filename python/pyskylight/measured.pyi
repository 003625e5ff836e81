from collections.abc import Callable
from os import PathLike
from typing import Any

def load_kider(path: str | PathLike[str] | None = ...) -> list[dict[str, Any]]: ...
def compare(model: str, kider: str | PathLike[str] | None = ...,
            progress: Callable[[int, int, str], Any] | None = ..., **options: Any) -> dict[str, Any]: ...
