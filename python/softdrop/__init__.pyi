# Types of the softdrop package (__init__.py), so that editors complete its calls and type
# checkers check them. The classes come from the compiled core (_core.pyi).
from os import PathLike
from typing import Any, Callable, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt
import pandas as pd

from ._core import DropletParams as DropletParams
from ._core import Medium as Medium
from ._core import RunOptions as RunOptions
from ._core import StoreError as StoreError
from ._core import __version__ as __version__

_Path = Union[str, PathLike[str]]
_MediumLike = Union[Medium, _Path]
_Event = dict[str, Any]

__all__ = ["DropletParams", "Medium", "Result", "RunOptions", "StoreError", "simulate", "simulate_many", "simulate_pair",
           "simulate_pairs", "held_out", "tortuosity", "optimize",
           "sweep", "rigid_descent", "read_history", "read_sweep", "sweep_droplet", "best_arrangement", "columns",
           "__version__"]

class Result(dict[str, Any]):
    def __getattr__(self, name: str) -> Any: ...

def simulate(medium: _MediumLike, x0: Optional[float] = ..., params: Optional[DropletParams] = ...,
             run: Optional[RunOptions] = ..., path: bool = ..., trace: bool = ...,
             trace_interval: int = ...) -> Result: ...
def simulate_many(medium: _MediumLike, n: int, seed: int = ..., threads: int = ...,
                  params: Optional[DropletParams] = ..., run: Optional[RunOptions] = ...) -> pd.DataFrame: ...
def simulate_pair(medium: _MediumLike, x0: Optional[float] = ..., release: str = ..., after: float = ...,
                  offset_x: float = ..., params: Optional[DropletParams] = ..., run: Optional[RunOptions] = ...,
                  path: bool = ..., trace: bool = ..., trace_interval: int = ...) -> Result: ...
def simulate_pairs(medium: _MediumLike, n: int, seed: int = ..., threads: int = ..., release: str = ...,
                   after: float = ..., offset_x: float = ..., params: Optional[DropletParams] = ...,
                   run: Optional[RunOptions] = ...) -> pd.DataFrame: ...
def held_out(medium: _MediumLike, starts: int = ..., seed: int = ..., half_dt: bool = ..., threads: int = ...,
             params: Optional[DropletParams] = ..., run: Optional[RunOptions] = ...) -> Result: ...
def tortuosity(medium: Union[_MediumLike, npt.NDArray[Any]], pixels: int = ..., pixel_size: float = ...,
               periodic: bool = ..., flow: bool = ..., buffer_rows: int = ...) -> Result: ...
def rigid_descent(medium: Medium, x0: Union[float, Sequence[float], npt.NDArray[np.float64]], radius: float = ...,
                  path: bool = ...) -> pd.DataFrame: ...
def optimize(db: _Path = ..., callback: Optional[Callable[[_Event], Optional[bool]]] = ..., progress: bool = ...,
             **options: Any) -> Result: ...
def sweep(db: _Path = ..., callback: Optional[Callable[[_Event], Optional[bool]]] = ..., progress: bool = ...,
          **options: Any) -> Result: ...
def read_history(db: _Path, arrangements: bool = ...) -> dict[str, pd.DataFrame]: ...
def read_sweep(db: _Path, sweep: Optional[int] = ...) -> dict[str, pd.DataFrame]: ...
def sweep_droplet(db: _Path, porosity_index: int, medium_index: int, droplet: int,
                  sweep: Optional[int] = ...) -> Result: ...
def best_arrangement(db: _Path, run: int = ..., generation: int = ...) -> Result: ...
def columns() -> pd.DataFrame: ...
