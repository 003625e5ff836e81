from typing import Any

import numpy.typing as npt

def turbidity(image: npt.ArrayLike, mask: npt.ArrayLike | None = ..., **options: Any) -> dict[str, Any]: ...
