from os import PathLike
from typing import Any, Callable, Sequence

def tune_allocator() -> None: ...
def sky_matrices(epw_paths: Sequence[str | PathLike[str]], out_dir: str | PathLike[str],
                 patches: str = ..., quantity: str = ..., sun_patches: int = ...,
                 client: Any = ..., overwrite: bool = ..., progress: bool = ...,
                 before_task: Callable[[tuple[str, str]], None] | None = ...,
                 **options: Any) -> list[dict[str, Any]]: ...
def estimate_turbidity(image_paths: Sequence[str | PathLike[str]], client: Any = ...,
                       progress: bool = ..., **options: Any) -> list[dict[str, Any]]: ...
def measured_compare(capture_dirs: Sequence[str | PathLike[str] | None],
                     models: Sequence[str] = ..., client: Any = ..., progress: bool = ...,
                     **options: Any) -> list[dict[str, Any]]: ...
def train_networks(configs: dict[str, dict[str, Any]], out_dir: str | PathLike[str],
                   client: Any = ..., overwrite: bool = ...,
                   progress: bool = ...) -> list[dict[str, Any]]: ...
