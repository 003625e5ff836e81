from collections.abc import Callable
from os import PathLike
from typing import Any

def train(output: str | PathLike[str], source: str = ...,
          progress: Callable[[int, float], Any] | None = ..., **options: Any) -> dict[str, Any]: ...
def load(path: str | PathLike[str], **parameters: Any) -> Any: ...
