# Types of softdrop.plot (plot.py): each function draws into `ax` or a new figure and returns the
# matplotlib Figure.
from typing import Any, Iterable, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from . import Medium, Result, _Path

PAPER_FIT: dict[str, float]

def paper_fit(phi: Union[float, npt.ArrayLike]) -> Any: ...
def medium(m: Medium, ax: Optional[Axes] = ..., touched: Iterable[int] = ..., color: str = ...,
           touched_color: str = ..., shares: Optional[npt.ArrayLike] = ...) -> Figure: ...
def paths(m: Medium, runs: Sequence[Union[Result, dict[str, Any], npt.NDArray[np.float64]]], ax: Optional[Axes] = ...,
          color: str = ..., linewidth: float = ..., alpha: float = ..., shade: bool = ...) -> Figure: ...
def best_curve(history: Union[_Path, dict[str, pd.DataFrame]], run: int = ..., ax: Optional[Axes] = ...) -> Figure: ...
def porosity(points: pd.DataFrame, ax: Optional[Axes] = ..., paper: bool = ..., mean: str = ..., error: str = ...,
             residuals: bool = ..., label: str = ...) -> Figure: ...
def area_trace(run: Result, ax: Optional[Axes] = ...) -> Figure: ...
