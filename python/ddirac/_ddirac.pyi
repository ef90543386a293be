"""Type stubs of the extension module (the package's public API is in its Python modules)."""

from os import PathLike
from typing import Any, Callable, Optional, Sequence

__version__: str

class Error(Exception): ...
class SpecError(Error): ...

class ExpressionError(Error):
    origin: Optional[str]
    text: Optional[str]
    span: Optional[tuple[int, int]]
    help: Optional[str]

class InvarianceError(Error): ...

class ConvergenceError(Error):
    step: int
    t: float
    h: float
    residual: Optional[float]

class SystemHandle:
    name: str
    parameters: list[tuple[str, float]]
    @property
    def coordinates(self) -> list[tuple[str, str, str]]: ...

class RigidHandle:
    name: str
    parameters: list[tuple[str, float]]
    symmetry: str
    @property
    def shape(self) -> list[tuple[str, str]]: ...

class LoadedSpec:
    name: str
    parameters: list[tuple[str, float]]
    directory: PathLike[str]
    notes: list[str]
    @property
    def system(self) -> SystemHandle: ...
    @property
    def problem(self) -> tuple[float, int, list[float], Optional[list[float]], Optional[list[float]]]: ...
    @property
    def method(self) -> dict[str, Any]: ...
    def run_arrays(self, progress: Optional[Callable[[int], None]] = None) -> dict[str, Any]: ...
    def run_files(self, out: Optional[str] = None) -> PathLike[str]: ...

def builtin_system(name: str, parameters: Sequence[tuple[str, float]]) -> SystemHandle: ...
def builtin_names() -> list[tuple[str, str]]: ...
def text_system(
    lagrangian: str,
    shape: Sequence[str],
    group: Sequence[str],
    angles: Sequence[str],
    definitions: Sequence[tuple[str, str]],
    parameters: Sequence[tuple[str, float]],
    exact: Sequence[tuple[str, str]],
    order: Optional[Sequence[str]] = None,
    name: Optional[str] = None,
) -> SystemHandle: ...
def simulate(
    system: SystemHandle,
    run_args: dict[str, Any],
    every: int,
    wrap_angles: bool,
    progress: Optional[Callable[[int], None]] = None,
) -> dict[str, Any]: ...
def check(system: SystemHandle, run_args: dict[str, Any]) -> dict[str, Any]: ...
def relative_equilibrium(system: SystemHandle, run_args: dict[str, Any]) -> dict[str, Any]: ...
def relative_equilibrium_family(system: SystemHandle, run_args: dict[str, Any], along: str,
                                values: list[float]) -> dict[str, Any]: ...
def rigid_body(parameters: Sequence[tuple[str, float]]) -> RigidHandle: ...
def rigid_text_system(
    lagrangian: str,
    shape: Sequence[str],
    angles: Sequence[str],
    definitions: Sequence[tuple[str, str]],
    parameters: Sequence[tuple[str, float]],
    symmetry: str,
    name: Optional[str] = None,
) -> RigidHandle: ...
def simulate_rigid(
    handle: RigidHandle,
    run_args: dict[str, Any],
    every: int,
    progress: Optional[Callable[[int], None]] = None,
) -> dict[str, Any]: ...
def method_keys() -> list[str]: ...
def convergence_stability(orders: Sequence[Optional[float]]) -> Optional[tuple[int, int, float]]: ...
STABLE: float
def orders_agree(a: float, b: float) -> bool: ...
def time_grid(step: Optional[float], steps: Optional[int], duration: Optional[float]) -> tuple[float, int]: ...
def rust_seconds(system: SystemHandle, run_args: dict[str, Any]) -> float: ...
def load_spec(path: str, set: Sequence[str]) -> LoadedSpec: ...
def ensemble_members(path: str, text: Optional[str], set: Sequence[str]) -> tuple[list[str], Any]: ...
def ensemble(
    path: str,
    text: Optional[str],
    set: Sequence[str],
    columns: Optional[Sequence[tuple[str, Sequence[float]]]],
    offset: int = 0,
    threads: Optional[int] = None,
    trajectories: Optional[bool] = None,
    progress: Optional[Callable[[int], None]] = None,
) -> dict[str, Any]: ...
