from os import PathLike
from typing import Any, Literal, overload

import numpy as np
import numpy.typing as npt

@overload
def read(path: str | PathLike[str], metadata: Literal[False] = ...) -> np.ndarray: ...
@overload
def read(path: str | PathLike[str], metadata: Literal[True]) -> tuple[np.ndarray, dict[str, str]]: ...
def write(path: str | PathLike[str], image: npt.ArrayLike,
          metadata: dict[str, str] | None = ...) -> None: ...
