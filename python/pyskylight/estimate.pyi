from os import PathLike
from typing import Any

import numpy.typing as npt

def turbidity(image: npt.ArrayLike | str | PathLike[str],
              mask: npt.ArrayLike | str | PathLike[str] | None = ...,
              **options: Any) -> dict[str, Any]: ...
